/* SPDX-License-Identifier: MIT */
/* A lightmap's soft light painted from the solve's elements (sc_solve_lights,
 * sc_soft_elements, lm_paint: tools/bake/lightmap.h) rather than gathered at texels.
 *
 * The split: an open floor (nothing else to bounce light to it) under a sun and a
 * uniform sky. Each element's soft light is its radiosity's rise over its reflectance
 * past the lights split off: the sky's irradiance alone, the sun's left out, or
 * nothing with the skies split off too. The core holds radiosities in Q16.16 at the
 * glue's scale, so each is within 10^-3 relative of the same solve's sky-only
 * value (REL); the sky's raster covers an element to within a row of its pixels
 * (tests/test_direct.c: ELEMENT_COVERAGE), so against the closed form pi L each is
 * within that.
 *
 * The painting: elements given by hand on two coplanar polygons (one chart), their
 * light a linear function f of the element's centre: where a corner is inside the
 * grid (four elements about it, placed symmetrically), the area-weighted mean of
 * their values is f at the corner, exactly, so every texel whose sample lies within
 * the grid's inner corners holds f at its sample, to float rounding (the atlas stores
 * floats: 2^-24 relative, 1e-5 of these values as bound). A floor and a wall meeting
 * at an edge keep their own light (corners average within a plane only), on rad's
 * charts and on a file's UVs.
 *
 * Through rad_cli: the open floor under a sun and a uniform sky, baked with
 * --lightmap-soft elements, holds E + pi L at every covered texel (nothing bounces to
 * it; both lights a ray per texel, the sky's 48 directions summing to exactly pi L):
 * within REL and the .hdr file's rounding (RGBE: 2^-8 of a pixel's largest channel). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <sys/wait.h>

#include <cmocka.h>

#include "check.h"
#include "tmpdir.h"
#include "bake/lightmap.h"
#include "formats/hdr.h"
#include "host/scene.h"

TMPDIR_GROUP("paint")

#define PI               3.14159265358979323846
#define REL              1e-3 /* Q16.16 roundings, as above */
#define ELEMENT_COVERAGE 0.14 /* tests/test_direct.c's bound for a raster's element */
#define FLOAT_REL        1e-5 /* the atlas's floats */

static sc_poly floor_quad(double h, double rho)
{
    sc_poly p;
    memset(&p, 0, sizeof p);
    p.n = 4; /* facing up (+y) */
    p.v[0][0] = -h, p.v[0][2] = -h;
    p.v[1][0] = -h, p.v[1][2] = h;
    p.v[2][0] = h, p.v[2][2] = h;
    p.v[3][0] = h, p.v[3][2] = -h;
    p.rho[0] = p.rho[1] = p.rho[2] = rho;
    return p;
}

static sc_light sun_light(void)
{
    sc_light l;
    memset(&l, 0, sizeof l);
    l.type = 1;
    l.dir[0] = sin(PI / 6);
    l.dir[1] = -cos(PI / 6);
    l.rgb[0] = l.rgb[1] = l.rgb[2] = 2.0;
    return l;
}

static sc_light sky_light(double radiance)
{
    sc_light l;
    memset(&l, 0, sizeof l);
    l.type = 4;
    l.rgb[0] = l.rgb[1] = l.rgb[2] = radiance;
    l.horizon[0] = l.horizon[1] = l.horizon[2] = radiance;
    return l;
}

/* The floor of reflectance RHO under lights L (N), solved; sc_solve_lights with FLAGS
 * first unless FLAGS < 0. */
static sc_solver *solve(const sc_light *l, int n, double rho, int flags)
{
    sc_poly p = floor_quad(2, rho);
    sc_opts o;
    char err[256] = "";
    sc_solver *s;
    memset(&o, 0, sizeof o);
    o.res = 64;
    o.lights = l;
    o.nlights = n;
    s = sc_create(&p, 1, &o, NULL, NULL, err, sizeof err);
    if (!s) fail_msg("sc_create: %s", err);
    if (flags >= 0) CHECK_INT_EQ(sc_solve_lights(s, flags), 0, "sc_solve_lights");
    sc_solve(s, 10000, 1e-4, NULL, NULL);
    return s;
}

