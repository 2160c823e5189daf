/* SPDX-License-Identifier: MIT */
/* The split integer forms of the scalar shim (RAD__MUL_SPLIT: what the Cortex-M0 runs,
 * products from 16-bit halves and 64/32 division by 16-bit digits) against the host's
 * native 64-bit operations: they must be equal, bit for bit, or the M0's checksums
 * would differ from the host's. Edge values pairwise, then a pseudo-random stream. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "check.h"
#define RAD__MUL_SPLIT 1
#include "scalar.h"

/* The exact reference for products that may leave 64 bits (GCC and Clang on 64-bit
 * hosts). */
__extension__ typedef unsigned __int128 u128;

static uint64_t rng_state = 0x2545F4914F6CDD1Dull;
static uint64_t rnd(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return rng_state;
}

static const int32_t edges32[] = {0,          1,           -1,         2,          0xFFFF,
                                  0x10000,    -0x10000,    0x10001,    -0xFFFF,    0x7FFF,
                                  0x8000,     -0x8000,     0x7FFFFFFF, INT32_MIN,  INT32_MIN + 1,
                                  0x7FFF0000, -0x7FFF0000, 0x12345678, -0x3C5A0F1E};
#define N32 (sizeof edges32 / sizeof edges32[0])

static int32_t rnd32(void)
{
    return (int32_t)(uint32_t)(rnd() >> (rnd() % 33u));
}

/* rad__mul32 is the exact product of any two int32, signs and extremes included. */
static void test_mul32(void **st)
{
    size_t i, j;
    (void)st;
    for (i = 0; i < N32; i++)
        for (j = 0; j < N32; j++)
            CHECK_INT_EQ(rad__mul32(edges32[i], edges32[j]), (int64_t)edges32[i] * edges32[j],
                         "rad__mul32(%ld, %ld)", (long)edges32[i], (long)edges32[j]);
    for (i = 0; i < 200000; i++) {
        int32_t a = rnd() & 1 ? -rnd32() : rnd32(), b = rnd() & 1 ? -rnd32() : rnd32();
        CHECK_INT_EQ(rad__mul32(a, b), (int64_t)a * b, "rad__mul32(%ld, %ld)", (long)a, (long)b);
    }
}

/* rad__mul16 is x * m for |m| < 2^16 whenever the product fits int64 (its contract),
 * x over the whole int64 range. */
static void test_mul16(void **st)
{
    static const int64_t xs[] = {0,
                                 1,
                                 -1,
                                 0xFFFF,
                                 0x10000,
                                 0xFFFFFFFF,
                                 0x100000000,
                                 -0x100000000,
                                 (int64_t)1 << 46,
                                 -((int64_t)1 << 46),
                                 ((int64_t)1 << 60) - 1};
    static const int32_t ms[] = {0, 1, -1, 2, -2, 1023, -1024, 0x7FFF, -0x8000, 0xFFFF, -0xFFFF};
    size_t i, j, n = 0;
    (void)st;
    for (i = 0; i < sizeof xs / sizeof xs[0]; i++)
        for (j = 0; j < sizeof ms / sizeof ms[0]; j++)
            if ((u128)(xs[i] < 0 ? -xs[i] : xs[i]) * (uint32_t)(ms[j] < 0 ? -ms[j] : ms[j]) <
                ((u128)1 << 63))
                CHECK_INT_EQ(rad__mul16(xs[i], ms[j]), xs[i] * ms[j], "rad__mul16(%lld, %ld)",
                             (long long)xs[i], (long)ms[j]);
    for (i = 0; i < 200000; i++) {
        int64_t x = (int64_t)(rnd() >> (rnd() % 63u + 1u));
        int32_t m = (int32_t)(rnd() % 65536u);
        if (rnd() & 1) x = -x;
        if (rnd() & 1) m = -m;
        if ((u128)(x < 0 ? -x : x) * (uint32_t)(m < 0 ? -m : m) >= ((u128)1 << 63)) continue;
        n++;
        CHECK_INT_EQ(rad__mul16(x, m), x * m, "rad__mul16(%lld, %ld)", (long long)x, (long)m);
    }
    /* most of the stream is in range (a draw out of range is skipped, not counted) */
    CHECK_INT_GT(n, 100000, "in-range draws of 200000");
}

