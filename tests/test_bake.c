/* SPDX-License-Identifier: MIT */
/* Tests for what game tools bake: tools/formats/hdr.c (Radiance RGBE images),
 * tools/bake/lightmap.c (charts, atlas, texels, dilation) and tools/bake/probes.c. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include <cmocka.h>

#include "check.h"
#include "tmpdir.h"
#include "bake/lightmap.h"
#include "bench/level.h"
#include "bake/probes.h"
#include "formats/file_io.h"
#include "formats/hdr.h"
#include "host/polys.h"
#include "host/scene.h"
#include "reference/reference.h"

/* stb_image's own HDR reader, an independent decoder of what hdr_write writes (static:
 * its unused functions are reported at the end of the file, so that warning stays off). */
#if defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wmissing-prototypes"
#pragma GCC diagnostic ignored "-Wundef"
#pragma GCC diagnostic ignored "-Wpedantic"
#endif
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_HDR
#include <stb/stb_image.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

TMPDIR_GROUP("bake")

/* ---- hdr ---------------------------------------------------------------------------- */

/* A known image: channels m 2^e over e in -40..40 (a pixel's channels apart by up to
 * 2^12, so the small ones test the shared exponent), zeros, runs of one value (the
 * RLE's runs), and largest channels just below a power of two (m 256 rounding to 256). */
static float *hdr_known(int w, int h)
{
    float *p = malloc((size_t)w * h * 3 * sizeof *p);
    uint32_t x = 12345u;
    int i, k;
    for (i = 0; p && i < w * h; i++) {
        for (k = 0; k < 3; k++) {
            x = x * 1664525u + 1013904223u;
            p[3 * i + k] =
                (float)ldexp(0.5 + (x >> 8) / 33554432.0, (int)((x >> 4) % 81) - 40 - 6 * k);
        }
        if (i % 7 == 0) p[3 * i + 1] = 0.0f;
        if (i % 11 == 0) p[3 * i] = p[3 * i + 1] = p[3 * i + 2] = 0.0f;
        if (i % 13 == 0) p[3 * i] = (float)ldexp(1.0 - 1.0 / 1024.0, i % 9);
        if (i / w == 1) p[3 * i] = p[3 * i + 1] = p[3 * i + 2] = 0.25f; /* a run */
    }
    return p;
}

/* Every channel of every pixel within 2^-8 of the pixel's largest channel as read
 * back (hdr.h derives it: half a step of 2^(e-8), the largest at least 128 steps). */
static double hdr_check_close(const float *want, const float *got, int w, int h)
{
    double worst = 0.0;
    int i, k;
    for (i = 0; i < w * h; i++) {
        double m = fmax(got[3 * i], fmax(got[3 * i + 1], got[3 * i + 2]));
        for (k = 0; k < 3; k++) {
            double d = fabs((double)got[3 * i + k] - want[3 * i + k]);
            CHECK_LE(d, ldexp(m, -8),
                     "pixel %d channel %d: |read - written| against 2^-8 of the largest channel", i,
                     k);
            if (m > 0.0 && d / m > worst) worst = d / m;
        }
    }
    return worst;
}

static void hdr_round_trip(int w, int h)
{
    const char *path = tmp_path("rt.hdr");
    char err[256] = "";
    float *img = hdr_known(w, h), *stb;
    hdr_image back;
    int sw = 0, sh = 0, sn = 0;
    assert_non_null(img);
    CHECK_INT_EQ(hdr_write(path, img, w, h, err, sizeof err), 0, "hdr_write %dx%d (%s)", w, h, err);
    CHECK_INT_EQ(hdr_read(path, &back, err, sizeof err), 0, "hdr_read %dx%d (%s)", w, h, err);
    CHECK_INT_EQ(back.w, w, "width read back");
    CHECK_INT_EQ(back.h, h, "height read back");
    printf("hdr %dx%d: worst error %.6f of the pixel's largest channel (bound 2^-8 = %.6f)\n", w, h,
           hdr_check_close(img, back.rgb, w, h), ldexp(1.0, -8));
    /* stb_image decodes the same file to the same floats: the format is Radiance's. */
    stb = stbi_loadf(path, &sw, &sh, &sn, 3);
    assert_non_null(stb);
    CHECK_INT_EQ(sw * 100000 + sh, w * 100000 + h, "stb_image's size (w * 100000 + h)");
    assert_memory_equal(stb, back.rgb, (size_t)w * h * 3 * sizeof *stb);
    stbi_image_free(stb);
    hdr_free(&back);
    free(img);
}

/* Widths 8..32767 are run-length encoded, others flat: both, and one of a single pixel. */
static void test_hdr_round_trip(void **state)
{
    (void)state;
    hdr_round_trip(37, 23);
    hdr_round_trip(300, 4);
    hdr_round_trip(5, 9);
    hdr_round_trip(1, 1);
}

static void test_hdr_rle_smaller(void **state)
{
    const char *path = tmp_path("flat.hdr");
    char err[256] = "";
    float *img = calloc(512 * 64 * 3, sizeof *img);
    struct stat st;
    (void)state;
    assert_non_null(img);
    img[3 * 700] = 3.0f;
    CHECK_INT_EQ(hdr_write(path, img, 512, 64, err, sizeof err), 0, "hdr_write (%s)", err);
    CHECK_INT_EQ(stat(path, &st), 0, "stat of the written file");
    /* A black row is 4 channels of 4 runs of 127/128 bytes: 2 bytes each, 4 bytes of
     * row header: 36 bytes a row against 2048 flat. */
    CHECK_INT_LE(st.st_size, 64 * 48 + 200, "bytes of a 512 x 64 black image with one lit pixel");
    free(img);
}

static void test_hdr_bad_input(void **state)
{
    const char *path = tmp_path("bad.hdr"), *junk = tmp_path("junk.hdr");
    char err[256] = "";
    float img[3 * 12] = {0};
    hdr_image back;
    FILE *fp;
    (void)state;
    CHECK_INT_EQ(hdr_write(path, img, 4, 3, err, sizeof err), 0, "a black image (%s)", err);
    img[3 * 6 + 1] = -1.0f;
    CHECK_INT_EQ(hdr_write(path, img, 4, 3, err, sizeof err), -1, "a negative value refused");
    CHECK_CONTAINS(err, "pixel 2,1", "the message names the pixel");
    img[3 * 6 + 1] = NAN;
    CHECK_INT_EQ(hdr_write(path, img, 4, 3, err, sizeof err), -1, "NaN refused");
    img[3 * 6 + 1] = INFINITY;
    CHECK_INT_EQ(hdr_write(path, img, 4, 3, err, sizeof err), -1, "infinity refused");
    CHECK_INT_EQ(hdr_write(path, img, 0, 3, err, sizeof err), -1, "a width of 0 refused");
    CHECK_CONTAINS(err, "invalid image size", "the size named");
    /* The first, good file is still there, whole. */
    CHECK_INT_EQ(hdr_read(path, &back, err, sizeof err), 0, "the earlier file read (%s)", err);
    CHECK_INT_EQ(back.w * 10 + back.h, 43, "its size (w * 10 + h)");
    hdr_free(&back);
    fp = fopen(junk, "wb");
    assert_non_null(fp);
    fputs("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 40\n\2\2\0\50\1", fp);
    fclose(fp);
    CHECK_INT_EQ(hdr_read(junk, &back, err, sizeof err), -1, "a truncated file refused");
    CHECK_CONTAINS(err, "truncated or corrupt", "the message");
    assert_null(back.rgb);
    fp = fopen(junk, "wb");
    assert_non_null(fp);
    fputs("P6\n1 1\n255\nabc", fp);
    fclose(fp);
    CHECK_INT_EQ(hdr_read(junk, &back, err, sizeof err), -1, "a PPM is not an HDR file");
    CHECK_CONTAINS(err, "not a Radiance HDR", "the message");
}

/* ---- lightmaps ---------------------------------------------------------------------- */

/* A quad A B C D (counter-clockwise seen from its lit side) of reflectance RHO and
 * emission EMIT (grey). */
static sc_poly quad(const double *a, const double *b, const double *c, const double *d, double rho,
                    double emit)
{
    sc_poly q;
    int k;
    memset(&q, 0, sizeof q);
    q.n = 4;
    memcpy(q.v[0], a, sizeof q.v[0]);
    memcpy(q.v[1], b, sizeof q.v[1]);
    memcpy(q.v[2], c, sizeof q.v[2]);
    memcpy(q.v[3], d, sizeof q.v[3]);
    for (k = 0; k < 3; k++) {
        q.rho[k] = rho;
        q.emit[k] = emit;
    }
    return q;
}

/* A horizontal quad at height Y over [X0, X1] x [Z0, Z1], lit side up (UP 1) or down. */
static sc_poly flat(double x0, double x1, double z0, double z1, double y, int up, double rho,
                    double emit)
{
    double a[3] = {x0, y, z0}, b[3] = {x0, y, z1}, c[3] = {x1, y, z1}, d[3] = {x1, y, z0};
    return up ? quad(a, b, c, d, rho, emit) : quad(d, c, b, a, rho, emit);
}

typedef struct {
    sc_solver *s;
    sc_gatherer *g;
    int calls;
} baker;

static int gather_cb(void *ctx, const double p[3], const double n[3], double rgb[3])
{
    baker *b = ctx;
    b->calls++;
    return sc_gather(b->g, p, n, 1, rgb);
}

/* Builds and bakes A over solver S's solution (SIZE texels a side, gather resolution
 * RES, adaptive tolerance TOL, chart crease CREASE: lm_opts): the gathers done. */
