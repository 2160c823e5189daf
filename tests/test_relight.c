/* SPDX-License-Identifier: MIT */
/* Stored form factors through the host glue (tools/host/scene.c) and rad_cli: saving and
 * loading rows (tools/formats/ff_file.c), every way a file can be wrong, relighting a solved scene
 * without rendering a hemi-cube, Gauss-Seidel against progressive refinement, light
 * groups and their mix, --each-group and --animate.
 *
 * Scenes go through the glue as rad_cli sends them (scaled to +-32 units, the brightest
 * emission to 256), where Q16.16 energies keep their precision.
 *
 * Comparisons are per element and channel, over values above 1% of the brightest, with
 * the ambient term (the display value). The bound for "relit / mixed from stored rows"
 * against "solved afresh" is the 16-bit code's 2^-11 = 0.049% per form factor plus
 * rounding and the difference of two solves stopped at the same tolerance: REL_BOUND.
 * Measured figures are printed.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
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
#include "formats/ff_file.h"
#include "formats/image.h"
#include "tmpdir.h"
#include "formats/obj.h"
#include "host/clock.h"
#include "host/polys.h"
#include "reference/reference.h"
#include "host/scene.h"

extern char **environ;

#define FIXED   "build/rad_cli"
#define FLOAT   "build/rad_cli_float"
#define CORNELL "examples/cornell_box.obj"
#define GALLERY "examples/gallery.obj"
#define DATA    "tests/data/relight/"
#define COARSE  "--max-element", "0.1", "--res", "32" /* the 0.56 m Cornell box */
#define GCOARSE "--max-element", "0.3", "--res", "32" /* the 6 m gallery */

/* Relit or mixed from rows against a fresh solve: the code's 0.05% and what two solves
 * to a tolerance of 1e-4 differ by (the printed figures show the margin). */
#define REL_BOUND 0.002
/* Gauss-Seidel against shooting, the same equations solved two ways: 0.5% per element. */
#define GS_BOUND  0.005

/* ---- temporary directory ---------------------------------------------------------- */

TMPDIR_GROUP("relight")

static unsigned char *slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    unsigned char *buf = NULL;
    long n;
    if (!f) return NULL;
    if (fseek(f, 0, SEEK_END) == 0 && (n = ftell(f)) >= 0 && fseek(f, 0, SEEK_SET) == 0) {
        buf = malloc((size_t)n + 1);
        if (buf && fread(buf, 1, (size_t)n, f) != (size_t)n) {
            free(buf);
            buf = NULL;
        }
        if (buf) {
            buf[n] = 0;
            *len = (size_t)n;
        }
    }
    fclose(f);
    return buf;
}

static void spit(const char *path, const unsigned char *d, size_t n)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(d, 1, n, f), n);
    assert_int_equal(fclose(f), 0);
}

/* ---- scenes through the glue -------------------------------------------------------- */

typedef struct {
    obj_scene sc;
    sc_poly *p;
    int n;
} scene_t;

static void scene_load(scene_t *s, const char *path)
{
    char err[512];
    if (obj_load(path, &s->sc, NULL, NULL, err, sizeof err) < 0) fail_msg("%s", err);
    s->p = polys_from_obj(&s->sc, &s->n, NULL, NULL);
    assert_non_null(s->p);
}

static void scene_free(scene_t *s)
{
    free(s->p);
    obj_free(&s->sc);
}

static int material_of(const scene_t *s, const char *name)
{
    int m = obj_find_material(&s->sc, name);
    CHECK_INT_GE(m, 0, "material %s in the scene", name);
    return m;
}

/* Sets reflectance and/or emission of material M in the polygon list (a fresh scene). */
static void polys_set(scene_t *s, int m, const double *rho, const double *emit)
{
    int i;
    for (i = 0; i < s->n; i++)
        if (s->sc.faces[s->p[i].tag].material == m) {
            if (rho) memcpy(s->p[i].rho, rho, sizeof s->p[i].rho);
            if (emit) memcpy(s->p[i].emit, emit, sizeof s->p[i].emit);
        }
}

/* Relights material M of a solver built from S through the glue. */
static void relight(sc_solver *h, const scene_t *s, int m, const double *rho, const double *emit)
{
    char err[256];
    polys_material_match mt;
    mt.sc = &s->sc;
    mt.material = m;
    if (sc_set_surfaces(h, polys_match_material, &mt, rho, emit, err, sizeof err) <= 0)
        fail_msg("set_surfaces: %s", err);
}

static sc_solver *make(const scene_t *s, double max_element, int res)
{
    sc_opts o;
    char err[512];
    sc_solver *h;
    memset(&o, 0, sizeof o);
    o.max_element = max_element;
    o.res = res;
    h = sc_create(s->p, s->n, &o, NULL, NULL, err, sizeof err);
    if (!h) fail_msg("sc_create: %s", err);
    return h;
}

static scf_solver *makef(const scene_t *s, double max_element, int res)
{
    sc_opts o;
    char err[512];
    scf_solver *h;
    memset(&o, 0, sizeof o);
    o.max_element = max_element;
    o.res = res;
    h = scf_create(s->p, s->n, &o, NULL, NULL, err, sizeof err);
    if (!h) fail_msg("scf_create: %s", err);
    return h;
}

static void rows(sc_solver *h)
{
    char err[256];
    if (sc_rows_compute(h, NULL, NULL, err, sizeof err) < 0) fail_msg("rows: %s", err);
}

static unsigned long raster_calls(sc_solver *h)
{
    sc_stats st;
    sc_get_stats(h, &st);
    return st.raster_calls;
}

/* Display values (with the ambient term) of every element, in caller units. */
static double *values(sc_solver *h)
{
    sc_stats st;
    double *v;
    int e;
    sc_get_stats(h, &st);
    v = malloc((size_t)st.elements * 3 * sizeof *v);
    assert_non_null(v);
    for (e = 0; e < st.elements; e++) sc_element_rgb(h, e, 1, &v[3 * e]);
    return v;
}

/* Max relative difference of A against B over channels above 1% of B's brightest. */
static double max_rel(const double *a, const double *b, int n, double *rms)
{
    double worst, r;
    ref_rgb_diff(a, b, n, &worst, &r);
    if (rms) *rms = r;
    return worst;
}

static int n_elements(sc_solver *h)
{
    sc_stats st;
    sc_get_stats(h, &st);
    return st.elements;
}

/* ---- the file: save, load, every mismatch ------------------------------------------ */

static void expect_load_error(sc_solver *h, const char *path, const char *what)
{
    char err[1024] = "";
    assert_int_equal(sc_rows_load(h, path, err, sizeof err), -1);
    if (!strstr(err, what) || strncmp(err, path, strlen(path)) != 0)
        fail_msg("loading %s: '%s' does not name the file and '%s'", path, err, what);
}

