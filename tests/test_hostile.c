/* SPDX-License-Identifier: MIT */
/* Hostile input and limits: what the loader, the scene glue, the image writer and
 * rad_cli do with truncated and binary files, a megabyte line, millions of vertices,
 * indices out of range, emissions far outside the fixed-point range, scenes with no
 * light, unwritable outputs, the hemi-cube in bands, and small compile-time limits
 * (RAD_INDEX_BITS=16, RAD_MAX_RES=64: `make check` builds those variants). Every case
 * asserts the exact error or the documented behaviour.
 *
 * rad_cli runs as a subprocess (build/rad_cli from the working directory, like
 * test_cli; skipped when missing). RAD_TEST_LIGHT=1 (set by `make check`'s valgrind
 * stage) scales the large inputs down tenfold.
 *
 * The denormal-emission, denormal-extent and 16-bit pool defects this file found are
 * fixed; their tests ("Was a bug") guard the fixes.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <float.h>
#include <math.h>
#include <signal.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "check.h"
#include "formats/image.h"
#include "tmpdir.h"
#include "formats/obj.h"
#include "rad/rad.h"
#include "scenes.h"

extern char **environ;

#define CLI           "build/rad_cli"
#define CORNELL       "examples/cornell_box.obj"
#define RUN_TIMEOUT_S 300.0

/* ---- the temporary directory ------------------------------------------------------ */

TMPDIR_GROUP("hostile")

static int light(void)
{
    return getenv("RAD_TEST_LIGHT") != NULL;
}

static void write_file(const char *path, const void *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(data, 1, n, f), n);
    assert_int_equal(fclose(f), 0);
}

static void write_text(const char *path, const char *text)
{
    write_file(path, text, strlen(text));
}

static char *slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    char *buf;
    long n;
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    n = ftell(f);
    fseek(f, 0, SEEK_SET);
    buf = malloc((size_t)n + 1);
    assert_non_null(buf);
    assert_int_equal(fread(buf, 1, (size_t)n, f), (size_t)n);
    fclose(f);
    buf[n] = '\0';
    if (len) *len = (size_t)n;
    return buf;
}

/* The names in directory DIR, sorted and joined by '/', for before/after comparisons. */
static char *listing(const char *dir)
{
    DIR *d = opendir(dir);
    struct dirent *de;
    char *names[256], *out;
    int n = 0, i, j;
    size_t len = 1;
    assert_non_null(d);
    while ((de = readdir(d)) != NULL && n < 256)
        if (strcmp(de->d_name, ".") && strcmp(de->d_name, "..")) {
            names[n] = strdup(de->d_name);
            len += strlen(de->d_name) + 1;
            n++;
        }
    closedir(d);
    for (i = 1; i < n; i++)
        for (j = i; j > 0 && strcmp(names[j - 1], names[j]) > 0; j--) {
            char *t = names[j];
            names[j] = names[j - 1];
            names[j - 1] = t;
        }
    out = calloc(1, len);
    assert_non_null(out);
    for (i = 0; i < n; i++) {
        strcat(out, names[i]);
        strcat(out, "/");
        free(names[i]);
    }
    return out;
}

/* ---- the loader ------------------------------------------------------------------- */

/* obj_load of TEXT written to NAME: returns its status; ERR gets the message. */
static int load_text(const char *name, const char *text, size_t len, obj_scene *sc, char *err,
                     size_t errlen)
{
    const char *path = tmp_path(name);
    write_file(path, text, len);
    return obj_load(path, sc, NULL, NULL, err, errlen);
}

/* The load must fail with exactly "<path>:MSG". */
static void expect_load_error(const char *name, const char *text, size_t len, const char *msg)
{
    obj_scene sc;
    char err[512], want[512];
    assert_int_equal(load_text(name, text, len, &sc, err, sizeof err), -1);
    snprintf(want, sizeof want, "%s:%s", tmp_path(name), msg);
    assert_string_equal(err, want);
    assert_int_equal(sc.nverts, 0);
    assert_int_equal(sc.nfaces, 0);
    assert_null(sc.verts);
    obj_free(&sc);
}
#define EXPECT_LOAD_ERROR(name, text, msg) expect_load_error((name), (text), strlen(text), (msg))

static void test_obj_truncated(void **st)
{
    char *cornell;
    size_t len, cut, step;
    int ok = 0, failed = 0;
    (void)st;
    /* Cut inside a statement: the statement is judged as it stands. */
    EXPECT_LOAD_ERROR("cut_face.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2",
                      "4: face needs at least 3 vertices, got 2");
    EXPECT_LOAD_ERROR("cut_number.obj", "v 0 0 0\nv 1.5e", "2: bad number '1.5e'");
    EXPECT_LOAD_ERROR("cut_vertex.obj", "v 0 0 0\nv 1 0", "2: vertex needs 3 coordinates, got 2");
    EXPECT_LOAD_ERROR("cut_continuation.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 \\",
                      "4: face needs at least 3 vertices, got 2");
    EXPECT_LOAD_ERROR("cut_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -",
                      "4: bad face vertex '-'");
    EXPECT_LOAD_ERROR("cut_slash.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3/",
                      "4: bad face vertex '3/'");
    EXPECT_LOAD_ERROR("cut_usemtl.obj", "v 0 0 0\nusemtl", "2: usemtl without a material name");
    EXPECT_LOAD_ERROR("cut_mtllib.obj", "mtllib  \n", "1: mtllib without a file name");
    /* The Cornell box cut after every byte (every 7th in light mode): each prefix loads,
     * or fails with one located line; never anything else. */
    cornell = slurp(CORNELL, &len);
    assert_non_null(cornell);
    step = light() ? 7 : 1;
    for (cut = 0; cut <= len; cut += step) {
        obj_scene sc;
        char err[512];
        const char *path = tmp_path("cornell_cut.obj");
        int rc;
        write_file(path, cornell, cut);
        rc = obj_load(path, &sc, NULL, NULL, err, sizeof err);
        if (rc == 0) {
            ok++;
            CHECK_INT_LE(sc.nfaces, 17, "faces of a cut cornell_box.obj (the whole has 17)");
        } else {
            failed++;
            assert_int_equal(rc, -1);
            CHECK_THAT(strncmp(err, path, strlen(path)) == 0 && err[strlen(path)] == ':',
                       "the error \"%s\" starts with \"%s:\"", err, path);
            assert_null(strchr(err, '\n'));
        }
        obj_free(&sc);
    }
    print_message("cornell_box.obj cut at %zu places: %d load, %d fail with a located message\n",
                  (len + step) / step, ok, failed);
    CHECK_INT_GT(ok, 0, "cuts of cornell_box.obj that load");
    CHECK_INT_GT(failed, 0, "cuts of cornell_box.obj that fail with a located message");
    free(cornell);
}