/* rad__mulu64_32 is x * m mod 2^64 for any uint64 x and uint32 m (the energy and
 * projection products), and rad__mulu32 the full product of two uint32. */
static void test_mulu64_32(void **st)
{
    size_t i;
    (void)st;
    for (i = 0; i < 200000; i++) {
        uint64_t x = rnd() >> (rnd() % 64u);
        uint32_t m = (uint32_t)(rnd() >> (rnd() % 32u + 32u)), a = (uint32_t)rnd();
        if (i < 4) x = i & 1 ? ~(uint64_t)0 : 0, m = i & 2 ? 0xFFFFFFFFu : 1u, a = 0xFFFFFFFFu;
        CHECK_INT_EQ(rad__mulu64_32(x, m), x * m, "rad__mulu64_32(%llu, %lu)",
                     (unsigned long long)x, (unsigned long)m);
        CHECK_INT_EQ(rad__mulu32(a, m), (uint64_t)a * m, "rad__mulu32(%lu, %lu)", (unsigned long)a,
                     (unsigned long)m);
    }
}

/* rad__udiv64_32 is n / d for every n with n / d < 2^32: quotients and remainders at
 * their extremes (0, 2^32 - 1; 0, d - 1), divisors of every length. */
static void test_udiv64_32(void **st)
{
    size_t i;
    (void)st;
    for (i = 0; i < 400000; i++) {
        uint32_t d = (uint32_t)(rnd() >> (rnd() % 32u + 32u)),
                 q = (uint32_t)(rnd() >> (rnd() % 33u));
        uint64_t r, n;
        if (!d) d = 1;
        if (i % 5 == 0) q = 0xFFFFFFFFu;
        if (i % 7 == 0) q = 0;
        r = i % 3 == 0 ? d - 1u : rnd() % d;
        n = (uint64_t)q * d + r;
        CHECK_INT_EQ(rad__udiv64_32(n, d), q, "rad__udiv64_32(%llu, %lu)", (unsigned long long)n,
                     (unsigned long)d);
    }
}

/* rad__rec16, the long division's digit reciprocal found without a division, is
 * floor((2^31 - 1) / v) for every v in [2^15, 2^16). */
static void test_rec16(void **st)
{
    uint32_t v;
    (void)st;
    for (v = 0x8000u; v <= 0xFFFFu; v++)
        CHECK_INT_EQ(rad__rec16(v), 0x7FFFFFFFu / v, "rad__rec16(%lu)", (unsigned long)v);
}

/* rad__udiv_inv (a reciprocal and corrections: Moller and Granlund's division by an
 * invariant) is n / d for every n with n / d < 2^32, divisors of every length and the
 * extremes of both (d 1, 2^31, 2^32 - 1; quotient 0, 2^32 - 1; remainder 0, d - 1), and
 * rad__div_round_inv is rad__div_round with either sign. */