static void test_save_load_glue(void **state)
{
    scene_t cb;
    sc_solver *a, *b;
    scf_solver *f;
    sc_rows_stats ra, rb;
    char err[512];
    const char *path = tmp_path("cb.ff"), *fpath = tmp_path("cb_float.ff");
    struct stat st;
    (void)state;
    scene_load(&cb, CORNELL);
    a = make(&cb, 0.05, 64);
    b = make(&cb, 0.05, 64);
    rows(a);
    assert_int_equal(sc_rows_save(a, path, err, sizeof err), 0);
    assert_int_equal(sc_rows_load(b, path, err, sizeof err), 0);
    assert_int_equal(raster_calls(b), 0); /* loading renders nothing */
    sc_get_rows_stats(a, &ra);
    sc_get_rows_stats(b, &rb);
    assert_int_equal(ra.entries, rb.entries);
    assert_int_equal(ra.bytes, rb.bytes);
    assert_int_equal(stat(path, &st), 0);
    assert_int_equal((size_t)st.st_size, 48 + 4 * ((size_t)ra.rows + 1) + 6 * (size_t)ra.entries);
    CHECK_INT_GT(sc_rows_solve(a, 1000000, 0.001, NULL, NULL), 0, "shots from the rows");
    CHECK_INT_GT(sc_rows_solve(b, 1000000, 0.001, NULL, NULL), 0, "shots from the rows");
    assert_int_equal(sc_checksum(a), sc_checksum(b)); /* the same rows, the same bits */
    assert_int_equal(raster_calls(b), 0);

    /* The float twin's rows load in the float twin, and not in the fixed build. */
    f = makef(&cb, 0.05, 64);
    assert_int_equal(scf_rows_compute(f, NULL, NULL, err, sizeof err), 0);
    assert_int_equal(scf_rows_save(f, fpath, err, sizeof err), 0);
    assert_int_equal(scf_rows_load(f, fpath, err, sizeof err), 0);
    expect_load_error(b, fpath, "made by the float build, this is the fixed build");
    assert_int_equal(scf_rows_load(f, path, err, sizeof err), -1);
    CHECK_CONTAINS(err, "made by the fixed build", "the error message");
    scf_destroy(f);
    sc_destroy(a);
    sc_destroy(b);
    scene_free(&cb);
}

static void test_load_mismatch(void **state)
{
    scene_t cb, ga, moved;
    sc_solver *a, *h;
    char err[512];
    const char *path = tmp_path("mismatch.ff");
    int i, k;
    (void)state;
    scene_load(&cb, CORNELL);
    scene_load(&ga, GALLERY);
    scene_load(&moved, CORNELL);
    a = make(&cb, 0.05, 64);
    rows(a);
    assert_int_equal(sc_rows_save(a, path, err, sizeof err), 0);
    /* Another scene. */
    h = make(&ga, 0, 64);
    expect_load_error(h, path, "scene mismatch");
    sc_destroy(h);
    /* Another mesh size. */
    h = make(&cb, 0.06, 64);
    expect_load_error(h, path, "scene mismatch");
    sc_destroy(h);
    /* Another hemi-cube resolution. */
    h = make(&cb, 0.05, 32);
    expect_load_error(h, path, "resolution 64, this run uses 32");
    sc_destroy(h);
    /* The same counts, one block nudged by 1 mm: only the fingerprint tells. */
    for (i = 0; i < moved.n; i++)
        if (moved.p[i].tag >= 6 && moved.p[i].tag <= 10) /* faces of the short block */
            for (k = 0; k < moved.p[i].n; k++) moved.p[i].v[k][0] += 0.001;
    h = make(&moved, 0.05, 64);
    assert_int_equal(n_elements(h), n_elements(a));
    expect_load_error(h, path, "fingerprint differs");
    /* After a failed load there are no rows: solving from them is refused. */
    assert_int_equal(sc_rows_solve(h, 10, 0.001, NULL, NULL), -1);
    sc_destroy(h);
    sc_destroy(a);
    scene_free(&cb);
    scene_free(&ga);
    scene_free(&moved);
}

/* Rewrites the trailing checksum after an edit, so only the structure checks see it. */
static void reseal(unsigned char *d, size_t n)
{
    uint64_t h = ff_file_fnv(FF_FILE_FNV_START, d, n - 8);
    int i;
    for (i = 0; i < 8; i++) d[n - 8 + (size_t)i] = (unsigned char)(h >> (8 * i));
}

static void test_corrupt_files(void **state)
{
    scene_t cb;
    sc_solver *a;
    char err[512];
    const char *path = tmp_path("good.ff"), *bad = tmp_path("bad.ff");
    unsigned char *d, *c;
    size_t n;
    (void)state;
    scene_load(&cb, CORNELL);
    a = make(&cb, 0.1, 32);
    rows(a);
    assert_int_equal(sc_rows_save(a, path, err, sizeof err), 0);
    d = slurp(path, &n);
    assert_non_null(d);
    c = malloc(n);
    assert_non_null(c);

    memcpy(c, d, n);
    c[n / 2] ^= 0x10;
    spit(bad, c, n); /* a flipped bit mid-file */
    expect_load_error(a, bad, "checksum mismatch");
    memcpy(c, d, n);
    c[n - 3] ^= 1;
    spit(bad, c, n); /* in the checksum itself */
    expect_load_error(a, bad, "checksum mismatch");
    spit(bad, d, n - 1000); /* truncated */
    expect_load_error(a, bad, "truncated");
    spit(bad, d, 20); /* inside the header */
    expect_load_error(a, bad, "truncated");
    spit(bad, d, 0); /* empty */
    expect_load_error(a, bad, "truncated");
    spit(bad, d, n - 8); /* no checksum */
    expect_load_error(a, bad, "truncated");
    memcpy(c, d, n);
    c[0] = 'X';
    spit(bad, c, n); /* another kind of file */
    expect_load_error(a, bad, "bad magic");
    expect_load_error(a, CORNELL, "bad magic");
    memcpy(c, d, n);
    c[6] = 9;
    spit(bad, c, n); /* a future version */
    expect_load_error(a, bad, "unsupported format version 9");
    { /* bytes past the end */
        unsigned char *e = malloc(n + 4);
        assert_non_null(e);
        memcpy(e, d, n);
        memset(e + n, 0, 4);
        spit(bad, e, n + 4);
        expect_load_error(a, bad, "checksum mismatch");
        free(e);
    }
    /* A valid checksum over bad contents: an element id past the end, a code no
     * hemi-cube gives. */
    memcpy(c, d, n);
    {
        uint32_t patches =
            (uint32_t)c[12] | (uint32_t)c[13] << 8 | (uint32_t)c[14] << 16 | (uint32_t)c[15] << 24;
        size_t ids = 40 + 4 * ((size_t)patches + 1);
        c[ids] = 0xFF;
        c[ids + 1] = 0xFF;
        c[ids + 2] = 0xFF;
        c[ids + 3] = 0x7F;
        reseal(c, n);
        spit(bad, c, n);
        expect_load_error(a, bad, "corrupt entry");
        memcpy(c, d, n);
        c[n - 10] = 0xFF;
        c[n - 9] = 0xFF; /* the last code */
        reseal(c, n);
        spit(bad, c, n);
        expect_load_error(a, bad, "corrupt form factor code");
    }
    expect_load_error(a, tmp_path("missing.ff"), "cannot open");
    /* The good file still loads. */
    assert_int_equal(sc_rows_load(a, path, err, sizeof err), 0);
    /* Saving is atomic: into a folder that does not exist fails, nothing is left. */
    assert_int_equal(sc_rows_save(a, tmp_path("nodir/x.ff"), err, sizeof err), -1);
    CHECK_CONTAINS(err, "nodir/x.ff", "the error message");
    free(c);
    free(d);
    sc_destroy(a);
    scene_free(&cb);
}

