/* SPDX-License-Identifier: MIT */
/* Fixed-point primitives of the scalar shim against double (and exact 128-bit) maths,
 * over a table of edge values tested pairwise and a stream of pseudo-random values. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "check.h"
#include "scalar.h" /* the fixed build's shim (RAD_FLOAT is 0 here) */

/* The exact reference for 64x32-bit products (GCC and Clang on 64-bit hosts). */
__extension__ typedef unsigned __int128 u128;

static uint64_t rng_state = 0x9E3779B97F4A7C15ull;
static uint64_t rnd(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return rng_state;
}

/* Signed Q16.16 edge values within the core's coordinate range (|c| <= 64.0). */
static const int32_t edges[] = {
    0,      1,     -1,    2,      -2,    255,     256,        -256,          32767,   32768,
    -32768, 65535, 65536, -65536, 65537, 1 << 20, -(1 << 20), (1 << 22) - 1, 1 << 22, -(1 << 22)};
#define NEDGES (sizeof edges / sizeof edges[0])

static double q(int32_t v)
{
    return v / 65536.0;
}

static void test_isqrt(void **st)
{
    static const uint64_t t[] = {0,
                                 1,
                                 2,
                                 3,
                                 4,
                                 15,
                                 16,
                                 17,
                                 0xFFFFFFFFull,
                                 0x100000000ull,
                                 0x3FFFFFFFFFFFFFFFull,
                                 0x4000000000000000ull,
                                 0xFFFFFFFFFFFFFFFFull};
    size_t i;
    (void)st;
    /* Random values of every length, and squares of random roots, one less and 2r more
     * (floor(sqrt) changes between r^2 - 1 and r^2, and stays up to r^2 + 2r). */
    for (i = 0; i < sizeof t / sizeof t[0] + 200000; i++) {
        uint64_t v = i < sizeof t / sizeof t[0] ? t[i] : rnd() >> (rnd() % 64);
        if (i % 2 == 1) {
            uint64_t root = rnd() >> (rnd() % 32 + 32);
            v = root * root + (i % 3 == 0 ? (uint64_t)-1 : i % 3 == 1 ? 0 : 2 * root);
        }
        uint64_t r = rad__isqrt64(v);
        /* floor(sqrt(v)) exactly: r^2 <= v < (r+1)^2, in 128 bits. */
        CHECK_THAT((u128)r * r <= v && (u128)(r + 1) * (r + 1) > v,
                   "rad__isqrt64(%llu) = %llu: not floor(sqrt(v))", (unsigned long long)v,
                   (unsigned long long)r);
    }
}

/* rad__bitlen64 (rad__clz32 on each half) against its definition: 2^(b-1) <= v < 2^b,
 * at every power of two, one either side of it, and random values of every length. */
static void test_bitlen(void **st)
{
    size_t i;
    (void)st;
    CHECK_INT_EQ(rad__bitlen64(0), 0, "rad__bitlen64(0)");
    for (i = 0; i < 64 * 3 + 100000; i++) {
        uint64_t v =
            i < 64 * 3 ? ((uint64_t)1 << (i / 3)) + (uint64_t)(i % 3) - 1u : rnd() >> (rnd() % 64);
        unsigned b = rad__bitlen64(v);
        if (v == 0) continue;
        CHECK_THAT(b >= 1 && b <= 64 && v >> (b - 1) == 1,
                   "rad__bitlen64(%llu) = %u: not 1 + the index of the highest set bit",
                   (unsigned long long)v, b);
    }
}