static void test_udiv_inv(void **st)
{
    static const uint32_t ds[] = {1u,          2u,          3u,          0x7FFFFFFFu,
                                  0x80000000u, 0x80000001u, 0xFFFFFFFEu, 0xFFFFFFFFu};
    size_t i;
    (void)st;
    for (i = 0; i < 400000; i++) {
        uint32_t d = i < 64 ? ds[i % 8u] : (uint32_t)(rnd() >> (rnd() % 32u + 32u)),
                 q = (uint32_t)(rnd() >> (rnd() % 33u));
        uint64_t r, n;
        rad__udiv_inv_t iv;
        int64_t num, den;
        if (!d) d = 1;
        if (i % 5 == 0) q = 0xFFFFFFFFu;
        if (i % 7 == 0) q = 0;
        r = i % 3 == 0 ? d - 1u : i % 11 == 0 ? 0u : rnd() % d;
        n = (uint64_t)q * d + r;
        iv = rad__udiv_inv_init(d);
        CHECK_INT_EQ(rad__udiv_inv(n, &iv), q, "rad__udiv_inv(%llu, %lu)", (unsigned long long)n,
                     (unsigned long)d);
        if (q >= 0x7FFFFFFFu) continue; /* rad__div_round_inv's range: the quotient < 2^32 - 1 */
        num = rnd() & 1 ? -(int64_t)n : (int64_t)n;
        den = rnd() & 1 ? -(int64_t)d : (int64_t)d;
        iv = rad__udiv_inv_init(den);
        CHECK_INT_EQ(rad__div_round_inv(num, &iv), rad__div_round(num, den),
                     "rad__div_round_inv(%lld, %lld)", (long long)num, (long long)den);
    }
}

/* rad__energy_to_rad through an element's prepared divisor (rad__area_div) is the
 * rounded native quotient, and saturates, counted, exactly where it passes INT32_MAX:
 * areas of every length, powers up to 2^47, quotients placed at INT32_MAX, 2^32 and
 * either side of them (where the split path changes from rad__udiv_inv to the
 * saturation). */
static void test_energy_to_rad(void **st)
{
    static const uint64_t qs[] = {0u,          1u,          0x7FFFFFFEu, 0x7FFFFFFFu,
                                  0x80000000u, 0xFFFFFFFFu, 0x100000000u};
    size_t i;
    (void)st;
    for (i = 0; i < 400000; i++) {
        int32_t area = (int32_t)((rnd() >> (rnd() % 32u + 32u)) & 0x7FFFFFFFu); /* < 2^31 */
        uint64_t u = rnd() >> (rnd() % 47u + 17u);                              /* < 2^47 */
        uint64_t q, n;
        uint32_t sat = 0, want_sat;
        rad__area_div_t ad;
        int32_t got, want;
        if (!area) area = 1;
        ad = rad__area_div(area);
        if (i % 4 == 0) { /* a power whose quotient is one of qs, give or take rounding */
            u = ((qs[i / 4 % 7u] * (uint64_t)area) >> 16) + rnd() % 3u;
            if (u >> 47) u = ((uint64_t)1 << 47) - 1u;
        }
        n = (u << 16) + ((uint32_t)area >> 1);
        q = n / (uint32_t)area;
        want = q > 0x7FFFFFFFu ? INT32_MAX : (int32_t)q;
        want_sat = q > 0x7FFFFFFFu;
        got = rad__energy_to_rad((rad_energy_t)u, &ad, &sat);
        CHECK_INT_EQ(got, want, "rad__energy_to_rad(%llu, area %ld)", (unsigned long long)u,
                     (long)area);
        CHECK_INT_EQ(sat, want_sat, "saturations of rad__energy_to_rad(%llu, area %ld)",
                     (unsigned long long)u, (long)area);
    }
}

/* A numerator and a non-zero denominator of any sign, magnitudes below 2^62 of every
 * length. */
static void rnd_pair(int64_t *num, int64_t *den)
{
    *num = (int64_t)(rnd() >> (rnd() % 62u + 2u));
    *den = (int64_t)(rnd() >> (rnd() % 62u + 2u));
    if (!*den) *den = 1;
    if (rnd() & 1) *num = -*num;
    if (rnd() & 1) *den = -*den;
}

/* rad__div_round through the split path and past it (64-bit divisors, quotients of 2^32
 * and more) equals the native rounding. */
static void test_div_round(void **st)
{
    size_t i;
    (void)st;
    for (i = 0; i < 200000; i++) {
        int64_t num, den;
        uint64_t n, d, want;
        rnd_pair(&num, &den);
        n = num < 0 ? (uint64_t)-num : (uint64_t)num;
        d = den < 0 ? (uint64_t)-den : (uint64_t)den;
        want = (n + d / 2u) / d;
        CHECK_INT_EQ(rad__div_round(num, den),
                     (num < 0) != (den < 0) ? -(int64_t)want : (int64_t)want,
                     "rad__div_round(%lld, %lld)", (long long)num, (long long)den);
    }
}

