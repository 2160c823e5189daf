/* SPDX-License-Identifier: MIT */
/* gltf — glTF 2.0 binary export. See gltf.h.
 *
 * The scene is gathered in three passes: faces sorted into nodes (by canonical object
 * and group name, nodes in the order of their first face) and primitives (by material);
 * each primitive's triangle corners sorted by their weld key, equal keys one vertex;
 * then the BIN chunk (a bufferView per attribute, indices, images) and the JSON that
 * describes it. Sorting instead of hashing keeps it O(n log n) whatever the names. */
#include "formats/gltf.h"

#include "formats/file_io.h"
#include "formats/image.h"

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define GLB_MAGIC               0x46546C67u /* "glTF" */
#define CHUNK_JSON              0x4E4F534Au
#define CHUNK_BIN               0x004E4942u
#define GL_FLOAT                5126
#define GL_UNSIGNED_INT         5125
#define GL_ARRAY_BUFFER         34962
#define GL_ELEMENT_ARRAY_BUFFER 34963
#define GL_REPEAT               10497
#define GL_CLAMP_TO_EDGE        33071
#define GL_LINEAR               9729

/* ---- a growing byte buffer ----------------------------------------------------- */

typedef struct {
    unsigned char *p;
    size_t n, cap;
    int failed; /* out of memory: every later write is dropped */
} buf;

static void put(buf *b, const void *data, size_t n)
{
    if (b->failed || !n) /* an empty buffer's DATA may be NULL, which memcpy may not take */
        return;
    if (b->n + n > b->cap) {
        size_t cap = b->cap ? b->cap : 4096;
        unsigned char *q;
        while (cap < b->n + n && cap < SIZE_MAX / 2) cap *= 2;
        if (cap < b->n + n || !(q = realloc(b->p, cap))) {
            b->failed = 1;
            return;
        }
        b->p = q;
        b->cap = cap;
    }
    memcpy(b->p + b->n, data, n);
    b->n += n;
}

static void put_text(buf *b, const char *s)
{
    put(b, s, strlen(s));
}