static void test_split(void **state)
{
    const double radiance = 0.3;
    sc_light l[2] = {sun_light(), sky_light(radiance)};
    sc_solver *both = solve(l, 2, 0.5, 0), *sky = solve(&l[1], 1, 0.5, -1),
              *none = solve(l, 2, 0.5, SC_SKIES), *later = solve(l, 2, 0.5, -1),
              *dark = solve(l, 2, 0.01, 0);
    long n, m, e;
    sc_soft_element *el = sc_soft_elements(both, 0, &n), *no = sc_soft_elements(none, 0, &m);
    double worst = 0, worst_pi = 0;
    (void)state;
    assert_non_null(el);
    assert_non_null(no);
    CHECK_INT_EQ(m, n, "elements of the same floor");
    CHECK_INT_GE(n, 16, "elements");
    for (e = 0; e < n; e++) {
        double want[3], k = 0;
        int c;
        CHECK_INT_EQ(el[e].known, 1, "element %ld's soft light known", e);
        CHECK_INT_EQ(el[e].poly, 0, "element %ld's polygon", e);
        sc_element_rgb(sky, (int)e, 0, want);
        for (c = 0; c < 3; c++) {
            want[c] /= 0.5;
            k = fmax(k, fabs(el[e].rgb[c] - want[c]) / want[c]);
            CHECK_NEAR(el[e].rgb[c], want[c], want[c] * REL,
                       "element %ld: the sun and sky's soft light against the sky's alone", e);
            CHECK_NEAR(no[e].rgb[c], 0.0, want[c] * REL, "element %ld: skies split off too", e);
        }
        worst = fmax(worst, k);
        worst_pi = fmax(worst_pi, fabs(el[e].rgb[1] - PI * radiance) / (PI * radiance));
        CHECK_NEAR(el[e].rgb[1], PI * radiance, PI * radiance * ELEMENT_COVERAGE,
                   "element %ld: the uniform sky's pi L", e);
    }
    printf("%ld elements: soft light within %.2g of the sky-only solve's (bound %g), within "
           "%.2g of pi L (bound %g)\n",
           n, worst, REL, worst_pi, ELEMENT_COVERAGE);
    free(el);
    free(no);
    /* not known: no sc_solve_lights before the solve; a reflectance below SOFT_RHO_MIN */
    el = sc_soft_elements(later, 0, &n);
    for (e = 0; el && e < n; e++) CHECK_INT_EQ(el[e].known, 0, "element %ld, no split kept", e);
    free(el);
    el = sc_soft_elements(dark, 0, &n);
    for (e = 0; el && e < n; e++) CHECK_INT_EQ(el[e].known, 0, "element %ld, reflectance 0.01", e);
    free(el);
    CHECK_INT_EQ(sc_solve_lights(both, 0), -1, "sc_solve_lights after shooting");
    sc_destroy(both);
    sc_destroy(sky);
    sc_destroy(none);
    sc_destroy(later);
    sc_destroy(dark);
}

/* The linear light painted: polygons [-2, 0] x [-2, 2] and [0, 2] x [-2, 2] (one
 * chart), each cut into 4 x 8 square elements of side 0.5; f = 1 + 0.2 x + 0.1 z. */
#define SIDE 0.5
static double f_of(const double *p)
{
    return 1.0 + 0.2 * p[0] + 0.1 * p[2];
}

static int count_gathered(void *ctx, const double p[3], const double n[3], double rgb[3])
{
    (void)p, (void)n;
    ++*(long *)ctx;
    rgb[0] = rgb[1] = rgb[2] = -1.0;
    return 0;
}

