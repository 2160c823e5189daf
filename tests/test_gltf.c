/* SPDX-License-Identifier: MIT */
/* Tests for the glTF export: tools/formats/gltf.c (the .glb writer) and
 * tools/bake/gltf_export.c (the solution at the input's vertices). The files are read
 * back by a JSON reader written here and checked for structure, then by assimp
 * (Debian assimp-utils) when it is installed. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bake/lightmap.h"
#include "formats/gltf.h"
#include "formats/image.h"
#include "formats/obj.h"
#include "formats/texture.h"
#include "bake/gltf_export.h"
#include "host/polys.h"
#include "tmpdir.h"
#include "assimp.h"
#include "check.h"
#include "gltf_validate.h"

TMPDIR_GROUP("gltf")

/* ---- a small JSON reader: values in one array, children linked ------------------ */

enum { J_NULL, J_BOOL, J_NUM, J_STR, J_ARR, J_OBJ };

typedef struct {
    int type;
    double num;
    const char *str; /* J_STR: start in the text (escapes kept); J_OBJ member: its key */
    int len;
    const char *key;
    int keylen;
    int first, next; /* first child, next sibling: indices, -1 */
} jnode;

typedef struct {
    const char *s, *end;
    jnode *n;
    int count, cap, bad;
} jparser;

static void j_space(jparser *p)
{
    while (p->s < p->end && (*p->s == ' ' || *p->s == '\n' || *p->s == '\r' || *p->s == '\t'))
        p->s++;
}

static int j_new(jparser *p, int type)
{
    if (p->count == p->cap) {
        p->cap = p->cap ? 2 * p->cap : 256;
        p->n = realloc(p->n, (size_t)p->cap * sizeof *p->n);
        assert_non_null(p->n);
    }
    memset(&p->n[p->count], 0, sizeof p->n[0]);
    p->n[p->count].type = type;
    p->n[p->count].first = p->n[p->count].next = -1;
    return p->count++;
}

static int j_value(jparser *p);

static int j_string(jparser *p, const char **start, int *len)
{
    if (p->s >= p->end || *p->s != '"') return p->bad = 1, -1;
    *start = ++p->s;
    while (p->s < p->end && *p->s != '"') {
        if ((unsigned char)*p->s < 0x20) return p->bad = 1, -1;
        p->s += *p->s == '\\' ? 2 : 1;
    }
    if (p->s >= p->end) return p->bad = 1, -1;
    *len = (int)(p->s - *start);
    p->s++;
    return 0;
}

static int j_list(jparser *p, int type, char close)
{
    int me = j_new(p, type), last = -1;
    p->s++;
    j_space(p);
    if (p->s < p->end && *p->s == close) {
        p->s++;
        return me;
    }
    while (!p->bad) {
        const char *key = NULL;
        int keylen = 0, child;
        j_space(p);
        if (type == J_OBJ) {
            if (j_string(p, &key, &keylen)) return -1;
            j_space(p);
            if (p->s >= p->end || *p->s++ != ':') return p->bad = 1, -1;
        }
        child = j_value(p);
        if (child < 0) return -1;
        p->n[child].key = key;
        p->n[child].keylen = keylen;
        if (last < 0)
            p->n[me].first = child;
        else
            p->n[last].next = child;
        last = child;
        j_space(p);
        if (p->s < p->end && *p->s == ',') {
            p->s++;
            continue;
        }
        if (p->s < p->end && *p->s == close) {
            p->s++;
            return me;
        }
        p->bad = 1;
    }
    return -1;
}

static int j_value(jparser *p)
{
    int me;
    char *end;
    j_space(p);
    if (p->s >= p->end) return p->bad = 1, -1;
    if (*p->s == '{') return j_list(p, J_OBJ, '}');
    if (*p->s == '[') return j_list(p, J_ARR, ']');
    if (*p->s == '"') {
        me = j_new(p, J_STR);
        if (j_string(p, &p->n[me].str, &p->n[me].len)) return -1;
        return me;
    }
    if (!strncmp(p->s, "true", 4) || !strncmp(p->s, "null", 4) || !strncmp(p->s, "false", 5)) {
        me = j_new(p, *p->s == 'n' ? J_NULL : J_BOOL);
        p->s += *p->s == 'f' ? 5 : 4;
        return me;
    }
    me = j_new(p, J_NUM);
    p->n[me].num = strtod(p->s, &end);
    if (end == p->s) return p->bad = 1, -1;
    p->s = end;
    return me;
}

static int j_get(const jparser *p, int obj, const char *key)
{
    int c;
    if (obj < 0 || p->n[obj].type != J_OBJ) return -1;
    for (c = p->n[obj].first; c >= 0; c = p->n[c].next)
        if ((int)strlen(key) == p->n[c].keylen &&
            !strncmp(p->n[c].key, key, (size_t)p->n[c].keylen))
            return c;
    return -1;
}

static int j_at(const jparser *p, int arr, int i)
{
    int c;
    if (arr < 0 || p->n[arr].type != J_ARR) return -1;
    for (c = p->n[arr].first; c >= 0 && i > 0; c = p->n[c].next) i--;
    return c;
}

static int j_count(const jparser *p, int arr)
{
    int c, n = 0;
    if (arr < 0) return 0;
    for (c = p->n[arr].first; c >= 0; c = p->n[c].next) n++;
    return n;
}

static double j_num(const jparser *p, int obj, const char *key, double def)
{
    int c = j_get(p, obj, key);
    return c >= 0 && p->n[c].type == J_NUM ? p->n[c].num : def;
}

static int j_str_is(const jparser *p, int node, const char *s)
{
    return node >= 0 && p->n[node].type == J_STR && (int)strlen(s) == p->n[node].len &&
           !strncmp(p->n[node].str, s, (size_t)p->n[node].len);
}

/* ---- reading a .glb back --------------------------------------------------------- */

typedef struct {
    unsigned char *file;
    size_t size;
    const unsigned char *bin;
    uint32_t binlen;
    jparser j;
    int root;
} glb;

static uint32_t u32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static float f32(const unsigned char *p)
{
    uint32_t u = u32(p);
    float f;
    memcpy(&f, &u, 4);
    return f;
}

/* The chunk layout: header, JSON chunk (4-aligned, spaces), optional BIN chunk. */
static void read_glb(const char *path, glb *g)
{
    FILE *f = fopen(path, "rb");
    uint32_t jlen;
    long n;
    memset(g, 0, sizeof *g);
    assert_non_null(f);
    fseek(f, 0, SEEK_END);
    n = ftell(f);
    rewind(f);
    assert_true(n >= 20);
    g->size = (size_t)n;
    g->file = malloc(g->size);
    assert_non_null(g->file);
    assert_int_equal(fread(g->file, 1, g->size, f), g->size);
    fclose(f);
    assert_int_equal(u32(g->file), 0x46546C67u);
    assert_int_equal(u32(g->file + 4), 2);
    assert_int_equal(u32(g->file + 8), g->size);
    jlen = u32(g->file + 12);
    assert_int_equal(u32(g->file + 16), 0x4E4F534Au);
    assert_int_equal(jlen % 4, 0);
    assert_true(20 + (size_t)jlen <= g->size);
    if (20 + (size_t)jlen < g->size) {
        const unsigned char *c = g->file + 20 + jlen;
        assert_true(20 + (size_t)jlen + 8 <= g->size);
        g->binlen = u32(c);
        assert_int_equal(u32(c + 4), 0x004E4942u);
        assert_int_equal(g->binlen % 4, 0);
        assert_int_equal(20 + (size_t)jlen + 8 + g->binlen, g->size);
        g->bin = c + 8;
    }
    g->j.s = (const char *)g->file + 20;
    g->j.end = g->j.s + jlen;
    g->root = j_value(&g->j);
    j_space(&g->j);
    assert_false(g->j.bad);
    assert_true(g->j.s == g->j.end); /* only padding spaces after the value */
}

static void free_glb(glb *g)
{
    free(g->file);
    free(g->j.n);
}

/* Every bufferView inside the buffer and 4-aligned; every accessor inside its view,
   exactly filling it; POSITION's min/max those of its data; indices below the vertex
   count. Returns the number of triangles. */