static void putf(buf *b, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
static void putf(buf *b, const char *fmt, ...)
{
    char s[512];
    va_list ap;
    int n;
    va_start(ap, fmt);
    n = vsnprintf(s, sizeof s, fmt, ap);
    va_end(ap);
    put(b, s, n < 0 ? 0 : (size_t)n < sizeof s ? (size_t)n : sizeof s - 1);
}

static void pad4(buf *b, unsigned char with)
{
    while (b->n % 4) put(b, &with, 1);
}

static void put_u32(buf *b, uint32_t v)
{
    unsigned char c[4];
    c[0] = (unsigned char)v;
    c[1] = (unsigned char)(v >> 8);
    c[2] = (unsigned char)(v >> 16);
    c[3] = (unsigned char)(v >> 24);
    put(b, c, 4);
}

static void put_f32(buf *b, double v)
{
    float f = isfinite(v) ? (float)v : 0.0f;
    uint32_t u;
    memcpy(&u, &f, 4);
    put_u32(b, u);
}

/* Length of the UTF-8 sequence at s (1 to 4), or 0 if it is not one. */
static int utf8_len(const unsigned char *s)
{
    int n = s[0] < 0x80             ? 1
            : (s[0] & 0xE0) == 0xC0 ? 2
            : (s[0] & 0xF0) == 0xE0 ? 3
            : (s[0] & 0xF8) == 0xF0 ? 4
                                    : 0,
        i;
    if (n == 2 && s[0] < 0xC2) return 0; /* overlong */
    for (i = 1; i < n; i++)
        if ((s[i] & 0xC0) != 0x80) return 0;
    return n;
}

/* A JSON string: quotes, backslashes and control characters escaped, bytes that are
   not UTF-8 replaced by '?'. */
static void put_string(buf *b, const char *s)
{
    const unsigned char *c = (const unsigned char *)s;
    put_text(b, "\"");
    while (*c) {
        int n = utf8_len(c);
        if (*c == '"' || *c == '\\')
            putf(b, "\\%c", *c);
        else if (*c < 0x20)
            putf(b, "\\u%04x", *c);
        else if (n)
            put(b, c, (size_t)n);
        else
            put_text(b, "?");
        c += n ? n : 1;
    }
    put_text(b, "\"");
}

/* ---- gathering: nodes, primitives, welded vertices ------------------------------ */

typedef struct {
    int node_o, node_g; /* canonical names (smallest names index of equal strings), -1 */
    int node;           /* node number, by first face */
    int material, face;
} face_rec;

typedef struct {
    int v, vt;
    float n[3];
    float uv1[2]; /* the lightmap's UV, 0 without one */
    int corner;   /* sc->indices position of this face corner */
    int tri;      /* position in the primitive's index list */
} corner_rec;

static const obj_scene *g_sc; /* for the qsort comparisons (single-threaded) */

static int cmp_name(const void *a, const void *b)
{
    int x = *(const int *)a, y = *(const int *)b, c = strcmp(g_sc->names[x], g_sc->names[y]);
    return c ? c : (x > y) - (x < y);
}

static int cmp_node_key(const void *a, const void *b)
{
    const face_rec *x = a, *y = b;
    if (x->node_o != y->node_o) return (x->node_o > y->node_o) - (x->node_o < y->node_o);
    if (x->node_g != y->node_g) return (x->node_g > y->node_g) - (x->node_g < y->node_g);
    return (x->face > y->face) - (x->face < y->face);
}

static int cmp_primitive(const void *a, const void *b)
{
    const face_rec *x = a, *y = b;
    if (x->node != y->node) return (x->node > y->node) - (x->node < y->node);
    if (x->material != y->material)
        return (x->material > y->material) - (x->material < y->material);
    return (x->face > y->face) - (x->face < y->face);
}

static int cmp_corner(const void *a, const void *b)
{
    const corner_rec *x = a, *y = b;
    int c = memcmp(x->n, y->n, sizeof x->n);
    if (!c) c = memcmp(x->uv1, y->uv1, sizeof x->uv1);
    if (x->v != y->v) return (x->v > y->v) - (x->v < y->v);
    if (x->vt != y->vt) return (x->vt > y->vt) - (x->vt < y->vt);
    if (c) return c;
    return (x->corner > y->corner) - (x->corner < y->corner);
}

static int same_vertex(const corner_rec *x, const corner_rec *y)
{
    return x->v == y->v && x->vt == y->vt && !memcmp(x->n, y->n, sizeof x->n) &&
           !memcmp(x->uv1, y->uv1, sizeof x->uv1);
}

/* canon[i]: the smallest names index with the same string as names[i]. */
static int *canonical_names(const obj_scene *sc)
{
    int *order = malloc(((size_t)sc->nnames + 1) * sizeof *order);
    int *canon = malloc(((size_t)sc->nnames + 1) * sizeof *canon), i;
    if (!order || !canon) {
        free(order);
        free(canon);
        return NULL;
    }
    for (i = 0; i < sc->nnames; i++) order[i] = i;
    g_sc = sc;
    qsort(order, (size_t)sc->nnames, sizeof *order, cmp_name);
    for (i = 0; i < sc->nnames; i++)
        canon[order[i]] = i > 0 && !strcmp(sc->names[order[i]], sc->names[order[i - 1]])
                              ? canon[order[i - 1]]
                              : order[i];
    free(order);
    return canon;
}

/* Faces as records sorted by node (numbered by first face), material, face. */
static face_rec *sort_faces(const obj_scene *sc, const int *canon, int *nodes)
{
    face_rec *r = malloc(((size_t)sc->nfaces + 1) * sizeof *r);
    int i, node = -1, prev;
    if (!r) return NULL;
    for (i = 0; i < sc->nfaces; i++) {
        r[i].node_o = sc->faces[i].object >= 0 ? canon[sc->faces[i].object] : -1;
        r[i].node_g = sc->faces[i].group >= 0 ? canon[sc->faces[i].group] : -1;
        r[i].material = sc->faces[i].material;
        r[i].face = i;
    }
    qsort(r, (size_t)sc->nfaces, sizeof *r, cmp_node_key);
    /* Each run of one key: its first face is the run's first record. Number the runs
       by that face, so nodes come in the order of their first face. */
    for (i = 0; i < sc->nfaces; i++)
        r[i].node = i > 0 && r[i].node_o == r[i - 1].node_o && r[i].node_g == r[i - 1].node_g
                        ? r[i - 1].node
                        : r[i].face;
    qsort(r, (size_t)sc->nfaces, sizeof *r, cmp_primitive);
    for (i = 0, prev = -1; i < sc->nfaces; i++) { /* first faces, increasing: 0, 1, ... */
        node += r[i].node != prev;
        prev = r[i].node;
        r[i].node = node;
    }
    *nodes = node + 1;
    return r;
}

/* The face's unit normal from the OBJ's vn at corner K, else the face's own. */
static void corner_normal(const obj_scene *sc, const obj_face *f, int k, float n[3])
{
    int vn = sc->normal_indices[f->first + k];
    obj_vec3 v = vn >= 0 ? sc->normals[vn] : obj_face_normal(sc, f);
    double len = sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    if (!(len > 0) || !isfinite(len)) {
        v = obj_face_normal(sc, f);
        len = sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    }
    if (!(len > 0) || !isfinite(len)) {
        v.x = v.z = 0;
        v.y = len = 1;
    }
    n[0] = (float)(v.x / len);
    n[1] = (float)(v.y / len);
    n[2] = (float)(v.z / len);
}

/* The corner of face F whose vertex is VERT (the first one). */
static int corner_of(const obj_scene *sc, const obj_face *f, int vert)
{
    int k;
    for (k = 0; k < f->count; k++)
        if (sc->indices[f->first + k] == vert) return k;
    return 0;
}

/* Appends face F's triangles, as corner numbers of the face, to *TRI; returns how many
   or -1 when out of memory. A face obj_triangulate refuses is left out. */
static int face_triangles(const obj_scene *sc, const obj_face *f, int **tri, size_t *cap)
{
    int nt = f->count - 2, t, k, *v;
    if ((size_t)nt * 3 > *cap) {
        int *q = realloc(*tri, (size_t)nt * 3 * sizeof *q);
        if (!q) return -1;
        *tri = q;
        *cap = (size_t)nt * 3;
    }
    if (f->count <= 4) {
        for (t = 0; t < nt; t++) {
            (*tri)[3 * t] = 0;
            (*tri)[3 * t + 1] = t + 1;
            (*tri)[3 * t + 2] = t + 2;
        }
        return nt;
    }
    v = malloc((size_t)nt * 3 * sizeof *v);
    if (!v) return -1;
    nt = obj_triangulate(sc, f, v);
    for (t = 0; t < nt; t++)
        for (k = 0; k < 3; k++) (*tri)[3 * t + k] = corner_of(sc, f, v[3 * t + k]);
    free(v);
    return nt < 0 ? 0 : nt;
}

/* ---- the binary chunk and its description --------------------------------------- */

typedef struct {
    buf bin, views, accessors, meshes, nodes;
    int nviews, naccessors, nmeshes, nloose; /* nodes: the loose ones (no obj_node) */
    const gltf_input *in;
    int *mesh_of_node; /* per obj_node: its mesh, -1 */
    /* the node being written: its world transform inverted (vertices written in its
       frame), its linear part (normals: by its transpose), and 1 if it mirrors */
    double inv[3][4], lin[3][3];
    int framed, mirror; /* framed 0: the world's frame, written as they are */
    int *image_of;      /* per material: image index, -1 */
    int *texture_of;    /* per material: texture index, when image_of >= 0 */
} writer;

/* A bufferView of the last LEN bytes of bin (already padded) and an accessor over it. */
static int add_accessor(writer *w, size_t offset, int target, int component, int count,
                        const char *type, const float *min, const float *max, int ncomp)
{
    int k;
    putf(&w->views, "%s{\"buffer\":0,\"byteOffset\":%lu,\"byteLength\":%lu,\"target\":%d}",
         w->nviews ? "," : "", (unsigned long)offset, (unsigned long)(w->bin.n - offset), target);
    putf(&w->accessors, "%s{\"bufferView\":%d,\"componentType\":%d,\"count\":%d,\"type\":\"%s\"",
         w->naccessors ? "," : "", w->nviews++, component, count, type);
    if (min) {
        put_text(&w->accessors, ",\"min\":[");
        for (k = 0; k < ncomp; k++) putf(&w->accessors, "%s%.9g", k ? "," : "", min[k]);
        put_text(&w->accessors, "],\"max\":[");
        for (k = 0; k < ncomp; k++) putf(&w->accessors, "%s%.9g", k ? "," : "", max[k]);
        put_text(&w->accessors, "]");
    }
    put_text(&w->accessors, "}");
    return w->naccessors++;
}

/* Vertex attributes of the welded corners C[0..n-1] (sorted, vertex ids in TRI order
   resolved by the caller): one entry per run of equal keys. */
typedef struct {
    const corner_rec *c;
    int n, nverts;
    int *first; /* nverts + 1 run starts into c */
    int textured;
    const obj_material *m;
} prim_verts;

static void vertex_uv(const obj_scene *sc, const obj_material *m, int vt, double uv[2])
{
    uv[0] = vt >= 0 ? sc->uvs[vt].u * m->map_kd.scale[0] + m->map_kd.offset[0] : 0;
    uv[1] = vt >= 0 ? 1.0 - (sc->uvs[vt].v * m->map_kd.scale[1] + m->map_kd.offset[1]) : 0;
}

/* A welded vertex's colour: the weighted mean of its distinct face corners'. */
static void vertex_colour(const gltf_input *in, const corner_rec *c, int n, double rgb[3])
{
    double sum = 0;
    int i, k;
    rgb[0] = rgb[1] = rgb[2] = 0;
    for (i = 0; i < n; i++) {
        double wt;
        if (i > 0 && c[i].corner == c[i - 1].corner) continue;
        wt = in->corner_weight ? in->corner_weight[c[i].corner] : 1.0;
        wt = wt > 0 && isfinite(wt) ? wt : 0;
        for (k = 0; k < 3; k++) rgb[k] += wt * in->corner_rgb[3 * (size_t)c[i].corner + k];
        sum += wt;
    }
    for (k = 0; k < 3; k++) rgb[k] = sum > 0 ? rgb[k] / sum : 0;
}

/* The lightmap's UVs (each welded vertex's corners share one) as attribute NAME, with
   min and max. */
static void write_uv1(writer *w, const prim_verts *pv, const char *name, buf *p)
{
    float lo[2] = {HUGE_VALF, HUGE_VALF}, hi[2] = {-HUGE_VALF, -HUGE_VALF};
    size_t at = w->bin.n;
    int i, k, acc;
    for (i = 0; i < pv->nverts; i++)
        for (k = 0; k < 2; k++) {
            float f = pv->c[pv->first[i]].uv1[k];
            put_f32(&w->bin, f);
            lo[k] = f < lo[k] ? f : lo[k];
            hi[k] = f > hi[k] ? f : hi[k];
        }
    acc = add_accessor(w, at, GL_ARRAY_BUFFER, GL_FLOAT, pv->nverts, "VEC2", lo, hi, 2);
    putf(p, ",\"%s\":%d", name, acc);
}

/* World normal N in the node's frame: by the transpose of its linear part (the
   inverse of the inverse transpose that took it to the world), unit again. */
static void local_normal(const writer *w, const float *n, double *o)
{
    double len;
    int k;
    for (k = 0; k < 3; k++)
        o[k] = w->framed ? w->lin[0][k] * n[0] + w->lin[1][k] * n[1] + w->lin[2][k] * n[2] : n[k];
    if (!w->framed) return;
    len = sqrt(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]);
    for (k = 0; k < 3 && len > 0 && isfinite(len); k++) o[k] /= len;
}