/* ---- relighting, Gauss-Seidel, light groups ----------------------------------------- */

static void test_relight_cornell(void **state)
{
    scene_t cb, fresh;
    sc_solver *h, *f, *r;
    sc_rows_stats rs;
    static const double blue_light[3] = {4.4, 12.8, 24.0}; /* brighter: another scale */
    static const double teal[3] = {0.1, 0.45, 0.6};
    double *a, *b, *c, d, rms, t0, t_relight, t_fresh, t_rows;
    unsigned long calls;
    int light, red, ne;
    (void)state;
    scene_load(&cb, CORNELL);
    scene_load(&fresh, CORNELL);
    light = material_of(&cb, "light");
    red = material_of(&cb, "red");
    h = make(&cb, 0, 64);
    t0 = host_now();
    rows(h);
    t_rows = host_now() - t0;
    sc_get_rows_stats(h, &rs);
    ne = n_elements(h);
    print_message("Cornell box (default mesh, res 64): %d rows, %lu entries, %zu bytes (%.0f per "
                  "patch), %.3f s\n",
                  rs.rows, rs.entries, rs.bytes, (double)rs.bytes / rs.rows, t_rows);
    CHECK_INT_GT(sc_rows_solve(h, 1000000, 1e-4, NULL, NULL), 0, "shots from the rows");

    /* New light colour and new wall colour: no hemi-cube. */
    calls = raster_calls(h);
    t0 = host_now();
    relight(h, &cb, light, NULL, blue_light);
    relight(h, &cb, red, teal, NULL);
    CHECK_INT_GT(sc_rows_solve(h, 1000000, 1e-4, NULL, NULL), 0, "shots from the rows");
    t_relight = host_now() - t0;
    assert_int_equal(raster_calls(h), calls);
    a = values(h);

    /* A fresh hemi-cube solve of the changed scene. */
    polys_set(&fresh, light, NULL, blue_light);
    polys_set(&fresh, red, teal, NULL);
    f = make(&fresh, 0, 64);
    t0 = host_now();
    CHECK_INT_GT(sc_solve(f, 1000000, 1e-4, NULL, NULL), 0, "shots of the hemi-cube solve");
    t_fresh = host_now() - t0;
    b = values(f);
    d = max_rel(a, b, ne, &rms);
    print_message("relit from rows vs fresh hemi-cube solve: max %.4f%%, rms %.4f%% per element; "
                  "relight %.3f s vs fresh solve %.3f s\n",
                  100 * d, 100 * rms, t_relight, t_fresh);
    CHECK_LE(
        d, REL_BOUND,
        "relit from rows against a fresh hemi-cube solve: max relative difference per element");

    /* Against a fresh solve from fresh rows: the same bits (relighting is exact). */
    r = make(&fresh, 0, 64);
    rows(r);
    CHECK_INT_GT(sc_rows_solve(r, 1000000, 1e-4, NULL, NULL), 0, "shots from the rows");
    c = values(r);
    assert_int_equal(sc_checksum(r), sc_checksum(h));
    assert_memory_equal(a, c, (size_t)ne * 3 * sizeof *a);
    free(a);
    free(b);
    free(c);
    sc_destroy(h);
    sc_destroy(f);
    sc_destroy(r);
    scene_free(&cb);
    scene_free(&fresh);
}

static void gs_vs_shoot(const char *path, const char *name, double max_element)
{
    scene_t s;
    sc_solver *h;
    sc_rows_stats rs;
    char err[256];
    double *a, *b, d, rms;
    unsigned long calls;
    int sweeps, ne;
    scene_load(&s, path);
    h = make(&s, max_element, 64);
    rows(h);
    ne = n_elements(h);
    calls = raster_calls(h);
    CHECK_INT_GT(sc_rows_solve(h, 1000000, 1e-5, NULL, NULL), 0, "shots from the rows");
    a = values(h);
    sweeps = sc_rows_gauss_seidel(h, 1000, 1e-5, err, sizeof err);
    if (sweeps < 0) fail_msg("%s", err);
    b = values(h);
    assert_int_equal(raster_calls(h), calls);
    sc_get_rows_stats(h, &rs);
    d = max_rel(b, a, ne, &rms);
    print_message("%s: Gauss-Seidel (%d sweeps, %d patches, matrix %zu bytes) vs shooting: max "
                  "%.4f%%, rms %.4f%% "
                  "per element\n",
                  name, sweeps, rs.rows, rs.matrix_bytes, 100 * d, 100 * rms);
    CHECK_INT_GT(sweeps, 1, "%s: Gauss-Seidel sweeps", name);
    CHECK_INT_LT(sweeps, 1000, "%s: Gauss-Seidel sweeps", name);
    CHECK_LE(d, GS_BOUND, "%s: Gauss-Seidel against shooting, max relative difference per element",
             name);
    /* Solving again after Gauss-Seidel (which leaves nothing unshot) starts afresh. */
    sc_restart(h);
    CHECK_INT_GT(sc_rows_solve(h, 1000000, 1e-5, NULL, NULL), 0, "shots from the rows");
    free(b);
    b = values(h);
    assert_memory_equal(a, b, (size_t)ne * 3 * sizeof *a);
    free(a);
    free(b);
    sc_destroy(h);
    scene_free(&s);
}

static void test_gauss_seidel_vs_shoot(void **state)
{
    (void)state;
    gs_vs_shoot(CORNELL, "cornell_box.obj", 0);
    gs_vs_shoot(GALLERY, "gallery.obj", 0);
}

/* The gallery's two lights as two groups, mixed, against one solve with the emissions
 * summed (intensities 1) and scaled (other intensities). */
