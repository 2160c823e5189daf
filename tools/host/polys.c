/* SPDX-License-Identifier: MIT */
/* rad host glue: OBJ faces to the core's polygons (see polys.h). */
#include "host/polys.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define STR_(x) #x
#define STR(x)  STR_(x) /* a macro's value as a string */

/* The texture coordinates of vertex VERT in face FC (its first corner of that vertex). */
static const obj_vec2 *corner_uv(const obj_scene *sc, const obj_face *fc, int vert)
{
    int k;
    for (k = 0; k < fc->count; k++)
        if (sc->indices[fc->first + k] == vert) return &sc->uvs[sc->uv_indices[fc->first + k]];
    return &sc->uvs[sc->uv_indices[fc->first]];
}

/* Polygon P (of face FC, whose vertex indices are VERTS) textured by T: the mean of the
   texture over its UV footprint (tex_polygon_mean). */
static void textured_rho(const obj_scene *sc, const obj_face *fc, const int *verts,
                         const tex_image *t, const double kd[3], sc_poly *p)
{
    double mean[3];
    obj_vec2 uv[4];
    int k;
    for (k = 0; k < p->n; k++) uv[k] = *corner_uv(sc, fc, verts[k]);
    tex_polygon_mean(t, (const double(*)[3])p->v, uv, p->n, NULL, mean);
    tex_reflectance(kd, mean, p->rho);
}

static void poly_material(sc_poly *p, const obj_material *m, int tag)
{
    memcpy(p->rho, m->kd, sizeof p->rho);
    memcpy(p->emit, m->ke, sizeof p->emit);
    p->tag = tag;
}

/* Per material, the texture's mean (whole[m][3] set once needed) for faces without
   texture coordinates: their footprint is unknown, and Kd alone is often 0 beside a
   map_Kd, so the image's own mean stands for it. */
typedef struct {
    const tex_image *maps;
    double (*whole)[4];
} textures;

/* Fills polygon P from the N vertices VERTS of face F. */
static void make_poly(const obj_scene *sc, int f, const int *verts, int n, textures *tx, sc_poly *p)
{
    const obj_face *fc = &sc->faces[f];
    const obj_material *m = &sc->materials[fc->material];
    int k;
    p->n = n;
    for (k = 0; k < n; k++) {
        const obj_vec3 *v = &sc->verts[verts[k]];
        p->v[k][0] = v->x;
        p->v[k][1] = v->y;
        p->v[k][2] = v->z;
    }
    poly_material(p, m, f);
    if (!tx->maps || !tx->maps[fc->material].rgb) return;
    if (sc->uv_indices[fc->first] >= 0) {
        textured_rho(sc, fc, verts, &tx->maps[fc->material], m->kd, p);
        return;
    }
    if (!tx->whole[fc->material][3]) {
        tex_image_mean(&tx->maps[fc->material], tx->whole[fc->material]);
        tx->whole[fc->material][3] = 1;
    }
    tex_reflectance(m->kd, tx->whole[fc->material], p->rho);
}

sc_poly *polys_from_obj(const obj_scene *sc, int *n, polys_warn_fn warn, void *ctx)
{
    return polys_from_obj_tex(sc, NULL, n, warn, ctx);
}

sc_poly *polys_from_obj_tex(const obj_scene *sc, const tex_image *maps, int *n, polys_warn_fn warn,
                            void *ctx)
{
    int f, cap = 0, cnt = 0, *tri = NULL, tcap = 0;
    textures tx;
    sc_poly *p;
    for (f = 0; f < sc->nfaces; f++) cap += sc->faces[f].count <= 4 ? 1 : sc->faces[f].count - 2;
    p = calloc((size_t)(cap ? cap : 1), sizeof *p);
    tx.maps = maps;
    tx.whole = maps ? calloc((size_t)sc->nmaterials + 1, sizeof *tx.whole) : NULL;
    if (!p || (maps && !tx.whole)) {
        free(p);
        free(tx.whole);
        return NULL;
    }
    for (f = 0; f < sc->nfaces; f++) {
        const obj_face *fc = &sc->faces[f];
        int t, nt;
        if (fc->count <= 4) {
            make_poly(sc, f, sc->indices + fc->first, fc->count, &tx, &p[cnt++]);
            continue;
        }
        if (3 * (fc->count - 2) > tcap) {
            int *nt2 = realloc(tri, (size_t)(3 * (fc->count - 2)) * sizeof *tri);
            if (!nt2) {
                free(tri);
                free(p);
                free(tx.whole);
                return NULL;
            }
            tri = nt2;
            tcap = 3 * (fc->count - 2);
        }
        nt = obj_triangulate(sc, fc, tri);
        if (nt < 0) {
            if (warn)
                warn(ctx, fc->line,
                     nt == OBJ_TOO_MANY_VERTICES ? "skipped a face of more than " STR(
                                                       OBJ_MAX_FACE_VERTICES) " vertices (split it)"
                                                 : "skipped a degenerate polygon");
            continue;
        }
        for (t = 0; t < nt; t++) make_poly(sc, f, tri + 3 * t, 3, &tx, &p[cnt++]);
    }
    free(tri);
    free(tx.whole);
    *n = cnt;
    return p;
}

