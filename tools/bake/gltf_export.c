/* SPDX-License-Identifier: MIT */
/* rad host glue: the solution on the input's meshes, as glTF (see gltf_export.h). */
#if defined(RAD_FLOAT) && RAD_FLOAT
#include "host/float_names.h"
#endif
#include "bake/gltf_export.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rad/rad.h"

static int emits(const double *e)
{
    return e && (e[0] > 0 || e[1] > 0 || e[2] > 0);
}

typedef struct {
    int *start, *elements; /* the elements of face f: elements[start[f] .. start[f + 1]) */
    const double **emit;   /* per face: its polygons' emission, NULL if it has none */
    double *erg;           /* per element: sc_shade_elements' radiosity (3 each) */
    const double *ve;      /* per core vertex: the light arriving, gathered (NULL: none) */
    const unsigned char *vok;
    double tol; /* distance within which a corner is an element's vertex */
} faces_index;

/* Elements bucketed by face (a counting sort on their tags). */
static int index_faces(sc_solver *s, const obj_scene *sc, const sc_poly *polys, int n,
                       faces_index *fx)
{
    sc_stats st;
    int e, f, *fill;
    sc_get_stats(s, &st);
    fx->start = calloc((size_t)sc->nfaces + 2, sizeof *fx->start);
    fx->elements = malloc(((size_t)st.elements + 1) * sizeof *fx->elements);
    fx->emit = calloc((size_t)sc->nfaces + 1, sizeof *fx->emit);
    fill = calloc((size_t)sc->nfaces + 1, sizeof *fill);
    fx->erg = malloc(((size_t)st.elements + 1) * 3 * sizeof *fx->erg);
    /* The radiosities at once: the ambient term is one pass over the patches, so a
       call per corner made the export O(corners x patches). */
    if (!fx->start || !fx->elements || !fx->emit || !fill || !fx->erg ||
        sc_shade_elements(s, 1, fx->erg) != 0) {
        free(fill);
        return -1;
    }
    for (e = 0; e < st.elements; e++) fx->start[sc_element_tag(s, e) + 1]++;
    for (f = 0; f < sc->nfaces; f++) fx->start[f + 1] += fx->start[f];
    for (e = 0; e < st.elements; e++) {
        int t = sc_element_tag(s, e);
        fx->elements[fx->start[t] + fill[t]++] = e;
    }
    for (f = 0; f < n; f++) fx->emit[polys[f].tag] = polys[f].emit;
    free(fill);
    return 0;
}

/* A corner matches an element's vertex within 1e-5 of the scene's extent: the fixed
   core holds coordinates to 2^-16 of 64 units across (2.4e-7 of the extent). */
static double match_tolerance(const obj_scene *sc)
{
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    double ext = 0;
    int i, k;
    for (i = 0; i < sc->nverts; i++) {
        const double c[3] = {sc->verts[i].x, sc->verts[i].y, sc->verts[i].z};
        for (k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], c[k]);
            hi[k] = fmax(hi[k], c[k]);
        }
    }
    for (k = 0; k < 3 && sc->nverts; k++) ext = fmax(ext, hi[k] - lo[k]);
    return 1e-5 * ext;
}

/* Squared distance from P to element E's nearest vertex, that vertex into *NEAR. */
static double vertex_distance(sc_solver *s, int e, const double p[3], int *near)
{
    int v[4], n = sc_element_vertices(s, e, v), k, a;
    double best = HUGE_VAL;
    for (k = 0; k < n; k++) {
        double q[3], d = 0;
        sc_vertex_pos(s, v[k], q);
        for (a = 0; a < 3; a++) d += (q[a] - p[a]) * (q[a] - p[a]);
        if (d < best) {
            best = d;
            *near = v[k];
        }
    }
    return best;
}

/* The light arriving at element E of a face emitting EMIT (NULL: none), or, gathered,
   at its vertex nearest P. */