/* Writes the attribute arrays; appends their accessors to the primitive's JSON P. */
static void write_attributes(writer *w, const prim_verts *pv, buf *p)
{
    const obj_scene *sc = w->in->sc;
    float lo[3], hi[3];
    size_t at;
    int i, k, acc;
    for (k = 0; k < 3; k++) {
        lo[k] = HUGE_VALF;
        hi[k] = -HUGE_VALF;
    }
    at = w->bin.n;
    for (i = 0; i < pv->nverts; i++) {
        const obj_vec3 *v = &sc->verts[pv->c[pv->first[i]].v];
        float f[3];
        for (k = 0; k < 3; k++)
            f[k] = !w->framed ? (float)(k == 0   ? v->x
                                        : k == 1 ? v->y
                                                 : v->z)
                              : (float)(w->inv[k][0] * v->x + w->inv[k][1] * v->y +
                                        w->inv[k][2] * v->z + w->inv[k][3]);
        for (k = 0; k < 3; k++) {
            put_f32(&w->bin, f[k]);
            lo[k] = f[k] < lo[k] ? f[k] : lo[k];
            hi[k] = f[k] > hi[k] ? f[k] : hi[k];
        }
    }
    acc = add_accessor(w, at, GL_ARRAY_BUFFER, GL_FLOAT, pv->nverts, "VEC3", lo, hi, 3);
    putf(p, "\"attributes\":{\"POSITION\":%d", acc);
    at = w->bin.n;
    for (i = 0; i < pv->nverts; i++) {
        double n[3];
        local_normal(w, pv->c[pv->first[i]].n, n);
        for (k = 0; k < 3; k++) put_f32(&w->bin, n[k]);
    }
    acc = add_accessor(w, at, GL_ARRAY_BUFFER, GL_FLOAT, pv->nverts, "VEC3", NULL, NULL, 0);
    putf(p, ",\"NORMAL\":%d", acc);
    if (pv->textured) {
        at = w->bin.n;
        for (i = 0; i < pv->nverts; i++) {
            double uv[2];
            vertex_uv(sc, pv->m, pv->c[pv->first[i]].vt, uv);
            put_f32(&w->bin, uv[0]);
            put_f32(&w->bin, uv[1]);
        }
        acc = add_accessor(w, at, GL_ARRAY_BUFFER, GL_FLOAT, pv->nverts, "VEC2", NULL, NULL, 0);
        putf(p, ",\"TEXCOORD_0\":%d", acc);
    }
    /* TEXCOORD_n must count from 0: without texture coordinates of its own, a primitive
       gets the lightmap's as TEXCOORD_0 too (no texture of its own reads them). */
    if (w->in->corner_uv1 && !pv->textured) write_uv1(w, pv, "TEXCOORD_0", p);
    if (w->in->corner_uv1) write_uv1(w, pv, "TEXCOORD_1", p);
    if (w->in->corner_rgb) {
        double scale = w->in->color_scale > 0 ? w->in->color_scale : 1;
        int light;
        at = w->bin.n;
        for (i = 0; i < pv->nverts; i++) {
            double rgb[3];
            vertex_colour(w->in, pv->c + pv->first[i], pv->first[i + 1] - pv->first[i], rgb);
            for (k = 0; k < 3; k++) put_f32(&w->bin, rgb[k]);
        }
        light = add_accessor(w, at, GL_ARRAY_BUFFER, GL_FLOAT, pv->nverts, "VEC3", NULL, NULL, 0);
        at = w->bin.n;
        for (i = 0; i < pv->nverts; i++) {
            double rgb[3];
            vertex_colour(w->in, pv->c + pv->first[i], pv->first[i + 1] - pv->first[i], rgb);
            for (k = 0; k < 3; k++) /* NaN fails both tests: 0 */
                put_f32(&w->bin,
                        rgb[k] / scale < 1 ? (rgb[k] / scale > 0 ? rgb[k] / scale : 0) : 1);
        }
        acc = add_accessor(w, at, GL_ARRAY_BUFFER, GL_FLOAT, pv->nverts, "VEC3", NULL, NULL, 0);
        putf(p, ",\"COLOR_0\":%d,\"_LIGHT\":%d", acc, light);
    }
    put_text(p, "}");
}