static int bake_atlas(sc_solver *s, const sc_poly *polys, int n, int size, int res, double tol,
                      double crease, lm_atlas *a)
{
    lm_opts lo = {size, 0.0, 0, tol, crease};
    char err[256] = "";
    baker b = {NULL, NULL, 0};
    b.s = s;
    b.g = sc_gatherer_new(s, res, 0);
    assert_non_null(b.g);
    CHECK_INT_EQ(lm_build(a, polys, n, &lo, err, sizeof err), 0, "lm_build (%s)", err);
    CHECK_INT_EQ(lm_bake(a, gather_cb, NULL, &b), 0, "lm_bake");
    CHECK_INT_EQ(sc_gatherer_saturations(b.g), 0, "values saturated in the gathers");
    sc_gatherer_free(b.g);
    return b.calls;
}

/* Solves POLYS, then builds and bakes A (SIZE texels a side, gather resolution RES,
 * chart crease CREASE) at the default tolerance. */
static void bake_scene(const sc_poly *polys, int n, int size, int res, double crease, lm_atlas *a)
{
    sc_opts o = {.res = 64};
    char err[256] = "";
    sc_solver *s = sc_create(polys, n, &o, NULL, NULL, err, sizeof err);
    assert_non_null(s);
    sc_solve(s, 100000, 1e-4, NULL, NULL);
    bake_atlas(s, polys, n, size, res, LM_TOL, crease, a);
    sc_destroy(s);
}

/* Lambert's point-to-polygon form factor from P (normal +y) to polygon Q: Q in the
 * frame of ref_point_ff (P at the origin, the normal along +z). */
static double ff_up(const double *p, const sc_poly *q)
{
    sc_poly t = *q;
    int k;
    for (k = 0; k < q->n; k++) {
        t.v[k][0] = q->v[k][0] - p[0];
        t.v[k][1] = q->v[k][2] - p[2];
        t.v[k][2] = q->v[k][1] - p[1];
    }
    return ref_point_ff(&t);
}

/* A floor of reflectance 0 under a square emitter of emission 1 (reflectance 0): the
 * light arriving at each floor texel is the point's form factor to the emitter, which
 * the gather at resolution 64 finds within 1% (the brief's bound; tests/test_gather.c
 * bounds one point so). The error is the cube's aliasing of the emitter's outline, so
 * it grows as the emitter shrinks on the cube: the floor is 4 x 4 under a 2 x 2 emitter
 * at height 1 (its far corners at 3 units; on an 8 x 8 floor under one at height 2,
 * the corners' texels err by 3.9%). The atlas is 66 texels a side: a texel of 0.107,
 * the samples where 64 put them with two texels between charts (other texel sizes put
 * a few samples by the floor's far edge where the cube errs by up to 1.3%, every texel
 * gathered: the same aliasing). */
static void test_lightmap_lambert(void **state)
{
    sc_poly polys[2];
    lm_atlas a;
    double worst = 0.0;
    int x, y, n = 0;
    (void)state;
    polys[0] = flat(-2, 2, -2, 2, 0, 1, 0.0, 0.0);
    polys[1] = flat(-1, 1, -1, 1, 1, 0, 0.0, 1.0);
    bake_scene(polys, 2, 66, 64, 0.0, &a);
    for (y = 0; y < a.size; y++)
        for (x = 0; x < a.size; x++) {
            double p[3], want, rel;
            size_t at = (size_t)y * a.size + x;
            if (!lm_texel_point(&a, x, y, p) || a.owner[at] != a.poly_chart[0]) continue;
            want = ff_up(p, &polys[1]);
            rel = fabs(a.rgb[3 * at + 1] - want) / want;
            CHECK_LE(rel, 0.01, "texel %d,%d at (%.3f, %.3f, %.3f): E %.6f against F %.6f", x, y,
                     p[0], p[1], p[2], a.rgb[3 * at + 1], want);
            if (rel > worst) worst = rel;
            n++;
        }
    printf("lightmap under a square emitter: %d texels, worst %.4f%% from Lambert's form factor "
           "(bound 1%%)\n",
           n, 100.0 * worst);
    CHECK_INT_GE(n, (int)pow(floor(4.0 / a.texel), 2),
                 "floor texels compared (the floor is 4 / %g texels wide)", a.texel);
    lm_free(&a);
}

/* A terrain of TN x TN cells over [-4, 4]^2, two triangles a cell, heights of gentle
 * slopes (up to 0.05 / 1.1 = 2.6 degrees), under a 16 x 16 emitter at height 3: every
 * triangle its own chart. POLYS holds 2 TN^2 + 1. Returns the count. */
#define TN 8
static int terrain(sc_poly *polys)
{
    double h[TN + 1][TN + 1][3];
    int i, j, n = 0, k;
    for (i = 0; i <= TN; i++)
        for (j = 0; j <= TN; j++) {
            double x = -4.0 + 8.0 * i / TN, z = -4.0 + 8.0 * j / TN;
            h[i][j][0] = x;
            h[i][j][1] = 0.05 * sin(0.9 * x) * cos(0.7 * z);
            h[i][j][2] = z;
        }
    for (i = 0; i < TN; i++)
        for (j = 0; j < TN; j++) {
            const double *a = h[i][j], *b = h[i][j + 1], *c = h[i + 1][j + 1], *d = h[i + 1][j];
            sc_poly t[2];
            memset(t, 0, sizeof t);
            t[0].n = t[1].n = 3;
            memcpy(t[0].v[0], a, sizeof t[0].v[0]);
            memcpy(t[0].v[1], b, sizeof t[0].v[0]);
            memcpy(t[0].v[2], c, sizeof t[0].v[0]);
            memcpy(t[1].v[0], a, sizeof t[0].v[0]);
            memcpy(t[1].v[1], c, sizeof t[0].v[0]);
            memcpy(t[1].v[2], d, sizeof t[0].v[0]);
            for (k = 0; k < 3; k++) t[0].rho[k] = t[1].rho[k] = 0.5;
            polys[n++] = t[0];
            polys[n++] = t[1];
        }
    polys[n++] = flat(-8, 8, -8, 8, 3, 0, 0.0, 1.0);
    return n;
}

/* Edge K of polygon P is edge L of polygon Q (the same two vertices). */
static int shared_edge(const sc_poly *p, int k, const sc_poly *q, int *l)
{
    const double *a = p->v[k], *b = p->v[(k + 1) % p->n];
    for (*l = 0; *l < q->n; (*l)++) {
        const double *c = q->v[*l], *d = q->v[(*l + 1) % q->n];
        if (!memcmp(a, d, sizeof p->v[0]) && !memcmp(b, c, sizeof p->v[0])) return 1;
    }
    return 0;
}

/* No seams: with coplanar charts only (lm_opts.crease -1), along every edge two charts
 * share, bilinear lookups from both sides (at
 * nine points of the edge) agree within 2% (the brief's bound). The light arriving is
 * continuous across a fold of a few degrees, so a difference is the atlas's: a texel
 * of padding or of another chart read, a wrong UV, or the interpolation of the light's
 * gradient across the texel at the edge, which each side takes from its own inside:
 * the terrain's texels span 0.80..0.90, and under a smaller emitter
 * (12 x 12), where it falls 19% a unit near the edge, the 0.4-unit texels of a 128
 * atlas differ by 2.9% (by 4.2% when only the texels that the chart touches are
 * gathered and their ring is dilated). A gather resolution of 32 is enough here: 64
 * changes the worst by 0.05 points. */
static void test_lightmap_no_seams(void **state)
{
    sc_poly polys[2 * TN * TN + 1];
    lm_atlas a;
    int n = terrain(polys), p, q, k, l, t, edges = 0;
    double worst = 0.0, lo = HUGE_VAL, hi = 0.0;
    (void)state;
    bake_scene(polys, n, 192, 32, -1.0, &a); /* coplanar charts only: seams everywhere */
    CHECK_INT_EQ(a.ncharts, n, "charts of the terrain: every triangle");
    for (p = 0; p < n; p++)
        for (q = 0; q < n; q++)
            for (k = 0; k < polys[p].n; k++) {
                if (p == q || a.poly_chart[p] == a.poly_chart[q] ||
                    !shared_edge(&polys[p], k, &polys[q], &l))
                    continue;
                edges++;
                for (t = 1; t <= 9; t++) {
                    double w = t / 10.0, x[3], uvp[2], uvq[2], cp[3], cq[3], rel;
                    int c;
                    for (c = 0; c < 3; c++)
                        x[c] = polys[p].v[k][c] +
                               w * (polys[p].v[(k + 1) % polys[p].n][c] - polys[p].v[k][c]);
                    lm_uv(&a, p, x, uvp);
                    lm_uv(&a, q, x, uvq);
                    lm_lookup(&a, uvp, cp);
                    lm_lookup(&a, uvq, cq);
                    rel = fabs(cp[1] - cq[1]) / fmax(cp[1], cq[1]);
                    CHECK_LE(rel, 0.02,
                             "polygons %d and %d at (%.3f, %.3f, %.3f): %.6f against %.6f", p, q,
                             x[0], x[1], x[2], cp[1], cq[1]);
                    if (rel > worst) worst = rel;
                }
            }
    for (p = 0; p < a.size * a.size; p++)
        if (!isnan(a.sample[2 * p]) && a.owner[p] < n - 1) {
            lo = fmin(lo, a.rgb[3 * p + 1]);
            hi = fmax(hi, a.rgb[3 * p + 1]);
        }
    printf("lightmap seams: terrain texels %.4f..%.4f; %d shared edges (each seen from both sides) "
           "of %d charts, worst %.3f%% (bound 2%%)\n",
           lo, hi, edges, a.ncharts, 100.0 * worst);
    CHECK_INT_EQ(edges, 2 * (3 * TN * TN - 2 * TN), "shared edges found, from both sides");
    lm_free(&a);
}

/* The texel of the atlas holding world point X of polygon P. */
static size_t texel_at(const lm_atlas *a, int p, const double *x)
{
    double uv[2];
    lm_uv(a, p, x, uv);
    return (size_t)floor(uv[1]) * a->size + (size_t)floor(uv[0]);
}