static int check_structure(const glb *g)
{
    const jparser *p = &g->j;
    int views = j_get(p, g->root, "bufferViews"), accs = j_get(p, g->root, "accessors");
    int meshes = j_get(p, g->root, "meshes"), buffers = j_get(p, g->root, "buffers");
    int i, m, tris = 0;
    double buflen = j_num(p, j_at(p, buffers, 0), "byteLength", 0);
    assert_true(buflen == g->binlen);
    for (i = 0; i < j_count(p, views); i++) {
        int v = j_at(p, views, i);
        double off = j_num(p, v, "byteOffset", 0), len = j_num(p, v, "byteLength", -1);
        assert_true(fmod(off, 4) == 0);
        assert_true(len > 0 && off + len <= buflen);
    }
    for (i = 0; i < j_count(p, accs); i++) {
        int a = j_at(p, accs, i), type = j_get(p, a, "type");
        int v = j_at(p, views, (int)j_num(p, a, "bufferView", -1));
        int ncomp = j_str_is(p, type, "SCALAR") ? 1 : j_str_is(p, type, "VEC2") ? 2 : 3;
        double count = j_num(p, a, "count", 0);
        assert_true(v >= 0 && count >= 1);
        assert_true(count * ncomp * 4 == j_num(p, v, "byteLength", -1));
    }
    for (m = 0; m < j_count(p, meshes); m++) {
        int prims = j_get(p, j_at(p, meshes, m), "primitives"), k;
        assert_true(j_count(p, prims) >= 1);
        for (k = 0; k < j_count(p, prims); k++) {
            int pr = j_at(p, prims, k), at = j_get(p, pr, "attributes");
            int pa = j_at(p, accs, (int)j_num(p, at, "POSITION", -1));
            int ia = j_at(p, accs, (int)j_num(p, pr, "indices", -1));
            int pv = j_at(p, views, (int)j_num(p, pa, "bufferView", -1));
            int iv = j_at(p, views, (int)j_num(p, ia, "bufferView", -1));
            int nv = (int)j_num(p, pa, "count", 0), ni = (int)j_num(p, ia, "count", 0), x, c;
            const unsigned char *pd = g->bin + (size_t)j_num(p, pv, "byteOffset", 0);
            const unsigned char *id = g->bin + (size_t)j_num(p, iv, "byteOffset", 0);
            float lo[3] = {HUGE_VALF, HUGE_VALF, HUGE_VALF},
                  hi[3] = {-HUGE_VALF, -HUGE_VALF, -HUGE_VALF};
            assert_true(pa >= 0 && ia >= 0 && nv >= 3 && ni % 3 == 0);
            assert_int_equal(j_num(p, ia, "componentType", 0), 5125);
            assert_int_equal(j_num(p, pr, "mode", 4), 4);
            for (x = 0; x < nv; x++)
                for (c = 0; c < 3; c++) {
                    float f = f32(pd + 12 * x + 4 * c);
                    lo[c] = f < lo[c] ? f : lo[c];
                    hi[c] = f > hi[c] ? f : hi[c];
                }
            for (c = 0; c < 3; c++) {
                assert_true((float)p->n[j_at(p, j_get(p, pa, "min"), c)].num ==
                            lo[c]); /* 9 digits: a float */
                assert_true((float)p->n[j_at(p, j_get(p, pa, "max"), c)].num == hi[c]);
            }
            for (x = 0; x < ni; x++) assert_true(u32(id + 4 * x) < (uint32_t)nv);
            tris += ni / 3;
        }
    }
    return tris;
}

/* Primitive PR's attribute NAME: its float data (3 a vertex for VEC3) and vertex count
   into *N; NULL if the primitive has none. */
static const unsigned char *attribute(const glb *g, int pr, const char *name, int *n)
{
    const jparser *p = &g->j;
    int a = j_at(p, j_get(p, g->root, "accessors"),
                 (int)j_num(p, j_get(p, pr, "attributes"), name, -1));
    int v = j_at(p, j_get(p, g->root, "bufferViews"), (int)j_num(p, a, "bufferView", -1));
    *n = (int)j_num(p, a, "count", 0);
    return a >= 0 && v >= 0 ? g->bin + (size_t)j_num(p, v, "byteOffset", 0) : NULL;
}

/* Every primitive of G: COLOR_0 in [0, 1] and, where below 1, COLOR_0 x colorScale (the
   extras of its material) = _LIGHT within float rounding (2^-23 relative, a division
   and two roundings to float: 4 ulps). Returns the largest _LIGHT value met. */
static double check_colours(const glb *g)
{
    const jparser *p = &g->j;
    int meshes = j_get(p, g->root, "meshes"), mats = j_get(p, g->root, "materials"), m, k, i;
    double top = 0;
    for (m = 0; m < j_count(p, meshes); m++) {
        int prims = j_get(p, j_at(p, meshes, m), "primitives");
        for (k = 0; k < j_count(p, prims); k++) {
            int pr = j_at(p, prims, k), nc = 0, nl = 0;
            int mat = j_at(p, mats, (int)j_num(p, pr, "material", -1));
            double scale = j_num(p, j_get(p, mat, "extras"), "colorScale", -1);
            const unsigned char *c = attribute(g, pr, "COLOR_0", &nc),
                                *l = attribute(g, pr, "_LIGHT", &nl);
            assert_non_null(c);
            assert_non_null(l);
            assert_int_equal(nc, nl);
            CHECK_THAT(scale >= 1, "material %d's colorScale %g, at least 1",
                       (int)j_num(p, pr, "material", -1), scale);
            for (i = 0; i < 3 * nc; i++) {
                double cv = f32(c + 4 * i), lv = f32(l + 4 * i);
                top = fmax(top, lv);
                CHECK_THAT(cv >= 0 && cv <= 1, "COLOR_0 value %d = %.9g, in [0, 1]", i, cv);
                if (cv < 1)
                    CHECK_THAT(fabs(cv * scale - lv) <= 4 * FLT_EPSILON * fmax(lv, 1e-30),
                               "COLOR_0 %.9g x colorScale %.9g = _LIGHT %.9g", cv, scale, lv);
                else
                    CHECK_THAT(lv >= scale * (1 - 4 * FLT_EPSILON),
                               "_LIGHT %.9g where COLOR_0 is 1: at least "
                               "the scale %.9g",
                               lv, scale);
            }
        }
    }
    return top;
}

/* ---- helpers: scenes -------------------------------------------------------------- */

static void write_text(const char *name, const char *text)
{
    FILE *f = fopen(tmp_path(name), "wb");
    assert_non_null(f);
    fputs(text, f);
    assert_int_equal(fclose(f), 0);
}

/* The OBJ NAME loaded into SC, its polygons into *POLYS (*N), solved with O to TOL in at
   most SHOTS shots. */
static sc_solver *solved(const char *name, obj_scene *sc, sc_poly **polys, int *n, const sc_opts *o,
                         int shots, double tol)
{
    char err[600];
    sc_solver *s;
    assert_int_equal(obj_load(tmp_path(name), sc, NULL, NULL, err, sizeof err), 0);
    *polys = polys_from_obj(sc, n, NULL, NULL);
    s = sc_create(*polys, *n, o, NULL, NULL, err, sizeof err);
    assert_non_null(s);
    sc_solve(s, shots, tol, NULL, NULL);
    return s;
}

static void collect(void *ctx, const char *msg)
{
    int *n = ctx;
    print_message("warning: %s\n", msg);
    (*n)++;
}

/* ---- tests ------------------------------------------------------------------------ */

/* Two objects, one with two groups; a cube without vn (flat: 24 welded vertices), a
   quad with shared vn (4), a pentagon (ear-clipped); names with a quote, a backslash
   and a byte that is not UTF-8. No solution: the writer alone, no COLOR_0. */
static void test_structure(void **state)
{
    obj_scene sc;
    char err[600];
    gltf_input in;
    glb g;
    int nodes, tris, i;
    (void)state;
    write_text("s.obj", "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n"
                        "v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
                        "vn 0 0 1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                        "o cube\ng side \"a\\b\xff\n"
                        "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\n"
                        "g other\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n"
                        "o quad\nf 5/1/1 6/2/1 7/3/1 8/4/1\n"
                        "f 1 2 3 7 8\n");
    assert_int_equal(obj_load(tmp_path("s.obj"), &sc, NULL, NULL, err, sizeof err), 0);
    memset(&in, 0, sizeof in);
    in.sc = &sc;
    assert_int_equal(gltf_write(tmp_path("s.glb"), &in, err, sizeof err), 0);
    read_glb(tmp_path("s.glb"), &g);
    tris = check_structure(&g);
    assert_int_equal(tris, 6 * 2 + 2 + 3);
    nodes = j_get(&g.j, g.root, "nodes");
    assert_int_equal(j_count(&g.j, nodes), 3);
    assert_true(j_str_is(&g.j, j_get(&g.j, j_at(&g.j, nodes, 0), "name"), "cube/side \\\"a\\\\b?"));
    assert_true(j_str_is(&g.j, j_get(&g.j, j_at(&g.j, nodes, 1), "name"), "cube/other"));
    /* o does not end the group: the quad is in quad/other */
    assert_true(j_str_is(&g.j, j_get(&g.j, j_at(&g.j, nodes, 2), "name"), "quad/other"));
    {
        const jparser *p = &g.j;
        int meshes = j_get(p, g.root, "meshes"), accs = j_get(p, g.root, "accessors");
        int want[3] = {12, 12, 4 + 5}; /* flat faces: 4 a face; the quad 4 + pentagon 5 */
        for (i = 0; i < 3; i++) {
            int pr = j_at(p, j_get(p, j_at(p, meshes, i), "primitives"), 0);
            int at = j_get(p, pr, "attributes");
            assert_int_equal(j_num(p, j_at(p, accs, (int)j_num(p, at, "POSITION", -1)), "count", 0),
                             want[i]);
            assert_int_equal(j_get(p, at, "COLOR_0"), -1);
            assert_true((j_get(p, at, "TEXCOORD_0") >= 0) == (i == 2));
        }
        assert_int_equal(j_count(p, j_get(p, g.root, "materials")), 1);
    }
    free_glb(&g);
    gltf_validates(tmp_path("s.glb"));
    assimp_reads(tmp_path("s.glb"));
    obj_free(&sc);
}