int polys_match_material(void *ctx, int tag)
{
    const polys_material_match *m = ctx;
    return tag >= 0 && tag < m->sc->nfaces && m->sc->faces[tag].material == m->material;
}

/* Reverses face FC's corners: positions, both texture coordinate sets and normals together. */
static void reverse_face(obj_scene *sc, const obj_face *fc)
{
    int i, j;
    for (i = fc->first, j = fc->first + fc->count - 1; i < j; i++, j--) {
        int t = sc->indices[i];
        sc->indices[i] = sc->indices[j];
        sc->indices[j] = t;
        if (sc->uv_indices) {
            t = sc->uv_indices[i];
            sc->uv_indices[i] = sc->uv_indices[j];
            sc->uv_indices[j] = t;
        }
        if (sc->normal_indices) {
            t = sc->normal_indices[i];
            sc->normal_indices[i] = sc->normal_indices[j];
            sc->normal_indices[j] = t;
        }
        if (sc->uv2) {
            obj_vec2 w = sc->uv2[i];
            sc->uv2[i] = sc->uv2[j];
            sc->uv2[j] = w;
        }
    }
}

int polys_orient_by_normals(obj_scene *sc, double *area)
{
    double total = 0.0, turned = 0.0;
    int f, k, n = 0;
    for (f = 0; f < sc->nfaces; f++) {
        const obj_face *fc = &sc->faces[f];
        obj_vec3 g = obj_face_normal(sc, fc);
        double a = 0.5 * sqrt(g.x * g.x + g.y * g.y + g.z * g.z);
        int with = 0, against = 0;
        total += a;
        for (k = 0; sc->normal_indices && k < fc->count; k++) {
            int ni = sc->normal_indices[fc->first + k];
            double d;
            if (ni < 0) continue;
            with++;
            d = sc->normals[ni].x * g.x + sc->normals[ni].y * g.y + sc->normals[ni].z * g.z;
            against += d < 0;
        }
        if (2 * against > with) {
            reverse_face(sc, fc);
            turned += a;
            n++;
        }
    }
    if (area) *area = total > 0.0 ? turned / total : 0.0;
    return n;
}

int polys_two_sided(obj_scene *sc)
{
    int nf = sc->nfaces, ni = sc->nindices, nn = sc->nnormals, f, k;
    int has_uv = sc->uv_indices != NULL,
        has_n = sc->normal_indices != NULL; /* NULL: none (a scene by hand) */
    obj_face *faces;
    int *ix, *uv, *nx;
    obj_vec3 *normals;
    if (nf > INT_MAX / 2 || ni > INT_MAX / 2 || nn > INT_MAX / 2) return -1;
    faces = realloc(sc->faces, 2 * (size_t)nf * sizeof *faces + 1);
    if (faces) sc->faces = faces;
    ix = realloc(sc->indices, 2 * (size_t)ni * sizeof *ix + 1);
    if (ix) sc->indices = ix;
    uv = realloc(sc->uv_indices, 2 * (size_t)ni * sizeof *uv + 1);
    if (uv) sc->uv_indices = uv;
    nx = realloc(sc->normal_indices, 2 * (size_t)ni * sizeof *nx + 1);
    if (nx) sc->normal_indices = nx;
    normals = realloc(sc->normals, 2 * (size_t)nn * sizeof *normals + 1);
    if (normals) sc->normals = normals;
    if (sc->uv2) {
        obj_vec2 *uv2 = realloc(sc->uv2, 2 * (size_t)ni * sizeof *uv2);
        if (!uv2) return -1;
        sc->uv2 = uv2;
        memcpy(uv2 + ni, uv2, (size_t)ni * sizeof *uv2);
    }
    if (!faces || !ix || !uv || !nx || !normals) return -1; /* grown, but the counts stay */
    for (k = 0; k < nn; k++) {
        normals[nn + k].x = -normals[k].x;
        normals[nn + k].y = -normals[k].y;
        normals[nn + k].z = -normals[k].z;
    }
    for (k = 0; k < ni; k++) {
        if (!has_uv) uv[k] = -1;
        if (!has_n) nx[k] = -1;
        ix[ni + k] = ix[k];
        uv[ni + k] = uv[k];
        nx[ni + k] = nx[k] < 0 ? -1 : nn + nx[k];
    }
    for (f = 0; f < nf; f++) {
        faces[nf + f] = faces[f];
        faces[nf + f].first += ni;
        reverse_face(sc, &faces[nf + f]);
    }
    sc->nfaces = 2 * nf;
    sc->nindices = 2 * ni;
    sc->nnormals = 2 * nn;
    return 0;
}