/* No leaks: a room's floor meets a wall at x = 0, and behind the wall a bright emitter
 * (10, against 1 of the room's light) faces it. The floor's light at the wall (a
 * bilinear lookup, which reads the texels there and their ring) is not brighter than
 * one texel further in, beyond the gathers' aliasing (up to 0.84% in the Lambert test
 * above, either side: 2%): the samples stay inside the room, off the wall's plane. A
 * sample on it sees the wall edge-on and past it the bright emitter: with the samples
 * at the nearest point of the floor, not moved in, the wall's texels measured 9 times
 * the next ones in. The room's light is over its middle, so the light falls off
 * towards the wall (but for the gathers' aliasing: 1.6% brighter at one point). */
static void test_lightmap_no_leaks(void **state)
{
    double w0[3] = {0, 0, 0}, w1[3] = {0, 0, 4}, w2[3] = {0, 3, 4}, w3[3] = {0, 3, 0};
    double e0[3] = {-2, 0, 0}, e1[3] = {-2, 0, 4}, e2[3] = {-2, 3, 4}, e3[3] = {-2, 3, 0};
    sc_poly polys[4];
    lm_atlas a;
    int i, n = 0;
    double worst = -HUGE_VAL;
    (void)state;
    polys[0] = flat(0, 4, 0, 4, 0, 1, 0.5, 0.0);
    polys[1] = quad(w0, w3, w2, w1, 0.5, 0.0);  /* faces +x, into the room */
    polys[2] = quad(e0, e3, e2, e1, 0.0, 10.0); /* faces +x, at the wall's back */
    polys[3] = flat(1, 3, 1, 3, 3, 0, 0.0, 1.0);
    bake_scene(polys, 4, 128, 64, 0.0, &a);
    for (i = 0; i < 40; i++) {
        double z = 0.05 + 3.9 * i / 39.0, x0[3] = {1e-3 * a.texel, 0, z},
               x1[3] = {1.001 * a.texel, 0, z};
        double uv0[2], uv1[2], c0[3], c1[3];
        lm_uv(&a, 0, x0, uv0);
        lm_uv(&a, 0, x1, uv1);
        lm_lookup(&a, uv0, c0);
        lm_lookup(&a, uv1, c1);
        CHECK_LE(c0[1], 1.02 * c1[1],
                 "floor at the wall, z = %.3f (bilinear), against 1.02 x one texel further in", z);
        if (c0[1] / c1[1] > worst) worst = c0[1] / c1[1];
        n++;
    }
    printf("lightmap leaks: %d floor points at the wall, at most %.4f of the next one in (bound "
           "1.02)\n",
           n, worst);
    lm_free(&a);
}

static int cube(sc_poly *q, double lo, double hi, int inward, double emit);

/* The scene of test_lightmap_adaptive with its floor cut into TILES x TILES coplanar
 * quads, baked both ways: the adaptive bake's gathers into *NA, the every-texel
 * bake's into *NE, the interpolated texels' worst and rms errors into *WORST, *RMS. */
static void adaptive_case(int tiles, int *na, int *ne, double *worst, double *rms)
{
    sc_opts o = {.res = 64};
    char err[256] = "";
    lm_atlas ex, ad;
    sc_poly polys[7 + 256];
    sc_solver *s;
    int n = 0, covered = 0, lerped = 0, same = 1, tx, tz;
    size_t i;
    double sq = 0.0, w = 4.0 / tiles;
    for (tz = 0; tz < tiles; tz++)
        for (tx = 0; tx < tiles; tx++)
            polys[n++] = flat(-2 + tx * w, -2 + (tx + 1) * w, -2 + tz * w, -2 + (tz + 1) * w, 0, 1,
                              0.5, 0.0);
    polys[n++] = flat(-1, 1, -1, 1, 2, 0, 0.0, 1.0);
    cube(polys + n, 0.0, 0.6, 0, 0.0);
    for (i = (size_t)n; i < (size_t)n + 6; i++)
        polys[i].rho[0] = polys[i].rho[1] = polys[i].rho[2] = 0.5;
    n += 6;
    s = sc_create(polys, n, &o, NULL, NULL, err, sizeof err);
    assert_non_null(s);
    sc_solve(s, 100000, 1e-4, NULL, NULL);
    *ne = bake_atlas(s, polys, n, 128, 32, 0.0, 0.0, &ex);
    *na = bake_atlas(s, polys, n, 128, 32, LM_TOL, 0.0, &ad);
    *worst = 0.0;
    for (i = 0; i < (size_t)ex.size * ex.size; i++) {
        double top = 0.0, d = 0.0;
        int k;
        if (isnan(ex.sample[2 * i])) continue;
        covered++;
        if (ad.state[i] & LM_GATHERED) {
            same &= !memcmp(&ad.rgb[3 * i], &ex.rgb[3 * i], 3 * sizeof *ad.rgb);
            continue;
        }
        CHECK_THAT(ad.state[i] & LM_LERPED, "texel %d,%d gathered or interpolated",
                   (int)(i % ex.size), (int)(i / ex.size));
        for (k = 0; k < 3; k++) {
            top = fmax(top, ex.rgb[3 * i + k]);
            d = fmax(d, fabs(ad.rgb[3 * i + k] - ex.rgb[3 * i + k]));
        }
        d = top > 0.0 ? d / top : d;
        *worst = fmax(*worst, d);
        sq += d * d;
        lerped++;
    }
    *rms = sqrt(sq / (lerped ? lerped : 1));
    printf("lightmap adaptive (tolerance %g, floor of %d x %d quads) against every texel: %d of "
           "%d texels gathered (%.1f%%), %d interpolated: worst %.2f%%, rms %.2f%%\n",
           LM_TOL, tiles, tiles, *na, *ne, 100.0 * *na / *ne, lerped, 100.0 * *worst, 100.0 * *rms);
    CHECK_INT_EQ(*ne, covered, "the every-texel bake's gathers: the covered texels");
    CHECK_INT_EQ(*na + lerped, covered, "texels gathered or interpolated");
    CHECK_THAT(same, "the texels both bakes gather: the same bits");
    CHECK_INT_EQ(lm_undecided(&ad), 0, "texels neither gathered nor interpolated after the bake");
    { /* lm_undecided (rad_cli's note on long bakes): every covered texel before the
       * first pass, all but its gathers after it */
        lm_opts lo = {128, 0.0, 0, LM_TOL, 0.0};
        lm_atlas f;
        baker b = {NULL, NULL, 0};
        long first;
        b.s = s;
        b.g = sc_gatherer_new(s, 32, 0);
        assert_non_null(b.g);
        CHECK_INT_EQ(lm_build(&f, polys, n, &lo, err, sizeof err), 0, "lm_build (%s)", err);
        first = lm_plan(&f);
        CHECK_INT_EQ(lm_undecided(&f), covered, "texels undecided before the first pass");
        CHECK_INT_EQ(lm_gather_rows(&f, 0, 1, gather_cb, &b), 0, "the first pass");
        CHECK_INT_EQ(lm_undecided(&f), covered - first,
                     "texels undecided after the first pass's %ld gathers", first);
        lm_free(&f);
        sc_gatherer_free(b.g);
    }
    lm_free(&ex);
    lm_free(&ad);
    sc_destroy(s);
}

/* Adaptive gathering against gathering every texel, over one solution: a floor of
 * reflectance 0.5 under a 2 x 2 emitter at height 2, a box (a cube of 0.6, reflectance
 * 0.5) standing on it, at 128 x 128 texels, gather resolution 32: the box's shadow,
 * its contact with the floor and the light's fall-off towards the floor's edges. Every
 * texel the adaptive bake gathers has the every-texel bake's bits (the same sample,
 * the same gather); the others, interpolated, are compared per texel (the largest
 * channel difference over the exact texel's largest channel). Measured: 85.4% of the
 * texels gathered (a small atlas: most blocks touch a boundary, the box or the ring),
 * the interpolated within 3.20%, rms 0.56%; the bounds leave a margin over that. Part
 * of what is measured is the every-texel bake's own noise: the cube's pixels that the
 * emitter's outline covers change from texel to texel, and interpolation keeps only the
 * corners' share of it. */
static void test_lightmap_adaptive(void **state)
{
    int na1, ne1, nat, net;
    double worst, rms;
    (void)state;
    adaptive_case(1, &na1, &ne1, &worst, &rms);
    CHECK_LE(worst, 0.07, "the worst interpolated texel's error");
    CHECK_LE(rms, 0.01, "the interpolated texels' rms error");
    CHECK_LE(na1, 0.9 * ne1, "texels gathered of the every-texel bake's");
    /* A floor of tiles is one surface to the adaptive bake: blocks spanning coplanar
     * polygons interpolate as within one (a level's floors and walls are tiles; when a
     * block had to lie on one polygon, 84% of a generated level's texels were gathered
     * at 1024 x 1024 under constant light, 49% with blocks on one plane). The floor cut
     * into 16 x 16 quads (8 texels a side: every block of 4 spans two) interpolates at
     * least 0.95 of the texels the whole floor does, within the same error bounds.
     * Measured: 1,418 against 1,408 (one polygon a block: 1,155). */
    adaptive_case(16, &nat, &net, &worst, &rms);
    CHECK_LE(worst, 0.07, "the worst interpolated texel's error, 16 x 16 tiles");
    CHECK_LE(rms, 0.01, "the interpolated texels' rms error, 16 x 16 tiles");
    CHECK_LE(0.95 * (ne1 - na1), net - nat,
             "texels interpolated on 16 x 16 tiles (%d) against one floor quad (%d)", net - nat,
             ne1 - na1);
}