/* A closed box whose walls all emit E and reflect rho: B = E / (1 - rho) everywhere
   (the closed form of tools/reference) up to the hemi-cube's error per element;
   emitting faces carry B in _LIGHT, an area-weighted mean of elements' B, so every
   vertex's lies within the elements' range and near the closed form; COLOR_0 is it
   over the scale, in [0, 1] (check_colours). A textured lamp-lit room: the PNG
   texture embedded as it is, a TGA one re-encoded as PNG (test_bmp_texture checks the
   pixels), no warning. */
static void test_solution_colours(void **state)
{
    obj_scene sc;
    sc_poly *polys;
    sc_solver *s;
    sc_opts o = {.max_element = 0.25, .res = 64};
    char err[600];
    tex_image maps[4];
    glb g;
    int n, i, warnings = 0;
    double worst = 0;
    (void)state;
    write_text("box.mtl", "newmtl glow\nKd 0.5 0.5 0.5\nKe 1 2 3\n");
    write_text("box.obj", "mtllib box.mtl\nusemtl glow\n"
                          "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n"
                          "v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
                          "f 1 2 3 4\nf 8 7 6 5\nf 5 6 2 1\nf 6 7 3 2\nf 7 8 4 3\nf 8 5 1 4\n");
    s = solved("box.obj", &sc, &polys, &n, &o, 100000, 1e-5);
    assert_int_equal(sc_export_gltf(s, &sc, polys, n, NULL, NULL, tmp_path("box.glb"), NULL, NULL,
                                    err, sizeof err),
                     0);
    read_glb(tmp_path("box.glb"), &g);
    check_structure(&g);
    {
        const jparser *p = &g.j;
        int accs = j_get(p, g.root, "accessors"), views = j_get(p, g.root, "bufferViews");
        int pr = j_at(p, j_get(p, j_at(p, j_get(p, g.root, "meshes"), 0), "primitives"), 0);
        int ca = j_at(p, accs, (int)j_num(p, j_get(p, pr, "attributes"), "_LIGHT", -1));
        int cv = j_at(p, views, (int)j_num(p, ca, "bufferView", -1)),
            nv = (int)j_num(p, ca, "count", 0);
        const unsigned char *d = g.bin + (size_t)j_num(p, cv, "byteOffset", 0);
        const double want[3] = {1 / 0.5, 2 / 0.5, 3 / 0.5};
        double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {0, 0, 0}, b[3];
        sc_stats st;
        int e, k;
        sc_get_stats(s, &st);
        for (e = 0; e < st.elements; e++) {
            sc_element_rgb(s, e, 1, b);
            for (k = 0; k < 3; k++) {
                lo[k] = fmin(lo[k], b[k]);
                hi[k] = fmax(hi[k], b[k]);
            }
        }
        assert_true(ca >= 0 && nv == 24);
        for (i = 0; i < 3 * nv; i++) {
            double c = f32(d + 4 * i);
            worst = fmax(worst, fabs(c / want[i % 3] - 1));
            /* a mean of elements' values, stored as float (2^-24 relative) */
            assert_true(c >= lo[i % 3] * (1 - 1e-6) && c <= hi[i % 3] * (1 + 1e-6));
        }
        print_message("closed glowing box: _LIGHT against E / (1 - rho), worst %.3g%% (elements "
                      "%.4f to %.4f of %.1f)\n",
                      100 * worst, lo[0], hi[0], want[0]);
        /* The elements' own spread about the closed form is the hemi-cube's aliasing
           (docs/library.md: elements' form factors within 4.9% at res 512): measured -2.4% to
           +1.6% here at res 64, so 5% bounds it with the reason stated. */
        assert_true(worst <= 0.05);
        /* every face emits: the scale is the brightest channel, about 6 / (1 - 0.5) here,
           which a vertex of one corner stores as a float (2^-24 relative) */
        {
            double top = check_colours(&g),
                   scale = j_num(p, j_get(p, j_at(p, j_get(p, g.root, "materials"), 0), "extras"),
                                 "colorScale", -1);
            CHECK_NEAR(top, scale, scale * FLT_EPSILON,
                       "the brightest _LIGHT value against colorScale");
        }
        { /* an emitter's base colour is 1: COLOR_0 carries its radiosity */
            int f = j_get(
                p, j_get(p, j_at(p, j_get(p, g.root, "materials"), 0), "pbrMetallicRoughness"),
                "baseColorFactor");
            for (i = 0; i < 4; i++) assert_true(p->n[j_at(p, f, i)].num == 1);
        }
    }
    free_glb(&g);
    gltf_validates(tmp_path("box.glb"));
    sc_destroy(s);
    free(polys);
    obj_free(&sc);

    /* A room: textured walls (PNG, embedded), a TGA-textured floor (left out), a lamp. */
    {
        unsigned char rgb[4 * 2 * 3];
        for (i = 0; i < 24; i++) rgb[i] = (unsigned char)(40 + 9 * i);
        assert_int_equal(img_write(tmp_path("w.png"), rgb, 4, 2, NULL, 0), 0);
    }
    {
        /* an uncompressed 2x2 TGA */
        static const unsigned char tga[18 + 12] = {0,  0,  2,  0,  0,  0,  0,  0,  0,  0,
                                                   0,  0,  2,  0,  2,  0,  24, 0,  90, 90,
                                                   90, 90, 90, 90, 90, 90, 90, 90, 90, 90};
        FILE *f = fopen(tmp_path("floor.tga"), "wb");
        assert_non_null(f);
        fwrite(tga, 1, sizeof tga, f);
        fclose(f);
    }
    write_text("room.mtl", "newmtl walls\nKd 0 0 0\nmap_Kd w.png\n"
                           "newmtl floor\nKd 0 0 0\nmap_Kd floor.tga\n"
                           "newmtl lamp\nKd 0 0 0\nKe 5 5 5\n"
                           "newmtl tinted\nKd 0.5 0.9 0.9\nmap_Kd -clamp on w.png\n");
    write_text("room.obj", "mtllib room.mtl\n"
                           "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n"
                           "v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
                           "v -0.3 0.99 -0.3\nv 0.3 0.99 -0.3\nv 0.3 0.99 0.3\nv -0.3 0.99 0.3\n"
                           "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                           "o room\nusemtl walls\n"
                           "f 1/1 2/2 3/3 4/4\nf 8/1 7/2 6/3 5/4\nf 6/1 7/2 3/3 2/4\n"
                           "f 7/1 8/2 4/3 3/4\nusemtl tinted\nf 8/1 5/2 1/3 4/4\n"
                           "usemtl floor\nf 5/1 6/2 2/3 1/4\n"
                           "o lamp\nusemtl lamp\nf 9 10 11 12\n");
    assert_int_equal(obj_load(tmp_path("room.obj"), &sc, NULL, NULL, err, sizeof err), 0);
    assert_int_equal(tex_load_materials(&sc, maps, NULL, NULL, 1), 3);
    assert_int_equal(maps[3].borrowed, 1); /* w.png decoded once for two materials */
    assert_ptr_equal(maps[3].rgb, maps[0].rgb);
    assert_int_equal(maps[3].clamp, 1); /* with its own options */
    assert_int_equal(maps[0].clamp, 0);
    polys = polys_from_obj_tex(&sc, maps, &n, NULL, NULL);
    s = sc_create(polys, n, &o, NULL, NULL, err, sizeof err);
    assert_non_null(s);
    sc_solve(s, 100000, 1e-3, NULL, NULL);
    assert_int_equal(sc_export_gltf(s, &sc, polys, n, maps, NULL, tmp_path("room.glb"), collect,
                                    &warnings, err, sizeof err),
                     0);
    assert_int_equal(warnings, 0); /* the TGA is embedded too */
    read_glb(tmp_path("room.glb"), &g);
    assert_int_equal(check_structure(&g), 14);
    {
        const jparser *p = &g.j;
        int imgs = j_get(p, g.root, "images"), mats = j_get(p, g.root, "materials");
        int pbr0 = j_get(p, j_at(p, mats, 0), "pbrMetallicRoughness");
        int pbr1 = j_get(p, j_at(p, mats, 1), "pbrMetallicRoughness");
        assert_int_equal(j_count(p, imgs), 2); /* w.png once for two materials, the TGA */
        assert_int_equal(j_count(p, j_get(p, g.root, "textures")), 3);
        assert_int_equal(j_num(p, j_at(p, j_get(p, g.root, "samplers"), 2), "wrapS", 0), 33071);
        assert_true(j_str_is(p, j_get(p, j_at(p, imgs, 0), "mimeType"), "image/png"));
        assert_true(j_str_is(p, j_get(p, j_at(p, imgs, 1), "mimeType"), "image/png"));
        assert_true(j_get(p, pbr0, "baseColorTexture") >= 0);
        assert_true(j_get(p, pbr1, "baseColorTexture") >= 0);
        assert_true(j_get(p, j_get(p, j_at(p, mats, 2), "extensions"), "KHR_materials_unlit") >= 0);
        {
            /* The embedded image is the file, byte for byte. */
            int v = j_at(p, j_get(p, g.root, "bufferViews"),
                         (int)j_num(p, j_at(p, imgs, 0), "bufferView", -1));
            FILE *f = fopen(tmp_path("w.png"), "rb");
            unsigned char file[4096];
            size_t len = fread(file, 1, sizeof file, f);
            fclose(f);
            assert_int_equal(j_num(p, v, "byteLength", 0), len);
            assert_memory_equal(g.bin + (size_t)j_num(p, v, "byteOffset", 0), file, len);
        }
    }
    free_glb(&g);
    gltf_validates(tmp_path("room.glb"));
    assimp_reads(tmp_path("room.glb"));
    for (i = 0; i < sc.nmaterials; i++) tex_free(&maps[i]);
    sc_destroy(s);
    free(polys);
    obj_free(&sc);
}