static void test_mix_groups_glue(void **state)
{
    static const double dark[3] = {0, 0, 0};
    static const double k_amber[3] = {0.5, 1.0, 1.75}, k_panel[3] = {2.0, 0.25, 1.0};
    scene_t s, sum;
    sc_solver *h, *f;
    sc_solution *g[2];
    double k[2][3], *a, *b, d, rms, scaled[2][3];
    char err[256];
    unsigned long calls;
    int amber, panel, ne, c;
    (void)state;
    scene_load(&s, GALLERY);
    scene_load(&sum, GALLERY);
    amber = material_of(&s, "amber");
    panel = material_of(&s, "panel");
    h = make(&s, 0, 64);
    rows(h);
    ne = n_elements(h);
    calls = raster_calls(h);
    /* Group 0: amber alone; group 1: the panel alone. */
    relight(h, &s, panel, NULL, dark);
    CHECK_INT_GT(sc_rows_solve(h, 1000000, 1e-4, NULL, NULL), 0, "shots from the rows");
    g[0] = sc_keep(h, 1);
    relight(h, &s, panel, NULL, s.sc.materials[panel].ke);
    relight(h, &s, amber, NULL, dark);
    CHECK_INT_GT(sc_rows_solve(h, 1000000, 1e-4, NULL, NULL), 0, "shots from the rows");
    g[1] = sc_keep(h, 1);
    assert_non_null(g[0]);
    assert_non_null(g[1]);
    for (c = 0; c < 3; c++) k[0][c] = k[1][c] = 1.0;
    assert_int_equal(sc_mix(h, g, (const double(*)[3])k, 2, err, sizeof err), 0);
    assert_int_equal(raster_calls(h), calls);
    a = values(h); /* the mix: its ambient term is inside */

    f = make(&sum, 0, 64);
    CHECK_INT_GT(sc_solve(f, 1000000, 1e-4, NULL, NULL), 0, "shots of the hemi-cube solve");
    b = values(f);
    d = max_rel(a, b, ne, &rms);
    print_message("gallery: mix of 2 light groups vs both lights in one hemi-cube solve: max "
                  "%.4f%%, rms %.4f%%\n",
                  100 * d, 100 * rms);
    CHECK_LE(
        d, REL_BOUND,
        "gallery, two groups mixed against both lights solved at once: max relative difference");
    free(a);
    free(b);
    sc_destroy(f);

    /* Other intensities: the same as emissions scaled so. */
    memcpy(k[0], k_amber, sizeof k[0]);
    memcpy(k[1], k_panel, sizeof k[1]);
    assert_int_equal(sc_mix(h, g, (const double(*)[3])k, 2, err, sizeof err), 0);
    a = values(h);
    for (c = 0; c < 3; c++) {
        scaled[0][c] = s.sc.materials[amber].ke[c] * k_amber[c];
        scaled[1][c] = s.sc.materials[panel].ke[c] * k_panel[c];
    }
    polys_set(&sum, amber, NULL, scaled[0]);
    polys_set(&sum, panel, NULL, scaled[1]);
    f = make(&sum, 0, 64);
    CHECK_INT_GT(sc_solve(f, 1000000, 1e-4, NULL, NULL), 0, "shots of the hemi-cube solve");
    b = values(f);
    d = max_rel(a, b, ne, &rms);
    print_message("gallery: mix at intensities (0.5,1,1.75), (2,0.25,1) vs those emissions solved: "
                  "max %.4f%%, rms %.4f%%\n",
                  100 * d, 100 * rms);
    CHECK_LE(d, REL_BOUND,
             "gallery, groups mixed at other intensities against those emissions "
             "solved: max relative difference");
    /* Errors: a negative intensity; solving after a mix starts from the emission. */
    k[0][1] = -1;
    assert_int_equal(sc_mix(h, g, (const double(*)[3])k, 2, err, sizeof err), -1);
    free(a);
    free(b);
    sc_solution_free(g[0]);
    sc_solution_free(g[1]);
    sc_destroy(f);
    sc_destroy(h);
    scene_free(&s);
    scene_free(&sum);
}

static void test_set_surfaces_errors(void **state)
{
    scene_t s;
    sc_solver *h;
    char err[256];
    polys_material_match mt;
    const double inf[3] = {HUGE_VAL, 1, 1}, neg[3] = {-1, 0, 0};
    (void)state;
    scene_load(&s, CORNELL);
    h = make(&s, 0.1, 32);
    mt.sc = &s.sc;
    mt.material = material_of(&s, "light");
    assert_int_equal(sc_set_surfaces(h, polys_match_material, &mt, NULL, inf, err, sizeof err), -1);
    CHECK_CONTAINS(err, "finite", "the error message");
    assert_int_equal(sc_set_surfaces(h, polys_match_material, &mt, neg, NULL, err, sizeof err), -1);
    assert_int_equal(sc_rows_gauss_seidel(h, 10, 0.001, err, sizeof err), -1); /* no rows yet */
    CHECK_CONTAINS(err, "rows", "the error message");
    assert_int_equal(sc_rows_save(h, tmp_path("none.ff"), err, sizeof err), -1);
    sc_destroy(h);
    scene_free(&s);
}

/* ---- through rad_cli ------------------------------------------------------------------ */

typedef struct {
    int status;
    char *out, *err;
} run_t;

static int need(const char *bin)
{
    if (access(bin, X_OK) == 0) return 1;
    print_message("%s is missing (run make all): skipped\n", bin);
    return 0;
}

static void run_args(run_t *r, const char *bin, const char *const *args)
{
    static int seq;
    char *argv[72], outp[320], errp[320];
    posix_spawn_file_actions_t fa;
    pid_t pid;
    int n = 0, st = 0, rc;
    size_t len;
    double t0 = host_now();
    snprintf(outp, sizeof outp, "%s/run%03d.out", tmpdir, seq);
    snprintf(errp, sizeof errp, "%s/run%03d.err", tmpdir, seq);
    seq++;
    argv[n++] = (char *)bin;
    while (args[n - 1]) {
        CHECK_INT_LT(n, 70, "rad_cli arguments");
        argv[n] = (char *)args[n - 1];
        n++;
    }
    argv[n] = NULL;
    assert_int_equal(posix_spawn_file_actions_init(&fa), 0);
    assert_int_equal(posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0), 0);
    assert_int_equal(
        posix_spawn_file_actions_addopen(&fa, 1, outp, O_WRONLY | O_CREAT | O_TRUNC, 0600), 0);
    assert_int_equal(
        posix_spawn_file_actions_addopen(&fa, 2, errp, O_WRONLY | O_CREAT | O_TRUNC, 0600), 0);
    rc = posix_spawn(&pid, bin, &fa, NULL, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    if (rc != 0) fail_msg("posix_spawn %s: %s", bin, strerror(rc));
    for (;;) {
        struct timespec nap = {0, 5000000};
        pid_t w = waitpid(pid, &st, WNOHANG);
        if (w == pid) break;
        if (host_now() - t0 > 120) {
            kill(pid, SIGKILL);
            waitpid(pid, &st, 0);
            fail_msg("%s timed out", bin);
        }
        nanosleep(&nap, NULL);
    }
    r->status = WIFEXITED(st) ? WEXITSTATUS(st) : 128;
    r->out = (char *)slurp(outp, &len);
    r->err = (char *)slurp(errp, &len);
    assert_non_null(r->out);
    assert_non_null(r->err);
}