/* Packing: the charts' rectangles lie inside the atlas, apart; every polygon's
 * vertices inside its rectangle's ring and gutter; every point of a polygon (a lattice
 * of 55 points inside each triangle) in a covered texel of its own chart. */
static void test_lightmap_packing(void **state)
{
    sc_poly polys[2 * TN * TN + 1];
    lm_opts o = {160, 0.0, 0, LM_TOL, 0.0};
    lm_atlas a;
    char err[256] = "";
    int n = terrain(polys), i, j, k, points = 0;
    (void)state;
    CHECK_INT_EQ(lm_build(&a, polys, n, &o, err, sizeof err), 0, "lm_build (%s)", err);
    for (i = 0; i < a.ncharts; i++) {
        const lm_chart *c = &a.charts[i];
        CHECK_THAT(c->x >= 0 && c->y >= 0 && c->x + c->w <= a.size && c->y + c->h <= a.size,
                   "chart %d's rectangle %d,%d %dx%d inside the atlas of %d", i, c->x, c->y, c->w,
                   c->h, a.size);
        for (j = 0; j < i; j++) {
            const lm_chart *d = &a.charts[j];
            int apart = c->x >= d->x + d->w || d->x >= c->x + c->w || c->y >= d->y + d->h ||
                        d->y >= c->y + c->h;
            CHECK_THAT(apart, "charts %d and %d: rectangles %d,%d %dx%d and %d,%d %dx%d apart", i,
                       j, c->x, c->y, c->w, c->h, d->x, d->y, d->w, d->h);
        }
    }
    for (i = 0; i < n; i++) {
        const lm_chart *c = &a.charts[a.poly_chart[i]];
        for (k = 0; k < polys[i].n; k++) {
            double uv[2];
            lm_uv(&a, i, polys[i].v[k], uv);
            int e = a.padding + 1; /* the gutter and the ring */
            CHECK_THAT(uv[0] >= c->x + e - 1e-9 && uv[0] <= c->x + c->w - e + 1e-9 &&
                           uv[1] >= c->y + e - 1e-9 && uv[1] <= c->y + c->h - e + 1e-9,
                       "polygon %d vertex %d at %.3f,%.3f inside its rectangle's ring and gutter "
                       "(to 1e-9)",
                       i, k, uv[0], uv[1]);
        }
        for (j = 0; j < 10; j++)
            for (k = 0; k < 10 - j; k++) {
                double x[3], w1 = (j + 1) / 12.0, w2 = (k + 1) / 12.0;
                size_t t;
                int c3;
                for (c3 = 0; c3 < 3; c3++)
                    x[c3] = polys[i].v[0][c3] + w1 * (polys[i].v[1][c3] - polys[i].v[0][c3]) +
                            w2 * (polys[i].v[2][c3] - polys[i].v[0][c3]);
                t = texel_at(&a, i, x);
                CHECK_THAT(!isnan(a.sample[2 * t]) && a.owner[t] == a.poly_chart[i],
                           "polygon %d point %d,%d: its texel covered and of its chart", i, j, k);
                points++;
            }
    }
    printf("lightmap packing: %d charts in %dx%d at a texel of %.4f, %d polygon points in covered "
           "texels\n",
           a.ncharts, a.size, a.size, a.texel, points);
    lm_free(&a);
}

/* The square [X0, X0 + 4] x [0, 4] at height 0, lit side up, as four 2 x 2 regions
 * tessellated 3x3 in quads, 4x4 in triangles, 5x5 in quads and 2x2 in triangles: where
 * two regions meet, vertices of one lie inside the other's edges (T-junctions). Into
 * POLYS (at most 9 + 32 + 25 + 8); returns the count. */
static int tessellated(sc_poly *polys, double x0, double rho)
{
    static const int res[4] = {3, 4, 5, 2};
    int r, i, j, n = 0;
    for (r = 0; r < 4; r++) {
        double ox = x0 + 2.0 * (r % 2), oz = 2.0 * (r / 2), s = 2.0 / res[r];
        for (j = 0; j < res[r]; j++)
            for (i = 0; i < res[r]; i++) {
                double a[3] = {ox + s * i, 0, oz + s * j}, b[3] = {ox + s * i, 0, oz + s * (j + 1)};
                double c[3] = {ox + s * (i + 1), 0, oz + s * (j + 1)},
                       d[3] = {ox + s * (i + 1), 0, oz + s * j};
                polys[n] = quad(a, b, c, d, rho, 0.0);
                if (r % 2) { /* two triangles: a b c and a c d */
                    polys[n].n = 3;
                    polys[++n] = quad(a, c, d, d, rho, 0.0);
                    polys[n].n = 3;
                }
                n++;
            }
    }
    return n;
}

/* Charts: the tessellated square (T-junctions between its regions) is one chart; a
 * coplanar square apart from it another; a wall standing on its edge (a 90 degree
 * bend, sharing the square's vertices) a third. */
static void test_lightmap_charts(void **state)
{
    sc_poly polys[80];
    lm_opts o = {128, 0.0, 0, LM_TOL, 0.0};
    lm_atlas a;
    char err[256] = "";
    int n = tessellated(polys, 0.0, 0.5), i, plane;
    double w0[3] = {0, 0, 0}, w1[3] = {0, 2, 0}, w2[3] = {0, 2, 2}, w3[3] = {0, 0, 2};
    (void)state;
    plane = n;
    polys[n++] = flat(6, 8, 0, 2, 0, 1, 0.5, 0);
    polys[n++] = quad(w0, w1, w2, w3, 0.5, 0); /* x = 0, facing +x */
    CHECK_INT_EQ(lm_build(&a, polys, n, &o, err, sizeof err), 0, "lm_build (%s)", err);
    for (i = 1; i < plane; i++)
        CHECK_INT_EQ(a.poly_chart[i], a.poly_chart[0],
                     "polygon %d of the tessellated square: its chart", i);
    CHECK_THAT(a.poly_chart[plane] != a.poly_chart[0], "the square apart has a chart of its own");
    CHECK_THAT(a.poly_chart[plane + 1] != a.poly_chart[0],
               "the wall (a 90 degree bend) has a chart of its own");
    CHECK_INT_EQ(a.ncharts, 3, "charts");
    printf("lightmap charts: %d polygons (a square in %d with T-junctions, a square apart, a "
           "wall): %d charts\n",
           n, plane, a.ncharts);
    lm_free(&a);
}

/* The merged chart's light against one quad's: the tessellated square and a single
 * 4 x 4 quad, each black (rho 0: only the emitter's direct light, so the solver's
 * meshes do not matter) under a 2 x 2 emitter at height 1, baked at one texel size
 * (0.1) with every texel gathered: bilinear lookups at a lattice of 39 x 39 points over
 * the square agree within 0.5%. Both charts put texel centres at the same points (the
 * same extent and texel), so they can differ only where a sample moves 1/8 texel in
 * from a boundary edge, which the tessellated square may have inside (its T-junctions'
 * edges are not shared whole); the light's gradient here is below 0.4 a unit, 0.005
 * over 1/8 texel against values above 0.03: below 0.2%, and 0.5% leaves room for the
 * gather's aliasing of the emitter's outline at moved points. (Before T-junctions
 * joined charts, its four regions' charts agreed within 0.17%.) */
static void test_lightmap_merged_light(void **state)
{
    sc_poly polys[2][80];
    lm_opts o = {128, 0.1, 0, 0.0, 0.0};
    lm_atlas a[2];
    int n[2], m, i, j, charts[2];
    double worst = 0.0;
    (void)state;
    n[0] = tessellated(polys[0], 0.0, 0.0);
    polys[1][0] = flat(0, 4, 0, 4, 0, 1, 0.0, 0.0);
    n[1] = 1;
    for (m = 0; m < 2; m++) {
        sc_opts so = {0, 0, 64, 0, 0, 0, 0, 0, NULL, 0};
        char err[256] = "";
        sc_solver *s;
        baker b = {NULL, NULL, 0};
        polys[m][n[m]++] = flat(1, 3, 1, 3, 1, 0, 0.0, 1.0);
        s = sc_create(polys[m], n[m], &so, NULL, NULL, err, sizeof err);
        assert_non_null(s);
        sc_solve(s, 100000, 1e-4, NULL, NULL);
        b.s = s;
        b.g = sc_gatherer_new(s, 64, 0);
        CHECK_INT_EQ(lm_build(&a[m], polys[m], n[m], &o, err, sizeof err), 0, "lm_build (%s)", err);
        CHECK_INT_EQ(lm_bake(&a[m], gather_cb, NULL, &b), 0, "lm_bake");
        charts[m] = a[m].ncharts;
        sc_gatherer_free(b.g);
        sc_destroy(s);
    }
    for (j = 1; j < 40; j++)
        for (i = 1; i < 40; i++) {
            double x[3] = {0.1 * i, 0.0, 0.1 * j}, uv[2], e[2][3], rel;
            int p;
            for (m = 0; m < 2; m++) {
                for (p = 0; p < n[m] - 1; p++) { /* the polygon holding X */
                    double lo[2] = {HUGE_VAL, HUGE_VAL}, hi[2] = {-HUGE_VAL, -HUGE_VAL};
                    int k;
                    for (k = 0; k < polys[m][p].n; k++) {
                        lo[0] = fmin(lo[0], polys[m][p].v[k][0]);
                        hi[0] = fmax(hi[0], polys[m][p].v[k][0]);
                        lo[1] = fmin(lo[1], polys[m][p].v[k][2]);
                        hi[1] = fmax(hi[1], polys[m][p].v[k][2]);
                    }
                    if (x[0] >= lo[0] && x[0] <= hi[0] && x[2] >= lo[1] && x[2] <= hi[1]) break;
                }
                CHECK_INT_EQ(lm_uv(&a[m], p, x, uv), 0, "lm_uv");
                lm_lookup(&a[m], uv, e[m]);
            }
            rel = fabs(e[0][1] - e[1][1]) / e[1][1];
            CHECK_LE(rel, 0.005, "at (%.1f, 0, %.1f): tessellated %.6f against one quad %.6f", x[0],
                     x[2], e[0][1], e[1][1]);
            worst = fmax(worst, rel);
        }
    printf(
        "lightmap merged light: %d and %d charts, 1521 points, worst %.4f%% apart (bound 0.5%%)\n",
        charts[0], charts[1], 100.0 * worst);
    lm_free(&a[0]);
    lm_free(&a[1]);
}