static void test_shr_and_div_round(void **st)
{
    size_t i, j;
    (void)st;
    for (i = 0; i < NEDGES; i++)
        for (j = 0; j < NEDGES; j++) {
            int64_t a = (int64_t)edges[i] * 4096 + edges[j];
            double want = a / 65536.0;
            /* Round half away from zero: within half a unit of the exact quotient. */
            CHECK_NEAR((double)rad__shr_round(a, 16), want, 0.5, "rad__shr_round(%lld, 16)",
                       (long long)a);
            if (edges[j] != 0) {
                double wq = (double)a / edges[j];
                CHECK_NEAR((double)rad__div_round(a, edges[j]), wq, 0.5 + 1e-9,
                           "rad__div_round(%lld, %ld)", (long long)a, (long)edges[j]);
            }
        }
    /* The 32-bit form is the 64-bit one over its whole range: |v| < 2^30, n in 1..30,
     * halves (v = 2^(n-1) (2m + 1)) included. */
    for (i = 0; i < 300000; i++) {
        unsigned n = (unsigned)(i % 30u) + 1u;
        int32_t v = (int32_t)(rnd() % (2u * 0x3FFFFFFFu + 1u)) - 0x3FFFFFFF;
        if (i % 4 == 0)
            v = (int32_t)(((rnd() % (1u << (30u - n))) * 2u + 1u) << (n - 1u)) *
                (rnd() & 1 ? -1 : 1);
        CHECK_INT_EQ(rad__shr_round32(v, n), rad__shr_round(v, n), "rad__shr_round32(%ld, %u)",
                     (long)v, n);
    }
}

static void test_dot_cross_mul(void **st)
{
    size_t i, j;
    uint32_t sat = 0;
    (void)st;
    for (i = 0; i < NEDGES; i++)
        for (j = 0; j < NEDGES; j++) {
            rad_vec3_t a = {edges[i], edges[j], edges[(i + j) % NEDGES]};
            rad_vec3_t b = {edges[j], -edges[(i * 3) % NEDGES], edges[i]};
            double d = q(a.x) * q(b.x) + q(a.y) * q(b.y) + q(a.z) * q(b.z);
            /* One rounding of the exact int64 sum: within half an LSB. */
            CHECK_NEAR(q(rad__dot(a, b)), d, 0.5 / 65536.0 + 1e-12, "rad__dot, edge values %u, %u",
                       (unsigned)i, (unsigned)j);
            if (fabs(q(edges[i]) * q(edges[j])) < 32767.0) {
                CHECK_NEAR(q(rad__mul(edges[i], edges[j], &sat)), q(edges[i]) * q(edges[j]),
                           0.5 / 65536.0 + 1e-12, "rad__mul(%ld, %ld)", (long)edges[i],
                           (long)edges[j]);
            }
        }
    assert_int_equal(sat, 0);
    /* Saturation is counted, and clamps to the format's limits. */
    assert_int_equal(rad__mul(INT32_MAX, INT32_MAX, &sat), INT32_MAX);
    assert_int_equal(rad__mul(INT32_MAX, -INT32_MAX, &sat), INT32_MIN);
    assert_int_equal(sat, 2);
    {
        rad_vec3_t x = {65536, 0, 0}, y = {0, 65536, 0}, z = rad__cross(x, y);
        assert_int_equal(z.x, 0);
        assert_int_equal(z.y, 0);
        assert_int_equal(z.z, 65536);
    }
}