/* Corners of the triangles of faces R[0..n-1] (one material), sorted by weld key. */
static corner_rec *gather_corners(const gltf_input *in, const face_rec *r, int n, int mirror,
                                  int *ncorners, int *textured)
{
    const obj_scene *sc = in->sc;
    corner_rec *c = NULL;
    int *tri = NULL, i, t, k, count = 0;
    size_t cap = 0, tcap = 0;
    *textured = 0;
    for (i = 0; i < n; i++) {
        const obj_face *f = &sc->faces[r[i].face];
        int nt = face_triangles(sc, f, &tri, &tcap);
        if (nt < 0 || (size_t)count + 3u * (size_t)nt > cap) {
            size_t want = cap * 2 + 3u * (size_t)(nt > 0 ? nt : 0) + 64;
            corner_rec *q = nt < 0 ? NULL : realloc(c, want * sizeof *c);
            if (!q) {
                free(c);
                free(tri);
                return NULL;
            }
            c = q;
            cap = want;
        }
        for (t = 0; t < 3 * nt; t++) {
            corner_rec *x = &c[count];
            k = tri[mirror ? t - t % 3 + 2 - t % 3
                           : t]; /* a mirroring node's triangles as the file wound them */
            x->corner = f->first + k;
            x->v = sc->indices[x->corner];
            x->vt = sc->uv_indices[x->corner];
            *textured |= x->vt >= 0;
            corner_normal(sc, f, k, x->n);
            x->uv1[0] = in->corner_uv1 ? (float)in->corner_uv1[2 * (size_t)x->corner] : 0.0f;
            x->uv1[1] = in->corner_uv1 ? (float)in->corner_uv1[2 * (size_t)x->corner + 1] : 0.0f;
            x->tri = count++;
        }
    }
    free(tri);
    if (!c) c = malloc(sizeof *c); /* no triangle: an empty list, not a failure */
    if (c) qsort(c, (size_t)count, sizeof *c, cmp_corner);
    *ncorners = count;
    return c;
}