/* Errors: an unwritable path is one line and no file. */
static void test_errors(void **state)
{
    obj_scene sc;
    gltf_input in;
    char err[600];
    (void)state;
    write_text("t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    assert_int_equal(obj_load(tmp_path("t.obj"), &sc, NULL, NULL, err, sizeof err), 0);
    memset(&in, 0, sizeof in);
    in.sc = &sc;
    assert_int_equal(gltf_write(tmp_path("no/such/folder/t.glb"), &in, err, sizeof err), -1);
    print_message("%s\n", err);
    assert_non_null(strstr(err, "no/such/folder"));
    assert_null(strchr(err, '\n'));
    obj_free(&sc);
}

/* rad_cli: --export-gltf writes a .glb the checks above accept; textures colour the
   view by default and --no-textures switches them off (a different image, and a
   Kd 0 textured material shown grey, not black). Run from the repository root. */
static double mean_of(const char *png)
{
    img_t im;
    char err[600];
    double sum = 0;
    size_t i, n;
    assert_int_equal(img_read(png, &im, err, sizeof err), 0);
    n = (size_t)im.w * im.h * 3;
    for (i = 0; i < n; i++) sum += im.rgb[i];
    img_free(&im);
    return sum / n;
}

static void test_cli(void **state)
{
    static const unsigned char check[4 * 4 * 3] = {
        250, 30,  30,  250, 250, 250, 250, 30,  30,  250, 250, 250, 250, 250, 250, 250,
        30,  30,  250, 250, 250, 250, 30,  30,  250, 30,  30,  250, 250, 250, 250, 30,
        30,  250, 250, 250, 250, 250, 250, 250, 30,  30,  250, 250, 250, 250, 30,  30};
    char cmd[2048];
    glb g;
    int rc;
    (void)state;
    assert_int_equal(img_write(tmp_path("c.png"), check, 4, 4, NULL, 0), 0);
    write_text("c.mtl", "newmtl walls\nKd 0 0 0\nmap_Kd c.png\nnewmtl lamp\nKd 0 0 0\nKe 9 9 9\n");
    write_text("c.obj", "mtllib c.mtl\n"
                        "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n"
                        "v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
                        "v -0.3 0.99 -0.3\nv 0.3 0.99 -0.3\nv 0.3 0.99 0.3\nv -0.3 0.99 0.3\n"
                        "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                        "usemtl walls\nf 1/1 2/2 3/3 4/4\nf 6/1 7/2 3/3 2/4\nf 8/1 5/2 1/3 4/4\n"
                        "f 7/1 8/2 4/3 3/4\nf 5/1 6/2 2/3 1/4\n"
                        "usemtl lamp\nf 12 11 10 9\n");
    snprintf(cmd, sizeof cmd,
             "build/rad_cli '%s' --camera 0,0,0.99,0,0,-1,70 -o '%s' --width 64 "
             "--height 64 --export-gltf '%s' --quiet",
             tmp_path("c.obj"), tmp_path("c_tex.png"), tmp_path("c.glb"));
    rc = system(cmd);
    assert_int_equal(rc, 0);
    snprintf(cmd, sizeof cmd,
             "build/rad_cli '%s' --camera 0,0,0.99,0,0,-1,70 -o '%s' --width 64 "
             "--height 64 --no-textures --quiet",
             tmp_path("c.obj"), tmp_path("c_plain.png"));
    rc = system(cmd);
    assert_int_equal(rc, 0);
    read_glb(tmp_path("c.glb"), &g);
    assert_int_equal(check_structure(&g), 12);
    assert_int_equal(j_count(&g.j, j_get(&g.j, g.root, "images")), 1);
    free_glb(&g);
    gltf_validates(tmp_path("c.glb"));
    assimp_reads(tmp_path("c.glb"));
    {
        double t = mean_of(tmp_path("c_tex.png")), p = mean_of(tmp_path("c_plain.png"));
        print_message("mean pixel: textured %.1f, --no-textures %.1f\n", t, p);
        assert_true(p > 20); /* Kd 0 beside map_Kd: 0.5 grey, not black */
        assert_true(fabs(t - p) > 1);
    }
}

/* ---- the lightmap in the .glb ------------------------------------------------------ */

static int lm_gather_cb(void *ctx, const double p[3], const double n[3], double rgb[3])
{
    return sc_gather(ctx, p, n, 1, rgb);
}

/* sRGB code C (0..255) back to linear. */
static double srgb_decode8(int c)
{
    double v = c / 255.0;
    return v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4);
}

/* The decoded image IM bilinearly at atlas position XY (texel centres at half-integers,
   clamped at the border, as lm_lookup and a GPU's CLAMP_TO_EDGE LINEAR), times SCALE. */
static void image_lookup(const img_t *im, const double xy[2], double scale, double rgb[3])
{
    double fx = xy[0] - 0.5, fy = xy[1] - 0.5, x0 = floor(fx), y0 = floor(fy);
    int dx, dy, k;
    rgb[0] = rgb[1] = rgb[2] = 0;
    for (dy = 0; dy < 2; dy++)
        for (dx = 0; dx < 2; dx++) {
            double w = (dx ? fx - x0 : 1 - (fx - x0)) * (dy ? fy - y0 : 1 - (fy - y0));
            int x = (int)fmin(fmax(x0 + dx, 0), im->w - 1),
                y = (int)fmin(fmax(y0 + dy, 0), im->h - 1);
            for (k = 0; k < 3; k++)
                rgb[k] += w * scale * srgb_decode8(im->rgb[3 * ((size_t)y * im->w + x) + k]);
        }
}

/* The embedded image I (PNG) decoded into IM through a file of its own. */
static void embedded_image(const glb *g, int i, img_t *im)
{
    const jparser *p = &g->j;
    int img = j_at(p, j_get(p, g->root, "images"), i);
    int v = j_at(p, j_get(p, g->root, "bufferViews"), (int)j_num(p, img, "bufferView", -1));
    char err[600];
    FILE *f = fopen(tmp_path("lm_embedded.png"), "wb");
    assert_true(img >= 0 && v >= 0 && f);
    assert_true(j_str_is(p, j_get(p, img, "mimeType"), "image/png"));
    assert_int_equal(fwrite(g->bin + (size_t)j_num(p, v, "byteOffset", 0), 1,
                            (size_t)j_num(p, v, "byteLength", 0), f),
                     (size_t)j_num(p, v, "byteLength", 0));
    assert_int_equal(fclose(f), 0);
    assert_int_equal(img_read(tmp_path("lm_embedded.png"), im, err, sizeof err), 0);
}

/* Blender (Debian blender), when installed, imports PATH with its own glTF importer
   and shows the image "lightmap" on the second UV map through the Emission of MATERIALS
   materials, at an Emission Strength of SCALE (tests/blender_lightmap.py); skipped
   with a message when it is not installed. */