static void test_unit_and_length(void **st)
{
    int i;
    (void)st;
    for (i = 0; i < 3000; i++) {
        /* Vectors from tiny (a few LSB) to the largest differences (2^24). */
        int sh = (int)(rnd() % 24);
        rad_vec3_t v, u;
        double dx, dy, dz, l;
        v.x = (int32_t)((int64_t)(rnd() % (1u << 25)) - (1 << 24)) >> sh;
        v.y = (int32_t)((int64_t)(rnd() % (1u << 25)) - (1 << 24)) >> sh;
        v.z = (int32_t)((int64_t)(rnd() % (1u << 25)) - (1 << 24)) >> sh;
        if (!v.x && !v.y && !v.z) continue;
        dx = v.x;
        dy = v.y;
        dz = v.z;
        l = sqrt(dx * dx + dy * dy + dz * dz);
        CHECK_INT_NE(rad__normalize(v, &u), 0, "rad__normalize of a non-zero vector");
        /* The unit vector is a correctly rounded Q16.16 of v / |v| (error < 1 LSB). */
        CHECK_NEAR(q(u.x), dx / l, 1.0 / 65536.0, "unit vector x, within 1 LSB");
        CHECK_NEAR(q(u.y), dy / l, 1.0 / 65536.0, "unit vector y, within 1 LSB");
        CHECK_NEAR(q(u.z), dz / l, 1.0 / 65536.0, "unit vector z, within 1 LSB");
        /* The length, in the input's units, within one unit (30-bit intermediate). */
        CHECK_NEAR((double)rad__length(v), l, 1.0 + l * 1e-8, "rad__length, within one unit");
    }
    {
        rad_vec3_t zero = {0, 0, 0}, u;
        CHECK_INT_EQ(rad__normalize(zero, &u), 0, "rad__normalize of the zero vector");
        assert_int_equal(rad__length(zero), 0);
    }
}

static void test_area_normal(void **st)
{
    int i;
    (void)st;
    for (i = 0; i < 3000; i++) {
        int sh = (int)(rnd() % 16);
        rad_vec3_t a, b, n;
        double ax, ay, az, bx, by, bz, cx, cy, cz, l;
        a.x = (int32_t)((int64_t)(rnd() % (1u << 24)) - (1 << 23)) >> sh;
        a.y = (int32_t)((int64_t)(rnd() % (1u << 24)) - (1 << 23)) >> sh;
        a.z = (int32_t)((int64_t)(rnd() % (1u << 24)) - (1 << 23)) >> sh;
        b.x = (int32_t)((int64_t)(rnd() % (1u << 24)) - (1 << 23)) >> sh;
        b.y = (int32_t)((int64_t)(rnd() % (1u << 24)) - (1 << 23)) >> sh;
        b.z = (int32_t)((int64_t)(rnd() % (1u << 24)) - (1 << 23)) >> sh;
        ax = q(a.x);
        ay = q(a.y);
        az = q(a.z);
        bx = q(b.x);
        by = q(b.y);
        bz = q(b.z);
        cx = ay * bz - az * by;
        cy = az * bx - ax * bz;
        cz = ax * by - ay * bx;
        l = sqrt(cx * cx + cy * cy + cz * cz);
        if (l < 1e-3) continue;
        /* Half the cross product's length, rounded once to Q16.16 (+ one unit of
         * the 30-bit square root). */
        CHECK_NEAR(q(rad__area_normal(a, b, &n)), 0.5 * l, 1.0 / 65536.0 + l * 1e-8,
                   "rad__area_normal's area: half the cross product, rounded once");
        CHECK_NEAR(q(n.x), cx / l, 1.0 / 65536.0, "rad__area_normal's unit normal x, within 1 LSB");
        CHECK_NEAR(q(n.y), cy / l, 1.0 / 65536.0, "rad__area_normal's unit normal y, within 1 LSB");
    }
}