/* One primitive: faces R[0..n-1] of material M. Returns 1 if written, 0 if it has no
   triangle, -1 when out of memory. */
static int write_primitive(writer *w, const face_rec *r, int n, buf *prims, int first_prim)
{
    const obj_scene *sc = w->in->sc;
    prim_verts pv;
    corner_rec *c;
    uint32_t *index;
    size_t at;
    int i, v, acc;
    buf p = {0};
    if (!(c = gather_corners(w->in, r, n, w->mirror, &pv.n, &pv.textured))) return -1;
    pv.c = c;
    pv.m = &sc->materials[r[0].material];
    pv.first = malloc(((size_t)pv.n + 1) * sizeof *pv.first);
    index = malloc(((size_t)pv.n + 1) * sizeof *index);
    if (!pv.first || !index) {
        free(c);
        free(pv.first);
        free(index);
        return -1;
    }
    for (i = 0, v = -1; i < pv.n; i++) {
        if (i == 0 || !same_vertex(&c[i], &c[i - 1])) pv.first[++v] = i;
        index[c[i].tri] = (uint32_t)v;
    }
    pv.nverts = v + 1;
    pv.first[pv.nverts] = pv.n;
    if (pv.n > 0) {
        put_text(&p, first_prim ? "{" : ",{");
        write_attributes(w, &pv, &p);
        at = w->bin.n;
        for (i = 0; i < pv.n; i++) put_u32(&w->bin, index[i]);
        acc = add_accessor(w, at, GL_ELEMENT_ARRAY_BUFFER, GL_UNSIGNED_INT, pv.n, "SCALAR", NULL,
                           NULL, 0);
        putf(&p, ",\"indices\":%d,\"material\":%d,\"mode\":4}", acc, r[0].material);
        put(prims, p.p, p.n);
        prims->failed |= p.failed;
    }
    free(p.p);
    free(c);
    free(pv.first);
    free(index);
    return pv.n > 0;
}

static const char *node_name(const obj_scene *sc, const face_rec *r, char *s, size_t n)
{
    const obj_face *f = &sc->faces[r->face];
    if (f->object >= 0 && f->group >= 0)
        snprintf(s, n, "%s/%s", sc->names[f->object], sc->names[f->group]);
    else if (f->object >= 0 || f->group >= 0)
        snprintf(s, n, "%s", sc->names[f->object >= 0 ? f->object : f->group]);
    else
        snprintf(s, n, "(default)");
    return s;
}

/* Faces R[0..n-1] of one node: its mesh, and its node unless it is obj_node NODE
   (>= 0: written by write_hierarchy). Returns -1 when out of memory. */
static int write_node(writer *w, const face_rec *r, int n, int node)
{
    buf prims = {0};
    char name[600];
    int i = 0, written = 0;
    while (i < n) {
        int j = i, rc;
        while (j < n && r[j].material == r[i].material) j++;
        if ((rc = write_primitive(w, r + i, j - i, &prims, !written)) < 0) {
            free(prims.p);
            return -1;
        }
        written += rc;
        i = j;
    }
    if (written) {
        node_name(w->in->sc, r, name, sizeof name);
        put_text(&w->meshes, w->nmeshes ? ",{\"name\":" : "{\"name\":");
        put_string(&w->meshes, name);
        put_text(&w->meshes, ",\"primitives\":[");
        put(&w->meshes, prims.p, prims.n);
        put_text(&w->meshes, "]}");
        if (node >= 0) {
            w->mesh_of_node[node] = w->nmeshes++;
        } else {
            put_text(&w->nodes, w->nloose++ ? ",{\"name\":" : "{\"name\":");
            put_string(&w->nodes, name);
            putf(&w->nodes, ",\"mesh\":%d}", w->nmeshes++);
        }
    }
    i = prims.failed;
    free(prims.p);
    return i ? -1 : 0;
}

/* ---- materials and images -------------------------------------------------------- */

static const char *image_mime(const unsigned char *d, size_t n)
{
    if (n >= 8 && !memcmp(d, "\x89PNG\r\n\x1a\n", 8)) return "image/png";
    if (n >= 3 && d[0] == 0xFF && d[1] == 0xD8 && d[2] == 0xFF) return "image/jpeg";
    return NULL;
}

/* Bytes DATA (SIZE) as a bufferView of their own, 4-aligned; returns its index. */
static int embed_bytes(writer *w, const void *data, size_t size)
{
    size_t at;
    pad4(&w->bin, 0);
    at = w->bin.n;
    put(&w->bin, data, size);
    putf(&w->views, "%s{\"buffer\":0,\"byteOffset\":%lu,\"byteLength\":%lu}", w->nviews ? "," : "",
         (unsigned long)at, (unsigned long)size);
    pad4(&w->bin, 0);
    return w->nviews++;
}

/* Material M's decoded texture encoded as PNG, embedded; its bufferView, or -1 with
   MSG. */
static int embed_as_png(writer *w, int m, char *msg, size_t n)
{
    const tex_image *t = w->in->texture_image ? &w->in->texture_image[m] : NULL;
    unsigned char *png;
    size_t size;
    char err[600];
    int view;
    if (!t || !t->rgb) {
        snprintf(msg, n, "%s: neither PNG nor JPEG and not decoded, left out of the glTF",
                 w->in->texture[m]);
        return -1;
    }
    if (img_encode_png(t->rgb, t->w, t->h, &png, &size, err, sizeof err)) {
        snprintf(msg, n, "%s: %s, left out of the glTF", w->in->texture[m], err);
        return -1;
    }
    view = embed_bytes(w, png, size);
    free(png);
    return view;
}