static void blender_shows_lightmap(const char *path, int materials, double scale)
{
    char cmd[1200], line[256] = "";
    FILE *f;
    int n = -1;
    double strength = -1;
    if (system("command -v blender >/dev/null 2>&1") != 0) {
        print_message("blender not installed (Debian blender): its import check skipped\n");
        return;
    }
    snprintf(cmd, sizeof cmd,
             "blender -b --factory-startup --python-exit-code 1 --python "
             "tests/blender_lightmap.py -- '%s' > '%s' 2>&1",
             path, tmp_path("blender.txt"));
    if (system(cmd) != 0) {
        snprintf(cmd, sizeof cmd, "cat '%s' >&2", tmp_path("blender.txt"));
        if (system(cmd)) {}
        fail_msg("blender could not import %s", path);
    }
    f = fopen(tmp_path("blender.txt"), "rb");
    assert_non_null(f);
    while (fgets(line, sizeof line, f))
        if (sscanf(line, "lightmap: %d %lf", &n, &strength) == 2) break;
    fclose(f);
    print_message("blender: %d materials show the lightmap as emission, strength %.6g\n", n,
                  strength);
    CHECK_INT_EQ(n, materials, "materials blender shows the lightmap on (emission, second UV map)");
    /* the script rounds to 5 decimals; Blender keeps a float */
    CHECK_NEAR(strength, scale, 1e-5 + scale * FLT_EPSILON,
               "blender's Emission Strength against the scale");
}

/* A lit room with a block (12 charts) baked into a 64 x 64 atlas and exported with it:
   every primitive has TEXCOORD_1 with one UV per vertex, inside [0, 1] and within its
   accessor's min and max; every material that does not emit names the lightmap in its
   extras (texCoord 1, the scale); and the embedded PNG, bilinearly sampled at each
   vertex's TEXCOORD_1, gives the light the atlas holds there (lm_lookup) within the
   8-bit quantisation: half a code's step of the sRGB curve at its steepest (2.4 / 1.055
   per unit at 1) times the scale, which the bilinear weights (summing to 1) keep.
   The block's faces share one vn, so without TEXCOORD_1 its corners would weld into 8
   vertices; each face is a chart of its own, so they stay 20. assimp reads the file. */
static void test_lightmap(void **state)
{
    obj_scene sc;
    sc_poly *polys;
    sc_solver *s;
    sc_gatherer *gt;
    sc_opts o = {.max_element = 0.25, .res = 32};
    lm_opts lo = {64, 0, 0, LM_TOL, 0};
    lm_atlas a;
    char err[600];
    img_t im;
    glb g;
    int n, m, k, checked = 0;
    double worst = 0, bound, scale = -1;
    (void)state;
    write_text("lm.mtl", "newmtl wall\nKd 0.6 0.5 0.4\nnewmtl red\nKd 0.7 0.1 0.1\n"
                         "newmtl lamp\nKd 0.5 0.5 0.5\nKe 8 8 8\n");
    write_text("lm.obj",
               "mtllib lm.mtl\n"
               "v -1 0 -1\nv 1 0 -1\nv 1 2 -1\nv -1 2 -1\n"
               "v -1 0 1\nv 1 0 1\nv 1 2 1\nv -1 2 1\n"
               "v -0.3 1.99 -0.3\nv 0.3 1.99 -0.3\nv 0.3 1.99 0.3\nv -0.3 1.99 0.3\n"
               "v -0.5 0 -0.5\nv 0 0 -0.5\nv 0 0.5 -0.5\nv -0.5 0.5 -0.5\n"
               "v -0.5 0 0\nv 0 0 0\nv 0 0.5 0\nv -0.5 0.5 0\nvn 0 1 0\n"
               "usemtl wall\no room\nf 1 5 6 2\nf 1 2 3 4\nf 5 8 7 6\nf 1 4 8 5\nf 2 6 7 3\n"
               "f 4 3 7 8\n"
               "usemtl lamp\no lamp\nf 9 10 11 12\n"
               "usemtl red\no block\nf 20//1 19//1 15//1 16//1\nf 13//1 16//1 15//1 14//1\n"
               "f 17//1 18//1 19//1 20//1\nf 13//1 17//1 20//1 16//1\nf 14//1 15//1 19//1 18//1\n");
    s = solved("lm.obj", &sc, &polys, &n, &o, 100000, 1e-3);
    gt = sc_gatherer_new(s, 16, 0);
    assert_non_null(gt);
    assert_int_equal(lm_build(&a, polys, n, &lo, err, sizeof err), 0);
    assert_int_equal(lm_bake(&a, lm_gather_cb, NULL, gt), 0);
    assert_int_equal(sc_export_gltf_lightmap(s, &sc, polys, n, NULL, NULL, &a, NULL,
                                             tmp_path("lm.glb"), NULL, NULL, NULL, NULL, err,
                                             sizeof err),
                     0);
    read_glb(tmp_path("lm.glb"), &g);
    check_structure(&g);
    embedded_image(&g, 0, &im); /* the lightmap's */
    assert_int_equal(im.w, 64);
    assert_int_equal(im.h, 64);
    {
        const jparser *p = &g.j;
        int meshes = j_get(p, g.root, "meshes"), accs = j_get(p, g.root, "accessors");
        int views = j_get(p, g.root, "bufferViews"), mats = j_get(p, g.root, "materials");
        for (m = 0; m < j_count(p, mats); m++) {
            int lm = j_get(p, j_get(p, j_at(p, mats, m), "extras"), "lightmap");
            int lamp = m == 2; /* materials in MTL order: wall, red, lamp */
            assert_true((lm >= 0) == !lamp);
            if (lm < 0) continue;
            assert_int_equal(j_num(p, lm, "texCoord", -1), 1);
            assert_int_equal(j_num(p, lm, "index", -1), 0);
            scale = j_num(p, lm, "scale", -1);
            { /* where importers look: emissive = lightmap x Kd x scale on a black base */
                static const double kd[2][3] = {{0.6, 0.5, 0.4}, {0.7, 0.1, 0.1}};
                int mat = j_at(p, mats, m), et = j_get(p, mat, "emissiveTexture");
                int ef = j_get(p, mat, "emissiveFactor"), ext = j_get(p, mat, "extensions");
                int bc = j_get(p, j_get(p, mat, "pbrMetallicRoughness"), "baseColorFactor");
                assert_int_equal(j_num(p, et, "index", -1), 0);
                assert_int_equal(j_num(p, et, "texCoord", -1), 1);
                assert_int_equal(j_get(p, ext, "KHR_materials_unlit"), -1);
                CHECK_EQ(j_num(p, j_get(p, ext, "KHR_materials_emissive_strength"),
                               "emissiveStrength", -1),
                         scale, "material %d: emissiveStrength against the lightmap's scale", m);
                for (k = 0; k < 3; k++) {
                    CHECK_EQ(p->n[j_at(p, bc, k)].num, 0, "material %d: baseColorFactor[%d]", m, k);
                    CHECK_NEAR(p->n[j_at(p, ef, k)].num, kd[m][k], 1e-9,
                               "material %d: emissiveFactor[%d], Kd", m, k);
                }
            }
        }
        {
            int used = j_get(p, g.root, "extensionsUsed");
            assert_int_equal(j_count(p, used), 2); /* the lamp stays unlit */
            assert_true(j_str_is(p, j_at(p, used, 0), "KHR_materials_unlit"));
            assert_true(j_str_is(p, j_at(p, used, 1), "KHR_materials_emissive_strength"));
            assert_true(j_get(p, j_get(p, j_at(p, mats, 2), "extensions"), "KHR_materials_unlit") >=
                        0);
            assert_int_equal(j_get(p, j_at(p, mats, 2), "emissiveTexture"), -1);
        }
        assert_true(scale > 0);
        bound = scale * 0.5 * (2.4 / 1.055) / 255;
        for (m = 0; m < j_count(p, meshes); m++) {
            int pr = j_at(p, j_get(p, j_at(p, meshes, m), "primitives"), 0),
                at = j_get(p, pr, "attributes");
            int ua = j_at(p, accs, (int)j_num(p, at, "TEXCOORD_1", -1));
            int pa = j_at(p, accs, (int)j_num(p, at, "POSITION", -1));
            int uv = j_at(p, views, (int)j_num(p, ua, "bufferView", -1)),
                nv = (int)j_num(p, ua, "count", 0), x;
            const unsigned char *d = g.bin + (size_t)j_num(p, uv, "byteOffset", 0);
            assert_true(ua >= 0 && uv >= 0);
            assert_int_equal(nv, (int)j_num(p, pa, "count", -1));
            for (x = 0; x < nv; x++) {
                double xy[2], want[3], got[3];
                for (k = 0; k < 2; k++) {
                    float f = f32(d + 8 * x + 4 * k);
                    assert_true(f >= 0 && f <= 1);
                    assert_true(f >= (float)p->n[j_at(p, j_get(p, ua, "min"), k)].num);
                    assert_true(f <= (float)p->n[j_at(p, j_get(p, ua, "max"), k)].num);
                    xy[k] = f * 64.0;
                }
                lm_lookup(&a, xy, want);
                image_lookup(&im, xy, scale, got);
                for (k = 0; k < 3; k++) worst = fmax(worst, fabs(got[k] - want[k]));
                checked++;
            }
        }
        /* the room's 6 faces, the lamp, the block's 5: 4 corners each, none welded */
        assert_int_equal(checked, 6 * 4 + 4 + 5 * 4);
    }
    print_message("lightmap in the glb: %d vertices, scale %.4g, largest difference %.3g "
                  "(bound %.3g: half an sRGB code at its steepest)\n",
                  checked, scale, worst, bound);
    assert_true(worst <= bound);
    img_free(&im);
    free_glb(&g);
    gltf_validates(tmp_path("lm.glb"));
    assimp_reads(tmp_path("lm.glb"));
    blender_shows_lightmap(tmp_path("lm.glb"), 2, scale);
    lm_free(&a);
    sc_gatherer_free(gt);
    sc_destroy(s);
    free(polys);
    obj_free(&sc);
}