static void test_obj_binary(void **st)
{
    unsigned char bytes[1024];
    obj_scene sc;
    char err[512], want[600];
    size_t i, len;
    char *png;
    int line = 1;
    (void)st;
    /* A NUL byte is binary data, reported at its line. */
    {
        static const char nul[] = "v 0 0 0\nv 1 0 0\n\0v 0 1 0\n";
        expect_load_error("nul.obj", nul, sizeof nul - 1, "3: binary data (NUL byte)");
    }
    /* Every other byte value: lines of unknown statements, loaded, with no faces. */
    for (i = 0; i < sizeof bytes; i++) bytes[i] = (unsigned char)(1 + i % 255);
    assert_int_equal(
        load_text("bytes.obj", (const char *)bytes, sizeof bytes, &sc, err, sizeof err), 0);
    assert_int_equal(sc.nfaces, 0);
    assert_int_equal(sc.nverts, 0);
    CHECK_INT_GT(sc.unknown_statements, 0, "unknown statements among lines of every byte value");
    obj_free(&sc);
    /* A PNG (the README's picture) given as a scene: refused at its first NUL. */
    png = slurp("docs/cornell_box.png", &len);
    assert_non_null(png);
    for (i = 0; i < len && png[i]; i++) line += png[i] == '\n';
    CHECK_INT_LT(i, len, "offset of the first NUL byte in docs/cornell_box.png");
    snprintf(want, sizeof want, "%d: binary data (NUL byte)", line);
    expect_load_error("picture.obj", png, len, want);
    free(png);
}