#define TURN 6.283185307179586 /* radians a turn */

/* Quad A B C D turned (reversed) so that its lit side faces along WANT. */
static sc_poly facing(const double *a, const double *b, const double *c, const double *d,
                      const double *want)
{
    double e[3], f[3], nn[3];
    int k;
    for (k = 0; k < 3; k++) {
        e[k] = c[k] - a[k];
        f[k] = d[k] - b[k];
    }
    nn[0] = e[1] * f[2] - e[2] * f[1];
    nn[1] = e[2] * f[0] - e[0] * f[2];
    nn[2] = e[0] * f[1] - e[1] * f[0];
    return nn[0] * want[0] + nn[1] * want[1] + nn[2] * want[2] >= 0 ? quad(a, b, c, d, 0.5, 0.0)
                                                                    : quad(d, c, b, a, 0.5, 0.0);
}

/* Quad of corners at angles A (about the y axis), radii R and heights Y, turned to
 * face WANT. */
static sc_poly ring_quad(const double *a, const double *r, const double *y, const double *want)
{
    double v[4][3];
    int k;
    for (k = 0; k < 4; k++) {
        v[k][0] = r[k] * cos(a[k]);
        v[k][1] = y[k];
        v[k][2] = r[k] * sin(a[k]);
    }
    return facing(v[0], v[1], v[2], v[3], want);
}

/* A cylinder's side of SEG facets, radius 1, from y 0 to 2 in 4 rings, facing out.
 * Returns the quads written to P. */
static int cylinder(sc_poly *p, int seg)
{
    int i, j, n = 0;
    for (i = 0; i < seg; i++)
        for (j = 0; j < 4; j++) {
            double a0 = TURN * i / seg, a1 = TURN * (i + 1) / seg, mid = 0.5 * (a0 + a1);
            double a[4] = {a0, a1, a1, a0}, r[4] = {1, 1, 1, 1},
                   y[4] = {0.5 * j, 0.5 * j, 0.5 * j + 0.5, 0.5 * j + 0.5};
            double want[3] = {cos(mid), 0.0, sin(mid)};
            p[n++] = ring_quad(a, r, y, want);
        }
    return n;
}

/* A spiral ramp between radii 1 and 2 (2 quads across), SEG quads along it of DA
 * radians each, rising RISE a turn, facing up. Returns the quads written to P. */
static int ramp(sc_poly *p, int seg, double da, double rise)
{
    int i, j, n = 0;
    for (i = 0; i < seg; i++)
        for (j = 0; j < 2; j++) {
            double a0 = da * i, a1 = da * (i + 1), y0 = rise * a0 / TURN, y1 = rise * a1 / TURN;
            double a[4] = {a0, a1, a1, a0},
                   r[4] = {1 + 0.5 * j, 1 + 0.5 * j, 1.5 + 0.5 * j, 1.5 + 0.5 * j};
            double y[4] = {y0, y1, y1, y0}, up[3] = {0, 1, 0};
            p[n++] = ring_quad(a, r, y, up);
        }
    return n;
}

/* No texel of a chart holds two parts of the surface: at a lattice of 5 x 5 points
 * inside each quad of P[0..N), the texel that lm_uv puts the point in has its sample
 * within 2 texels of the point. A sample lies within its texel's square on the chart's
 * plane (half a diagonal, 0.71 texels) lifted onto the polygon (times 1 / cos 25
 * degrees at most: 0.78), or moved out of geometry by its rays (3/4 texel more): 1.6
 * texels; a layout that folds over itself puts it on the other sheet instead. Returns
 * the worst distance in texels. */
static double texel_nearness(const lm_atlas *a, const sc_poly *p, int n)
{
    double worst = 0.0;
    int i, si, ti, k;
    for (i = 0; i < n; i++)
        for (si = 0; si < 5; si++)
            for (ti = 0; ti < 5; ti++) {
                double s = 0.1 + 0.2 * si, t = 0.1 + 0.2 * ti, x[3], uv[2], q[3], d;
                for (k = 0; k < 3; k++)
                    x[k] = (1 - t) * ((1 - s) * p[i].v[0][k] + s * p[i].v[1][k]) +
                           t * ((1 - s) * p[i].v[3][k] + s * p[i].v[2][k]);
                CHECK_INT_EQ(lm_uv(a, i, x, uv), 0, "lm_uv of quad %d", i);
                CHECK_INT_EQ(lm_texel_point(a, (int)floor(uv[0]), (int)floor(uv[1]), q), 1,
                             "quad %d at (%.3f, %.3f, %.3f): its texel covered", i, x[0], x[1],
                             x[2]);
                d = sqrt((q[0] - x[0]) * (q[0] - x[0]) + (q[1] - x[1]) * (q[1] - x[1]) +
                         (q[2] - x[2]) * (q[2] - x[2])) /
                    a->texel;
                CHECK_LE(
                    d, 2.0,
                    "quad %d at (%.3f, %.3f, %.3f): its texel's sample %.3f texels away (chart %d)",
                    i, x[0], x[1], x[2], d, a->poly_chart[i]);
                worst = fmax(worst, d);
            }
    return worst;
}

/* The charts of the N quads P (in an atlas of 256 texels a side) number LO..HI, and
 * none of their texels holds two parts of the surface; the counts printed. */
static void smooth_shape(const char *what, const sc_poly *p, int n, int lo, int hi)
{
    lm_opts o = {256, 0.0, 0, 0.0, 0.0};
    lm_atlas a;
    char err[256] = "";
    double worst;
    CHECK_INT_EQ(lm_build(&a, p, n, &o, err, sizeof err), 0, "lm_build (%s)", err);
    CHECK_INT_GE(a.ncharts, lo, "charts of %s", what);
    CHECK_INT_LE(a.ncharts, hi, "charts of %s", what);
    worst = texel_nearness(&a, p, n);
    printf("lightmap smooth charts: %s (%d quads): %d charts (bounds %d..%d), samples within %.2f "
           "texels\n",
           what, n, a.ncharts, lo, hi, worst);
    lm_free(&a);
}

/* Charts joined across gentle folds (lm_opts.crease, LM_CREASE 25 degrees by default):
 * a floor of 12 x 12 quads is one chart and an L of two perpendicular walls (3 x 3
 * quads each, standing on the floor) two more; a cylinder of 24 facets (15 degrees
 * apart) in 4 rings has fewer charts than facets, at least 24 / 3 (a chart's facets lie
 * within 25 degrees of its seed's: three, so 8 or more); a spiral ramp of 1.5 turns
 * (every normal within 6 degrees of up) folds over itself on any one plane, so it takes
 * two charts or more (about a turn each: up to 4). None of their texels holds two parts of the surface (texel_nearness). */
static void test_lightmap_smooth_charts(void **state)
{
    static sc_poly polys[400];
    lm_opts o = {256, 0.0, 0, 0.0, 0.0};
    lm_atlas a;
    char err[256] = "";
    int n = 0, i, j, floor_n, walls;
    double worst;
    (void)state;
    for (i = 0; i < 12; i++)
        for (j = 0; j < 12; j++)
            polys[n++] = flat(0.5 * i, 0.5 * (i + 1), 0.5 * j, 0.5 * (j + 1), 0, 1, 0.5, 0);
    floor_n = n;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) {
            double a0[3] = {0, j, 2.0 * i}, a1[3] = {0, j, 2.0 * i + 2},
                   a2[3] = {0, j + 1, 2.0 * i + 2}, a3[3] = {0, j + 1, 2.0 * i},
                   b0[3] = {2.0 * i, j, 0}, b1[3] = {2.0 * i + 2, j, 0},
                   b2[3] = {2.0 * i + 2, j + 1, 0}, b3[3] = {2.0 * i, j + 1, 0}, px[3] = {1, 0, 0},
                   pz[3] = {0, 0, 1};
            polys[n++] = facing(a0, a1, a2, a3, px);
            polys[n++] = facing(b0, b1, b2, b3, pz);
        }
    walls = n - floor_n;
    CHECK_INT_EQ(lm_build(&a, polys, n, &o, err, sizeof err), 0, "lm_build (%s)", err);
    for (i = 1; i < floor_n; i++)
        CHECK_INT_EQ(a.poly_chart[i], a.poly_chart[0], "floor quad %d: its chart", i);
    for (i = floor_n + 2; i < n; i++)
        CHECK_INT_EQ(a.poly_chart[i], a.poly_chart[floor_n + (i - floor_n) % 2],
                     "wall quad %d: its wall's chart", i);
    CHECK_INT_EQ(a.ncharts, 3, "charts of the floor and the L of walls");
    worst = texel_nearness(&a, polys, n);
    printf("lightmap smooth charts: a floor of %d quads and an L of two walls of %d: %d charts, "
           "samples within %.2f "
           "texels\n",
           floor_n, walls, a.ncharts, worst);
    lm_free(&a);

    smooth_shape("a cylinder of 24 facets", polys, cylinder(polys, 24), 8, 23);
    smooth_shape("a spiral ramp of 1.5 turns", polys, ramp(polys, 54, TURN / 36, 0.6), 2, 4);
}

/* The terrain (gentle slopes of up to 2.6 degrees) baked as one chart (the default
 * crease) against coplanar charts only (every triangle its own): bilinear lookups at
 * each triangle's centroid and the midpoints of its edges agree within 2%, the no-seams
 * bound: the light is continuous over the terrain, and the two atlases differ only in
 * where their texel centres fall (their texel sizes differ) and so in how each
 * interpolates the light's gradient. */