/* Embeds material M's texture file; returns its bufferView or -1 (warned). */
static int embed_image(writer *w, int m, const char **mime)
{
    char *data, err[600], msg[800];
    size_t size;
    if (fio_read_all(w->in->texture[m], FIO_LIMIT_IMAGE, &data, &size, err, sizeof err)) {
        /* no file to copy (a texture the scene file held): the decoded image as PNG */
        const tex_image *t = w->in->texture_image ? &w->in->texture_image[m] : NULL;
        if (t && t->rgb) {
            int view = embed_as_png(w, m, msg, sizeof msg);
            *mime = "image/png";
            if (view >= 0) return view;
        } else {
            snprintf(msg, sizeof msg, "%s: left out of the glTF", err);
        }
    } else if (!(*mime = image_mime((const unsigned char *)data, size))) {
        int view = embed_as_png(w, m, msg, sizeof msg);
        free(data);
        *mime = "image/png";
        if (view >= 0) return view;
    } else {
        int view = embed_bytes(w, data, size);
        free(data);
        return view;
    }
    if (w->in->warn) w->in->warn(w->in->ctx, msg);
    return -1;
}

/* The lightmap's image, sampler and texture after the materials' N textures and NIMG
   images; returns its texture index, or -1 without one. */
static int lightmap_texture(writer *w, int n, int nimg, buf *tex, buf *img, buf *smp)
{
    int view;
    if (!w->in->lightmap_png) return -1;
    view = embed_bytes(w, w->in->lightmap_png, w->in->lightmap_png_size);
    putf(img, "%s{\"name\":\"lightmap\",\"bufferView\":%d,\"mimeType\":\"image/png\"}",
         nimg ? "," : "", view);
    putf(smp, "%s{\"magFilter\":%d,\"minFilter\":%d,\"wrapS\":%d,\"wrapT\":%d}", n ? "," : "",
         GL_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE, GL_CLAMP_TO_EDGE);
    putf(tex, "%s{\"name\":\"lightmap\",\"sampler\":%d,\"source\":%d}", n ? "," : "", n, nimg);
    return n;
}

/* An earlier material's image of the same texture file, or -1. */
static int image_before(const writer *w, int m)
{
    int i;
    for (i = 0; i < m; i++)
        if (w->image_of[i] >= 0 && !strcmp(w->in->texture[i], w->in->texture[m]))
            return w->image_of[i];
    return -1;
}

/* Material M is shown by the lightmap (gltf_input's lightmap_use). */
static int lit_by_lightmap(const gltf_input *in, int m)
{
    return in->lightmap_png && (!in->lightmap_use || in->lightmap_use[m]);
}

/* Three factors C, each in [0, 1] (NaN: 0), comma-separated. */
static void put_factors(buf *j, const double *c)
{
    int k;
    for (k = 0; k < 3; k++)
        putf(j, "%s%.9g", k ? "," : "", isfinite(c[k]) && c[k] > 0 ? (c[k] < 1 ? c[k] : 1.0) : 0.0);
}

/* Material M's extras: COLOR_0's scale, and the lightmap LM (-1: none) if it uses it. */
static void extras(const writer *w, buf *j, int m, int lm)
{
    int lit = lm >= 0 && lit_by_lightmap(w->in, m);
    if (!w->in->corner_rgb && !lit) return;
    put_text(j, ",\"extras\":{");
    if (w->in->corner_rgb)
        putf(j, "\"colorScale\":%.9g%s", w->in->color_scale > 0 ? w->in->color_scale : 1.0,
             lit ? "," : "");
    if (lit)
        putf(j, "\"lightmap\":{\"index\":%d,\"texCoord\":1,\"scale\":%.9g}", lm,
             w->in->lightmap_scale);
    put_text(j, "}");
}

/* Materials, textures and samplers (one each per textured material), images (one per
   file, embedded once). */
static void write_materials(writer *w, buf *j)
{
    const obj_scene *sc = w->in->sc;
    buf tex = {0}, img = {0}, smp = {0};
    int m, n = 0, nimg = 0, lm;
    for (m = 0; m < sc->nmaterials; m++) {
        const char *mime = NULL;
        int has = w->in->texture && w->in->texture[m], image = has ? image_before(w, m) : -1;
        int view = has && image < 0 ? embed_image(w, m, &mime) : -1;
        w->image_of[m] = -1;
        if (image < 0 && view < 0) continue;
        if (image < 0) {
            putf(&img, "%s{\"bufferView\":%d,\"mimeType\":\"%s\"}", nimg ? "," : "", view, mime);
            image = nimg++;
        }
        w->image_of[m] = image;
        putf(&smp, "%s{\"wrapS\":%d,\"wrapT\":%d}", n ? "," : "",
             sc->materials[m].map_kd.clamp ? GL_CLAMP_TO_EDGE : GL_REPEAT,
             sc->materials[m].map_kd.clamp ? GL_CLAMP_TO_EDGE : GL_REPEAT);
        putf(&tex, "%s{\"sampler\":%d,\"source\":%d}", n ? "," : "", n, image);
        w->texture_of[m] = n++;
    }
    lm = lightmap_texture(w, n, nimg, &tex, &img, &smp);
    put_text(j, ",\"materials\":[");
    for (m = 0; m < sc->nmaterials; m++) {
        static const double black[3] = {0, 0, 0};
        const double *c = w->in->base_color ? w->in->base_color + 3 * m : sc->materials[m].kd;
        int lit = lm >= 0 && lit_by_lightmap(w->in, m);
        put_text(j, m ? ",{\"name\":" : "{\"name\":");
        put_string(j, sc->materials[m].name);
        put_text(j, ",\"pbrMetallicRoughness\":{\"baseColorFactor\":[");
        put_factors(j, lit ? black : c);
        put_text(j, ",1]");
        if (w->image_of[m] >= 0) putf(j, ",\"baseColorTexture\":{\"index\":%d}", w->texture_of[m]);
        put_text(j, ",\"metallicFactor\":0,\"roughnessFactor\":1}");
        if (lit) { /* the light leaving: lightmap x emissiveStrength (its scale) x factor */
            putf(j, ",\"emissiveTexture\":{\"index\":%d,\"texCoord\":1},\"emissiveFactor\":[", lm);
            put_factors(j, w->in->lightmap_factor ? w->in->lightmap_factor + 3 * m : c);
            putf(j,
                 "],\"extensions\":{\"KHR_materials_emissive_strength\":{\"emissiveStrength\":%.9g}"
                 "}",
                 w->in->lightmap_scale);
        } else {
            put_text(j, ",\"extensions\":{\"KHR_materials_unlit\":{}}");
        }
        extras(w, j, m, lm);
        put_text(j, "}");
    }
    put_text(j, "]");
    if (n || lm >= 0) {
        put_text(j, ",\"textures\":[");
        put(j, tex.p, tex.n);
        put_text(j, "],\"images\":[");
        put(j, img.p, img.n);
        put_text(j, "],\"samplers\":[");
        put(j, smp.p, smp.n);
        put_text(j, "]");
    }
    j->failed |= tex.failed | img.failed | smp.failed;
    free(tex.p);
    free(img.p);
    free(smp.p);
}