static void arriving(sc_solver *s, const faces_index *fx, int e, const double *emit,
                     const double p[3], double out[3])
{
    double rho[3];
    int k, lamp = emits(emit), near = 0;
    if (fx->ve && !lamp && vertex_distance(s, e, p, &near) < HUGE_VAL && fx->vok[near]) {
        memcpy(out, &fx->ve[3 * near], 3 * sizeof *out);
        return;
    }
    memcpy(out, &fx->erg[3 * (size_t)e], 3 * sizeof *out);
    sc_element_rho(s, e, rho); /* the element's own, where it has one */
    for (k = 0; k < 3 && !lamp; k++) out[k] = rho[k] > 0 ? out[k] / rho[k] : 0;
}

/* The vertices of one face's elements sorted by x, for the corners to look up: a corner
   finds the elements with a vertex within the tolerance in O(log m + hits), where a
   scan of the face's m elements per corner made a face of many corners and elements
   O(corners x m). */
typedef struct {
    double p[3];
    int slot; /* the element's place in faces_index.elements */
} face_vertex;

typedef struct {
    face_vertex *v;
    int n;
    int *hit;  /* the slots a corner matched */
    int *mark; /* per slot of the face (slot - start): the last corner that matched it, + 1 */
} face_search;

static int cmp_x(const void *a, const void *b)
{
    double x = ((const face_vertex *)a)->p[0], y = ((const face_vertex *)b)->p[0];
    return (x > y) - (x < y);
}

static int cmp_int(const void *a, const void *b)
{
    int x = *(const int *)a, y = *(const int *)b;
    return (x > y) - (x < y);
}

/* FS for face F: its elements' vertices, sorted by x; marks cleared. */
static void face_vertices(sc_solver *s, const faces_index *fx, int f, face_search *fs)
{
    int i, k;
    fs->n = 0;
    for (i = fx->start[f]; i < fx->start[f + 1]; i++) {
        int v[4], nv = sc_element_vertices(s, fx->elements[i], v);
        for (k = 0; k < nv; k++) {
            sc_vertex_pos(s, v[k], fs->v[fs->n].p);
            fs->v[fs->n++].slot = i;
        }
        fs->mark[i - fx->start[f]] = 0;
    }
    qsort(fs->v, (size_t)fs->n, sizeof *fs->v, cmp_x);
}

/* Corner C of face F: the area-weighted mean of the light arriving at the face's
   elements with a vertex within fx->tol of it, summed in the face's element order, or
   the nearest element's when none has. */
static void corner(sc_solver *s, const obj_scene *sc, const faces_index *fx, face_search *fs, int f,
                   int c, double *rgb, double *weight)
{
    const obj_vec3 *v = &sc->verts[sc->indices[c]];
    const double p[3] = {v->x, v->y, v->z};
    double sum[3] = {0, 0, 0}, area = 0, best = HUGE_VAL, h[3];
    int i, j, k, lo = 0, hi = fs->n, nhit = 0, nearest = -1;
    while (lo < hi) { /* the first vertex at x >= p.x - tol */
        int mid = lo + (hi - lo) / 2;
        if (fs->v[mid].p[0] < p[0] - fx->tol)
            lo = mid + 1;
        else
            hi = mid;
    }
    for (j = lo; j < fs->n && fs->v[j].p[0] <= p[0] + fx->tol; j++) {
        double d = 0;
        int *m = &fs->mark[fs->v[j].slot - fx->start[f]];
        for (k = 0; k < 3; k++) d += (fs->v[j].p[k] - p[k]) * (fs->v[j].p[k] - p[k]);
        if (d <= fx->tol * fx->tol && *m != c + 1) {
            *m = c + 1;
            fs->hit[nhit++] = fs->v[j].slot;
        }
    }
    qsort(fs->hit, (size_t)nhit, sizeof *fs->hit, cmp_int);
    for (i = 0; i < nhit; i++) {
        int e = fx->elements[fs->hit[i]];
        double a = sc_element_area(s, e);
        arriving(s, fx, e, fx->emit[f], p, h);
        for (k = 0; k < 3; k++) sum[k] += a * h[k];
        area += a;
    }
    for (i = fx->start[f]; !(area > 0) && i < fx->start[f + 1]; i++) { /* none: the nearest */
        int nv = 0;
        double d = vertex_distance(s, fx->elements[i], p, &nv);
        if (d < best) {
            best = d;
            nearest = fx->elements[i];
        }
    }
    if (!(area > 0) && nearest >= 0) {
        arriving(s, fx, nearest, fx->emit[f], p, sum);
        area = sc_element_area(s, nearest);
        for (k = 0; k < 3; k++) sum[k] *= area;
    }
    for (k = 0; k < 3; k++) rgb[3 * c + k] = area > 0 ? sum[k] / area : 0;
    weight[c] = area > 0 ? area : 0;
}