static void run_free(run_t *r)
{
    free(r->out);
    free(r->err);
}

#define RUN(r, bin, ...) run_args((r), (bin), (const char *const[]){__VA_ARGS__, NULL})

static void expect_status_at(const run_t *r, int status, const char *file, int line)
{
    if (r->status == status) return;
    print_error("exit status %d, expected %d\nstdout: %s\nstderr: %s\n", r->status, status, r->out,
                r->err);
    _fail(file, line);
}
#define expect_status(r, s) expect_status_at((r), (s), __FILE__, __LINE__)

/* Exit 1 (or 2) with one line on stderr that contains WHAT. */
static void expect_error_at(const run_t *r, int status, const char *what, const char *file,
                            int line)
{
    const char *nl = strchr(r->err, '\n');
    expect_status_at(r, status, file, line);
    if (!strstr(r->err, what) || strncmp(r->err, "rad_cli", 7) != 0 ||
        (status == 1 && (!nl || nl[1] != '\0'))) {
        print_error("stderr should be one line naming '%s':\n%s\n", what, r->err);
        _fail(file, line);
    }
}
#define expect_error(r, s, w) expect_error_at((r), (s), (w), __FILE__, __LINE__)

static void load_img(const char *path, img_t *im)
{
    char e[512];
    if (img_read(path, im, e, sizeof e) < 0) fail_msg("img_read: %s", e);
}

static int same_image(const char *a, const char *b)
{
    img_t x, y;
    int same;
    load_img(a, &x);
    load_img(b, &y);
    same = x.w == y.w && x.h == y.h && memcmp(x.rgb, y.rgb, (size_t)x.w * (size_t)x.h * 3) == 0;
    img_free(&x);
    img_free(&y);
    return same;
}

/* Largest difference of one 8-bit channel between two images of one size. */
static int max_pixel_diff(const char *a, const char *b)
{
    img_t x, y;
    size_t i;
    int worst = 0;
    load_img(a, &x);
    load_img(b, &y);
    assert_int_equal(x.w, y.w);
    assert_int_equal(x.h, y.h);
    for (i = 0; i < (size_t)x.w * (size_t)x.h * 3; i++) {
        int d = abs((int)x.rgb[i] - (int)y.rgb[i]);
        if (d > worst) worst = d;
    }
    img_free(&x);
    img_free(&y);
    return worst;
}

static void test_cli_save_load(void **state)
{
    run_t r;
    const char *ff = tmp_path("cli.ff"), *a = tmp_path("saved.png"), *b = tmp_path("loaded.png"),
               *c = tmp_path("computed.png"), *p = tmp_path("plain.png"),
               *ff2 = tmp_path("cli_float.ff");
    (void)state;
    if (!need(FIXED)) skip();
    RUN(&r, FIXED, "--quiet", "--width", "96", "--height", "96", COARSE, "--save-ff", ff, "-o", a,
        CORNELL);
    expect_status(&r, 0);
    run_free(&r);
    RUN(&r, FIXED, "--quiet", "--stats", "--width", "96", "--height", "96", COARSE, "--load-ff", ff,
        "-o", b, CORNELL);
    expect_status(&r, 0);
    /* No hemi-cube at all: the counters of the whole run are zero. */
    CHECK_CONTAINS(r.out, "hemi-cube: resolution 32, 0 polygons, 0 pixels", "rad_cli's stdout");
    CHECK_CONTAINS(r.out, "0 polygons rendered during the solve", "rad_cli's stdout");
    CHECK_CONTAINS(r.out, "loaded from", "rad_cli's stdout");
    run_free(&r);
    /* Rows computed in memory only (a light group of the one light): the same image. */
    RUN(&r, FIXED, "--quiet", "--width", "96", "--height", "96", COARSE, "--light-group",
        "lamp=light", "-o", c, CORNELL);
    expect_status(&r, 0);
    run_free(&r);
    CHECK_THAT(same_image(a, b), "%s and %s: the same pixels", a, b);
    CHECK_THAT(same_image(a, c), "%s and %s: the same pixels", a, c);
    /* The plain hemi-cube solve: within the code's 0.05%, a step of sRGB at most. */
    RUN(&r, FIXED, "--quiet", "--width", "96", "--height", "96", COARSE, "-o", p, CORNELL);
    expect_status(&r, 0);
    run_free(&r);
    print_message("rad_cli: rows vs hemi-cube image: max %d/255 per channel\n",
                  max_pixel_diff(a, p));
    CHECK_INT_LE(max_pixel_diff(a, p), 2,
                 "rows against hemi-cube image: max difference per channel (/255)");

    /* Mismatches: another scene, another mesh, another resolution, another build. */
    RUN(&r, FIXED, "--quiet", GCOARSE, "--load-ff", ff, "-o", tmp_path("x.png"), GALLERY);
    expect_error(&r, 1, "scene mismatch");
    run_free(&r);
    RUN(&r, FIXED, "--quiet", "--max-element", "0.09", "--res", "32", "--load-ff", ff, "-o",
        tmp_path("x.png"), CORNELL);
    expect_error(&r, 1, "scene mismatch");
    run_free(&r);
    RUN(&r, FIXED, "--quiet", "--max-element", "0.1", "--res", "64", "--load-ff", ff, "-o",
        tmp_path("x.png"), CORNELL);
    expect_error(&r, 1, "resolution 32, this run uses 64");
    run_free(&r);
    if (need(FLOAT)) {
        RUN(&r, FLOAT, "--quiet", COARSE, "--load-ff", ff, "-o", tmp_path("x.png"), CORNELL);
        expect_status(&r, 1);
        CHECK_CONTAINS(r.err, "made by the fixed build, this is the float build",
                       "rad_cli's stderr");
        run_free(&r);
        RUN(&r, FLOAT, "--quiet", "--width", "64", "--height", "64", COARSE, "--save-ff", ff2, "-o",
            tmp_path("f1.png"), CORNELL);
        expect_status(&r, 0);
        run_free(&r);
        RUN(&r, FLOAT, "--quiet", "--width", "64", "--height", "64", COARSE, "--load-ff", ff2, "-o",
            tmp_path("f2.png"), CORNELL);
        expect_status(&r, 0);
        run_free(&r);
        CHECK_THAT(same_image(tmp_path("f1.png"), tmp_path("f2.png")), "%s and %s: the same pixels",
                   tmp_path("f1.png"), tmp_path("f2.png"));
    }
}