/* ---- cost: linear in the elements --------------------------------------------- */

/* NAME: a floor of N x N unit-grid quads (one element each at max_element 2) under a
   lamp. */
static void write_grid(const char *name, int n)
{
    FILE *f = fopen(tmp_path(name), "wb");
    int i, j;
    assert_non_null(f);
    fprintf(f, "mtllib grid.mtl\n");
    for (j = 0; j <= n; j++)
        for (i = 0; i <= n; i++) fprintf(f, "v %g 0 %g\n", 4.0 * i / n - 2, 2 - 4.0 * j / n);
    fprintf(f, "usemtl floor\n");
    for (j = 0; j < n; j++)
        for (i = 0; i < n; i++) {
            int a = j * (n + 1) + i + 1;
            fprintf(f, "f %d %d %d %d\n", a, a + 1, a + n + 2, a + n + 1);
        }
    fprintf(f,
            "v -0.5 2 -0.5\nv 0.5 2 -0.5\nv 0.5 2 0.5\nv -0.5 2 0.5\nusemtl lamp\n"
            "f %d %d %d %d\n",
            (n + 1) * (n + 1) + 1, (n + 1) * (n + 1) + 2, (n + 1) * (n + 1) + 3,
            (n + 1) * (n + 1) + 4);
    assert_int_equal(fclose(f), 0);
}

/* One build of the glue (sc_ fixed, scf_ the float twin) behind one set of calls. */
typedef struct {
    const char *name;
    void *(*create)(const sc_poly *polys, int n, const sc_opts *o);
    void (*destroy)(void *s);
    void (*stats)(void *s, sc_stats *st);
    int (*export_glb)(void *s, const obj_scene *sc, const sc_poly *polys, int n, const char *path);
    int (*shade_all)(void *s, double *rgb);
    void (*shade_one)(void *s, int e, double rgb[3]);
} twin_ops;

static void *fx_create(const sc_poly *p, int n, const sc_opts *o)
{
    sc_solver *s = sc_create(p, n, o, NULL, NULL, NULL, 0);
    if (s) sc_solve(s, 20, 1e-3, NULL, NULL);
    return s;
}
static void fx_destroy(void *s)
{
    sc_destroy(s);
}
static void fx_stats(void *s, sc_stats *st)
{
    sc_get_stats(s, st);
}
static int fx_export(void *s, const obj_scene *sc, const sc_poly *p, int n, const char *path)
{
    return sc_export_gltf(s, sc, p, n, NULL, NULL, path, NULL, NULL, NULL, 0);
}
static int fx_all(void *s, double *rgb)
{
    return sc_shade_elements(s, 1, rgb);
}
static void fx_one(void *s, int e, double rgb[3])
{
    sc_element_rgb(s, e, 1, rgb);
}
static void *fl_create(const sc_poly *p, int n, const sc_opts *o)
{
    scf_solver *s = scf_create(p, n, o, NULL, NULL, NULL, 0);
    if (s) scf_solve(s, 20, 1e-3, NULL, NULL);
    return s;
}
static void fl_destroy(void *s)
{
    scf_destroy(s);
}
static void fl_stats(void *s, sc_stats *st)
{
    scf_get_stats(s, st);
}
static int fl_export(void *s, const obj_scene *sc, const sc_poly *p, int n, const char *path)
{
    return scf_export_gltf(s, sc, p, n, NULL, NULL, path, NULL, NULL, NULL, 0);
}
static int fl_all(void *s, double *rgb)
{
    return scf_shade_elements(s, 1, rgb);
}
static void fl_one(void *s, int e, double rgb[3])
{
    scf_element_rgb(s, e, 1, rgb);
}

/* The export's cost: the ambient term (a pass over every patch) is computed once per
   export, not once per corner, so the export of a grid of 4N faces makes as many core
   passes as one of N (a quadratic export made one per face corner: 4 x 65 and
   4 x 257 here). Counted, not timed: sc_stats.ambient_terms counts the core calls
   that compute it. sc_shade_elements, which the export uses, gives sc_element_rgb's
   values bit for bit; in both builds of the glue. */
static void test_linear_export(void **state)
{
    static const int sides[2] = {8, 16};
    static const twin_ops twins[2] = {
        {"fixed", fx_create, fx_destroy, fx_stats, fx_export, fx_all, fx_one},
        {"float", fl_create, fl_destroy, fl_stats, fl_export, fl_all, fl_one}};
    int t, b;
    (void)state;
    write_text("grid.mtl", "newmtl floor\nKd 0.6 0.6 0.6\nnewmtl lamp\nKd 0 0 0\nKe 40 40 40\n");
    for (t = 0; t < 2; t++)
        for (b = 0; b < 2; b++) {
            const twin_ops *w = &twins[b];
            obj_scene sc;
            sc_poly *polys;
            sc_opts o = {.max_element = 2, .max_patch = 2, .res = 32};
            sc_stats st;
            char err[600], name[32];
            double *rgb;
            unsigned long before;
            int n, e, k;
            void *s;
            snprintf(name, sizeof name, "grid%d.obj", sides[t]);
            write_grid(name, sides[t]);
            assert_int_equal(obj_load(tmp_path(name), &sc, NULL, NULL, err, sizeof err), 0);
            polys = polys_from_obj(&sc, &n, NULL, NULL);
            s = w->create(polys, n, &o);
            assert_non_null(s);
            w->stats(s, &st);
            assert_int_equal(st.elements, sides[t] * sides[t] + 1);
            before = st.ambient_terms;
            assert_int_equal(w->export_glb(s, &sc, polys, n, tmp_path("grid.glb")), 0);
            w->stats(s, &st);
            print_message(
                "%s export of %d elements: the ambient term computed %lu times (bound 1)\n",
                w->name, st.elements, st.ambient_terms - before);
            assert_int_equal(st.ambient_terms - before, 1);
            gltf_validates(tmp_path("grid.glb"));
            rgb = malloc(3 * (size_t)st.elements * sizeof *rgb);
            assert_non_null(rgb);
            assert_int_equal(w->shade_all(s, rgb), 0);
            for (e = 0; e < st.elements; e++) {
                double one[3];
                w->shade_one(s, e, one);
                for (k = 0; k < 3; k++) assert_true(one[k] == rgb[3 * e + k]);
            }
            free(rgb);
            w->destroy(s);
            free(polys);
            obj_free(&sc);
        }
}

/* The corners' search (sorted vertices, gltf_export.c's face_search) finds what a scan
   of every element of the face finds: on a 40-gon floor meshed into hundreds of
   elements under a lamp, each corner's light is the area-weighted mean, over the
   face's elements with a vertex within 1e-5 of the extent of it, of their radiosity
   over their reflectance (the rule in gltf_export.h), computed here by that scan, to
   the last bit (the same terms summed in the same element order). */