int sc_corner_light(sc_solver *s, const obj_scene *sc, const sc_poly *polys, int n, double *rgb,
                    double *weight)
{
    return sc_corner_light_fg(s, NULL, sc, polys, n, rgb, weight, NULL, NULL);
}

int sc_corner_light_fg(sc_solver *s, sc_fgather *fg, const obj_scene *sc, const sc_poly *polys,
                       int n, double *rgb, double *weight, sc_fraction_fn progress, void *pctx)
{
    faces_index fx;
    face_search fs;
    int f, k, rc, most = 0;
    memset(&fx, 0, sizeof fx);
    rc = index_faces(s, sc, polys, n, &fx);
    if (rc == 0 && fg) rc = sc_fgather_vertices(fg, &fx.ve, &fx.vok);
    fx.tol = match_tolerance(sc);
    for (f = 0; rc == 0 && f < sc->nfaces; f++)
        most = fx.start[f + 1] - fx.start[f] > most ? fx.start[f + 1] - fx.start[f] : most;
    fs.v = malloc((4 * (size_t)most + 1) * sizeof *fs.v);
    fs.hit = malloc(((size_t)most + 1) * sizeof *fs.hit);
    fs.mark = malloc(((size_t)most + 1) * sizeof *fs.mark);
    if (!fs.v || !fs.hit || !fs.mark) rc = -1;
    for (f = 0; rc == 0 && f < sc->nfaces; f++) {
        if (progress && f % SC_EXPORT_EVERY == 0) progress(pctx, (double)f / sc->nfaces);
        face_vertices(s, &fx, f, &fs);
        for (k = 0; k < sc->faces[f].count; k++)
            corner(s, sc, &fx, &fs, f, sc->faces[f].first + k, rgb, weight);
    }
    free(fs.v);
    free(fs.hit);
    free(fs.mark);
    free(fx.start);
    free(fx.elements);
    free((void *)fx.emit);
    free(fx.erg);
    return rc;
}

/* COLOR_0's scale: the largest channel of the light at the corners of faces that do
   not emit (of every face when all emit), at least 1. An emitter brighter than that
   shows white; _LIGHT keeps its value. */
static double colour_scale(const obj_scene *sc, const sc_poly *polys, int n, const double *rgb)
{
    unsigned char *lamp = calloc((size_t)sc->nfaces + 1, 1);
    double top[2] = {1, 1}; /* [0]: faces that do not emit, [1]: every face */
    int f, i, k, lit = 0;
    if (!lamp) return 1; /* no memory: COLOR_0 clamped at 1 instead */
    for (i = 0; i < n; i++) lamp[polys[i].tag] |= emits(polys[i].emit);
    for (f = 0; f < sc->nfaces; f++) {
        lit |= !lamp[f];
        for (i = sc->faces[f].first; i < sc->faces[f].first + sc->faces[f].count; i++)
            for (k = 0; k < 3; k++) {
                double v = rgb[3 * (size_t)i + k];
                top[1] = v > top[1] ? v : top[1];
                if (!lamp[f]) top[0] = v > top[0] ? v : top[0];
            }
    }
    free(lamp);
    return top[lit ? 0 : 1];
}

/* Material M's baseColorFactor (see sc_export_gltf). */
static void base_colour(const obj_material *m, int textured, double c[3])
{
    static const double one[3] = {1, 1, 1};
    int k, lamp = emits(m->ke);
    if (lamp || textured)
        tex_reflectance(m->kd, one, c);
    else
        tex_reflectance(one, m->kd, c);
    for (k = 0; k < 3 && lamp; k++) c[k] = 1;
}

/* The lightmap's part of IN from atlas LM: TEXCOORD_1 per corner into UV (2 per corner),
   the PNG into *PNG, the lightmap shown by every material that does not emit (USE)
   with its reflectance as the emissive factor (FACTOR, 3 a material): Kd, or with a
   texture the mean of its texels' (tex_reflectance). 0, or -1 with err. */