static void test_energy_ops(void **st)
{
    int i;
    uint32_t sat = 0;
    (void)st;
    for (i = 0; i < 5000; i++) {
        uint64_t u = rnd() >> 18; /* < 2^46: the unshot power's range */
        uint32_t f = (uint32_t)(rnd() % ((1u << 30) + 1u));
        int32_t rho = (int32_t)(rnd() % 65536u);
        int32_t area = (int32_t)(rnd() % 0x7FFFFFFFu) + 1;
        u128 exact = ((u128)u * f + (1u << 29)) >> 30;
        /* Exactly the rounded 94-bit product, without 128-bit arithmetic. */
        assert_int_equal((uint64_t)rad__energy_ff((rad_energy_t)u, f), (uint64_t)exact);
        assert_int_equal((uint64_t)rad__energy_refl((rad_energy_t)u, rho),
                         (u * (uint64_t)rho + 32768u) >> 16);
        {
            double want = ldexp((double)u, 16) / area;
            const rad__area_div_t ad = rad__area_div(area);
            rad_real_t b = rad__energy_to_rad((rad_energy_t)(u >> 2), &ad, &sat);
            want = ldexp((double)(u >> 2), 16) / area;
            if (want < 2147483647.0)
                CHECK_NEAR((double)b, want, 0.5 + want * 1e-15, "rad__energy_to_rad, area %ld",
                           (long)area);
            else
                assert_int_equal(b, INT32_MAX);
        }
    }
    /* Saturation of radiosity is counted. */
    sat = 0;
    {
        const rad__area_div_t one = rad__area_div(1);
        assert_int_equal(rad__energy_to_rad((rad_energy_t)1 << 46, &one, &sat), INT32_MAX);
    }
    assert_int_equal(sat, 1);
    assert_int_equal(rad__add_sat(INT32_MAX - 1, 5, &sat), INT32_MAX);
    assert_int_equal(sat, 2);
    /* Ratios of any two energies. */
    assert_int_equal(rad__energy_ratio(1, 2), 32768);
    assert_int_equal(rad__energy_ratio((rad_energy_t)1 << 62, (rad_energy_t)1 << 62), 65536);
    assert_int_equal(rad__energy_ratio(0, 0), 0);
}

static void test_projection_and_depth(void **st)
{
    size_t i, j;
    (void)st;
    for (i = 0; i < NEDGES; i++)
        for (j = 0; j < NEDGES; j++) {
            int32_t d = edges[i] < 0 ? -edges[i] : edges[i];
            int32_t num = edges[j] < 0 ? -edges[j] : edges[j];
            if (d < RAD__NEAR || num > 2 * d) continue;
            /* A screen position in subpixels across a 2048-pixel raster, through the
             * rounded reciprocal 2^46 / d: half a subpixel of rounding plus at most
             * 0.5 num scale / 2^46 <= 2^-6 from the reciprocal. */
            CHECK_NEAR((double)rad__proj(num, rad__recip(d), 2048 * 8), (double)num * 2048 * 8 / d,
                       0.5 + 1.0 / 64, "rad__proj(%ld) at depth %ld, in subpixels", (long)num,
                       (long)d);
            /* Depth w = 2^30 NEAR / d, at most 2^30 at the near plane. */
            CHECK_NEAR((double)rad__depth(rad__recip(d)), 1073741824.0 * (256.0 / d),
                       0.5 + 1.0 / 256, "rad__depth at depth %ld", (long)d);
            CHECK_INT_LE(rad__depth(rad__recip(d)), RAD__DEPTH_ONE,
                         "rad__depth at depth %ld: at most 2^30", (long)d);
        }
    for (i = 0; i < 2000; i++) {
        int32_t a = (int32_t)(rnd() % (1u << 26)) - (1 << 25),
                b = (int32_t)(rnd() % (1u << 26)) - (1 << 25);
        int32_t da = (int32_t)(rnd() % (1u << 25)) + 1, db = -(int32_t)(rnd() % (1u << 25));
        double want = a + (double)(b - (double)a) * da / ((double)da - db);
        const rad__clip_t c = rad__clip_init(da, db);
        CHECK_NEAR((double)rad__clip_lerp(a, b, &c), want, 0.5 + 1e-6,
                   "rad__clip_lerp(%ld, %ld, %ld, %ld)", (long)a, (long)b, (long)da, (long)db);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_isqrt),
        cmocka_unit_test(test_bitlen),
        cmocka_unit_test(test_shr_and_div_round),
        cmocka_unit_test(test_dot_cross_mul),
        cmocka_unit_test(test_unit_and_length),
        cmocka_unit_test(test_area_normal),
        cmocka_unit_test(test_energy_ops),
        cmocka_unit_test(test_projection_and_depth),
    };
    return cmocka_run_group_tests_name("fixmath", tests, NULL, NULL);
}