static void test_corner_search(void **state)
{
    obj_scene sc;
    sc_poly *polys;
    sc_solver *s;
    sc_opts o = {.max_element = 0.3, .res = 32};
    sc_stats st;
    char text[4096];
    double *rgb, *weight, tol;
    size_t at;
    int n, c, e, k, matched = 0, most = 0;
    (void)state;
    at = (size_t)snprintf(text, sizeof text, "mtllib grid.mtl\n");
    for (c = 0; c < 40; c++)
        at += (size_t)snprintf(text + at, sizeof text - at, "v %.6f 0 %.6f\n",
                               2 * cos(c * 6.283185307179586 / 40),
                               -2 * sin(c * 6.283185307179586 / 40));
    at += (size_t)snprintf(text + at, sizeof text - at,
                           "v -0.5 2 -0.5\nv 0.5 2 -0.5\nv 0.5 2 0.5\nv -0.5 2 0.5\n"
                           "usemtl floor\nf");
    for (c = 0; c < 40; c++) at += (size_t)snprintf(text + at, sizeof text - at, " %d", c + 1);
    snprintf(text + at, sizeof text - at, "\nusemtl lamp\nf 41 42 43 44\n");
    write_text("grid.mtl", "newmtl floor\nKd 0.6 0.6 0.6\nnewmtl lamp\nKd 0 0 0\nKe 40 40 40\n");
    write_text("ngon.obj", text);
    s = solved("ngon.obj", &sc, &polys, &n, &o, 200, 1e-3);
    sc_get_stats(s, &st);
    rgb = malloc(3 * (size_t)sc.nindices * sizeof *rgb);
    weight = malloc((size_t)sc.nindices * sizeof *weight);
    assert_true(rgb && weight);
    assert_int_equal(sc_corner_light(s, &sc, polys, n, rgb, weight), 0);
    tol = 1e-5 * 4; /* the floor's extent, 4 across */
    for (c = 0; c < sc.faces[0].count; c++) {
        const obj_vec3 *p = &sc.verts[sc.indices[sc.faces[0].first + c]];
        double sum[3] = {0, 0, 0}, area = 0;
        int hits = 0;
        for (e = 0; e < st.elements; e++) {
            int v[4], nv, j, near = 0;
            double b[3], rho[3], a;
            if (sc_element_tag(s, e) != 0) continue;
            nv = sc_element_vertices(s, e, v);
            for (j = 0; j < nv; j++) {
                double q[3];
                sc_vertex_pos(s, v[j], q);
                near |= (q[0] - p->x) * (q[0] - p->x) + (q[1] - p->y) * (q[1] - p->y) +
                            (q[2] - p->z) * (q[2] - p->z) <=
                        tol * tol;
            }
            if (!near) continue;
            sc_element_rgb(s, e, 1, b);
            sc_element_rho(s, e, rho);
            a = sc_element_area(s, e);
            for (k = 0; k < 3; k++) sum[k] += a * (rho[k] > 0 ? b[k] / rho[k] : 0);
            area += a;
            hits++;
        }
        CHECK_INT_GE(hits, 1, "corner %d of the 40-gon: elements with a vertex there", c);
        most = hits > most ? hits : most;
        for (k = 0; k < 3; k++)
            CHECK_THAT(rgb[3 * (sc.faces[0].first + c) + k] == sum[k] / area,
                       "corner %d channel %d: %.17g, the scan's %.17g", c, k,
                       rgb[3 * (sc.faces[0].first + c) + k], sum[k] / area);
        CHECK_THAT(weight[sc.faces[0].first + c] == area,
                   "corner %d: weight %.17g, the scan's %.17g", c, weight[sc.faces[0].first + c],
                   area);
        matched++;
    }
    print_message(
        "40-gon of %d elements: %d corners as the scan finds them (up to %d elements a corner)\n",
        st.elements, matched, most);
    free(rgb);
    free(weight);
    sc_destroy(s);
    free(polys);
    obj_free(&sc);
}

/* rad_cli --stats times the exports and counts the ambient terms they had computed:
   one each (--dump-radiosity and --export-gltf) for N and for 4N faces. */
static void test_cli_export_stats(void **state)
{
    static const int sides[2] = {8, 16};
    char cmd[2048], *out, *line;
    int t;
    (void)state;
    write_text("grid.mtl", "newmtl floor\nKd 0.6 0.6 0.6\nnewmtl lamp\nKd 0 0 0\nKe 40 40 40\n");
    for (t = 0; t < 2; t++) {
        FILE *f;
        double tc = -1, tg = -1, scale = 0;
        unsigned long terms = 0;
        glb g;
        long len;
        char name[32];
        snprintf(name, sizeof name, "cgrid%d.obj", sides[t]);
        write_grid(name, sides[t]);
        snprintf(cmd, sizeof cmd,
                 "build/rad_cli '%s' --quiet --stats --res 32 --max-element 2 --max-patch 2 "
                 "--width 16 --height 16 -o '%s' --dump-radiosity '%s' --export-gltf '%s' > '%s'",
                 tmp_path(name), tmp_path("cgrid.png"), tmp_path("cgrid.csv"),
                 tmp_path("cgrid.glb"), tmp_path("cgrid.txt"));
        assert_int_equal(system(cmd), 0);
        f = fopen(tmp_path("cgrid.txt"), "rb");
        assert_non_null(f);
        fseek(f, 0, SEEK_END);
        len = ftell(f);
        rewind(f);
        out = calloc((size_t)len + 1, 1);
        assert_non_null(out);
        assert_int_equal(fread(out, 1, (size_t)len, f), (size_t)len);
        fclose(f);
        line = strstr(out, "\nexports:");
        if (!line ||
            sscanf(line, "\nexports:  COLOR_0 scale %lf  ambient term computed %lu", &scale,
                   &terms) != 2 ||
            !(line = strstr(out, "\ntime:")) || !strstr(line, "  csv ") ||
            sscanf(strstr(line, "  csv "), "  csv %lfs", &tc) != 1 || !strstr(line, "  gltf ") ||
            sscanf(strstr(line, "  gltf "), "  gltf %lfs", &tg) != 1)
            fail_msg("no exports line, or no csv and gltf times, in rad_cli --stats:\n%s", out);
        print_message("rad_cli, %d faces: dump-radiosity %.3fs, export-gltf %.3fs (COLOR_0 scale "
                      "%g), ambient "
                      "term computed %lu times (bound 2)\n",
                      sides[t] * sides[t] + 1, tc, tg, scale, terms);
        assert_true(tc >= 0 && tg >= 0);
        assert_int_equal(terms, 2);
        /* --stats gives the scale the file's materials carry */
        read_glb(tmp_path("cgrid.glb"), &g);
        { /* --stats prints 6 digits: within half a unit of the 6th */
            double want =
                j_num(&g.j, j_get(&g.j, j_at(&g.j, j_get(&g.j, g.root, "materials"), 0), "extras"),
                      "colorScale", -1);
            CHECK_THAT(want > 1, "a lamp of 40 lights the floor above 1: colorScale %g", want);
            CHECK_NEAR(scale, want, 5e-6 * want,
                       "--stats' COLOR_0 scale against the file's colorScale");
        }
        check_colours(&g);
        free_glb(&g);
        gltf_validates(tmp_path("cgrid.glb"));
        free(out);
    }
}

/* ---- the validator catches broken files --------------------------------------- */

/* Broken files and what the validator must say of each (gltf_refused). */
typedef struct {
    char path[16][600];
    const char *path_of[16], *what[16];
    int n;
} breaks;

/* G's file with N bytes at AT replaced by BYTES, written to NAME, which the validator
   must refuse naming WHAT: added to B. */
static void broken(breaks *b, const glb *g, const char *name, size_t at, const void *bytes,
                   size_t n, const char *what)
{
    unsigned char *d = malloc(g->size);
    FILE *f = fopen(tmp_path(name), "wb");
    assert_true(d && f && at + n <= g->size);
    memcpy(d, g->file, g->size);
    memcpy(d + at, bytes, n);
    assert_int_equal(fwrite(d, 1, g->size, f), g->size);
    assert_int_equal(fclose(f), 0);
    free(d);
    assert_true(b->n < 16);
    snprintf(b->path[b->n], sizeof b->path[0], "%s", tmp_path(name));
    b->path_of[b->n] = b->path[b->n];
    b->what[b->n++] = what;
}

/* Where TEXT first occurs in G's JSON chunk, as a file offset. */
static size_t json_at(const glb *g, const char *text)
{
    size_t i, n = strlen(text), end = 20 + u32(g->file + 12);
    for (i = 20; i + n <= end; i++)
        if (!memcmp(g->file + i, text, n)) return i;
    fail_msg("'%s' not in the JSON", text);
    return 0;
}

/* tests/gltf_validate.py passes the files the writer makes (every test above) and
   refuses each of them broken in one way: the header, a chunk, an index, a value. */