static int lightmap_input(const lm_atlas *lm, const obj_scene *sc, const tex_image *maps,
                          double *uv, unsigned char *use, double *factor, unsigned char **png,
                          gltf_input *in, char *err, size_t errlen)
{
    static const double one[3] = {1, 1, 1};
    int m;
    if (!uv || !use || !factor || lm_corner_uvs(lm, sc, uv) != 0) {
        snprintf(err, errlen, "out of memory for the lightmap's UVs");
        return -1;
    }
    if (lm_png(lm, png, &in->lightmap_png_size, &in->lightmap_scale, err, errlen) != 0) return -1;
    for (m = 0; m < sc->nmaterials; m++) {
        double mean[3];
        use[m] = !emits(sc->materials[m].ke);
        if (maps && maps[m].rgb) {
            tex_image_mean(&maps[m], mean);
            tex_reflectance(sc->materials[m].kd, mean, factor + 3 * m);
        } else {
            tex_reflectance(one, sc->materials[m].kd, factor + 3 * m);
        }
    }
    in->lightmap_factor = factor;
    in->corner_uv1 = uv;
    in->lightmap_png = *png;
    in->lightmap_use = use;
    return 0;
}

int sc_export_gltf(sc_solver *s, const obj_scene *sc, const sc_poly *polys, int n,
                   const tex_image *maps, sc_fgather *fg, const char *path, gltf_warn_fn warn,
                   void *ctx, char *err, size_t errlen)
{
    return sc_export_gltf_lightmap(s, sc, polys, n, maps, fg, NULL, NULL, path, warn, ctx, NULL,
                                   NULL, err, errlen);
}

int sc_export_gltf_lightmap(sc_solver *s, const obj_scene *sc, const sc_poly *polys, int n,
                            const tex_image *maps, sc_fgather *fg, const lm_atlas *lm,
                            double *color_scale, const char *path, gltf_warn_fn warn, void *ctx,
                            sc_fraction_fn progress, void *pctx, char *err, size_t errlen)
{
    double *uv = lm ? malloc(2 * ((size_t)sc->nindices + 1) * sizeof *uv) : NULL;
    unsigned char *use = lm ? malloc((size_t)sc->nmaterials + 1) : NULL, *png = NULL;
    double *factor = lm ? malloc(3 * ((size_t)sc->nmaterials + 1) * sizeof *factor) : NULL;
    char why[600] = "";
    size_t corners = (size_t)sc->nindices + 1, mats = (size_t)sc->nmaterials + 1;
    double *rgb = malloc(3 * corners * sizeof *rgb), *weight = malloc(corners * sizeof *weight);
    double *base = malloc(3 * mats * sizeof *base);
    const char **tex = calloc(mats, sizeof *tex);
    gltf_input in;
    int m, rc = -1;
    if (rgb && weight && base && tex &&
        sc_corner_light_fg(s, fg, sc, polys, n, rgb, weight, progress, pctx) == 0) {
        for (m = 0; m < sc->nmaterials; m++) {
            int textured = maps && maps[m].rgb;
            const obj_material *mt = &sc->materials[m];
            base_colour(mt, textured, base + 3 * m);
            tex[m] = textured && !emits(mt->ke) ? mt->map_kd.path : NULL;
        }
        memset(&in, 0, sizeof in);
        in.sc = sc;
        in.corner_rgb = rgb;
        in.corner_weight = weight;
        in.color_scale = colour_scale(sc, polys, n, rgb);
        if (color_scale) *color_scale = in.color_scale;
        in.base_color = base;
        in.texture = tex;
        in.texture_image = maps;
        in.warn = warn;
        in.ctx = ctx;
        if (lm && lightmap_input(lm, sc, maps, uv, use, factor, &png, &in, why, sizeof why) != 0) {
            snprintf(err, errlen, "%s: %s", path, why);
        } else {
            if (progress) progress(pctx, 1.0);
            rc = gltf_write(path, &in, err, errlen);
        }
    } else if (err && errlen) {
        snprintf(err, errlen, "%s: out of memory", path);
    }
    free(uv);
    free(use);
    free(factor);
    free(png);
    free(rgb);
    free(weight);
    free(base);
    free((void *)tex);
    return rc;
}