/* Under RAD_TEST_LIGHT (make check's valgrind stage) the two largest cases below are
 * left to the other runs: 3.5 and 1.8 of test_bake's 10.6 s of its own (the rest is
 * rad_cli, not under valgrind), 40 times that under valgrind; the code they run (the
 * bake, lm_build) is run by the smaller cases. */
static int skip_when_light(const char *what)
{
    if (!getenv("RAD_TEST_LIGHT")) return 0;
    printf("%s: left to the runs without RAD_TEST_LIGHT\n", what);
    return 1;
}

static void test_lightmap_smooth_light(void **state)
{
    sc_poly polys[2 * TN * TN + 1];
    lm_atlas a[2];
    int n, p, k, m, c, points = 0;
    double worst = 0.0;
    (void)state;
    if (skip_when_light("lightmap smooth light")) skip();
    n = terrain(polys);
    bake_scene(polys, n, 192, 32, -1.0, &a[0]);
    bake_scene(polys, n, 192, 32, 0.0, &a[1]);
    CHECK_INT_EQ(a[1].ncharts, 2, "charts of the terrain and its emitter at the default crease");
    for (p = 0; p < n - 1; p++)
        for (k = 0; k <= polys[p].n; k++) {
            double x[3], uv[2], e[2][3], rel;
            for (c = 0; c < 3; c++)
                x[c] = k == polys[p].n
                           ? (polys[p].v[0][c] + polys[p].v[1][c] + polys[p].v[2][c]) / 3.0
                           : 0.5 * (polys[p].v[k][c] + polys[p].v[(k + 1) % 3][c]);
            for (m = 0; m < 2; m++) {
                lm_uv(&a[m], p, x, uv);
                lm_lookup(&a[m], uv, e[m]);
            }
            rel = fabs(e[0][1] - e[1][1]) / fmax(e[0][1], e[1][1]);
            CHECK_LE(
                rel, 0.02,
                "triangle %d at (%.3f, %.3f, %.3f): one chart %.6f against coplanar charts %.6f", p,
                x[0], x[1], x[2], e[1][1], e[0][1]);
            worst = fmax(worst, rel);
            points++;
        }
    printf("lightmap smooth light: the terrain as %d chart(s) against %d, %d points, worst %.3f%% "
           "apart (bound 2%%)\n",
           a[1].ncharts - 1, a[0].ncharts - 1, points, 100.0 * worst);
    lm_free(&a[0]);
    lm_free(&a[1]);
}

/* The generated level (tools/bench/level.h, rad_bench --level): over 60,000 polygons,
 * laid out in a 1024 x 1024 atlas in fewer than 3,000 charts (the goal for a
 * level of Sponza's class, whose coplanar charts were 27,172); its coplanar charts alone
 * are more (its columns' and arches' facets each one). */
static void test_lightmap_level_charts(void **state)
{
    sc_light lights[LEVEL_LIGHTS];
    lm_opts o = {1024, 0.0, 0, LM_TOL, 0.0};
    lm_atlas a;
    char err[256] = "";
    int n, smooth;
    sc_poly *p;
    (void)state;
    if (skip_when_light("lightmap level")) skip();
    p = level_atrium(&n, lights);
    assert_non_null(p);
    CHECK_INT_GE(n, 60000, "polygons of the generated level");
    CHECK_INT_EQ(lm_build(&a, p, n, &o, err, sizeof err), 0, "lm_build (%s)", err);
    smooth = a.ncharts;
    CHECK_INT_LE(smooth, 2999, "charts of the generated level at the default crease");
    lm_free(&a);
    o.crease = -1.0;
    CHECK_INT_EQ(lm_build(&a, p, n, &o, err, sizeof err), 0, "lm_build (%s)", err);
    CHECK_INT_GE(a.ncharts, smooth + 1, "coplanar charts of the level: more than smooth ones");
    printf(
        "lightmap level: %d polygons, %d charts (coplanar only: %d) in 1024 x 1024 (bound 2999)\n",
        n, smooth, a.ncharts);
    lm_free(&a);
    free(p);
}

/* Light by position: pure red left of x = 2, pure green right of it. */
static int two_colour_cb(void *ctx, const double p[3], const double n[3], double rgb[3])
{
    (void)ctx;
    (void)n;
    rgb[0] = p[0] < 2.0 ? 1.0 : 0.0;
    rgb[1] = p[0] < 2.0 ? 0.0 : 1.0;
    rgb[2] = 0.0;
    return 0;
}

/* Gutters for mipmaps: two coplanar but disjoint squares (two charts), one lit red and
 * one green. Every texel within the padding of a chart's covered texels holds none of
 * the other chart's colour (the gutter is dilated from its own chart only), and in the
 * box-filtered mip levels m with 2^m <= padding + 1 every texel whose block holds a
 * chart's covered texel holds none of the other's: the block reaches at most 2^m - 1
 * texels past the chart's texels, inside its own gutter. Exact: the colours are pure. */
static void test_lightmap_gutter(void **state)
{
    sc_poly polys[2];
    lm_opts o = {512, 0.0, 0, 0.0, 0.0};
    lm_atlas a;
    char err[256] = "";
    int x, y, m, dx, dy, checked = 0, levels = 0;
    (void)state;
    polys[0] = flat(0, 1, 0, 1, 0, 1, 0.5, 0);
    polys[1] = flat(3, 4, 0, 1, 0, 1, 0.5, 0);
    CHECK_INT_EQ(lm_build(&a, polys, 2, &o, err, sizeof err), 0, "lm_build (%s)", err);
    CHECK_INT_EQ(a.ncharts, 2, "coplanar disjoint squares: charts");
    CHECK_INT_EQ(a.padding, LM_PADDING, "the default padding at 512 texels");
    CHECK_INT_EQ(lm_bake(&a, two_colour_cb, NULL, NULL), 0, "lm_bake");
    for (y = 0; y < a.size; y++)
        for (x = 0; x < a.size; x++) {
            size_t at = (size_t)y * a.size + (size_t)x;
            int other = a.poly[at] == 0 ? 1 : 0;
            if (isnan(a.sample[2 * at])) continue;
            for (dy = -a.padding; dy <= a.padding; dy++)
                for (dx = -a.padding; dx <= a.padding; dx++) {
                    size_t b = (size_t)(y + dy) * a.size + (size_t)(x + dx);
                    if (x + dx < 0 || y + dy < 0 || x + dx >= a.size || y + dy >= a.size) continue;
                    CHECK_THAT(a.rgb[3 * b + other] == 0.0f,
                               "texel %d,%d (%d,%d from chart %d's covered texel) holds %g of the "
                               "other chart",
                               x + dx, y + dy, dx, dy, a.owner[at], a.rgb[3 * b + other]);
                    checked++;
                }
        }
    for (m = 1; (1 << m) <= a.padding + 1; m++, levels++)
        for (y = 0; y < a.size; y += 1 << m)
            for (x = 0; x < a.size; x += 1 << m) {
                double sum[2] = {0, 0};
                int has[2] = {0, 0};
                for (dy = 0; dy < 1 << m && y + dy < a.size; dy++)
                    for (dx = 0; dx < 1 << m && x + dx < a.size; dx++) {
                        size_t b = (size_t)(y + dy) * a.size + (size_t)(x + dx);
                        sum[0] += a.rgb[3 * b];
                        sum[1] += a.rgb[3 * b + 1];
                        if (!isnan(a.sample[2 * b])) has[a.poly[b]] = 1;
                    }
                CHECK_THAT(!(has[0] && sum[1] > 0) && !(has[1] && sum[0] > 0),
                           "mip level %d texel %d,%d: a chart's covered texels mixed with the "
                           "other's light "
                           "(red %g, green %g)",
                           m, x >> m, y >> m, sum[0], sum[1]);
            }
    printf("lightmap gutter: padding %d, %d texel pairs within it clean, mip levels 1..%d clean\n",
           a.padding, checked, levels);
    CHECK_INT_EQ(levels >= 2, 1, "mip levels kept clean by the default padding (1 and 2 at least)");
    lm_free(&a);
    for (m = 64; m <= 1024; m *= 2) { /* the default by size */
        o.size = m;
        CHECK_INT_EQ(lm_build(&a, polys, 2, &o, err, sizeof err), 0, "lm_build (%s)", err);
        CHECK_INT_EQ(a.padding,
                     m < 256   ? 1
                     : m < 512 ? 2
                               : 4,
                     "the default padding at %d texels (size / 128 in 1..4)", m);
        lm_free(&a);
    }
}