static void test_validator(void **state)
{
    static const float two = 2.0f, far = 1e6f;
    static const unsigned char big[4] = {0x00, 0xff, 0xff, 0xff};
    obj_scene sc;
    sc_poly *polys;
    sc_solver *s;
    sc_opts o = {.max_element = 0.5, .res = 32};
    char err[600];
    glb g;
    int n, nv;
    size_t at;
    const unsigned char *d;
    (void)state;
    static breaks b;
    const char *null = "/dev/null";
    if (gltf_validator(&null, 1) < 0) skip();
    b.n = 0;
    write_text("v.mtl", "newmtl wall\nKd 0.5 0.5 0.5\nnewmtl lamp\nKd 0 0 0\nKe 9 9 9\n");
    write_text("v.obj", "mtllib v.mtl\nv -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\n"
                        "v -0.2 1 -0.2\nv 0.2 1 -0.2\nv 0.2 1 0.2\nv -0.2 1 0.2\n"
                        "usemtl wall\nf 4 3 2 1\nusemtl lamp\nf 5 6 7 8\n");
    s = solved("v.obj", &sc, &polys, &n, &o, 1000, 1e-3);
    assert_int_equal(sc_export_gltf(s, &sc, polys, n, NULL, NULL, tmp_path("v.glb"), NULL, NULL,
                                    err, sizeof err),
                     0);
    gltf_validates(tmp_path("v.glb"));
    read_glb(tmp_path("v.glb"), &g);
    broken(&b, &g, "magic.glb", 0, "gltf", 4, "bad magic");
    broken(&b, &g, "version.glb", 4, "\1\0\0\0", 4, "GLB version 1");
    broken(&b, &g, "length.glb", 8, "\0\0\0\0", 4, "header length 0");
    broken(&b, &g, "chunk.glb", 16, "BIN\0", 4, "the first chunk is not JSON");
    broken(&b, &g, "chunklen.glb", 12, "\1\0\0\0", 4, "not a multiple of 4");
    broken(&b, &g, "mode.glb", json_at(&g, "\"mode\":4") + 7, "9", 1, "mode 9");
    broken(&b, &g, "material.glb", json_at(&g, "\"material\":1") + 11, "7", 1,
           "material = 7 out of range");
    broken(&b, &g, "asset.glb", json_at(&g, "\"version\""), "\"vexsion\"", 9,
           "asset.version missing");
    broken(&b, &g, "unlit.glb", json_at(&g, "\"extensionsUsed\":[\"KHR_materials_unlit\"]") + 19,
           "X", 1, "not in extensionsUsed");
    broken(&b, &g, "factor.glb", json_at(&g, "\"metallicFactor\":0") + 17, "2", 1,
           "metallicFactor");
    {
        const jparser *p = &g.j;
        int pr = j_at(p, j_get(p, j_at(p, j_get(p, g.root, "meshes"), 0), "primitives"), 0);
        int ia = j_at(p, j_get(p, g.root, "accessors"), (int)j_num(p, pr, "indices", -1));
        d = attribute(&g, pr, "COLOR_0", &nv);
        assert_non_null(d);
        broken(&b, &g, "colour.glb", (size_t)(d - g.file), &two, 4, "outside [0, 1]");
        d = attribute(&g, pr, "POSITION", &nv);
        broken(&b, &g, "position.glb", (size_t)(d - g.file), &far, 4, "(3.6.2.5)");
        d = attribute(&g, pr, "NORMAL", &nv);
        broken(&b, &g, "normal.glb", (size_t)(d - g.file), &two, 4, "not unit length");
        at = (size_t)(g.bin - g.file) + (size_t)j_num(p,
                                                      j_at(p, j_get(p, g.root, "bufferViews"),
                                                           (int)j_num(p, ia, "bufferView", -1)),
                                                      "byteOffset", 0);
        broken(&b, &g, "index.glb", at, big, 4, "indices >= the vertex count");
    }
    gltf_refused(b.path_of, b.what, b.n);
    free_glb(&g);
    sc_destroy(s);
    free(polys);
    obj_free(&sc);
}

/* ---- textures glTF cannot carry: re-encoded ------------------------------------ */

static void put_le(unsigned char *d, uint32_t v, int n)
{
    int i;
    for (i = 0; i < n; i++) d[i] = (unsigned char)(v >> (8 * i));
}

/* A BMP map_Kd (3 x 2, 24-bit, rows bottom-up and padded to 4 bytes, as BMP stores
   them) is embedded as image/png, and that PNG decodes to the BMP's pixels exactly
   (8-bit sRGB both, PNG lossless). */
static void test_bmp_texture(void **state)
{
    static const unsigned char want[2][3][3] = {/* row 0 at the top, RGB */
                                                {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}},
                                                {{10, 20, 30}, {200, 150, 100}, {255, 255, 255}}};
    unsigned char bmp[54 + 2 * 12];
    obj_scene sc;
    sc_poly *polys;
    sc_solver *s;
    sc_opts o = {.max_element = 0.5, .res = 32};
    tex_image maps[2];
    char err[600];
    img_t im;
    glb g;
    FILE *f;
    int n, x, y, k, warnings = 0, img;
    (void)state;
    memset(bmp, 0, sizeof bmp);
    bmp[0] = 'B';
    bmp[1] = 'M';
    put_le(bmp + 2, sizeof bmp, 4);
    put_le(bmp + 10, 54, 4);
    put_le(bmp + 14, 40, 4);
    put_le(bmp + 18, 3, 4);
    put_le(bmp + 22, 2, 4);
    put_le(bmp + 26, 1, 2);
    put_le(bmp + 28, 24, 2);
    put_le(bmp + 34, 2 * 12, 4);
    for (y = 0; y < 2; y++) /* the file's first row is the image's bottom one */
        for (x = 0; x < 3; x++)
            for (k = 0; k < 3; k++)
                bmp[54 + 12 * (1 - y) + 3 * x + k] = want[y][x][2 - k]; /* BGR */
    f = fopen(tmp_path("t.bmp"), "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(bmp, 1, sizeof bmp, f), sizeof bmp);
    assert_int_equal(fclose(f), 0);
    write_text("bmp.mtl",
               "newmtl floor\nKd 0 0 0\nmap_Kd t.bmp\nnewmtl lamp\nKd 0 0 0\nKe 5 5 5\n");
    write_text("bmp.obj", "mtllib bmp.mtl\nv -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\n"
                          "v -0.2 1 -0.2\nv 0.2 1 -0.2\nv 0.2 1 0.2\nv -0.2 1 0.2\n"
                          "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                          "usemtl floor\nf 4/1 3/2 2/3 1/4\nusemtl lamp\nf 5 6 7 8\n");
    assert_int_equal(obj_load(tmp_path("bmp.obj"), &sc, NULL, NULL, err, sizeof err), 0);
    assert_int_equal(tex_load_materials(&sc, maps, NULL, NULL, 1), 1);
    polys = polys_from_obj_tex(&sc, maps, &n, NULL, NULL);
    s = sc_create(polys, n, &o, NULL, NULL, err, sizeof err);
    assert_non_null(s);
    sc_solve(s, 1000, 1e-3, NULL, NULL);
    assert_int_equal(sc_export_gltf(s, &sc, polys, n, maps, NULL, tmp_path("bmp.glb"), collect,
                                    &warnings, err, sizeof err),
                     0);
    assert_int_equal(warnings, 0);
    gltf_validates(tmp_path("bmp.glb"));
    assimp_reads(tmp_path("bmp.glb"));
    read_glb(tmp_path("bmp.glb"), &g);
    {
        const jparser *p = &g.j;
        int bt =
            j_get(p, j_get(p, j_at(p, j_get(p, g.root, "materials"), 0), "pbrMetallicRoughness"),
                  "baseColorTexture");
        int tex = j_at(p, j_get(p, g.root, "textures"), (int)j_num(p, bt, "index", -1));
        assert_true(bt >= 0 && tex >= 0);
        img = (int)j_num(p, tex, "source", -1);
    }
    embedded_image(&g, img, &im); /* image/png, decoded */
    assert_int_equal(im.w, 3);
    assert_int_equal(im.h, 2);
    for (y = 0; y < 2; y++)
        for (x = 0; x < 3; x++)
            for (k = 0; k < 3; k++)
                CHECK_INT_EQ(im.rgb[3 * (3 * y + x) + k], want[y][x][k],
                             "embedded PNG texel (%d, %d) channel %d "
                             "against the BMP's",
                             x, y, k);
    print_message("BMP map_Kd: embedded as image/png, its 3 x 2 texels the BMP's\n");
    { /* the validator refuses an image whose bytes are not its mimeType's */
        static breaks b;
        const jparser *p = &g.j;
        int v = j_at(p, j_get(p, g.root, "bufferViews"),
                     (int)j_num(p, j_at(p, j_get(p, g.root, "images"), img), "bufferView", -1));
        broken(&b, &g, "notpng.glb",
               (size_t)(g.bin - g.file) + (size_t)j_num(p, v, "byteOffset", 0), "BM", 2,
               "are not image/png");
        broken(&b, &g, "source.glb", json_at(&g, "\"source\":0") + 9, "5", 1,
               "source = 5 out of range");
        gltf_refused(b.path_of, b.what, b.n);
    }
    img_free(&im);
    free_glb(&g);
    for (k = 0; k < sc.nmaterials; k++) tex_free(&maps[k]);
    sc_destroy(s);
    free(polys);
    obj_free(&sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_structure),     cmocka_unit_test(test_solution_colours),
        cmocka_unit_test(test_errors),        cmocka_unit_test(test_cli),
        cmocka_unit_test(test_lightmap),      cmocka_unit_test(test_linear_export),
        cmocka_unit_test(test_corner_search), cmocka_unit_test(test_cli_export_stats),
        cmocka_unit_test(test_validator),     cmocka_unit_test(test_bmp_texture),
    };
    return cmocka_run_group_tests(tests, group_setup, group_teardown);
}