/* ---- the file -------------------------------------------------------------------- */

static void free_writer(writer *w)
{
    free(w->bin.p);
    free(w->views.p);
    free(w->accessors.p);
    free(w->meshes.p);
    free(w->nodes.p);
    free(w->mesh_of_node);
    free(w->image_of);
    free(w->texture_of);
}

/* The scene's obj_nodes: name, children, matrix (unless the identity), mesh. */
static void write_hierarchy(writer *w, buf *j)
{
    const obj_scene *sc = w->in->sc;
    int *first = malloc(((size_t)sc->nnodes + 1) * sizeof *first);
    int *next = malloc(((size_t)sc->nnodes + 1) * sizeof *next), i, c, k;
    if (!first || !next) {
        j->failed = 1;
        free(first);
        free(next);
        return;
    }
    for (i = 0; i < sc->nnodes; i++) first[i] = -1;
    for (c = sc->nnodes - 1; c >= 0; c--) /* children in order, each list by its parent */
        if (sc->nodes[c].parent >= 0) {
            next[c] = first[sc->nodes[c].parent];
            first[sc->nodes[c].parent] = c;
        }
    for (i = 0; i < sc->nnodes; i++) {
        const obj_node *o = &sc->nodes[i];
        put_text(j, i ? ",{\"name\":" : "{\"name\":");
        put_string(j, o->name);
        for (c = first[i]; c >= 0; c = next[c])
            putf(j, "%s%d%s", c == first[i] ? ",\"children\":[" : ",", c, next[c] < 0 ? "]" : "");
        for (k = 0; k < 16 && o->local[k] == (k % 5 == 0); k++) {}
        for (c = 0; k < 16 && c < 16; c++)
            putf(j, "%s%.17g%s", c ? "," : ",\"matrix\":[", o->local[c], c == 15 ? "]" : "");
        if (w->mesh_of_node[i] >= 0) putf(j, ",\"mesh\":%d", w->mesh_of_node[i]);
        put_text(j, "}");
    }
    free(first);
    free(next);
}

/* The JSON chunk's text. */
static void write_json(writer *w, buf *j)
{
    const obj_scene *sc = w->in->sc;
    int i, n, nh = sc->nnodes;
    int lit = 0, unlit = 0;
    for (i = 0; i < w->in->sc->nmaterials; i++) {
        lit |= lit_by_lightmap(w->in, i);
        unlit |= !lit_by_lightmap(w->in, i);
    }
    put_text(j, "{\"asset\":{\"version\":\"2.0\",\"generator\":\"rad\"}");
    if (lit || unlit)
        putf(j, ",\"extensionsUsed\":[%s%s%s]", unlit ? "\"KHR_materials_unlit\"" : "",
             lit && unlit ? "," : "", lit ? "\"KHR_materials_emissive_strength\"" : "");
    put_text(j, ",\"scene\":0,\"scenes\":[{");
    if (nh + w->nloose) {
        put_text(j, "\"nodes\":[");
        for (i = 0, n = 0; i < nh + w->nloose; i++)
            if (i >= nh || sc->nodes[i].parent < 0) putf(j, "%s%d", n++ ? "," : "", i);
        put_text(j, "]");
    }
    put_text(j, "}]");
    if (nh + w->nloose) {
        put_text(j, ",\"nodes\":[");
        write_hierarchy(w, j);
        if (nh && w->nloose) put_text(j, ",");
        put(j, w->nodes.p, w->nodes.n);
        put_text(j, "]");
    }
    if (w->nmeshes) {
        put_text(j, ",\"meshes\":[");
        put(j, w->meshes.p, w->meshes.n);
        put_text(j, "]");
    }
    write_materials(w, j);
    if (w->naccessors) {
        put_text(j, ",\"accessors\":[");
        put(j, w->accessors.p, w->accessors.n);
        put_text(j, "]");
    }
    if (w->nviews) {
        put_text(j, ",\"bufferViews\":[");
        put(j, w->views.p, w->views.n);
        put_text(j, "]");
    }
    pad4(&w->bin, 0);
    if (w->bin.n) putf(j, ",\"buffers\":[{\"byteLength\":%lu}]", (unsigned long)w->bin.n);
    put_text(j, "}");
    pad4(j, ' ');
}

