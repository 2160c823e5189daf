/* SPDX-License-Identifier: MIT */
/* Tests for the PLY export: tools/formats/ply.c (ASCII 8-bit sRGB, binary linear float
 * with welded vertices) and tools/host/ply_export.c (the element mesh, its colours and
 * normals). Files are read back by a PLY reader written here, checked against the
 * solver they came from, and read by assimp (Debian assimp-utils) when it is installed.
 * Run from the repository root (make test does). */
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
#include <sys/wait.h>

#include "check.h"
#include "formats/file_io.h"
#include "formats/image.h"
#include "formats/obj.h"
#include "formats/ply.h"
#include "host/polys.h"
#include "host/ply_export.h"
#include "rad/rad.h"
#include "tmpdir.h"
#include "assimp.h"

TMPDIR_GROUP("ply")

#define CORNELL "examples/cornell_box.obj"

/* ---- a PLY reader for the two forms rad writes ---------------------------------- */

typedef struct {
    int binary, nv, nf;
    double exposure; /* from the header's comment */
    float (*v)[9];   /* x y z nx ny nz r g b (ASCII: x y z, 0 0 0, r g b in 0..255) */
    int (*face)[4];  /* face[f][3] = -1 for a triangle */
} ply_file;

static const char *const binary_props[] = {
    "property float x",   "property float y",     "property float z",
    "property float nx",  "property float ny",    "property float nz",
    "property float red", "property float green", "property float blue",
};
static const char *const ascii_props[] = {
    "property float x",   "property float y",     "property float z",
    "property uchar red", "property uchar green", "property uchar blue",
};

/* The next header line of *P (at most 255 characters) into LINE. */
static void header_line(const char **p, const char *end, char line[256])
{
    const char *nl = memchr(*p, '\n', (size_t)(end - *p));
    assert_non_null(nl);
    CHECK_INT_LT(nl - *p, 256, "PLY header line length");
    memcpy(line, *p, (size_t)(nl - *p));
    line[nl - *p] = '\0';
    *p = nl + 1;
}