/* Bad sizes: a clear one-line error, nothing built. */
static void test_lightmap_bad_sizes(void **state)
{
    sc_poly polys[2 * TN * TN + 1];
    lm_atlas a;
    char err[256] = "";
    int n = terrain(polys);
    /* coplanar charts only: every triangle of the terrain its own */
    lm_opts zero = {0, 0.0, 0, LM_TOL, -1}, big = {8193, 0.0, 0, LM_TOL, -1},
            small = {8, 0.0, 0, LM_TOL, -1};
    lm_opts fine = {64, 0.001, 0, LM_TOL, -1}, o64 = {64, 0.0, 0, LM_TOL, -1},
            tol = {64, 0.0, 0, 1.5, -1};
    lm_opts crease = {64, 0.0, 0, LM_TOL, 61};
    (void)state;
    CHECK_INT_EQ(lm_build(&a, polys, n, &zero, err, sizeof err), -1, "a size of 0 refused");
    CHECK_CONTAINS(err, "a lightmap size of 0 is outside 1..8192", "the message");
    CHECK_INT_EQ(lm_build(&a, polys, n, &big, err, sizeof err), -1, "a size of 8193 refused");
    CHECK_CONTAINS(err, "a lightmap size of 8193 is outside 1..8192", "the message");
    CHECK_INT_EQ(lm_build(&a, polys, n, &small, err, sizeof err), -1,
                 "129 charts in 8 x 8 texels refused");
    CHECK_CONTAINS(err, "cannot fit 129 charts", "the message");
    CHECK_INT_EQ(lm_build(&a, polys, n, &fine, err, sizeof err), -1,
                 "a texel of 0.001 in 64 x 64 refused");
    CHECK_CONTAINS(err, "cannot fit 129 charts at a texel of 0.001", "the message");
    CHECK_INT_EQ(lm_build(&a, polys, n, &tol, err, sizeof err), -1, "a tolerance of 1.5 refused");
    CHECK_CONTAINS(err, "a lightmap tolerance of 1.5 is outside 0..1", "the message");
    tol.tol = NAN;
    CHECK_INT_EQ(lm_build(&a, polys, n, &tol, err, sizeof err), -1, "a tolerance of NaN refused");
    CHECK_INT_EQ(lm_build(&a, polys, n, &crease, err, sizeof err), -1,
                 "a crease of 61 degrees refused");
    CHECK_CONTAINS(err, "a chart crease of 61 degrees is outside 0..60", "the message");
    crease.crease = NAN;
    CHECK_INT_EQ(lm_build(&a, polys, n, &crease, err, sizeof err), -1, "a crease of NaN refused");
    assert_null(a.rgb);
    memset(polys, 0, sizeof polys[0]);
    polys[0].n = 3; /* three vertices at the origin */
    CHECK_INT_EQ(lm_build(&a, polys, 1, &o64, err, sizeof err), -1,
                 "polygons of no extent refused");
    CHECK_CONTAINS(err, "the polygons have no extent", "the message");
}

/* ---- probes ------------------------------------------------------------------------- */

/* An axis-aligned box [LO, HI]^3 as six quads, lit side in (INWARD 1) or out. */
static int cube(sc_poly *q, double lo, double hi, int inward, double emit)
{
    int f, k, n = 0;
    for (f = 0; f < 6; f++) {
        int a = f / 2, b = (a + 1) % 3, c = (a + 2) % 3, plus = (f & 1) ^ (inward != 0);
        double v[4][3], side = f & 1 ? hi : lo;
        double us[4] = {lo, hi, hi, lo}, vs[4] = {lo, lo, hi, hi};
        for (k = 0; k < 4; k++) {
            v[k][a] = side;
            v[k][b] = us[k];
            v[k][c] = vs[k];
        }
        /* (b, c) counter-clockwise seen from +a: the normal +a (the hi side out, the lo in). */
        q[n] = plus ? quad(v[0], v[1], v[2], v[3], 0.0, emit)
                    : quad(v[3], v[2], v[1], v[0], 0.0, emit);
        n++;
    }
    return n;
}

typedef struct {
    sc_gatherer *g;
} sh_baker;

static int sh_cb(void *ctx, const double p[3], double sh[9][3])
{
    return sc_gather_sh(((sh_baker *)ctx)->g, p, 1, sh);
}

static int count_of(const char *text, const char *part)
{
    int n = 0;
    for (; (text = strstr(text, part)) != NULL; text++) n++;
    return n;
}

/* A room of emission 1 (every wall, reflectance 0) with a closed box of emission 1
 * inside: every probe outside the box sees radiosity 1 in every direction, so its SH is
 * sqrt(4 pi) and zeros (rad.h: the gather's tables make a uniform environment's
 * exact; measured 0, bound 1% of SH[0] for the fixed core's rounding). The grid's 4 x 4 x 4
 * probes sit at the cells' centres; the one at (0.5, 0.5, 0.5) is inside the box: all
 * its rays meet back faces, the others' none. The JSON holds every probe. */
static void test_probes_grid(void **state)
{
    sc_poly polys[12];
    sc_opts o = {.res = 64};
    int dims[3], n = cube(polys, -2, 2, 1, 1.0), i, k, inside = 0;
    char err[256] = "", *json;
    size_t len;
    double *pts, worst = 0.0;
    pr_probe pr[64];
    sh_baker b;
    sc_solver *s;
    (void)state;
    n += cube(polys + n, 0.2, 0.8, 0, 1.0);
    s = sc_create(polys, n, &o, NULL, NULL, err, sizeof err);
    assert_non_null(s);
    sc_solve(s, 100000, 1e-4, NULL, NULL);
    b.g = sc_gatherer_new(s, 32, 1);
    assert_non_null(b.g);
    CHECK_INT_EQ(pr_parse_grid("4,4,4", dims, err, sizeof err), 0, "grid 4,4,4 (%s)", err);
    pts = pr_grid_points(polys, n, dims);
    assert_non_null(pts);
    CHECK_INT_EQ(pr_bake(polys, n, pts, 64, sh_cb, &b, pr, err, sizeof err), 0, "pr_bake (%s)",
                 err);
    for (i = 0; i < 64; i++) {
        int in = fabs(pr[i].p[0] - 0.5) < 1e-12 && fabs(pr[i].p[1] - 0.5) < 1e-12 &&
                 fabs(pr[i].p[2] - 0.5) < 1e-12;
        CHECK_NEAR(pr[i].p[0], -1.5 + (i % 4), 1e-12, "probe %d's x", i);
        CHECK_NEAR(pr[i].p[2], -1.5 + i / 16, 1e-12, "probe %d's z", i);
        CHECK_INT_EQ(pr[i].inside, in, "probe %d at (%g, %g, %g) flagged inside", i, pr[i].p[0],
                     pr[i].p[1], pr[i].p[2]);
        CHECK_NEAR(pr[i].back, in ? 1.0 : 0.0, 1e-12, "probe %d's rays meeting back faces", i);
        inside += pr[i].inside;
        if (in) continue;
        for (k = 0; k < 9; k++) {
            double want = k ? 0.0 : sqrt(16.0 * atan(1.0)),
                   d = fabs(pr[i].sh[k][1] - want) / sqrt(16.0 * atan(1.0));
            CHECK_LE(d, 0.01, "probe %d SH[%d] %.6f against %.6f", i, k, pr[i].sh[k][1], want);
            if (d > worst) worst = d;
        }
    }
    printf("probes: 64 in a glowing room, %d inside the box; SH within %.4f%% of sqrt(4 pi) and "
           "zeros (bound 1%%)\n",
           inside, 100.0 * worst);
    CHECK_INT_EQ(pr_write_json(tmp_path("probes.json"), pr, 64, dims, err, sizeof err), 0,
                 "pr_write_json (%s)", err);
    CHECK_INT_EQ(fio_read_all(tmp_path("probes.json"), 1u << 20, &json, &len, err, sizeof err), 0,
                 "read back (%s)", err);
    CHECK_INT_EQ(count_of(json, "{\"p\": ["), 64, "probes in the JSON");
    CHECK_INT_EQ(count_of(json, "\"inside\": true"), 1, "probes flagged inside in the JSON");
    CHECK_CONTAINS(json, "\"grid\": [4, 4, 4]", "the grid in the JSON");
    free(json);
    free(pts);
    sc_gatherer_free(b.g);
    sc_destroy(s);
}

/* Points files and grids: what is read, and one-line errors naming the file and line. */
static void test_probes_input(void **state)
{
    const char *path = tmp_path("points.txt");
    char err[256] = "";
    int n = -1, dims[3];
    double *p;
    FILE *fp = fopen(path, "w");
    (void)state;
    assert_non_null(fp);
    fputs("# probes\n1 2 3\n\n  -0.5\t4e-1 7 \r\n", fp);
    fclose(fp);
    p = pr_read_points(path, &n, err, sizeof err);
    assert_non_null(p);
    CHECK_INT_EQ(n, 2, "points read");
    CHECK_EQ(p[3], -0.5, "the second point's x");
    CHECK_EQ(p[4], 0.4, "the second point's y");
    free(p);
    fp = fopen(path, "w");
    assert_non_null(fp);
    fputs("1 2 3\n1 2\n", fp);
    fclose(fp);
    assert_null(pr_read_points(path, &n, err, sizeof err));
    CHECK_CONTAINS(err, "points.txt:2: a probe is three numbers", "the message");
    fp = fopen(path, "w");
    assert_non_null(fp);
    fputs("# nothing\n", fp);
    fclose(fp);
    assert_null(pr_read_points(path, &n, err, sizeof err));
    CHECK_CONTAINS(err, "no probes in the file", "the message");
    CHECK_INT_EQ(pr_parse_grid("0,2,2", dims, err, sizeof err), -1, "a grid of 0 refused");
    CHECK_CONTAINS(err, "a grid of 0 along an axis is outside 1..256", "the message");
    CHECK_INT_EQ(pr_parse_grid("101,100,100", dims, err, sizeof err), -1,
                 "1,010,000 probes refused");
    CHECK_CONTAINS(err, "a grid of 1010000 probes is above 1000000", "the message");
    CHECK_INT_EQ(pr_parse_grid("4,4", dims, err, sizeof err), -1, "two numbers refused");
    CHECK_CONTAINS(err, "is not NX,NY,NZ", "the message");
}

/* ---- rad_cli ------------------------------------------------------------------------ */

/* Runs build/rad_cli with ARGS on the bundled Cornell box (quick settings), stderr into
 * the temporary directory; returns the exit status, *ERR the text (malloc'd). */