static void test_cli_corrupt(void **state)
{
    run_t r;
    const char *ff = tmp_path("cli_c.ff"), *bad = tmp_path("cli_bad.ff");
    unsigned char *d;
    size_t n;
    (void)state;
    if (!need(FIXED)) skip();
    RUN(&r, FIXED, "--quiet", "--width", "16", "--height", "16", COARSE, "--save-ff", ff, "-o",
        tmp_path("c.png"), CORNELL);
    expect_status(&r, 0);
    run_free(&r);
    d = slurp(ff, &n);
    assert_non_null(d);
    d[n / 2] ^= 0x40;
    spit(bad, d, n);
    RUN(&r, FIXED, "--quiet", COARSE, "--load-ff", bad, "-o", tmp_path("x.png"), CORNELL);
    expect_error(&r, 1, "checksum mismatch");
    CHECK_CONTAINS(r.err, bad, "rad_cli's stderr");
    run_free(&r);
    d[n / 2] ^= 0x40;
    spit(bad, d, n / 3);
    RUN(&r, FIXED, "--quiet", COARSE, "--load-ff", bad, "-o", tmp_path("x.png"), CORNELL);
    expect_error(&r, 1, "truncated");
    run_free(&r);
    RUN(&r, FIXED, "--quiet", COARSE, "--load-ff", CORNELL, "-o", tmp_path("x.png"), CORNELL);
    expect_error(&r, 1, "bad magic");
    run_free(&r);
    free(d);
}

/* Element radiosities from a --dump-radiosity CSV: r,g,b are the last three fields. */
static double *read_csv(const char *path, int *n)
{
    size_t len;
    char *t = (char *)slurp(path, &len), *p, *line;
    double *v = NULL;
    int cap = 0, k = 0;
    assert_non_null(t);
    p = strchr(t, '\n');
    assert_non_null(p);
    for (line = p + 1; *line; line = p + 1) {
        char *c;
        int f;
        p = strchr(line, '\n');
        if (!p) break;
        *p = '\0';
        for (c = p, f = 0; c > line && f < 3; c--)
            if (c[-1] == ',') f++;
        if (k == cap) {
            v = realloc(v, (size_t)(cap = cap ? 2 * cap : 1024) * 3 * sizeof *v);
            assert_non_null(v);
        }
        assert_int_equal(sscanf(c + 1, "%lf,%lf,%lf", &v[3 * k], &v[3 * k + 1], &v[3 * k + 2]), 3);
        k++;
    }
    free(t);
    *n = k;
    return v;
}

static void test_cli_groups(void **state)
{
    run_t r;
    const char *sum = tmp_path("sum.csv"), *mix = tmp_path("mix.csv"), *out = tmp_path("eg.png");
    double *a, *b, d, rms;
    int na, nb, files = 0;
    DIR *dir;
    struct dirent *de;
    (void)state;
    if (!need(FIXED)) skip();
    /* Mixed groups at intensity 1 against both lights in one solve from the same rows. */
    RUN(&r, FIXED, "--quiet", "--width", "16", "--height", "16", "--res", "64", "--tol", "0.0001",
        "--save-ff", tmp_path("g.ff"), "--dump-radiosity", sum, "-o", tmp_path("sum.png"), GALLERY);
    expect_status(&r, 0);
    run_free(&r);
    RUN(&r, FIXED, "--quiet", "--stats", "--width", "16", "--height", "16", "--res", "64", "--tol",
        "0.0001", "--load-ff", tmp_path("g.ff"), "--light-group", "warm=amber", "--dump-radiosity",
        mix, "-o", tmp_path("mix.png"), GALLERY);
    expect_status(&r, 0);
    CHECK_CONTAINS(r.out, "light groups 2: warm (1,1,1) other (1,1,1)", "rad_cli's stdout");
    CHECK_CONTAINS(r.out, "hemi-cube: resolution 64, 0 polygons", "rad_cli's stdout");
    run_free(&r);
    a = read_csv(mix, &na);
    b = read_csv(sum, &nb);
    assert_int_equal(na, nb);
    d = max_rel(a, b, na, &rms);
    print_message("rad_cli gallery: --light-group mix vs one solve, from the same rows: max "
                  "%.4f%%, rms %.4f%%\n",
                  100 * d, 100 * rms);
    CHECK_LE(d, REL_BOUND,
             "rad_cli gallery, --light-group mix against one solve: max relative "
             "difference");
    free(a);
    free(b);

    /* --each-group: one file per group, named after it; the base name is not written. */
    RUN(&r, FIXED, "--quiet", "--width", "48", "--height", "48", GCOARSE, "--light-group",
        "warm=amber", "--light-group", "cool=panel", "--each-group", "-o", out, GALLERY);
    expect_status(&r, 0);
    run_free(&r);
    dir = opendir(tmpdir);
    assert_non_null(dir);
    while ((de = readdir(dir)) != NULL) files += strncmp(de->d_name, "eg.", 3) == 0;
    closedir(dir);
    assert_int_equal(files, 2);
    CHECK_INT_EQ(access(tmp_path("eg.warm.png"), R_OK), 0, "access(%s): the file was written",
                 tmp_path("eg.warm.png"));
    CHECK_INT_EQ(access(tmp_path("eg.cool.png"), R_OK), 0, "access(%s): the file was written",
                 tmp_path("eg.cool.png"));
    CHECK_THAT(!same_image(tmp_path("eg.warm.png"), tmp_path("eg.cool.png")), "%s and %s differ",
               tmp_path("eg.warm.png"), tmp_path("eg.cool.png"));

    /* Errors. */
    RUN(&r, FIXED, "--quiet", GCOARSE, "--light-group", "warm=amber,brass", "-o", out, GALLERY);
    expect_error(&r, 1, "no material or light named 'brass'");
    run_free(&r);
    RUN(&r, FIXED, "--quiet", GCOARSE, "--light-group", "warm=amber", "--light-group", "warm=panel",
        "-o", out, GALLERY);
    expect_error(&r, 2, "a group name given twice");
    run_free(&r);
    RUN(&r, FIXED, "--quiet", GCOARSE, "--light-group", "a=amber", "--light-group", "b=amber", "-o",
        out, GALLERY);
    expect_error(&r, 1, "already in group 'a'");
    run_free(&r);
    RUN(&r, FIXED, "--quiet", GCOARSE, "--each-group", "-o", out, GALLERY);
    expect_error(&r, 2, "--each-group needs at least one --light-group");
    run_free(&r);
    RUN(&r, FIXED, "--quiet", GCOARSE, "--save-ff", tmp_path("a.ff"), "--load-ff", tmp_path("b.ff"),
        "-o", out, GALLERY);
    expect_error(&r, 2, "exclude each other");
    run_free(&r);
    RUN(&r, FIXED, "--quiet", GCOARSE, "--group-intensity", "warm=1,1,1", "-o", out, GALLERY);
    expect_error(&r, 2, "no --light-group of that name");
    run_free(&r);
    RUN(&r, FIXED, "--quiet", GCOARSE, "--light-group", "all=amber,panel", "--group-intensity",
        "other=1,1,1", "-o", out, GALLERY);
    expect_error(&r, 1, "no group 'other'");
    run_free(&r);
    RUN(&r, FIXED, "--quiet", GCOARSE, "--solver", "jacobi", "-o", out, GALLERY);
    expect_error(&r, 2, "--solver wants shoot or gauss-seidel");
    run_free(&r);
}