static int32_t le32(const unsigned char *b)
{
    return (int32_t)((uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 |
                     (uint32_t)b[3] << 24);
}

static void read_header(const char **p, const char *end, ply_file *f)
{
    char line[256];
    int i, nprops;
    header_line(p, end, line);
    assert_string_equal(line, "ply");
    header_line(p, end, line);
    f->binary = strcmp(line, "format binary_little_endian 1.0") == 0;
    if (!f->binary) assert_string_equal(line, "format ascii 1.0");
    header_line(p, end, line);
    f->exposure = -1;
    if (f->binary)
        assert_int_equal(sscanf(line,
                                "comment rad radiosity, linear float vertex colours in the "
                                "scene's units (the images' exposure %lf)",
                                &f->exposure),
                         1);
    else
        assert_int_equal(sscanf(line, "comment rad radiosity, sRGB vertex colours at exposure %lf",
                                &f->exposure),
                         1);
    header_line(p, end, line);
    assert_int_equal(sscanf(line, "element vertex %d", &f->nv), 1);
    nprops = f->binary ? 9 : 6;
    for (i = 0; i < nprops; i++) {
        header_line(p, end, line);
        assert_string_equal(line, f->binary ? binary_props[i] : ascii_props[i]);
    }
    header_line(p, end, line);
    assert_int_equal(sscanf(line, "element face %d", &f->nf), 1);
    header_line(p, end, line);
    assert_string_equal(line, "property list uchar int vertex_indices");
    header_line(p, end, line);
    assert_string_equal(line, "end_header");
    CHECK_INT_GE(f->nv, 0, "PLY vertex count");
    CHECK_INT_GE(f->nf, 0, "PLY face count");
}

static void read_binary(const unsigned char *b, const unsigned char *end, ply_file *f)
{
    int v, k, i;
    CHECK_INT_GE(end - b, 36 * (intmax_t)f->nv, "bytes for the PLY's vertices");
    for (v = 0; v < f->nv; v++)
        for (k = 0; k < 9; k++) {
            int32_t u = le32(b + 36 * v + 4 * k);
            memcpy(&f->v[v][k], &u, 4);
        }
    b += 36 * (size_t)f->nv;
    for (i = 0; i < f->nf; i++) {
        int n;
        assert_true(b < end);
        n = *b++;
        CHECK_THAT(n == 3 || n == 4, "PLY face %d has %d corners: elements are triangles or quads",
                   i, n);
        CHECK_INT_GE(end - b, 4 * n, "bytes for PLY face %d", i);
        for (k = 0; k < 4; k++) f->face[i][k] = k < n ? le32(b + 4 * k) : -1;
        b += 4 * n;
    }
    CHECK_INT_EQ(end - b, 0, "bytes after the PLY's last face");
}

static void read_ascii(const char *p, ply_file *f)
{
    int v, i, k, used;
    for (v = 0; v < f->nv; v++) {
        double x[3];
        unsigned c[3];
        if (sscanf(p, "%lf %lf %lf %u %u %u\n%n", &x[0], &x[1], &x[2], &c[0], &c[1], &c[2],
                   &used) != 6)
            fail_msg("bad PLY vertex line %d", v);
        for (k = 0; k < 3; k++) {
            CHECK_INT_LE(c[k], 255, "PLY vertex %d: colour channel %d", v, k);
            f->v[v][k] = (float)x[k];
            f->v[v][3 + k] = 0;
            f->v[v][6 + k] = (float)c[k];
        }
        p += used;
    }
    for (i = 0; i < f->nf; i++) {
        int n;
        assert_int_equal(sscanf(p, "%d%n", &n, &used), 1);
        CHECK_THAT(n == 3 || n == 4, "PLY face %d has %d corners: elements are triangles or quads",
                   i, n);
        p += used;
        for (k = 0; k < 4; k++) {
            f->face[i][k] = -1;
            if (k < n) assert_int_equal(sscanf(p, "%d%n", &f->face[i][k], &used), 1);
            if (k < n) p += used;
        }
        assert_int_equal(*p++, '\n');
    }
    assert_int_equal(*p, '\0');
}

/* Reads PATH; every face index in [0, nv), and every vertex used by a face. */
static void read_ply(const char *path, ply_file *f)
{
    char err[600], *data;
    size_t size;
    const char *p;
    unsigned char *used;
    int i, k;
    assert_int_equal(fio_read_all(path, FIO_LIMIT_OBJ, &data, &size, err, sizeof err), 0);
    p = data;
    read_header(&p, data + size, f);
    f->v = malloc(((size_t)f->nv + 1) * sizeof *f->v);
    f->face = malloc(((size_t)f->nf + 1) * sizeof *f->face);
    assert_true(f->v && f->face);
    if (f->binary)
        read_binary((const unsigned char *)p, (const unsigned char *)data + size, f);
    else
        read_ascii(p, f);
    free(data);
    used = calloc((size_t)f->nv + 1, 1);
    assert_non_null(used);
    for (i = 0; i < f->nf; i++)
        for (k = 0; k < 4 && f->face[i][k] >= 0; k++) {
            CHECK_INT_LT(f->face[i][k], f->nv,
                         "PLY face %d corner %d's vertex against the vertices", i, k);
            used[f->face[i][k]] = 1;
        }
    for (i = 0; i < f->nv; i++) CHECK_INT_EQ(used[i], 1, "PLY vertex %d used by a face", i);
    free(used);
}

static void ply_free(ply_file *f)
{
    free(f->v);
    free(f->face);
}

/* ---- welding, counted independently: sort the nine floats, count distinct ---------- */

static int cmp_key(const void *a, const void *b)
{
    return memcmp(a, b, 9 * sizeof(float));
}

/* Distinct records among N (sorted in place); -0 must already be +0. */
static int distinct(float (*v)[9], int n)
{
    int i, d = n > 0;
    qsort(v, (size_t)n, sizeof *v, cmp_key);
    for (i = 1; i < n; i++) d += cmp_key(v[i], v[i - 1]) != 0;
    return d;
}

static float f32_of(double d)
{
    float f = (float)d;
    return f == 0 ? 0.0f : f;
}

/* ---- a solved scene ----------------------------------------------------------------- */

typedef struct {
    obj_scene sc;
    sc_poly *polys;
    int npolys;
    sc_solver *s;
    sc_stats st;
    double *rgb; /* sc_shade, with the ambient term */
} solved;

static void solve_file(const char *path, double max_element, solved *z)
{
    char err[600];
    sc_opts o = {.max_element = max_element, .res = 32};
    assert_int_equal(obj_load(path, &z->sc, NULL, NULL, err, sizeof err), 0);
    z->polys = polys_from_obj(&z->sc, &z->npolys, NULL, NULL);
    assert_non_null(z->polys);
    z->s = sc_create(z->polys, z->npolys, &o, NULL, NULL, err, sizeof err);
    assert_non_null(z->s);
    sc_solve(z->s, 100000, 0.01, NULL, NULL);
    sc_get_stats(z->s, &z->st);
    z->rgb = malloc(((size_t)z->st.vertices + 1) * 3 * sizeof *z->rgb);
    assert_non_null(z->rgb);
    assert_int_equal(sc_shade(z->s, 1, z->rgb), 0);
}

static void solved_free(solved *z)
{
    free(z->rgb);
    sc_destroy(z->s);
    free(z->polys);
    obj_free(&z->sc);
}

/* The unit normal of element E from its vertices (Newell), in double. */
static void element_normal(sc_solver *s, int e, double n[3])
{
    int v[4], k, c = sc_element_vertices(s, e, v);
    double len;
    n[0] = n[1] = n[2] = 0;
    for (k = 0; k < c; k++) {
        double a[3], b[3];
        sc_vertex_pos(s, v[k], a);
        sc_vertex_pos(s, v[(k + 1) % c], b);
        n[0] += (a[1] - b[1]) * (a[2] + b[2]);
        n[1] += (a[2] - b[2]) * (a[0] + b[0]);
        n[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (k = 0; k < 3; k++) n[k] /= len;
}

/* Face F of the binary file is element F: its corners carry the core vertices' position
 * and colour rounded once to float, and the element's normal. Returns the worst
 * relative colour difference against the solution's double. */
static double check_face(const ply_file *f, const solved *z, int e, double *normal_err)
{
    int cv[4], k, a, n = sc_element_vertices(z->s, e, cv);
    double worst = 0, en[3];
    element_normal(z->s, e, en);
    CHECK_INT_EQ(f->face[e][3] >= 0 ? 4 : 3, n, "PLY face %d's corners against element %d's", e, e);
    for (k = 0; k < n; k++) {
        const float *w = f->v[f->face[e][k]];
        double p[3], len = 0;
        sc_vertex_pos(z->s, cv[k], p);
        for (a = 0; a < 3; a++) {
            double c = z->rgb[3 * cv[k] + a];
            CHECK_EQ(w[a], f32_of(p[a]),
                     "face %d corner %d coordinate %d: the vertex's, as a float", e, k, a);
            CHECK_EQ(w[6 + a], f32_of(c), "face %d corner %d colour %d: the solution's, as a float",
                     e, k, a);
            if (c > 0) worst = fmax(worst, fabs(w[6 + a] - c) / c);
            *normal_err = fmax(*normal_err, fabs(w[3 + a] - en[a]));
            len += (double)w[3 + a] * w[3 + a];
        }
        CHECK_NEAR(sqrt(len), 1, 1e-6, "face %d corner %d: unit normal (float rounding)", e, k);
    }
    return worst;
}

/* Writes S's binary PLY and checks it: the counts, every face against its element
 * (normals within NORMAL_TOL of the element's own), no two vertices alike, and as many
 * vertices as the core's have distinct floats. Returns the vertices written. */
static int check_binary(const solved *z, const char *name, double normal_tol)
{
    ply_file f;
    char err[600];
    float(*keys)[9];
    double worst = 0, nerr = 0;
    int e, v, a, nw, expect;
    nw = sc_export_ply(z->s, z->rgb, tmp_path(name), PLY_BINARY_LINEAR, 2.5, err, sizeof err);
    CHECK_INT_GT(nw, 0, "sc_export_ply's vertices (%s)", err);
    read_ply(tmp_path(name), &f);
    assert_int_equal(f.binary, 1);
    CHECK_INT_EQ(f.nv, nw, "PLY vertices against sc_export_ply's count");
    CHECK_INT_EQ(f.nf, z->st.elements, "PLY faces against the elements");
    CHECK_EQ(f.exposure, 2.5, "the header's exposure");
    for (e = 0; e < f.nf; e++) worst = fmax(worst, check_face(&f, z, e, &nerr));
    CHECK_INT_EQ(distinct(f.v, f.nv), f.nv, "distinct vertices in the welded PLY");
    keys = malloc(((size_t)z->st.vertices + 1) * sizeof *keys);
    assert_non_null(keys);
    for (v = 0; v < z->st.vertices;
         v++) { /* the nine floats of each core vertex, from the file's faces */
        double p[3];
        sc_vertex_pos(z->s, v, p);
        for (a = 0; a < 3; a++) {
            keys[v][a] = f32_of(p[a]);
            keys[v][6 + a] = f32_of(z->rgb[3 * v + a]);
        }
    }
    for (e = 0; e < f.nf; e++) { /* normals as written (checked above against the element's) */
        int cv[4], k, n = sc_element_vertices(z->s, e, cv);
        for (k = 0; k < n; k++) memcpy(&keys[cv[k]][3], &f.v[f.face[e][k]][3], 3 * sizeof(float));
    }
    expect = distinct(keys, z->st.vertices);
    print_message(
        "%s: %d core vertices, %d distinct (position, normal, colour), %d written; colours "
        "within %.3g of the solution's (float: 2^-24 = %.3g), normals within %.3g of the "
        "elements'\n",
        name, z->st.vertices, expect, f.nv, worst, ldexp(1, -24), nerr);
    CHECK_INT_EQ(f.nv, expect, "welded vertices against the distinct ones counted by sorting");
    CHECK_LE(worst, ldexp(1, -24), "colour against the solution's: one rounding to float");
    CHECK_LE(nerr, normal_tol, "normal against the element's own (Newell, double)");
    free(keys);
    ply_free(&f);
    return nw;
}

/* ---- tests -------------------------------------------------------------------------- */

/* The bundled Cornell box, solved coarse: the binary file against the solver (see
   check_binary), then the ASCII one from the same solve: every core vertex in order, at
   %.7g, its colour the solution's through the images' tone map at the given exposure. */
static void test_cornell(void **state)
{
    solved z;
    ply_file f;
    char err[600];
    int v, a;
    (void)state;
    solve_file(CORNELL, 0.1, &z);
    /* A vertex has its surface's normal. The core takes a quad as planar when its corners
       lie within sqrt(area)/64 of its plane (the measured Cornell box's walls are not
       quite flat), and its elements, on the bilinear lattice between its edges, tilt
       from that plane by up to about twice that over the side: 1/32 rad. */
    check_binary(&z, "cornell.ply", 1.0 / 32);
    CHECK_INT_EQ(
        sc_export_ply(z.s, z.rgb, tmp_path("cornell_8.ply"), PLY_ASCII_SRGB, 3.5, err, sizeof err),
        z.st.vertices, "ASCII PLY vertices: every core vertex (%s)", err);
    read_ply(tmp_path("cornell_8.ply"), &f);
    assert_int_equal(f.binary, 0);
    CHECK_INT_EQ(f.nv, z.st.vertices, "ASCII PLY vertices");
    CHECK_INT_EQ(f.nf, z.st.elements, "ASCII PLY faces");
    CHECK_EQ(f.exposure, 3.5, "the ASCII header's exposure");
    for (v = 0; v < f.nv; v++) {
        double p[3];
        float lin[3];
        unsigned char c[3];
        sc_vertex_pos(z.s, v, p);
        for (a = 0; a < 3; a++) lin[a] = (float)z.rgb[3 * v + a];
        tonemap(lin, 1, 3.5, c);
        for (a = 0; a < 3; a++) {
            /* %.7g: 7 significant digits, half a unit of the 7th off at most (5e-7
               relative), read back into a float here (6e-8 more) */
            CHECK_NEAR(f.v[v][a], p[a], 5.6e-7 * fabs(p[a]) + 1e-30,
                       "ASCII vertex %d coordinate %d", v, a);
            CHECK_INT_EQ(f.v[v][6 + a], c[a],
                         "ASCII vertex %d colour %d: the tone map at exposure 3.5", v, a);
        }
    }
    ply_free(&f);
    solved_free(&z);
}

/* Welding across surfaces happens where their vertices are equal in every float: a lamp
   of Kd 0 made of two triangles radiates exactly its emission at every vertex, so the
   triangles' shared corners weld; the room around it, lit, keeps its creases split. */
static void test_weld(void **state)
{
    solved z;
    FILE *f;
    int nw;
    (void)state;
    f = fopen(tmp_path("lamp.mtl"), "w");
    assert_non_null(f);
    fputs("newmtl wall\nKd 0.6 0.6 0.6\nnewmtl lamp\nKd 0 0 0\nKe 4 4 4\n", f);
    assert_int_equal(fclose(f), 0);
    f = fopen(tmp_path("lamp.obj"), "w");
    assert_non_null(f);
    fputs("mtllib lamp.mtl\nusemtl wall\n"
          "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
          "f 1 2 3 4\nf 5 6 2 1\nf 6 7 3 2\nf 7 8 4 3\nf 8 5 1 4\n"
          "v -0.4 0.99 -0.4\nv 0.4 0.99 -0.4\nv 0.4 0.99 0.4\nv -0.4 0.99 0.4\n"
          "usemtl lamp\nf 9 10 11\nf 9 11 12\n",
          f);
    assert_int_equal(fclose(f), 0);
    solve_file(tmp_path("lamp.obj"), 0.25, &z);
    /* axis-aligned faces: the normals are exact (3 x 2^-16 allows the Q16.16 normal) */
    nw = check_binary(&z, "lamp.ply", 3 * ldexp(1, -16));
    /* at least the two input corners the triangles share */
    CHECK_INT_LE(nw, z.st.vertices - 2, "welded vertices: the lamp's shared corners are one");
    solved_free(&z);
}

/* ply_write alone: -0 welds with +0, a NaN is written as 0, a value beyond float's
   range as the largest float; an unwritable path is one line naming it, and the file
   already there stays as it was. */
static void test_values_and_errors(void **state)
{
    static const double pos[4 * 3] = {0, 0, 0, -0.0, 0, 0, 1, 0, 0, 0, 1, 0};
    static const double nrm[4 * 3] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    double rgb[4 * 3] = {1, 1, 1, 1, 1, 1, 0, 0, 0, 0, 1e300, -1e300};
    static const int face[2 * 4] = {0, 2, 3, -1, 1, 2, 3, -1};
    ply_mesh m = {
        .nv = 4,
        .nf = 2,
        .pos = pos,
        .rgb = rgb,
        .normal = nrm,
        .face = face,
        .comment = "rad radiosity, linear float vertex colours in the scene's units (the images' "
                   "exposure 1)"};
    ply_file f;
    char err[600], *data;
    size_t size;
    (void)state;
    rgb[6] = NAN;
    CHECK_INT_EQ(ply_write(tmp_path("v.ply"), &m, PLY_BINARY_LINEAR, 1, err, sizeof err), 3,
                 "vertices written: -0 and +0 one (%s)", err);
    read_ply(tmp_path("v.ply"), &f);
    CHECK_INT_EQ(f.nv, 3, "vertices in the file");
    CHECK_INT_EQ(f.face[0][0], f.face[1][0], "the two faces' first corners welded");
    CHECK_EQ(f.v[1][6], 0, "a NaN colour written as 0");
    CHECK_EQ(f.v[2][7], FLT_MAX, "1e300 written as the largest float");
    CHECK_EQ(f.v[2][8], -FLT_MAX, "-1e300 written as minus the largest float");
    ply_free(&f);

    CHECK_INT_EQ(
        ply_write(tmp_path("no/such/folder/v.ply"), &m, PLY_BINARY_LINEAR, 1, err, sizeof err), -1,
        "a folder that does not exist");
    print_message("%s\n", err);
    CHECK_CONTAINS(err, "no/such/folder", "the message names the file");
    CHECK_THAT(strchr(err, '\n') == NULL, "one line: %s", err);
    assert_int_equal(fio_read_all(tmp_path("v.ply"), FIO_LIMIT_OBJ, &data, &size, err, sizeof err),
                     0);
    free(data);
    CHECK_INT_EQ(ply_write(tmp_path("v.ply/x"), &m, PLY_ASCII_SRGB, 1, err, sizeof err), -1,
                 "a path through a file");
    assert_int_equal(fio_read_all(tmp_path("v.ply"), FIO_LIMIT_OBJ, &data, &size, err, sizeof err),
                     0);
    CHECK_INT_GT(size, 0, "v.ply still there");
    free(data);
}

/* Runs CMD (stdout to OUT); its exit status. */
static int run(const char *cmd, const char *out)
{
    char line[2048];
    int rc;
    snprintf(line, sizeof line, "%s > '%s' 2>&1", cmd, out);
    rc = system(line);
    return WIFEXITED(rc) ? WEXITSTATUS(rc) : 128;
}

/* The value of the first of FILE's lines that FMT (one %lf) reads, or -1. */
static double stat_of(const char *path, const char *fmt)
{
    char err[600], *data, *p;
    size_t size;
    double v = -1;
    assert_int_equal(fio_read_all(path, FIO_LIMIT_TEXT, &data, &size, err, sizeof err), 0);
    for (p = data; p && *p; p = strchr(p, '\n') ? strchr(p, '\n') + 1 : NULL)
        if (sscanf(p, fmt, &v) == 1) break;
    free(data);
    return v;
}

/* rad_cli and rad_cli_float: --ply-linear writes the binary file (faces = --stats'
   elements; assimp reads it); without it the ASCII file's exposure is --stats' and the
   line says so; --ply-linear alone is a usage error. */
static void test_cli(void **state)
{
    static const char *const bins[2] = {"build/rad_cli", "build/rad_cli_float"};
    char cmd[1024];
    ply_file f;
    int b;
    (void)state;
    for (b = 0; b < 2; b++) {
        snprintf(cmd, sizeof cmd,
                 "%s " CORNELL " --max-element 0.1 --res 32 --width 16 --height 16 --stats "
                 "--quiet -o '%s' --export-ply '%s' --ply-linear",
                 bins[b], tmp_path("c.png"), tmp_path("c.ply"));
        CHECK_INT_EQ(run(cmd, tmp_path("stats.txt")), 0, "%s", cmd);
        read_ply(tmp_path("c.ply"), &f);
        assert_int_equal(f.binary, 1);
        CHECK_EQ(f.nf, stat_of(tmp_path("stats.txt"), "patches %*d elements %lf"),
                 "%s: PLY faces against "
                 "--stats' elements",
                 bins[b]);
        CHECK_EQ(f.exposure, stat_of(tmp_path("stats.txt"), "exposure %lf"),
                 "%s: the header's exposure", bins[b]);
        CHECK_INT_EQ(distinct(f.v, f.nv), f.nv, "%s: distinct vertices", bins[b]);
        ply_free(&f);
        assimp_reads(tmp_path("c.ply"));
    }
    snprintf(cmd, sizeof cmd,
             "build/rad_cli " CORNELL " --max-element 0.1 --res 32 --width 16 --height 16 --stats "
             "--quiet -o '%s' --export-ply '%s'",
             tmp_path("c.png"), tmp_path("c8.ply"));
    CHECK_INT_EQ(run(cmd, tmp_path("stats.txt")), 0, "%s", cmd);
    read_ply(tmp_path("c8.ply"), &f);
    {
        double e = stat_of(tmp_path("stats.txt"), "exposure %lf");
        char *data, err[600];
        size_t size;
        /* the header's %g keeps 6 significant digits */
        CHECK_NEAR(f.exposure, e, 5e-6 * e, "the ASCII header's exposure against --stats'");
        assert_int_equal(
            fio_read_all(tmp_path("stats.txt"), FIO_LIMIT_TEXT, &data, &size, err, sizeof err), 0);
        CHECK_CONTAINS(data, "; also --export-ply's sRGB colours)",
                       "--stats names the PLY's exposure");
        free(data);
    }
    ply_free(&f);
    assimp_reads(tmp_path("c8.ply"));
    snprintf(cmd, sizeof cmd, "build/rad_cli " CORNELL " --ply-linear");
    CHECK_INT_EQ(run(cmd, tmp_path("usage.txt")), 2,
                 "--ply-linear without --export-ply: a usage error");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cornell),
        cmocka_unit_test(test_weld),
        cmocka_unit_test(test_values_and_errors),
        cmocka_unit_test(test_cli),
    };
    return cmocka_run_group_tests(tests, group_setup, group_teardown);
}