/* rad__sdiv64 truncates toward zero as C99's division does, signs of both kinds, and
 * rad__udiv64 (under it) past the 32-bit quotient and divisor. */
static void test_sdiv64(void **st)
{
    size_t i;
    (void)st;
    for (i = 0; i < 200000; i++) {
        int64_t num, den;
        rnd_pair(&num, &den);
        CHECK_INT_EQ(rad__sdiv64(num, den), num / den, "rad__sdiv64(%lld, %lld)", (long long)num,
                     (long long)den);
    }
}

/* rad__dot_unit is rad__dot's rounded value, computed natively here, over its whole
 * contract: components |a| <= 2^24, |u| < 2^17 (edges both ways, then random). */
static int64_t dot_native(rad_vec3_t a, rad_vec3_t u)
{
    int64_t s = (int64_t)a.x * u.x + (int64_t)a.y * u.y + (int64_t)a.z * u.z;
    return (s + 32768 + (INT64_C(1) << 62)) / 65536 -
           (INT64_C(1) << 46); /* floor: a positive numerator */
}

static void test_dot_unit(void **st)
{
    static const int32_t ea[] = {0,       1,        -1,        0xFFF,   0x1000,     -0x1000, 0x7FFF,
                                 -0x8000, 0xFFFFFF, -0xFFFFFF, 1 << 24, -(1 << 24), 0x123456};
    static const int32_t eu[] = {0,     1,      -1,      65535,    65536, -65536,
                                 65537, -65537, 0x1FFFF, -0x1FFFF, 46341};
    size_t i, j, na = sizeof ea / sizeof ea[0], nu = sizeof eu / sizeof eu[0];
    (void)st;
    for (i = 0; i < na * na * na; i++)
        for (j = 0; j < nu; j++) {
            rad_vec3_t a = {ea[i % na], ea[i / na % na], ea[i / na / na]};
            rad_vec3_t u = {eu[j], eu[(j + 3) % nu], eu[(j + 7) % nu]};
            CHECK_INT_EQ(rad__dot_unit(a, u), dot_native(a, u),
                         "rad__dot_unit(%ld %ld %ld, %ld %ld %ld)", (long)a.x, (long)a.y, (long)a.z,
                         (long)u.x, (long)u.y, (long)u.z);
        }
    for (i = 0; i < 200000; i++) {
        rad_vec3_t a, u;
        a.x = (int32_t)(rnd() % ((2u << 24) + 1u)) - (1 << 24);
        a.y = (int32_t)(rnd() % ((2u << 24) + 1u)) - (1 << 24);
        a.z = (int32_t)(rnd() % ((2u << 24) + 1u)) - (1 << 24);
        u.x = (int32_t)(rnd() % (2u << 17)) - 0x1FFFF;
        u.y = (int32_t)(rnd() % (2u << 17)) - 0x1FFFF;
        u.z = (int32_t)(rnd() % (2u << 17)) - 0x1FFFF;
        CHECK_INT_EQ(rad__dot_unit(a, u), dot_native(a, u),
                     "rad__dot_unit(%ld %ld %ld, %ld %ld %ld)", (long)a.x, (long)a.y, (long)a.z,
                     (long)u.x, (long)u.y, (long)u.z);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_mul32),         cmocka_unit_test(test_mul16),
        cmocka_unit_test(test_mulu64_32),     cmocka_unit_test(test_udiv64_32),
        cmocka_unit_test(test_udiv_inv),      cmocka_unit_test(test_div_round),
        cmocka_unit_test(test_sdiv64),        cmocka_unit_test(test_dot_unit),
        cmocka_unit_test(test_energy_to_rad), cmocka_unit_test(test_rec16),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