static void test_cli_gauss_seidel(void **state)
{
    run_t r;
    const char *gs = tmp_path("gs.csv"), *sh = tmp_path("sh.csv");
    double *a, *b, d, rms;
    int na, nb;
    (void)state;
    if (!need(FIXED)) skip();
    RUN(&r, FIXED, "--quiet", "--stats", "--width", "16", "--height", "16", COARSE, "--solver",
        "gauss-seidel", "--tol", "0.00001", "--dump-radiosity", gs, "-o", tmp_path("gs.png"),
        CORNELL);
    expect_status(&r, 0);
    CHECK_CONTAINS(r.out, "gauss-seidel sweeps", "rad_cli's stdout");
    run_free(&r);
    RUN(&r, FIXED, "--quiet", "--width", "16", "--height", "16", COARSE, "--tol", "0.00001",
        "--dump-radiosity", sh, "-o", tmp_path("sh.png"), CORNELL);
    expect_status(&r, 0);
    run_free(&r);
    a = read_csv(gs, &na);
    b = read_csv(sh, &nb);
    assert_int_equal(na, nb);
    d = max_rel(a, b, na, &rms);
    print_message("rad_cli Cornell (coarse): --solver gauss-seidel vs hemi-cube shooting: max "
                  "%.4f%%, rms %.4f%%\n",
                  100 * d, 100 * rms);
    CHECK_LE(
        d, GS_BOUND,
        "rad_cli Cornell box: --solver gauss-seidel against shooting, max relative difference");
    free(a);
    free(b);
}

/* The solve of ARGS (a NULL-terminated list after the common ones) dumped to CSV PATH:
 * the elements' radiosities, N of them. */
static double *cli_csv(const char *path, int *n, const char *const *args)
{
    const char *all[32];
    run_t r;
    int k = 0, j;
    const char *common[] = {"--quiet", "--width",
                            "16",      "--height",
                            "16",      COARSE,
                            "--tol",   "0.0001",
                            "--sun",   "0.3,-0.6,-1,4,4,3.5",
                            "--point", "-0.2,0.35,-0.3,0.02,0.02,0.015"};
    for (j = 0; j < (int)(sizeof common / sizeof common[0]); j++) all[k++] = common[j];
    for (j = 0; args[j]; j++) all[k++] = args[j];
    all[k++] = "--dump-radiosity";
    all[k++] = path;
    all[k++] = "-o";
    all[k++] = tmp_path("lights.png");
    all[k++] = CORNELL;
    all[k] = NULL;
    run_args(&r, FIXED, all);
    expect_status(&r, 0);
    run_free(&r);
    return read_csv(path, n);
}
#define CLI_CSV(path, n, ...) cli_csv((path), (n), (const char *const[]){__VA_ARGS__, NULL})

/* Lights (--sun through the Cornell box's open front, --point inside, and its ceiling
 * lamp) with stored form factors through rad_cli:
 *   - --save-ff then --load-ff: the same elements, bit for bit (the lights' shots are
 *     rendered again, the same bits); against the plain hemi-cube solve within
 *     REL_BOUND (the rows' codes on the bounced light, two solves to 1e-4);
 *   - the sun, the point light and the lamp each a group ('other': the lamp), mixed at
 *     intensity 1: within REL_BOUND of all in one solve (radiosity is linear in
 *     emission); the sun's group at 0 against a solve without --sun: REL_BOUND;
 *   - --solver gauss-seidel within GS_BOUND of shooting;
 *   - errors: a light in two groups, a light that is not there. */
static void test_cli_lights(void **state)
{
    const char *ff = tmp_path("lights.ff");
    double *saved, *loaded, *plain, *mix, *off, *nosun, *gs, d, rms;
    int n1, n2, n3, n4, n5, n6, n7;
    run_t r;
    (void)state;
    if (!need(FIXED)) skip();
    saved = CLI_CSV(tmp_path("l_saved.csv"), &n1, "--save-ff", ff);
    loaded = CLI_CSV(tmp_path("l_loaded.csv"), &n2, "--load-ff", ff);
    plain = CLI_CSV(tmp_path("l_plain.csv"), &n3, "--max-shots", "1000000");
    assert_int_equal(n1, n2);
    assert_int_equal(n1, n3);
    CHECK_THAT(memcmp(saved, loaded, (size_t)n1 * 3 * sizeof *saved) == 0,
               "rad_cli with lights: --save-ff and --load-ff give the same radiosities");
    d = max_rel(saved, plain, n1, &rms);
    print_message(
        "rad_cli Cornell with a sun and a point light: rows vs hemi-cubes max %.4f%%, rms %.4f%%\n",
        100 * d, 100 * rms);
    CHECK_LE(
        d, REL_BOUND,
        "rad_cli with lights: the solve from rows against hemi-cubes, max relative difference");
    mix = CLI_CSV(tmp_path("l_mix.csv"), &n4, "--load-ff", ff, "--light-group", "day=sun1",
                  "--light-group", "bulb=point1");
    assert_int_equal(n4, n1);
    d = max_rel(mix, saved, n1, &rms);
    print_message("rad_cli Cornell: the sun's, the point light's and the lamp's groups mixed vs "
                  "one solve: max "
                  "%.4f%%, rms %.4f%%\n",
                  100 * d, 100 * rms);
    CHECK_LE(d, REL_BOUND,
             "rad_cli with lights: --light-group mix against one solve, max relative difference");
    off = CLI_CSV(tmp_path("l_off.csv"), &n5, "--load-ff", ff, "--light-group", "day=sun1",
                  "--group-intensity", "day=0,0,0");
    {
        const char *args[] = {"--quiet",
                              "--width",
                              "16",
                              "--height",
                              "16",
                              COARSE,
                              "--tol",
                              "0.0001",
                              "--point",
                              "-0.2,0.35,-0.3,0.02,0.02,0.015",
                              "--load-ff",
                              ff,
                              "--dump-radiosity",
                              tmp_path("l_nosun.csv"),
                              "-o",
                              tmp_path("l_nosun.png"),
                              CORNELL,
                              NULL};
        run_args(&r, FIXED, args);
        expect_status(&r, 0);
        run_free(&r);
        nosun = read_csv(tmp_path("l_nosun.csv"), &n6);
    }
    assert_int_equal(n5, n6);
    d = max_rel(off, nosun, n5, &rms);
    print_message("rad_cli Cornell: the sun's group at 0 vs no sun: max %.4f%%, rms %.4f%%\n",
                  100 * d, 100 * rms);
    CHECK_LE(
        d, REL_BOUND,
        "rad_cli with lights: a group at 0 against the scene without it, max relative difference");
    gs = CLI_CSV(tmp_path("l_gs.csv"), &n7, "--load-ff", ff, "--solver", "gauss-seidel", "--tol",
                 "0.00001");
    assert_int_equal(n7, n1);
    d = max_rel(gs, saved, n1, &rms);
    print_message(
        "rad_cli Cornell with lights: gauss-seidel vs shooting from rows: max %.4f%%, rms %.4f%%\n",
        100 * d, 100 * rms);
    CHECK_LE(
        d, GS_BOUND,
        "rad_cli with lights: --solver gauss-seidel against shooting, max relative difference");
    free(saved);
    free(loaded);
    free(plain);
    free(mix);
    free(off);
    free(nosun);
    free(gs);
    /* errors */
    RUN(&r, FIXED, "--quiet", COARSE, "--sun", "0,-1,0,1,1,1", "--light-group", "a=sun1",
        "--light-group", "b=sun1", "-o", tmp_path("x.png"), CORNELL);
    expect_error(&r, 1, "light 'sun1' is already in group 'a'");
    run_free(&r);
    RUN(&r, FIXED, "--quiet", COARSE, "--sun", "0,-1,0,1,1,1", "--light-group", "a=sun2", "-o",
        tmp_path("x.png"), CORNELL);
    expect_error(&r, 1, "no material or light named 'sun2'");
    run_free(&r);
}

