/* SPDX-License-Identifier: MIT */
/* Tests for tools/host/sky_map.c: an equirectangular map as the core's sky dome of suns
 * (rad_cli --sky-hdr), against closed forms in doubles.
 *
 * A sun of irradiance E along unit d gives a plane of normal n the irradiance
 * E max(0, -d.n); the dome's suns summed so are what the map gives that plane when
 * every cell lies wholly in front of it or wholly behind (the cells' light is
 * integrated exactly: sky_map.h). The bounds below are double rounding over a few
 * thousand terms (1e-12 relative), not approximations. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "check.h"
#include "host/sky_map.h"

#define PI 3.14159265358979323846
#define W  64
#define H  32

/* A W x H map: radiance L (grey) where LIT(x, y), else black. */
static float *map(double l, int (*lit)(int x, int y))
{
    float *m = malloc(sizeof(float) * 3 * W * H);
    int x, y, c;
    assert_non_null(m);
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++)
            for (c = 0; c < 3; c++) m[3 * (y * W + x) + c] = lit(x, y) ? (float)l : 0.0f;
    return m;
}

static int all(int x, int y)
{
    return (void)x, (void)y, 1;
}
static int cap(int x, int y)
{
    return (void)x, y < H / 4;
} /* zenith angle < pi / 4 */
static int east(int x, int y)
{
    return y < H / 2 && x >= W / 4 && x < 3 * W / 4;
} /* +X half */

/* What the suns give a plane of normal N, channel C. */
static double on_plane(const sky_sun *s, int n, const double nrm[3], int c)
{
    double e = 0;
    int i;
    for (i = 0; i < n; i++) {
        double k = -(s[i].dir[0] * nrm[0] + s[i].dir[1] * nrm[1] + s[i].dir[2] * nrm[2]);
        if (k > 0) e += s[i].e[c] * k;
    }
    return e;
}

/* A uniform map of L: 3 m^2 suns whose sum on a floor is pi L, each along the core's
 * cell direction for a uniform sky (lib/light.c shoot_sky in doubles: the cell's
 * vertical integral (r2^2 - r1^2) / 2 and horizontal (asin r - r c) / 2 | r1..r2 times
 * sin(pi / n) / (pi / n), toward its middle azimuth in the frame f0, f1). */
static void test_uniform(void **state)
{
    static const int dirs[4] = {3, 48, 192, 768};
    const double f0[3] = {-0.8, 0, -0.6}, f1[3] = {-0.6, 0, 0.8}, up[3] = {0, 1, 0};
    float *m = map(2.0, all);
    sky_sun suns[SKY_MAP_MAX_DIRS];
    int k, i, j, a, s;
    (void)state;
    for (k = 0; k < 4; k++) {
        const int mb = sky_map_bands(dirs[k]);
        int n = sky_map_suns(m, W, H, 1.0, dirs[k], suns);
        double worst = 0;
        CHECK_INT_EQ(n, 3 * mb * mb, "suns of a uniform map at %d directions", dirs[k]);
        CHECK_NEAR(on_plane(suns, n, up, 0), 2 * PI, 2 * PI * 1e-12,
                   "a floor under a uniform map at %d directions", dirs[k]);
        for (i = 0, s = 0; i < mb; i++) {
            const int cells = 3 * (2 * i + 1);
            const double r1 = (double)i / mb, r2 = (double)(i + 1) / mb;
            const double c1 = sqrt(1 - r1 * r1), c2 = sqrt(1 - r2 * r2);
            const double vert = (r2 * r2 - r1 * r1) / 2;
            const double hor =
                ((asin(r2) - r2 * c2) - (asin(r1) - r1 * c1)) / 2 * sin(PI / cells) / (PI / cells);
            for (j = 0; j < cells; j++, s++) {
                const double psi = 2 * PI * (j + 0.5) / cells, len = sqrt(vert * vert + hor * hor);
                for (a = 0; a < 3; a++) {
                    double want =
                        -(vert * up[a] + hor * (cos(psi) * f0[a] + sin(psi) * f1[a])) / len;
                    worst = fmax(worst, fabs(suns[s].dir[a] - want));
                }
            }
        }
        CHECK_LE(worst, 1e-12, "the suns' directions against the core's cells at %d directions",
                 dirs[k]);
    }
    free(m);
}

/* A map lit in a region: a cap of zenith angles below pi / 4 gives a floor
 * pi L sin^2(pi / 4) = pi L / 2 (the cap's edge cuts cells: their lit part is
 * integrated, and the floor sees every cell whole); the half of the sky toward +X gives a
 * wall facing +X pi L / 2 (the quarter sphere's cosine integral) and one facing -X
 * nothing (every lit direction lies behind it), a floor pi L / 2 too. */
static void test_regions(void **state)
{
    const double up[3] = {0, 1, 0}, px[3] = {1, 0, 0}, mx[3] = {-1, 0, 0};
    sky_sun suns[SKY_MAP_MAX_DIRS];
    float *m = map(2.0, cap);
    int n = sky_map_suns(m, W, H, 1.0, 0, suns);
    (void)state;
    CHECK_NEAR(on_plane(suns, n, up, 1), PI, PI * 1e-12, "a floor under a cap of 45 degrees");
    free(m);
    m = map(2.0, east);
    n = sky_map_suns(m, W, H, 0.5, 0, suns); /* SCALE 0.5: L = 1 */
    CHECK_NEAR(on_plane(suns, n, px, 2), PI / 2, PI * 1e-12, "a wall facing +X under the +X half");
    CHECK_LE(on_plane(suns, n, mx, 2), 0, "a wall facing -X under the +X half");
    CHECK_NEAR(on_plane(suns, n, up, 2), PI / 2, PI * 1e-12, "a floor under the +X half");
    free(m);
}

/* The map's axes: one pixel lit at the middle column's left edge at row H / 4 (zenith
 * angle near pi / 4) lights from +X; a quarter further right from +Z; the left edge
 * from -X. And a black map gives no sun. */
static void test_axes(void **state)
{
    static const struct {
        int x;
        double from[3];
    } px[3] = {{W / 2, {1, 0, 0}}, {3 * W / 4, {0, 0, 1}}, {0, {-1, 0, 0}}};
    sky_sun suns[SKY_MAP_MAX_DIRS];
    float *m = calloc(3 * W * H, sizeof *m);
    int k, n, i;
    (void)state;
    assert_non_null(m);
    CHECK_INT_EQ(sky_map_suns(m, W, H, 1.0, 0, suns), 0, "suns of a black map");
    for (k = 0; k < 3; k++) {
        double sum[3] = {0, 0, 0}, len;
        memset(m, 0, sizeof *m * 3 * W * H);
        for (i = 0; i < 3; i++) m[3 * ((H / 4) * W + px[k].x) + i] = 1.0f;
        n = sky_map_suns(m, W, H, 1.0, 0, suns);
        CHECK_INT_GE(n, 1, "suns of a map of one pixel at column %d", px[k].x);
        for (i = 0; i < n; i++) {
            sum[0] -= suns[i].dir[0] * suns[i].e[0];
            sum[1] -= suns[i].dir[1] * suns[i].e[0];
            sum[2] -= suns[i].dir[2] * suns[i].e[0];
        }
        len = sqrt(sum[0] * sum[0] + sum[2] * sum[2]);
        CHECK_GT((sum[0] * px[k].from[0] + sum[2] * px[k].from[2]) / len, 0.99,
                 "the light of column %d comes from the side the map says (cosine)", px[k].x);
    }
    free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_uniform),
        cmocka_unit_test(test_regions),
        cmocka_unit_test(test_axes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
