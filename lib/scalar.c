/* SPDX-License-Identifier: MIT */
/* rad — the arithmetic behind the scalar shim that is too long to inline. */
#include "scalar.h"

/* floor(sqrt(V)) for V < 2^32: bit by bit, two of V's bits a step, in 32-bit words. */
static uint32_t isqrt32(uint32_t v)
{
    uint32_t r = 0, bit = (uint32_t)1 << 30;
    while (bit > v) bit >>= 2;
    while (bit) {
        if (v >= r + bit) {
            v -= r + bit;
            r = (r >> 1) + bit;
        } else
            r >>= 1;
        bit >>= 2;
    }
    return r;
}

/* In both builds: tables built in integers (gather.c) take square roots too.
 * V >= 2^32: S = isqrt32 of V's top 31 or 32 bits (V / 2^2k), so R0 = S 2^k <= sqrt(V)
 * < (S + 1) 2^k, R0 within 2^-15 of the root. One Newton step, floor((R0 + floor(V /
 * R0)) / 2), is never below floor(sqrt(V)) (integer Newton from any R0 > 0) and above
 * it by at most (sqrt(V) - R0)^2 / (2 R0) + 1 < R0 2^-31 + 1 < 3; the loop takes off
 * the rest. Below 2^62 (k <= 15) the quotient is below (S + 3) 2^15 < 2^32: one 64/32
 * division (rad__udiv64_32 on RAD__MUL_SPLIT targets) where the bit-by-bit loop took
 * 32 steps of 64-bit arithmetic, a thousand instructions on M0. Above 2^62, that loop. */
uint64_t rad__isqrt64(uint64_t v)
{
    uint32_t hi = (uint32_t)(v >> 32);
    if (hi == 0) return isqrt32((uint32_t)v);
    if (hi >> 30 == 0) {
        unsigned k = (33u - rad__clz32(hi)) >> 1; /* 2k = bitlen(hi) rounded up to even */
        uint32_t r0 = isqrt32((uint32_t)(v >> 2u * k)) << k, r;
        r = (uint32_t)(((uint64_t)r0 + rad__udiv64(v, r0)) >> 1);
        while (rad__mulu32(r, r) > v) r--;
        return r;
    } else {
        /* Bit by bit, two result bits per step: 32 iterations, no division. */
        uint64_t r = 0, bit = (uint64_t)1 << 62;
        while (bit) {
            if (v >= r + bit) {
                v -= r + bit;
                r = (r >> 1) + bit;
            } else
                r >>= 1;
            bit >>= 2;
        }
        return r;
    }
}

#if !RAD_FLOAT

static uint64_t mag(int64_t v)
{
    return v < 0 ? (uint64_t)0 - (uint64_t)v : (uint64_t)v;
}

uint64_t rad__unit64(int64_t x, int64_t y, int64_t z, rad_vec3_t *unit)
{
    /* Scale the components to 30 significant bits so the sum of squares fits 64 bits
     * and the square root keeps full precision, whatever the input's size. */
    uint64_t ax = mag(x), ay = mag(y), az = mag(z), m = ax, len;
    int64_t c[3];
    unsigned b, i;
    if (ay > m) m = ay;
    if (az > m) m = az;
    if (m == 0) {
        unit->x = unit->y = unit->z = 0;
        return 0;
    }
    b = rad__bitlen64(m);
    c[0] = x;
    c[1] = y;
    c[2] = z;
    for (i = 0; i < 3; i++) {
        if (b > 30)
            c[i] = rad__shr_round(c[i], b - 30);
        else
            c[i] *= (int64_t)1 << (30 - b);
    }
    len = rad__isqrt64((uint64_t)(c[0] * c[0]) + (uint64_t)(c[1] * c[1]) + (uint64_t)(c[2] * c[2]));
    unit->x = (rad_real_t)rad__div_round(c[0] * 65536, (int64_t)len);
    unit->y = (rad_real_t)rad__div_round(c[1] * 65536, (int64_t)len);
    unit->z = (rad_real_t)rad__div_round(c[2] * 65536, (int64_t)len);
    if (b > 30) return len << (b - 30);
    return (len + (((uint64_t)1 << (30 - b)) >> 1)) >> (30 - b);
}

#else

float rad__fsqrt(float x)
{
    /* Newton's method from a power-of-two first guess: the float twin needs no libm. */
    float g = 1.0f;
    int i;
    if (!(x > 0.0f)) return 0.0f;
    while (g * g < x) g *= 2.0f;
    while (g * g > 4.0f * x) g *= 0.5f;
    for (i = 0; i < 8; i++) g = 0.5f * (g + x / g);
    return g;
}

#endif

rad_vec3_t rad__scale2_vec(rad_vec3_t v, int n, uint32_t *sat)
{
    v.x = rad__scale2(v.x, n, sat);
    v.y = rad__scale2(v.y, n, sat);
    v.z = rad__scale2(v.z, n, sat);
    return v;
}

rad_rgb_t rad__scale2_rgb(rad_rgb_t c, int n, uint32_t *sat)
{
    c.r = rad__scale2(c.r, n, sat);
    c.g = rad__scale2(c.g, n, sat);
    c.b = rad__scale2(c.b, n, sat);
    return c;
}