static void test_cli_animate(void **state)
{
    run_t r;
    char name[64];
    int i;
    (void)state;
    if (!need(FIXED)) skip();
    RUN(&r, FIXED, "--quiet", "--stats", "--width", "48", "--height", "48", GCOARSE,
        "--light-group", "warm=amber", "--animate", DATA "frames.txt", "-o", tmp_path("fr.png"),
        GALLERY);
    expect_status(&r, 0);
    /* One visibility computation for every frame. */
    CHECK_CONTAINS(r.out, "0 polygons rendered during the solve", "rad_cli's stdout");
    run_free(&r);
    for (i = 0; i < 5; i++) {
        snprintf(name, sizeof name, "fr_%04d.png", i);
        CHECK_INT_EQ(access(tmp_path(name), R_OK), 0, "access(%s): the file was written",
                     tmp_path(name));
    }
    CHECK_INT_NE(access(tmp_path("fr_0005.png"), R_OK), 0, "access(%s): no such file is written",
                 tmp_path("fr_0005.png"));
    CHECK_INT_NE(access(tmp_path("fr.png"), R_OK), 0, "access(%s): no such file is written",
                 tmp_path("fr.png"));
    /* Frames 0 and 4 are the same camera and intensities; 1 and 2 change the lights,
     * 3 the camera. */
    CHECK_THAT(same_image(tmp_path("fr_0000.png"), tmp_path("fr_0004.png")),
               "%s and %s: the same pixels", tmp_path("fr_0000.png"), tmp_path("fr_0004.png"));
    CHECK_THAT(!same_image(tmp_path("fr_0000.png"), tmp_path("fr_0001.png")), "%s and %s differ",
               tmp_path("fr_0000.png"), tmp_path("fr_0001.png"));
    CHECK_THAT(!same_image(tmp_path("fr_0000.png"), tmp_path("fr_0002.png")), "%s and %s differ",
               tmp_path("fr_0000.png"), tmp_path("fr_0002.png"));
    CHECK_THAT(!same_image(tmp_path("fr_0001.png"), tmp_path("fr_0002.png")), "%s and %s differ",
               tmp_path("fr_0001.png"), tmp_path("fr_0002.png"));
    CHECK_THAT(!same_image(tmp_path("fr_0000.png"), tmp_path("fr_0003.png")), "%s and %s differ",
               tmp_path("fr_0000.png"), tmp_path("fr_0003.png"));
    /* Without --light-group every emitter is in "other". */
    {
        const char *f = tmp_path("frames2.txt");
        FILE *fp = fopen(f, "w");
        assert_non_null(fp);
        fputs("0 2 6 0 1.2 0\n0 2 6 0 1.2 0 45 other=0.25,0.25,0.25\n", fp);
        assert_int_equal(fclose(fp), 0);
        RUN(&r, FIXED, "--quiet", "--width", "32", "--height", "32", GCOARSE, "--animate", f, "-o",
            tmp_path("o.ppm"), GALLERY);
        expect_status(&r, 0);
        run_free(&r);
        CHECK_THAT(!same_image(tmp_path("o_0000.ppm"), tmp_path("o_0001.ppm")), "%s and %s differ",
                   tmp_path("o_0000.ppm"), tmp_path("o_0001.ppm"));
        fp = fopen(f, "w");
        assert_non_null(fp);
        fputs("0 2 6 0 1.2 0\n0 2 6 nope 1.2 0\n", fp);
        assert_int_equal(fclose(fp), 0);
        RUN(&r, FIXED, "--quiet", GCOARSE, "--animate", f, "-o", tmp_path("o.png"), GALLERY);
        expect_error(&r, 1, "frames2.txt:2: expected EX EY EZ");
        run_free(&r);
        fp = fopen(f, "w");
        assert_non_null(fp);
        fputs("0 2 6 0 1.2 0 warm=1,1,1\n", fp);
        assert_int_equal(fclose(fp), 0);
        RUN(&r, FIXED, "--quiet", GCOARSE, "--animate", f, "-o", tmp_path("o.png"), GALLERY);
        expect_error(&r, 1, "frames2.txt:1: no light group named 'warm'");
        run_free(&r);
    }
    RUN(&r, FIXED, "--quiet", GCOARSE, "--animate", DATA "frames.txt", "--camera", "0,2,6,0,1,0",
        "-o", tmp_path("o.png"), GALLERY);
    expect_error(&r, 2, "--animate takes its cameras from its file");
    run_free(&r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_save_load_glue),
        cmocka_unit_test(test_load_mismatch),
        cmocka_unit_test(test_corrupt_files),
        cmocka_unit_test(test_relight_cornell),
        cmocka_unit_test(test_gauss_seidel_vs_shoot),
        cmocka_unit_test(test_mix_groups_glue),
        cmocka_unit_test(test_set_surfaces_errors),
        cmocka_unit_test(test_cli_save_load),
        cmocka_unit_test(test_cli_corrupt),
        cmocka_unit_test(test_cli_groups),
        cmocka_unit_test(test_cli_gauss_seidel),
        cmocka_unit_test(test_cli_animate),
        cmocka_unit_test(test_cli_lights),
    };
    return cmocka_run_group_tests_name("relight", tests, group_setup, group_teardown);
}