static void test_obj_megabyte_lines(void **st)
{
    const size_t mb = (size_t)1 << 20;
    char *text = malloc(mb + 64);
    obj_scene sc;
    char err[512];
    size_t i, n;
    (void)st;
    assert_non_null(text);
    /* A number of a million digits: out of range, quoted to 40 characters. */
    n = (size_t)sprintf(text, "v ");
    memset(text + n, '1', mb);
    n += mb;
    n += (size_t)sprintf(text + n, " 0 0\n");
    expect_load_error(
        "long_number.obj", text, n,
        "1: number out of range '1111111111111111111111111111111111111111' (limit 1e30)");
    /* A megabyte comment, then a triangle: loads. */
    text[0] = '#';
    memset(text + 1, 'c', mb);
    n = 1 + mb + (size_t)sprintf(text + 1 + mb, "\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    assert_int_equal(load_text("long_comment.obj", text, n, &sc, err, sizeof err), 0);
    assert_int_equal(sc.nfaces, 1);
    assert_int_equal(sc.faces[0].line, 5);
    obj_free(&sc);
    /* A megabyte keyword: one unknown statement. */
    memset(text, 'k', mb);
    n = mb + (size_t)sprintf(text + mb, " x\nv 0 0 0\n");
    assert_int_equal(load_text("long_keyword.obj", text, n, &sc, err, sizeof err), 0);
    assert_int_equal(sc.unknown_statements, 1);
    assert_int_equal(sc.nverts, 1);
    obj_free(&sc);
    /* A face of 262,144 corners on one line: loaded as one face (ear clipping it is
     * another matter: see the report on obj_triangulate). */
    n = (size_t)sprintf(text, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf");
    for (i = 0; n + 4 < mb; i++) n += (size_t)sprintf(text + n, " %d", (int)(i % 3) + 1);
    text[n++] = '\n';
    assert_int_equal(load_text("long_face.obj", text, n, &sc, err, sizeof err), 0);
    assert_int_equal(sc.nfaces, 1);
    assert_int_equal(sc.faces[0].count, (int)i);
    CHECK_INT_GT(i, 250000, "corners of the long face");
    obj_free(&sc);
    free(text);
}

static void test_obj_index_out_of_range(void **st)
{
    (void)st;
    EXPECT_LOAD_ERROR("idx_high.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n",
                      "4: vertex index 4 out of range (3 vertices defined so far)");
    EXPECT_LOAD_ERROR("idx_negative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n",
                      "4: vertex index -4 out of range (3 vertices defined so far)");
    EXPECT_LOAD_ERROR("idx_zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n",
                      "4: vertex index 0 (OBJ indices start at 1)");
    EXPECT_LOAD_ERROR(
        "idx_huge.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999999\n",
        "4: vertex index 99999999999999999999999 out of range (3 vertices defined so far)");
    EXPECT_LOAD_ERROR("idx_int_min.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -2147483648\n",
                      "4: vertex index -2147483648 out of range (3 vertices defined so far)");
    EXPECT_LOAD_ERROR("idx_forward.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n",
                      "3: vertex index 3 out of range (2 vertices defined so far)");
    EXPECT_LOAD_ERROR("idx_texture.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1/1 2/2/2 9/3/3\n",
                      "4: vertex index 9 out of range (3 vertices defined so far)");
}

/* ---- millions of vertices ------------------------------------------------------------- */

/* An OBJ of NV vertices on a grid and NF triangles over them. */
static void write_big_obj(const char *path, long nv, long nf)
{
    FILE *f = fopen(path, "w");
    long i, w = 1000;
    assert_non_null(f);
    setvbuf(f, NULL, _IOFBF, 1 << 20);
    fprintf(f, "# %ld vertices, %ld faces\n", nv, nf);
    for (i = 0; i < nv; i++) fprintf(f, "v %ld %ld 0\n", i % w, i / w);
    for (i = 0; i < nf; i++) {
        long a = (2 * i) % (nv - w - 1);
        fprintf(f, "f %ld %ld %ld\n", a + 1, a + 2, a + w + 1);
    }
    assert_int_equal(fclose(f), 0);
}

static sc_poly *to_polys(const obj_scene *sc)
{
    sc_poly *p = calloc((size_t)sc->nfaces, sizeof *p);
    int f, k;
    assert_non_null(p);
    for (f = 0; f < sc->nfaces; f++) {
        p[f].n = 3;
        for (k = 0; k < 3; k++) {
            const obj_vec3 *v = &sc->verts[sc->indices[sc->faces[f].first + k]];
            p[f].v[k][0] = v->x;
            p[f].v[k][1] = v->y;
            p[f].v[k][2] = v->z;
        }
        set_mat(&p[f], 0.5, 0.5, 0.5, f == 0, f == 0, f == 0);
        p[f].tag = f;
    }
    return p;
}

static void test_millions_of_vertices(void **st)
{
    long nv = light() ? 200000 : 2000000, nf = nv / 2;
    const char *path = tmp_path("millions.obj");
    obj_scene sc;
    sc_poly *p;
    sc_opts o = {.res = 16, .max_elements = 5000};
    char err[512];
    sc_solver *s;
    scf_solver *sf;
    (void)st;
    write_big_obj(path, nv, nf);
    assert_int_equal(obj_load(path, &sc, NULL, NULL, err, sizeof err), 0);
    assert_int_equal(sc.nverts, nv);
    assert_int_equal(sc.nfaces, nf);
    assert_int_equal(sc.nindices, 3 * nf);
    p = to_polys(&sc);
    /* The pools fill: a clear message naming the limit, and nothing built. */
    s = sc_create(p, (int)nf, &o, NULL, NULL, err, sizeof err);
    assert_null(s);
    print_message("%ld vertices, %ld faces, max_elements 5000: \"%s\"\n", nv, nf, err);
    assert_string_equal(err, "the scene needs more than 5000 elements: raise the element size");
    sf = scf_create(p, (int)nf, &o, NULL, NULL, err, sizeof err);
    assert_null(sf);
    assert_string_equal(err, "the scene needs more than 5000 elements: raise the element size");
    free(p);
    obj_free(&sc);
    unlink(path);
}

/* ---- emissions beyond the fixed-point range ------------------------------------------- */

/* A closed room (inward quads) with a light on the ceiling of emission E and a second,
 * small one on the floor of emission E2; a block inside casts shadows. */
static int lit_room(sc_poly *p, double e, double e2)
{
    int n = box(p, -1, -1, -1, 1, 1, 1, 1), i;
    for (i = 0; i < n; i++) set_mat(&p[i], 0.6, 0.5, 0.4, 0, 0, 0);
    p[n] =
        quad(-0.3, 0.99, -0.3, 0.3, 0.99, -0.3, 0.3, 0.99, 0.3, -0.3, 0.99, 0.3); /* faces down */
    set_mat(&p[n++], 0.5, 0.5, 0.5, e, e, e);
    p[n] = quad(0.5, -0.99, 0.5, 0.5, -0.99, 0.7, 0.7, -0.99, 0.7, 0.7, -0.99, 0.5); /* faces up */
    set_mat(&p[n++], 0.5, 0.5, 0.5, e2, 0, 0);
    n += box(p + n, -0.4, -1, -0.4, 0, -0.4, 0, 0);
    for (i = n - 6; i < n; i++) set_mat(&p[i], 0.7, 0.7, 0.7, 0, 0, 0);
    return n;
}

typedef struct {
    uint64_t sum;
    unsigned long saturations;
    int shots, elements;
    double rgb0[3]; /* element 0, with the ambient term */
} solved_t;

static int solve_scene(int twin, const sc_poly *p, int n, solved_t *out, char *err, size_t errlen)
{
    sc_opts o = {.max_patch = 0.5, .max_element = 0.25, .res = 32};
    sc_stats st;
    if (twin) {
        scf_solver *s = scf_create(p, n, &o, NULL, NULL, err, errlen);
        if (!s) return -1;
        out->shots = scf_solve(s, 400, 1e-3, NULL, NULL);
        scf_get_stats(s, &st);
        out->sum = scf_checksum(s);
        scf_element_rgb(s, 0, 1, out->rgb0);
        scf_destroy(s);
    } else {
        sc_solver *s = sc_create(p, n, &o, NULL, NULL, err, errlen);
        if (!s) return -1;
        out->shots = sc_solve(s, 400, 1e-3, NULL, NULL);
        sc_get_stats(s, &st);
        out->sum = sc_checksum(s);
        sc_element_rgb(s, 0, 1, out->rgb0);
        sc_destroy(s);
    }
    out->saturations = st.saturations;
    out->elements = st.elements;
    return 0;
}

/* The glue scales the brightest emission to 256 before the core sees it (radiosity is
 * linear in emission) and scales results back: an emission of 1e30, or of DBL_MAX / 2,
 * gives bit for bit the core solution of an emission of 1, no saturation, and results
 * in the caller's units. */
static void test_emission_overflow(void **st)
{
    sc_poly p[16];
    static const double big[] = {1e30, 1e300, DBL_MAX / 2, 1e-300};
    solved_t ref, got;
    char err[256];
    int twin, n, k, c;
    (void)st;
    for (twin = 0; twin < 2; twin++) {
        n = lit_room(p, 1, 0);
        assert_int_equal(solve_scene(twin, p, n, &ref, err, sizeof err), 0);
        assert_int_equal(ref.saturations, 0);
        for (k = 0; k < 4; k++) {
            n = lit_room(p, big[k], 0);
            assert_int_equal(solve_scene(twin, p, n, &got, err, sizeof err), 0);
            assert_int_equal(got.sum, ref.sum);
            assert_int_equal(got.saturations, 0);
            assert_int_equal(got.shots, ref.shots);
            for (c = 0; c < 3; c++)
                CHECK_NEAR(got.rgb0[c] / big[k], ref.rgb0[c], 1e-12 * ref.rgb0[c],
                           "%s, emission %g: element 0's channel %d over the emission against "
                           "emission 1 (relative 1e-12)",
                           twin ? "float" : "fixed", big[k], c);
        }
        /* Dynamic range: the core keeps 2^-16 of the peak's 256, so a light 2^25 times
         * weaker than the brightest rounds to no light at all. */
        n = lit_room(p, 1e30, 1e30 / 67108864.0); /* 2^26 weaker */
        assert_int_equal(solve_scene(twin, p, n, &got, err, sizeof err), 0);
        if (!twin) assert_int_equal(got.sum, ref.sum); /* fixed: gone; the float twin keeps it */
        n = lit_room(p, 1e30, 1e30 / 1024.0);          /* 2^10 weaker: kept */
        assert_int_equal(solve_scene(twin, p, n, &got, err, sizeof err), 0);
        assert_int_not_equal(got.sum, ref.sum);
        /* Non-finite or negative emissions are refused with a message. */
        n = lit_room(p, INFINITY, 0);
        assert_int_equal(solve_scene(twin, p, n, &got, err, sizeof err), -1);
        assert_string_equal(err, "polygon 6 has a negative or non-finite reflectance or emission");
        n = lit_room(p, NAN, 0);
        assert_int_equal(solve_scene(twin, p, n, &got, err, sizeof err), -1);
        n = lit_room(p, -1, 0);
        assert_int_equal(solve_scene(twin, p, n, &got, err, sizeof err), -1);
    }
}

/* Was a bug (tools/host/scene.c, frame_scene()/emit_ch()): with the brightest emission
 * below 256 / DBL_MAX (about 1.4e-306, e.g. "Ke 1e-310 0 0", which the loader accepts),
 * escale = 256 / emax was +inf, 0 * inf = NaN went through RAD_REAL (undefined
 * behaviour) and sc_create failed with "polygon 0 (tag 0): value out of range". A
 * denormal peak must solve like an emission of 1. */
static void test_emission_denormal(void **st)
{
    sc_poly p[16];
    solved_t ref, got;
    char err[256];
    int n;
    (void)st;
    n = lit_room(p, 1, 0);
    assert_int_equal(solve_scene(0, p, n, &ref, err, sizeof err), 0);
    n = lit_room(p, 1e-310, 0);
    if (solve_scene(0, p, n, &got, err, sizeof err) != 0) fail_msg("sc_create: %s", err);
    assert_int_equal(got.sum, ref.sum);
}

/* Was a bug (tools/host/scene.c, frame_scene()): a denormal half-extent passed the
 * isfinite(half) check, gave scale = 32 / half = +inf, and to_core() converted NaN or
 * inf coordinates with RAD_REAL (undefined behaviour). Now: "the scene has no extent". */
static void test_extent_denormal(void **st)
{
    sc_poly p[1];
    char err[256];
    sc_solver *s;
    (void)st;
    p[0] = quad(0, 0, 0, 4e-323, 0, 0, 4e-323, 4e-323, 0, 0, 4e-323, 0);
    set_mat(&p[0], 0.5, 0.5, 0.5, 1, 1, 1);
    s = sc_create(p, 1, NULL, NULL, NULL, err, sizeof err);
    assert_null(s);
    assert_string_equal(err, "the scene has no extent");
}

/* ---- no light ------------------------------------------------------------------------- */

static void test_no_emitter(void **st)
{
    sc_poly p[16];
    sc_opts o = {.max_patch = 0.5, .max_element = 0.25, .res = 16};
    sc_stats stt;
    char err[256];
    int n = lit_room(p, 0, 0), e, twin;
    (void)st;
    for (twin = 0; twin < 2; twin++) {
        double rgb[3];
        float img[8 * 8 * 3];
        sc_camera cam = {.eye = {0, 0, 0.9}, .target = {0, 0, 0}, .up = {0, 1, 0}, .fov_deg = 60};
        int i;
        if (twin) {
            scf_solver *s = scf_create(p, n, &o, NULL, NULL, err, sizeof err);
            assert_non_null(s);
            assert_int_equal(scf_solve(s, 1000, 0.001, NULL, NULL), 0);
            scf_get_stats(s, &stt);
            for (e = 0; e < stt.elements; e++) {
                scf_element_rgb(s, e, 1, rgb);
                CHECK_EQ(rgb[0], 0, "float: element %d's red with no light", e);
                CHECK_EQ(rgb[1], 0, "float: element %d's green with no light", e);
                CHECK_EQ(rgb[2], 0, "float: element %d's blue with no light", e);
            }
            assert_int_equal(scf_render(s, &cam, 1, 8, 8, img, err, sizeof err), 0);
            scf_destroy(s);
        } else {
            sc_solver *s = sc_create(p, n, &o, NULL, NULL, err, sizeof err);
            assert_non_null(s);
            assert_int_equal(sc_solve(s, 1000, 0.001, NULL, NULL), 0);
            sc_get_stats(s, &stt);
            for (e = 0; e < stt.elements; e++) {
                sc_element_rgb(s, e, 1, rgb);
                CHECK_EQ(rgb[0], 0, "fixed: element %d's red with no light", e);
                CHECK_EQ(rgb[1], 0, "fixed: element %d's green with no light", e);
                CHECK_EQ(rgb[2], 0, "fixed: element %d's blue with no light", e);
            }
            assert_int_equal(sc_render(s, &cam, 1, 8, 8, img, err, sizeof err), 0);
            sc_destroy(s);
        }
        assert_int_equal(stt.shots, 0);
        CHECK_EQ(stt.unshot, 0.0, "%s: unshot fraction with no light", twin ? "float" : "fixed");
        assert_int_equal(stt.saturations, 0);
        for (i = 0; i < 8 * 8 * 3; i++)
            CHECK_EQ(img[i], 0.0f, "%s: image value %d with no light", twin ? "float" : "fixed", i);
    }
    /* The core directly: nothing emits, nothing to shoot, fraction 0. */
    {
        static rad_surface_t surf[4];
        static rad_patch_t pat[64];
        static rad_element_t el[64];
        static rad_vec3_t vert[256];
        static unsigned char work[RAD_WORK_BYTES(8, RAD_PIXELS_ALL(8), 256)];
        rad_pools_t pools = {.surfaces = surf,
                             .max_surfaces = 4,
                             .patches = pat,
                             .max_patches = 64,
                             .elements = el,
                             .max_elements = 64,
                             .vertices = vert,
                             .max_vertices = 256,
                             .work = work,
                             .work_bytes = sizeof work};
        rad_config_t cfg = {.max_patch = RAD_REAL(8.0), .max_element = RAD_REAL(4.0), .res = 8};
        rad_vec3_t v[3] = {{0, 0, 0}, {RAD_REAL(4.0), 0, 0}, {0, RAD_REAL(4.0), 0}};
        rad_rgb_t grey = {RAD_REAL(0.5), RAD_REAL(0.5), RAD_REAL(0.5)}, amb;
        rad_scene_t s;
        assert_int_equal(rad_init(&s, &pools, &cfg), RAD_OK);
        assert_int_equal(rad_add_polygon(&s, v, 3, &grey, NULL), 0);
        assert_int_equal(rad_shoot(&s, 10, 0), 0);
        assert_int_equal(rad_unshot_fraction(&s), 0);
        assert_int_equal(rad_ambient(&s, &amb), RAD_OK);
        CHECK_INT_EQ(amb.r, 0, "the core's ambient red with no light");
        CHECK_INT_EQ(amb.g, 0, "the core's ambient green with no light");
        CHECK_INT_EQ(amb.b, 0, "the core's ambient blue with no light");
    }
}

/* ---- unwritable outputs ---------------------------------------------------------------- */

static void expect_write_error(const char *path, int w, const char *msg)
{
    unsigned char rgb[2 * 2 * 3] = {0};
    char err[512], want[600], *before, *after;
    before = listing(tmpdir);
    assert_int_equal(img_write(path, rgb, w, 2, err, sizeof err), -1);
    snprintf(want, sizeof want, "%s: %s", path, msg);
    assert_string_equal(err, want);
    after = listing(tmpdir);
    assert_string_equal(after, before); /* no temporary file, nothing new */
    free(before);
    free(after);
}

static void test_img_write_unwritable(void **st)
{
    unsigned char rgb[2 * 2 * 3] = {0};
    char err[256], *sub;
    (void)st;
    expect_write_error(tmp_path("missing/out.png"), 2,
                       "cannot create temporary file: No such file or directory");
    write_text(tmp_path("a_file"), "x");
    expect_write_error(tmp_path("a_file/out.png"), 2,
                       "cannot create temporary file: Not a directory");
    assert_int_equal(mkdir(tmp_path("dir.png"), 0755), 0);
    expect_write_error(tmp_path("dir.png"), 2, "is a directory");
    expect_write_error(tmp_path("out.jpg"), 2, "unknown image extension (use .png or .ppm)");
    expect_write_error(tmp_path("out.png"), 0, "invalid image size 0x2 (each must be 1..32768)");
    /* img_write itself is atomic: a replaced file is whole, an old one kept on failure. */
    write_text(tmp_path("keep.ppm"), "old");
    assert_int_equal(img_write(tmp_path("keep.ppm"), rgb, 0, 2, err, sizeof err), -1);
    sub = slurp(tmp_path("keep.ppm"), NULL);
    assert_string_equal(sub, "old");
    free(sub);
    /* A read-only directory (meaningless for root, who may write anywhere). */
    if (geteuid() != 0) {
        assert_int_equal(mkdir(tmp_path("ro"), 0555), 0);
        expect_write_error(tmp_path("ro/out.png"), 2,
                           "cannot create temporary file: Permission denied");
        chmod(tmp_path("ro"), 0755);
    }
    remove_tree(tmp_path("dir.png"));
    unlink(tmp_path("a_file"));
    unlink(tmp_path("keep.ppm"));
    rmdir(tmp_path("ro"));
}

/* ---- the hemi-cube in bands ----------------------------------------------------------- */

/* The same scene solved with all faces at once and in bands of 1, 2, 3 and 7 rows (the
 * core's answer to a small work buffer): the same bits, in both builds. */
static void test_bands_bit_exact(void **st)
{
    static const int rows[] = {1, 2, 3, 7};
    sc_poly p[16];
    char err[256];
    int n = lit_room(p, 1, 0.5), r, twin, res, shots = light() ? 10 : 40;
    int top = light() ? 16 : 32;
    (void)st;
    for (res = 8; res <= (RAD_MAX_RES < top ? RAD_MAX_RES : top); res *= 2)
        for (twin = 0; twin < 2; twin++) {
            uint64_t all = 0;
            double *ff_all = NULL;
            int ne = 0;
            for (r = -1; r < 4; r++) {
                sc_opts o = {.max_patch = 0.5,
                             .max_element = 0.25,
                             .res = res,
                             .band_rows = r < 0 ? 0 : rows[r]};
                uint64_t sum;
                double *ff;
                sc_stats stt;
                if (twin) {
                    scf_solver *s = scf_create(p, n, &o, NULL, NULL, err, sizeof err);
                    assert_non_null(s);
                    scf_solve(s, shots, 1e-4, NULL, NULL);
                    sum = scf_checksum(s);
                    scf_get_stats(s, &stt);
                    ff = calloc((size_t)stt.elements, sizeof *ff);
                    assert_int_equal(scf_form_factors(s, 3, ff), 0);
                    scf_destroy(s);
                } else {
                    sc_solver *s = sc_create(p, n, &o, NULL, NULL, err, sizeof err);
                    assert_non_null(s);
                    sc_solve(s, shots, 1e-4, NULL, NULL);
                    sum = sc_checksum(s);
                    sc_get_stats(s, &stt);
                    ff = calloc((size_t)stt.elements, sizeof *ff);
                    assert_int_equal(sc_form_factors(s, 3, ff), 0);
                    sc_destroy(s);
                }
                if (r < 0) {
                    all = sum;
                    ff_all = ff;
                    ne = stt.elements;
                } else {
                    assert_int_equal(stt.elements, ne);
                    assert_int_equal(sum, all);
                    assert_memory_equal(ff, ff_all, (size_t)ne * sizeof *ff);
                    free(ff);
                }
            }
            free(ff_all);
        }
}

/* ---- small compile-time limits ---------------------------------------------------------- */

/* The hemi-cube resolution stops at RAD_MAX_RES, with a message from the glue. */
static void test_max_res(void **st)
{
    sc_poly p[16];
    sc_opts o = {.max_patch = 0.5, .max_element = 0.25, .res = RAD_MAX_RES};
    char err[256];
    int n = lit_room(p, 1, 0);
    sc_solver *s;
    (void)st;
    s = sc_create(p, n, &o, NULL, NULL, err, sizeof err);
    assert_non_null(s);
    CHECK_INT_EQ(sc_solve(s, light() ? 1 : 3, 0, NULL, NULL), light() ? 1 : 3,
                 "shots at RAD_MAX_RES");
    sc_destroy(s);
    o.res = RAD_MAX_RES + 2;
    assert_null(sc_create(p, n, &o, NULL, NULL, err, sizeof err));
    assert_string_equal(err, "cannot set up the solver: invalid argument");
    o.res = 6;
    assert_null(sc_create(p, n, &o, NULL, NULL, err, sizeof err));
    assert_string_equal(err, "cannot set up the solver: invalid argument");
}

/* Pool counts stop at RAD_INDEX_NONE - 1 (65534 with 16-bit indices): rad_init refuses
 * larger ones before touching any pool. */
static void test_index_limits(void **st)
{
    static rad_surface_t surf[1];
    static rad_patch_t pat[1];
    static rad_element_t el[1];
    static rad_vec3_t vert[1];
    static unsigned char work[1 << 16];
    rad_pools_t pools = {.surfaces = surf,
                         .max_surfaces = 1,
                         .patches = pat,
                         .max_patches = 1,
                         .elements = el,
                         .max_elements = 1,
                         .vertices = vert,
                         .max_vertices = 1,
                         .work = work,
                         .work_bytes = sizeof work};
    rad_config_t cfg = {.res = 8};
    rad_scene_t s;
    (void)st;
    /* Counts beyond the index width are refused before any pool is touched. */
    pools.max_elements = (uint32_t)RAD_INDEX_NONE;
    assert_int_equal(rad_init(&s, &pools, &cfg), RAD_ERR_ARG);
    pools.max_elements = 1;
    pools.max_vertices = (uint32_t)RAD_INDEX_NONE;
    assert_int_equal(rad_init(&s, &pools, &cfg), RAD_ERR_ARG);
    pools.max_vertices = 1;
    assert_int_equal(rad_init(&s, &pools, &cfg), RAD_OK);
}

#if RAD_INDEX_BITS == 16
/* Was a bug (16-bit indices, tools/host/scene.c, alloc_pools()): the pools were sized
 * from the element estimate (max_vertices = 3 * estimate, max_surfaces = 2 * polygons
 * + 1) without a cap at RAD_INDEX_NONE - 1, so rad_init refused them and sc_create
 * failed with "cannot set up the solver: invalid argument" for any scene estimated
 * above 21,845 elements, even one that fits, like these 6,000 one-element triangles
 * (6,000 elements, 18,000 vertices). */
static void test_index16_pools(void **st)
{
    int n = 6000, i;
    sc_poly *p = calloc((size_t)n, sizeof *p);
    char err[256];
    sc_solver *s;
    (void)st;
    assert_non_null(p);
    for (i = 0; i < n; i++) {
        double x = (i % 100) * 2.0, y = (i / 100) * 2.0;
        p[i].n = 3;
        p[i].v[0][0] = x;
        p[i].v[0][1] = y;
        p[i].v[1][0] = x + 1;
        p[i].v[1][1] = y;
        p[i].v[2][0] = x;
        p[i].v[2][1] = y + 1;
        set_mat(&p[i], 0.5, 0.5, 0.5, i == 0, i == 0, i == 0);
    }
    s = sc_create(p, n, NULL, NULL, NULL, err, sizeof err);
    if (!s) fail_msg("sc_create: %s", err);
    sc_destroy(s);
    free(p);
}
#endif

/* ---- rad_cli end to end ------------------------------------------------------------------ */

typedef struct {
    int status;
    char *out, *err;
} run_t;

static void need_cli(void)
{
    if (access(CLI, X_OK) != 0) {
        print_message("%s is missing (make all): skipped\n", CLI);
        skip();
    }
}

static void run_cli(run_t *r, const char *const *args)
{
    static int seq;
    char outp[300], errp[300], *argv[40];
    posix_spawn_file_actions_t fa;
    struct timespec t0, t, nap = {0, 5000000};
    pid_t pid;
    int n = 0, st = 0;
    snprintf(outp, sizeof outp, "%s/run%03d.out", tmpdir, seq);
    snprintf(errp, sizeof errp, "%s/run%03d.err", tmpdir, seq++);
    argv[n++] = (char *)CLI;
    while (args[n - 1] && n < 39) {
        argv[n] = (char *)args[n - 1];
        n++;
    }
    argv[n] = NULL;
    assert_int_equal(posix_spawn_file_actions_init(&fa), 0);
    posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&fa, 1, outp, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    posix_spawn_file_actions_addopen(&fa, 2, errp, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    assert_int_equal(posix_spawn(&pid, CLI, &fa, NULL, argv, environ), 0);
    posix_spawn_file_actions_destroy(&fa);
    clock_gettime(CLOCK_MONOTONIC, &t0);
    while (waitpid(pid, &st, WNOHANG) != pid) {
        clock_gettime(CLOCK_MONOTONIC, &t);
        if ((double)(t.tv_sec - t0.tv_sec) > RUN_TIMEOUT_S) {
            kill(pid, SIGKILL);
            waitpid(pid, &st, 0);
            fail_msg("rad_cli timed out after %.0f s", RUN_TIMEOUT_S);
        }
        nanosleep(&nap, NULL);
    }
    r->status = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
    r->out = slurp(outp, NULL);
    r->err = slurp(errp, NULL);
    assert_non_null(r->out);
    assert_non_null(r->err);
    unlink(outp);
    unlink(errp);
}
#define RUN(r, ...) run_cli((r), (const char *const[]){__VA_ARGS__, NULL})

static void run_free(run_t *r)
{
    free(r->out);
    free(r->err);
}

static void expect_cli(const run_t *r, int status, const char *err_line)
{
    if (r->status != status || (err_line && strcmp(r->err, err_line) != 0))
        fail_msg("exit %d (want %d)\nstderr: %s\nwanted: %s", r->status, status, r->err,
                 err_line ? err_line : "(anything)");
}

static int file_exists(const char *p)
{
    struct stat s;
    return stat(p, &s) == 0;
}

/* A copy of the Cornell box whose light has emission KE ("R G B"). */
static const char *cornell_with(const char *name, const char *ke)
{
    char mtl[64], *obj, *m, *at, *text;
    size_t len;
    snprintf(mtl, sizeof mtl, "%s.mtl", name);
    obj = slurp(CORNELL, &len);
    assert_non_null(obj);
    at = strstr(obj, "mtllib cornell_box.mtl");
    assert_non_null(at);
    text = malloc(len + 64);
    assert_non_null(text);
    sprintf(text, "%.*smtllib %s%s", (int)(at - obj), obj, mtl,
            at + strlen("mtllib cornell_box.mtl"));
    write_text(tmp_path(name), text);
    m = slurp("examples/cornell_box.mtl", NULL);
    assert_non_null(m);
    at = strstr(m, "Ke 18.0 12.8 4.4");
    assert_non_null(at);
    sprintf(text, "%.*sKe %s%s", (int)(at - m), m, ke, at + strlen("Ke 18.0 12.8 4.4"));
    write_text(tmp_path(mtl), text);
    free(text);
    free(obj);
    free(m);
    return tmp_path(name);
}

/* Emission 1e30 (the loader's limit) renders the image of emission 1 exactly: the glue
 * rescales, nothing saturates, auto exposure removes the scale. */
static void test_cli_huge_emission(void **st)
{
    run_t a, b;
    img_t ia, ib;
    char e1[256], e2[256], obj1[320], obj2[320];
    (void)st;
    need_cli();
    strcpy(obj1, cornell_with("ke1.obj", "1 0.7 0.25"));
    strcpy(obj2, cornell_with("ke30.obj", "1e30 0.7e30 0.25e30"));
    RUN(&a, obj1, "-o", tmp_path("ke1.png"), "--res", "16", "--width", "48", "--height", "48",
        "--max-element", "0.05", "--stats");
    RUN(&b, obj2, "-o", tmp_path("ke30.png"), "--res", "16", "--width", "48", "--height", "48",
        "--max-element", "0.05", "--stats");
    expect_cli(&a, 0, NULL);
    expect_cli(&b, 0, NULL);
    CHECK_CONTAINS(b.out, "saturations 0\n", "rad_cli's stdout");
    assert_int_equal(img_read(tmp_path("ke1.png"), &ia, e1, sizeof e1), 0);
    assert_int_equal(img_read(tmp_path("ke30.png"), &ib, e2, sizeof e2), 0);
    assert_int_equal(ia.w, ib.w);
    {
        size_t i, off = 0;
        for (i = 0; i < (size_t)ia.w * ia.h * 3; i++) {
            int d = ia.rgb[i] - ib.rgb[i];
            if (d < -1 || d > 1) off++;
        }
        assert_int_equal(off, 0); /* within one level: exposure is rounded once per scene */
    }
    img_free(&ia);
    img_free(&ib);
    run_free(&a);
    run_free(&b);
    /* Beyond the loader's limit: one located line, exit 1. */
    cornell_with("ke31.obj", "1e31 0 0");
    RUN(&a, tmp_path("ke31.obj"), "-o", tmp_path("ke31.png"));
    {
        char want[600];
        snprintf(want, sizeof want, "rad_cli: %s:11: number out of range '1e31' (limit 1e30)\n",
                 tmp_path("ke31.obj.mtl"));
        expect_cli(&a, 1, want);
    }
    CHECK_THAT(!file_exists(tmp_path("ke31.png")), "%s is not written", tmp_path("ke31.png"));
    run_free(&a);
}

/* Was a bug (see test_emission_denormal): through rad_cli an MTL with "Ke 1e-310 0 0"
 * failed with "polygon 0 (tag 0): value out of range" after undefined behaviour. */
static void test_cli_denormal_emission(void **st)
{
    run_t r;
    (void)st;
    need_cli();
    RUN(&r, cornell_with("ke_denormal.obj", "1e-310 0 0"), "-o", tmp_path("den.png"), "--res", "16",
        "--width", "16", "--height", "16");
    expect_cli(&r, 0, NULL);
    run_free(&r);
}

static void test_cli_hostile_files(void **st)
{
    run_t r;
    char want[600], *text;
    size_t n;
    (void)st;
    need_cli();
    /* Binary data. */
    write_file(tmp_path("bin.obj"), "v 0 0 0\n\0\x01\x02", 11);
    RUN(&r, tmp_path("bin.obj"), "-o", tmp_path("bin.png"));
    snprintf(want, sizeof want, "rad_cli: %s:2: binary data (NUL byte)\n", tmp_path("bin.obj"));
    expect_cli(&r, 1, want);
    CHECK_THAT(!file_exists(tmp_path("bin.png")), "%s is not written", tmp_path("bin.png"));
    run_free(&r);
    /* A megabyte line. */
    text = malloc((1 << 20) + 16);
    assert_non_null(text);
    n = (size_t)sprintf(text, "v 0 0 ");
    memset(text + n, '9', 1 << 20);
    strcpy(text + n + (1 << 20), "\n");
    write_text(tmp_path("mb.obj"), text);
    free(text);
    RUN(&r, tmp_path("mb.obj"), "-o", tmp_path("mb.png"));
    snprintf(want, sizeof want,
             "rad_cli: %s:1: number out of range '9999999999999999999999999999999999999999' (limit "
             "1e30)\n",
             tmp_path("mb.obj"));
    expect_cli(&r, 1, want);
    run_free(&r);
    /* Out-of-range index. */
    write_text(tmp_path("idx.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n");
    RUN(&r, tmp_path("idx.obj"), "-o", tmp_path("idx.png"));
    snprintf(want, sizeof want,
             "rad_cli: %s:4: vertex index -4 out of range (3 vertices defined so far)\n",
             tmp_path("idx.obj"));
    expect_cli(&r, 1, want);
    run_free(&r);
    /* No light: a warning, a black image, exit 0. */
    write_text(tmp_path("dark.obj"), "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
    RUN(&r, tmp_path("dark.obj"), "-o", tmp_path("dark.png"), "--res", "8", "--width", "8",
        "--height", "8");
    expect_cli(&r, 0, NULL);
    CHECK_CONTAINS(r.err, "no material emits light (Ke), so the image is black",
                   "rad_cli's stderr");
    CHECK_THAT(file_exists(tmp_path("dark.png")), "%s was written", tmp_path("dark.png"));
    run_free(&r);
    unlink(tmp_path("dark.png"));
}

/* The element pool fills (elements of 1/1024 of the scene: more than 4,000,000): one
 * line naming the limit, exit 1, and no image written. */
static void test_cli_pools_full(void **st)
{
    run_t r;
    char want[600], *before, *after;
    (void)st;
    need_cli();
    before = listing(tmpdir);
    RUN(&r, CORNELL, "-o", tmp_path("full.png"), "--max-element", "0.00055", "--max-patch", "0.5",
        "--res", "16", "--export-ply", tmp_path("full.ply"), "--dump-radiosity",
        tmp_path("full.csv"));
    snprintf(want, sizeof want,
             "rad_cli: %s: the scene needs more than %s elements: raise the element size\n",
             CORNELL,
             RAD_INDEX_BITS == 16 ? "65534" : "4000000"); /* the index width caps the pools */
    expect_cli(&r, 1, want);
    after = listing(tmpdir);
    assert_string_equal(after, before);
    free(before);
    free(after);
    run_free(&r);
}

/* Half a million faces (fifty thousand in light mode) go through: one shot, a small view
 * (with 16-bit indices: a clear refusal). */
static void test_cli_many_faces(void **st)
{
    long nv = light() ? 50000 : 500000, nf = nv;
    run_t r;
    const char *obj = tmp_path("many.obj");
    FILE *f;
    long i;
    (void)st;
    need_cli();
    write_big_obj(obj, nv, nf);
    f = fopen(obj, "a");
    assert_non_null(f);
    fprintf(f, "mtllib many.mtl\nusemtl lamp\nv 0 0 1\nv 10 0 1\nv 0 10 1\nf -3 -1 -2\n");
    fclose(f);
    write_text(tmp_path("many.mtl"), "newmtl lamp\nKd 0.5\nKe 1\n");
    RUN(&r, obj, "-o", tmp_path("many.png"), "--res", "8", "--width", "16", "--height", "16",
        "--max-shots", "1", "--stats", "--quiet");
#if RAD_INDEX_BITS == 16
    { /* more elements than 16-bit indices count: said so, nothing written (past the
         * limit in faces alone, on the face's line, before any polygon is built; else
         * once the mesh is planned) */
        expect_cli(&r, 1, NULL);
        CHECK_THAT(!strncmp(r.err, "rad_cli: ", 9) && strstr(r.err, obj) &&
                       strstr(r.err, "65534 elements") &&
                       strchr(r.err, '\n') == r.err + strlen(r.err) - 1,
                   "one line naming the file and the element limit: %s", r.err);
        CHECK_THAT(!file_exists(tmp_path("many.png")), "%s is not written", tmp_path("many.png"));
        run_free(&r);
        unlink(obj);
        return;
    }
#endif
    expect_cli(&r, 3, NULL); /* one shot: outputs written, not converged (exit 3) */
    CHECK_CONTAINS(r.out, "shots 1 ", "rad_cli's stdout");
    i = 0;
    sscanf(strstr(r.out, "elements ") + 9, "%ld", &i);
    CHECK_INT_GE(i, nf, "elements of the many-faces scene against its faces");
    CHECK_THAT(file_exists(tmp_path("many.png")), "%s was written", tmp_path("many.png"));
    run_free(&r);
    unlink(obj);
    unlink(tmp_path("many.png"));
}

/* Cost bombs from small files, refused before they cost: a scene over the memory
 * budget at the line where the budget runs out (RAD_MEMORY_BUDGET: 1 MB against 2.1
 * MB of parse for 30,000 faces), and more faces with an area than the solver holds
 * elements (4,000,001 faces "f 1 2 3", 32 MB: refused after the parse, before the
 * polygons; it took 3.3 GB at 100 MB to reach the same refusal). Nothing is written. */
static void test_cli_cost_bombs(void **st)
{
    run_t r;
    char want[600];
    const char *obj = tmp_path("bomb.obj");
    FILE *f;
    long i, nf = RAD_INDEX_BITS == 16 ? 65535 : 4000001;
    (void)st;
    need_cli();
    write_big_obj(obj, 30000, 30000); /* 24 + 60 bytes per line: over 1 MB within the faces */
    assert_int_equal(setenv("RAD_MEMORY_BUDGET", "1000000", 1), 0);
    RUN(&r, obj, "-o", tmp_path("bomb.png"));
    unsetenv("RAD_MEMORY_BUDGET");
    CHECK_THAT(r.status == 1 && strstr(r.err, "needs more than the memory budget of 1 MB (") &&
                   strstr(r.err, "bomb.obj:"),
               "exit %d, stderr %s", r.status, r.err);
    run_free(&r);
    CHECK_THAT(!file_exists(tmp_path("bomb.png")), "%s is not written", tmp_path("bomb.png"));
    if (light()) return; /* 32 MB and a 270 MB parse: not under valgrind */
    f = fopen(obj, "w");
    assert_non_null(f);
    setvbuf(f, NULL, _IOFBF, 1 << 20);
    fputs("v 0 0 0\nv 1 0 0\nv 0 1 0\n", f);
    for (i = 0; i < nf; i++) fputs("f 1 2 3\n", f);
    assert_int_equal(fclose(f), 0);
    RUN(&r, obj, "-o", tmp_path("bomb.png"), "--quiet");
    snprintf(want, sizeof want,
             "rad_cli: %s:%ld: face %ld with an area: more than the %ld elements the solver holds "
             "(each face is at least one element): simplify or split the scene\n",
             obj, nf + 3, nf, nf - 1);
    expect_cli(&r, 1, want);
    run_free(&r);
    CHECK_THAT(!file_exists(tmp_path("bomb.png")), "%s is not written", tmp_path("bomb.png"));
    unlink(obj);
}

/* Outputs that cannot be written: refused before the solve, nothing left behind. */
static void test_cli_unwritable_output(void **st)
{
    run_t r;
    char want[600], *before, *after;
    (void)st;
    need_cli();
    before = listing(tmpdir);
    RUN(&r, CORNELL, "-o", tmp_path("nodir/x.png"));
    snprintf(want, sizeof want, "rad_cli: %s: cannot write into '%s': No such file or directory\n",
             tmp_path("nodir/x.png"), tmp_path("nodir"));
    expect_cli(&r, 1, want);
    run_free(&r);
    /* The output is a directory: refused before the solve (fio_check_out); the
     * directory is untouched and no temporary file stays. */
    assert_int_equal(mkdir(tmp_path("d.png"), 0755), 0);
    free(before);
    before = listing(tmpdir);
    RUN(&r, CORNELL, "-o", tmp_path("d.png"), "--res", "8", "--width", "8", "--height", "8",
        "--max-element", "0.2");
    snprintf(want, sizeof want, "rad_cli: %s: is a directory\n", tmp_path("d.png"));
    expect_cli(&r, 1, want);
    after = listing(tmpdir);
    assert_string_equal(after, before);
    free(after);
    free(before);
    run_free(&r);
    rmdir(tmp_path("d.png"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_obj_truncated),
        cmocka_unit_test(test_obj_binary),
        cmocka_unit_test(test_obj_megabyte_lines),
        cmocka_unit_test(test_obj_index_out_of_range),
        cmocka_unit_test(test_millions_of_vertices),
        cmocka_unit_test(test_emission_overflow),
        cmocka_unit_test(test_emission_denormal),
        cmocka_unit_test(test_extent_denormal),
        cmocka_unit_test(test_no_emitter),
        cmocka_unit_test(test_img_write_unwritable),
        cmocka_unit_test(test_bands_bit_exact),
        cmocka_unit_test(test_max_res),
        cmocka_unit_test(test_index_limits),
#if RAD_INDEX_BITS == 16
        cmocka_unit_test(test_index16_pools),
#endif
        cmocka_unit_test(test_cli_huge_emission),
        cmocka_unit_test(test_cli_denormal_emission),
        cmocka_unit_test(test_cli_hostile_files),
        cmocka_unit_test(test_cli_pools_full),
        cmocka_unit_test(test_cli_many_faces),
        cmocka_unit_test(test_cli_unwritable_output),
        cmocka_unit_test(test_cli_cost_bombs),
    };
    return cmocka_run_group_tests_name("hostile", tests, group_setup, group_teardown);
}
