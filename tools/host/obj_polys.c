/* rad host glue: OBJ faces to the core's polygons (see obj_polys.h). */
#include "host/obj_polys.h"

#include <stdlib.h>
#include <string.h>

#define STR_(x) #x
#define STR(x) STR_(x) /* a macro's value as a string */

static void poly_material(sc_poly *p, const obj_material *m, int tag)
{
    memcpy(p->rho, m->kd, sizeof p->rho);
    memcpy(p->emit, m->ke, sizeof p->emit);
    p->tag = tag;
}

sc_poly *obj_to_polys(const obj_scene *sc, int *n, obj_poly_warn_fn warn, void *ctx)
{
    int f, cap = 0, cnt = 0, *tri = NULL, tcap = 0;
    sc_poly *p;
    for (f = 0; f < sc->nfaces; f++) cap += sc->faces[f].count <= 4 ? 1 : sc->faces[f].count - 2;
    p = calloc((size_t)(cap ? cap : 1), sizeof *p);
    if (!p) return NULL;
    for (f = 0; f < sc->nfaces; f++) {
        const obj_face *fc = &sc->faces[f];
        const obj_material *m = &sc->materials[fc->material];
        int k, t, nt;
        if (fc->count <= 4) {
            p[cnt].n = fc->count;
            for (k = 0; k < fc->count; k++) {
                const obj_vec3 *v = &sc->verts[sc->indices[fc->first + k]];
                p[cnt].v[k][0] = v->x; p[cnt].v[k][1] = v->y; p[cnt].v[k][2] = v->z;
            }
            poly_material(&p[cnt++], m, f);
            continue;
        }
        if (3 * (fc->count - 2) > tcap) {
            int *nt2 = realloc(tri, (size_t)(3 * (fc->count - 2)) * sizeof *tri);
            if (!nt2) { free(tri); free(p); return NULL; }
            tri = nt2;
            tcap = 3 * (fc->count - 2);
        }
        nt = obj_triangulate(sc, fc, tri);
        if (nt < 0) {
            if (warn)
                warn(ctx, fc->line, nt == OBJ_TOO_MANY_VERTICES
                                        ? "skipped a face of more than " STR(OBJ_MAX_FACE_VERTICES) " vertices (split it)"
                                        : "skipped a degenerate polygon");
            continue;
        }
        for (t = 0; t < nt; t++) {
            p[cnt].n = 3;
            for (k = 0; k < 3; k++) {
                const obj_vec3 *v = &sc->verts[tri[3 * t + k]];
                p[cnt].v[k][0] = v->x; p[cnt].v[k][1] = v->y; p[cnt].v[k][2] = v->z;
            }
            poly_material(&p[cnt++], m, f);
        }
    }
    free(tri);
    *n = cnt;
    return p;
}


int obj_match_material(void *ctx, int tag)
{
    const obj_material_match *m = ctx;
    return tag >= 0 && tag < m->sc->nfaces && m->sc->faces[tag].material == m->material;
}