static void test_paint_linear(void **state)
{
    sc_poly p[2];
    sc_soft_element el[64];
    lm_opts lo = {128, 0.0, 0, LM_TOL, 0.0};
    lm_atlas a;
    char err[256] = "";
    long left, gathered = 0, inner = 0, in_hole = 0;
    double worst = 0;
    int k, i, j, x, y, n = 0;
    (void)state;
    for (k = 0; k < 2; k++) {
        p[k] = floor_quad(2, 0.5);
        p[k].v[k ? 0 : 2][0] = p[k].v[k ? 1 : 3][0] = 0.0; /* the halves x < 0, x > 0 */
    }
    for (k = 0; k < 2; k++)
        for (i = 0; i < 4; i++)
            for (j = 0; j < 8; j++) {
                sc_soft_element *m = &el[n++];
                double x0 = (k ? 0.0 : -2.0) + i * SIDE, z0 = -2.0 + j * SIDE, c[3];
                memset(m, 0, sizeof *m);
                m->poly = k;
                m->n = 4;
                m->area = SIDE * SIDE;
                m->p[0][0] = x0, m->p[0][2] = z0;
                m->p[1][0] = x0, m->p[1][2] = z0 + SIDE;
                m->p[2][0] = x0 + SIDE, m->p[2][2] = z0 + SIDE;
                m->p[3][0] = x0 + SIDE, m->p[3][2] = z0;
                c[0] = x0 + SIDE / 2, c[1] = 0, c[2] = z0 + SIDE / 2;
                m->rgb[0] = m->rgb[1] = m->rgb[2] = f_of(c);
                /* the element at [0.5, 1] x [-0.5, 0]: not known */
                m->known = !(k == 1 && i == 1 && j == 3);
            }
    if (lm_build(&a, p, 2, &lo, err, sizeof err) != 0) fail_msg("lm_build: %s", err);
    CHECK_INT_EQ(a.ncharts, 1, "charts of the two halves");
    left = lm_paint(&a, el, n);
    for (y = 0; y < a.size; y++)
        for (x = 0; x < a.size; x++) {
            size_t at = (size_t)y * a.size + (size_t)x;
            double q[3], v = a.rgb[3 * at];
            if (!lm_texel_point(&a, x, y, q)) continue;
            if (q[0] > 0.5 && q[0] < 1.0 && q[2] > -0.5 && q[2] < 0.0) { /* the unknown one */
                in_hole++;
                CHECK_INT_EQ(a.state[at] & (LM_WANT | LM_LERPED), LM_WANT,
                             "texel (%d, %d) on the element not known: to gather", x, y);
                continue;
            }
            /* inside the inner corners, off the unknown element's corners' reach */
            if (fabs(q[0]) > 2 - SIDE || fabs(q[2]) > 2 - SIDE ||
                (q[0] > 0.5 - SIDE && q[0] < 1.0 + SIDE && q[2] > -0.5 - SIDE && q[2] < SIDE))
                continue;
            inner++;
            CHECK_INT_EQ(a.state[at] & (LM_WANT | LM_LERPED), LM_LERPED, "texel (%d, %d) painted",
                         x, y);
            worst = fmax(worst, fabs(v - f_of(q)) / f_of(q));
            CHECK_NEAR(v, f_of(q), f_of(q) * FLOAT_REL, "texel (%d, %d) at (%g, %g)", x, y, q[0],
                       q[2]);
        }
    printf("painted: %ld inner texels within %.2g of f (bound %g); %ld on the unknown element, "
           "%ld left to gather\n",
           inner, worst, FLOAT_REL, in_hole, left);
    CHECK_INT_GE(inner, 3000, "inner texels checked");
    CHECK_INT_GE(in_hole, 16, "texels on the unknown element");
    /* what is left is one pass of lm_plan's, gathered by the bake */
    CHECK_INT_GE(left, in_hole, "texels left to gather");
    CHECK_INT_LE(left, in_hole + 4 * (long)(SIDE / a.texel + 4), "texels left to gather");
    CHECK_INT_EQ(lm_bake(&a, count_gathered, NULL, &gathered), 0, "lm_bake");
    CHECK_INT_EQ(gathered, left, "gathers of the painted atlas's bake");
    lm_free(&a);
}

/* A floor and a wall meeting along an edge, each one element of constant light (1 and
 * 3), painted on rad's charts and on the file's UVs (islands side by side, one
 * rectangle for the whole atlas): every texel holds its own polygon's light exactly,
 * the corners on the shared edge averaged within each plane only. */