/* The node of each object (names index; -1: none) and each obj_node's mesh (-1 so
   far) for a scene with nodes; their names kept apart (two nodes may share one); with
   none, canonical_names. NULL out of memory. */
static int *node_names(writer *w, int **node_of)
{
    const obj_scene *sc = w->in->sc;
    int *canon, i;
    *node_of = NULL;
    if (!sc->nnodes) return canonical_names(sc);
    canon = malloc(((size_t)sc->nnames + 1) * sizeof *canon);
    *node_of = malloc(((size_t)sc->nnames + 1) * sizeof **node_of);
    w->mesh_of_node = malloc((size_t)sc->nnodes * sizeof *w->mesh_of_node);
    if (!canon || !*node_of || !w->mesh_of_node) {
        free(canon);
        free(*node_of);
        return NULL;
    }
    for (i = 0; i < sc->nnames; i++) canon[i] = i, (*node_of)[i] = -1;
    for (i = 0; i < sc->nnodes; i++) {
        w->mesh_of_node[i] = -1;
        if (sc->nodes[i].object >= 0 && sc->nodes[i].object < sc->nnames)
            (*node_of)[sc->nodes[i].object] = i;
    }
    return canon;
}

/* The frame faces are written in: obj_node NODE's (-1: the world's). */
static void set_frame(writer *w, int node)
{
    static const double id[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};
    const double(*m)[4] = node >= 0 ? (const double(*)[4])w->in->sc->nodes[node].world : id;
    double det;
    int r, c;
    for (r = 0; r < 3; r++)
        for (c = 0; c < 3; c++) w->lin[r][c] = m[r][c];
    det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
          m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
          m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    w->mirror = det < 0;
    w->framed = node >= 0;
    for (r = 0; r < 3; r++) { /* the inverse: cofactors over det, then the translation */
        for (c = 0; c < 3; c++) {
            int r1 = (c + 1) % 3, r2 = (c + 2) % 3, c1 = (r + 1) % 3, c2 = (r + 2) % 3;
            w->inv[r][c] =
                det != 0 ? (m[r1][c1] * m[r2][c2] - m[r1][c2] * m[r2][c1]) / det : id[r][c];
        }
    }
    for (r = 0; r < 3; r++)
        w->inv[r][3] = -(w->inv[r][0] * m[0][3] + w->inv[r][1] * m[1][3] + w->inv[r][2] * m[2][3]);
}

static int gather(writer *w)
{
    const obj_scene *sc = w->in->sc;
    int *node_of, *canon = node_names(w, &node_of), nodes = 0, i = 0, rc = 0;
    face_rec *r = canon ? sort_faces(sc, canon, &nodes) : NULL;
    while (r && i < sc->nfaces && rc == 0) {
        int j = i, o = sc->faces[r[i].face].object, node = node_of && o >= 0 ? node_of[o] : -1;
        while (j < sc->nfaces && r[j].node == r[i].node) j++;
        set_frame(w, node);
        rc = write_node(w, r + i, j - i, node);
        i = j;
    }
    free(canon);
    free(node_of);
    free(r);
    return r && rc == 0 ? 0 : -1;
}

static int write_glb(const char *path, writer *w, buf *json, char *err, size_t errlen)
{
    buf head = {0};
    fio_out *o;
    FILE *f;
    uint32_t total = 12 + 8 + (uint32_t)json->n + (w->bin.n ? 8 + (uint32_t)w->bin.n : 0);
    put_u32(&head, GLB_MAGIC);
    put_u32(&head, 2);
    put_u32(&head, total);
    put_u32(&head, (uint32_t)json->n);
    put_u32(&head, CHUNK_JSON);
    if (head.failed || !(o = fio_out_open(path, err, errlen))) {
        free(head.p);
        return -1;
    }
    f = fio_out_stream(o);
    fwrite(head.p, 1, head.n, f);
    fwrite(json->p, 1, json->n, f);
    if (w->bin.n) {
        head.n = 0;
        put_u32(&head, (uint32_t)w->bin.n);
        put_u32(&head, CHUNK_BIN);
        fwrite(head.p, 1, head.n, f);
        fwrite(w->bin.p, 1, w->bin.n, f);
    }
    free(head.p);
    return fio_out_commit(o, err, errlen);
}

int gltf_write(const char *path, const gltf_input *in, char *err, size_t errlen)
{
    writer w;
    buf json = {0};
    int rc = -1;
    memset(&w, 0, sizeof w);
    w.in = in;
    w.image_of = malloc(((size_t)in->sc->nmaterials + 1) * sizeof *w.image_of);
    w.texture_of = malloc(((size_t)in->sc->nmaterials + 1) * sizeof *w.texture_of);
    if (w.image_of && w.texture_of && gather(&w) == 0) {
        write_json(&w, &json);
        if (json.failed || w.bin.failed)
            ;
        else if (w.bin.n > 0xFFFFFFF0u - json.n - 64)
            snprintf(err, errlen, "%s: larger than a .glb can be (4 GiB)", path);
        else
            rc = write_glb(path, &w, &json, err, errlen);
        if (json.failed || w.bin.failed) snprintf(err, errlen, "%s: out of memory", path);
    } else if (err && errlen) {
        snprintf(err, errlen, "%s: out of memory", path);
    }
    free(json.p);
    free_writer(&w);
    return rc;
}