static int cli(const char *args, char **err)
{
    char cmd[2048];
    size_t len;
    int st;
    snprintf(cmd, sizeof cmd,
             "build/rad_cli examples/cornell_box.obj --res 16 --tol 0.05 --quiet -o %s %s 2> %s",
             tmp_path("cli.png"), args, tmp_path("cli.err"));
    st = system(cmd);
    if (fio_read_all(tmp_path("cli.err"), 1u << 20, err, &len, NULL, 0) != 0) *err = NULL;
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/* The options: a lightmap and probes written; a size of 0, a tolerance above 1, a
 * padding above 64 or a lightmap option without --lightmap a usage error, an atlas
 * too small for the charts an error naming
 * them before the solve, and then no file; the lightmap baked on 3 threads is the same
 * file as on one. */
static void test_cli_bake(void **state)
{
    char args[1024], *err = NULL, *json = NULL, *one = NULL, *three = NULL;
    const char *lm = tmp_path("lm.hdr"), *pj = tmp_path("p.json");
    hdr_image im;
    size_t len, len3 = 0, i;
    double peak = 0.0;
    struct stat st;
    (void)state;
    CHECK_INT_EQ(cli("--lightmap-size 0", &err), 2, "exit status of --lightmap-size 0 (%s)",
                 err ? err : "");
    CHECK_CONTAINS(err, "--lightmap-size wants a whole number from 1 to 8192", "the message");
    free(err);
    CHECK_INT_EQ(cli("--lightmap-tol 1.5", &err), 2, "exit status of --lightmap-tol 1.5 (%s)",
                 err ? err : "");
    CHECK_CONTAINS(err, "--lightmap-tol wants a number in [0, 1]", "the message");
    free(err);
    CHECK_INT_EQ(cli("--lightmap-pad 65", &err), 2, "exit status of --lightmap-pad 65 (%s)",
                 err ? err : "");
    CHECK_CONTAINS(err, "--lightmap-pad wants a whole number from 0 to 64", "the message");
    free(err);
    /* a lightmap option without the lightmap would be ignored: refused instead */
    CHECK_INT_EQ(cli("--lightmap-uv rad", &err), 2,
                 "exit status of --lightmap-uv without --lightmap (%s)", err ? err : "");
    CHECK_CONTAINS(err, "--lightmap-uv needs --lightmap FILE", "the message");
    free(err);
    snprintf(args, sizeof args, "--lightmap %s --lightmap-size 2", lm);
    CHECK_INT_EQ(cli(args, &err), 1, "exit status of an atlas of 2 x 2 texels (%s)",
                 err ? err : "");
    CHECK_CONTAINS(err, "cannot fit", "the message");
    CHECK_INT_EQ(stat(lm, &st), -1, "no lightmap file after the error");
    CHECK_INT_EQ(stat(tmp_path("cli.png"), &st), -1,
                 "no image either: the atlas is laid out before the solve");
    free(err);
    snprintf(args, sizeof args,
             "--lightmap %s --lightmap-size 64 --gather 8 --probes 2,2,2 --probes-out %s", lm, pj);
    CHECK_INT_EQ(cli(args, &err), 0, "exit status of a bake (%s)", err ? err : "");
    free(err);
    CHECK_INT_EQ(hdr_read(lm, &im, NULL, 0), 0, "the lightmap read back");
    CHECK_INT_EQ(im.w * 1000 + im.h, 64064, "its size (w * 1000 + h)");
    for (i = 0; i < (size_t)im.w * im.h * 3; i++) peak = fmax(peak, im.rgb[i]);
    CHECK_GT(peak, 0.0, "the brightest texel");
    hdr_free(&im);
    CHECK_INT_EQ(fio_read_all(pj, 1u << 20, &json, &len, NULL, 0), 0, "the probes read back");
    CHECK_INT_EQ(count_of(json, "{\"p\": ["), 8, "probes in the JSON");
    free(json);
    /* On 3 threads, the same file to the bit; at 128 texels and a tolerance of 0.2 the
     * adaptive passes interpolate (9366 of the 11,236 texels gathered). */
    snprintf(args, sizeof args, "--lightmap %s --lightmap-size 128 --gather 8 --lightmap-tol 0.2",
             lm);
    CHECK_INT_EQ(cli(args, &err), 0, "exit status of a bake on 1 thread (%s)", err ? err : "");
    free(err);
    CHECK_INT_EQ(fio_read_all(lm, 1u << 20, &one, &len, NULL, 0), 0, "the lightmap's bytes");
    snprintf(args, sizeof args,
             "--lightmap %s --lightmap-size 128 --gather 8 --lightmap-tol 0.2 --threads 3", lm);
    CHECK_INT_EQ(cli(args, &err), 0, "exit status of a bake on 3 threads (%s)", err ? err : "");
    free(err);
    CHECK_INT_EQ(fio_read_all(lm, 1u << 20, &three, &len3, NULL, 0), 0,
                 "the 3 threads' lightmap's bytes");
    CHECK_INT_EQ(len3, len, "bytes of the lightmap on 3 threads");
    assert_memory_equal(one, three, len);
    free(one);
    free(three);
}

/* Progress: with RAD_PROGRESS_DELAY=0 (progress.h: the delay before a stage shows,
 * 1 s by default) a bake prints lines for the solve, each lightmap pass and the view's
 * gathers, with the fraction done and an ETA; --quiet prints none of them, nor does a
 * delay longer than the run. --stats times every stage asked for. */
static int cli_progress(const char *env, const char *args, char **err, char **out)
{
    char cmd[2048];
    size_t len;
    int st;
    snprintf(cmd, sizeof cmd,
             "%s build/rad_cli examples/cornell_box.obj --res 16 --tol 0.05 --width 64 --height 64 "
             "-o %s %s > %s 2> %s",
             env, tmp_path("cli.png"), args, tmp_path("cli.out"), tmp_path("cli.err"));
    st = system(cmd);
    if (fio_read_all(tmp_path("cli.err"), 1u << 20, err, &len, NULL, 0) != 0) *err = NULL;
    if (fio_read_all(tmp_path("cli.out"), 1u << 20, out, &len, NULL, 0) != 0) *out = NULL;
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/* A bake and a glTF export with ENV and MORE arguments show no progress (WHY: when);
 * with QUIET, nothing at all on stderr. */
static void no_progress(const char *env, const char *more, const char *why, int quiet)
{
    char args[1024], *err = NULL, *out = NULL;
    snprintf(args, sizeof args, "--lightmap %s --lightmap-size 64 --gather 8 --export-gltf %s %s",
             tmp_path("lm.hdr"), tmp_path("q.glb"), more);
    CHECK_INT_EQ(cli_progress(env, args, &err, &out), 0, "exit status %s", why);
    CHECK_LACKS(err, "solving", "stderr %s", why);
    CHECK_LACKS(err, "lightmap pass", "stderr %s", why);
    CHECK_LACKS(err, "gathering", "stderr %s", why);
    CHECK_LACKS(err, "writing glTF", "stderr %s", why);
    if (quiet) CHECK_INT_EQ((int)strlen(err), 0, "bytes on stderr %s (%s)", why, err);
    free(err);
    free(out);
}

static void test_cli_progress(void **state)
{
    /* every stage of this run on --stats' time line */
    static const char *const stages[] = {"time: load ", "  mesh ",  "  layout ",         "  solve ",
                                         "  render ",   "  write ", "  vertex gathers ", "  csv ",
                                         "  lightmap ", "  gltf "};
    char args[1024], *err = NULL, *out = NULL;
    int i;
    const char *lm = tmp_path("lm.hdr");
    (void)state;
    snprintf(
        args, sizeof args,
        "--lightmap %s --lightmap-size 64 --gather 8 --stats --export-gltf %s --dump-radiosity %s",
        lm, tmp_path("p.glb"), tmp_path("p.csv"));
    CHECK_INT_EQ(cli_progress("RAD_PROGRESS_DELAY=0", args, &err, &out), 0, "exit status (%s)",
                 err ? err : "");
    CHECK_CONTAINS(err, "rad_cli: solving ", "the solve's progress");
    CHECK_CONTAINS(err, "rad_cli: lightmap pass 1 ", "the first lightmap pass's progress");
    CHECK_CONTAINS(err, "rad_cli: gathering the view ", "the view's gathers' progress");
    CHECK_CONTAINS(err, ", ETA ", "an ETA");
    CHECK_CONTAINS(err, "rad_cli: writing glTF ", "the glTF export's progress");
    for (i = 0; i < (int)(sizeof stages / sizeof *stages); i++)
        CHECK_CONTAINS(out, stages[i], "--stats' time line: the stage \"%s\"", stages[i]);
    printf("progress at delay 0: %d lines on stderr; --stats timed %d stages\n",
           count_of(err, "\n"), (int)(sizeof stages / sizeof *stages));
    free(err);
    free(out);
    no_progress("RAD_PROGRESS_DELAY=0", "--quiet", "with --quiet", 1);
    no_progress("RAD_PROGRESS_DELAY=1000", "", "when no stage runs for the delay", 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hdr_round_trip),
        cmocka_unit_test(test_hdr_rle_smaller),
        cmocka_unit_test(test_hdr_bad_input),
        cmocka_unit_test(test_lightmap_lambert),
        cmocka_unit_test(test_lightmap_no_seams),
        cmocka_unit_test(test_lightmap_no_leaks),
        cmocka_unit_test(test_lightmap_adaptive),

        cmocka_unit_test(test_lightmap_packing),
        cmocka_unit_test(test_lightmap_bad_sizes),
        cmocka_unit_test(test_lightmap_gutter),
        cmocka_unit_test(test_lightmap_charts),
        cmocka_unit_test(test_lightmap_merged_light),
        cmocka_unit_test(test_lightmap_smooth_charts),
        cmocka_unit_test(test_lightmap_smooth_light),
        cmocka_unit_test(test_lightmap_level_charts),
        cmocka_unit_test(test_probes_grid),
        cmocka_unit_test(test_probes_input),
        cmocka_unit_test(test_cli_bake),
        cmocka_unit_test(test_cli_progress),
    };
    return cmocka_run_group_tests_name("bake", tests, group_setup, group_teardown);
}