static void test_paint_planes(void **state)
{
    sc_poly p[2];
    sc_soft_element el[2];
    lm_opts lo = {64, 0.0, 0, LM_TOL, 0.0};
    lm_file_report rep;
    double uv[16];
    char err[256] = "";
    int f, k, x, y;
    (void)state;
    p[0] = floor_quad(1, 0.5);
    p[1] = p[0]; /* the wall x = -1, facing +x */
    for (k = 0; k < 4; k++) {
        p[1].v[k][1] = p[0].v[k][0] + 1.0;
        p[1].v[k][0] = -1.0;
    }
    for (k = 0; k < 2; k++) {
        memset(&el[k], 0, sizeof el[k]);
        el[k].poly = k;
        el[k].n = 4;
        el[k].known = 1;
        el[k].area = 4.0;
        memcpy(el[k].p, p[k].v, sizeof el[k].p);
        el[k].rgb[0] = el[k].rgb[1] = el[k].rgb[2] = k ? 3.0 : 1.0;
    }
    for (k = 0; k < 4; k++) { /* corner k at u = 0.05 + 0.4 (k == 2 || k == 3), v likewise */
        double u = 0.05 + 0.4 * (k >= 2), v = 0.05 + 0.4 * (k == 1 || k == 2);
        uv[2 * k] = u, uv[2 * k + 1] = v;
        uv[8 + 2 * k] = u + 0.5, uv[8 + 2 * k + 1] = v;
    }
    for (f = 0; f < 2; f++) {
        lm_atlas a;
        long seen[2] = {0, 0};
        if ((f ? lm_build_file(&a, p, 2, uv, &lo, &rep, err, sizeof err)
               : lm_build(&a, p, 2, &lo, err, sizeof err)) != 0)
            fail_msg("lm_build%s: %s", f ? "_file" : "", err);
        CHECK_INT_EQ(lm_paint(&a, el, 2), 0, "texels left to gather (%s)", f ? "file" : "rad");
        for (y = 0; y < a.size; y++)
            for (x = 0; x < a.size; x++) {
                size_t at = (size_t)y * a.size + (size_t)x;
                double q[3];
                if (!lm_texel_point(&a, x, y, q)) continue;
                seen[a.poly[at]]++;
                CHECK_NEAR(a.rgb[3 * at], a.poly[at] ? 3.0 : 1.0, 3.0 * FLOAT_REL,
                           "texel (%d, %d) of polygon %d (%s UVs)", x, y, a.poly[at],
                           f ? "the file's" : "rad's");
            }
        printf("%s UVs: %ld floor and %ld wall texels, each its own plane's light\n",
               f ? "the file's" : "rad's", seen[0], seen[1]);
        CHECK_INT_GE(seen[0], 200, "floor texels");
        CHECK_INT_GE(seen[1], 200, "wall texels");
        lm_free(&a);
    }
}

/* The exit status of shell command CMD. */
static int run(const char *cmd)
{
    int st = system(cmd);
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

static void test_cli(void **state)
{
    static const char obj[] = "v -2 0 -2\nv -2 0 2\nv 2 0 2\nv 2 0 -2\nf 1 2 3 4\n";
    const double want = 2.0 + PI * 0.3, bound = want * (REL + 1.0 / 256);
    char cmd[2048], err[256] = "", line[512];
    hdr_image im;
    FILE *f = fopen(tmp_path("open.obj"), "w");
    int i, lit = 0, warned = 0;
    double worst = 0;
    (void)state;
    assert_non_null(f);
    fputs(obj, f);
    fclose(f);
    snprintf(cmd, sizeof cmd,
             "build/rad_cli %s --quiet --sun 0,-1,0,2,2,2 --sky 0.3,0.3,0.3 --lightmap %s "
             "--lightmap-size 64 --lightmap-soft elements -o %s",
             tmp_path("open.obj"), tmp_path("open.hdr"), tmp_path("open.png"));
    CHECK_INT_EQ(run(cmd), 0, "rad_cli's exit status");
    if (hdr_read(tmp_path("open.hdr"), &im, err, sizeof err) != 0) fail_msg("%s", err);
    for (i = 0; i < im.w * im.h; i++) {
        double v = im.rgb[3 * i + 1];
        if (v <= 0) continue; /* no chart's */
        lit++;
        worst = fmax(worst, fabs(v - want));
        CHECK_NEAR(v, want, bound, "texel %d: the sun's E and the sky's pi L", i);
    }
    printf("rad_cli --lightmap-soft elements: %d texels, each within %.2g of E + pi L = %.6f "
           "(bound %.2g)\n",
           lit, worst, want, bound);
    CHECK_INT_GE(lit, 2000, "covered texels");
    hdr_free(&im);
    /* stored form factors: gathered instead, with a warning */
    snprintf(cmd, sizeof cmd,
             "build/rad_cli %s --sun 0,-1,0,2,2,2 --save-ff %s --lightmap %s --lightmap-size 16 "
             "--lightmap-soft elements -o %s 2> %s",
             tmp_path("open.obj"), tmp_path("open.ff"), tmp_path("ff.hdr"), tmp_path("ff.png"),
             tmp_path("ff.err"));
    CHECK_INT_EQ(run(cmd), 0, "rad_cli's exit status with --save-ff");
    f = fopen(tmp_path("ff.err"), "r");
    assert_non_null(f);
    while (fgets(line, sizeof line, f)) warned += strstr(line, "needs a shooting solve") != NULL;
    fclose(f);
    CHECK_INT_EQ(warned, 1, "the warning that the texels are gathered");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_split),
        cmocka_unit_test(test_paint_linear),
        cmocka_unit_test(test_paint_planes),
        cmocka_unit_test(test_cli),
    };
    return cmocka_run_group_tests(tests, group_setup, group_teardown);
}
