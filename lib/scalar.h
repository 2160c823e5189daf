/* SPDX-License-Identifier: MIT */
/* rad — the scalar shim: every operation whose fixed-point and float forms differ.
 *
 * The algorithm in lib/ sources is written once against these functions; RAD_FLOAT selects
 * the float twin. Formats and ranges (fixed build) are those of rad.h; each function
 * states the input ranges it relies on, which the callers guarantee by the limits
 * checked in rad_add_polygon() and rad_render(). Rounding is to nearest; signed values
 * are never right-shifted (rad__shr_round works on magnitudes).
 */
#ifndef RAD_SCALAR_H
#define RAD_SCALAR_H

#include "rad/rad.h"

/* The twin's private names differ too, so both libraries link into one program. */
#if RAD_FLOAT
#define rad__isqrt64       radf__isqrt64
#define rad__unit64        radf__unit64
#define rad__fsqrt         radf__fsqrt
#define rad__scale2_vec    radf__scale2_vec
#define rad__scale2_rgb    radf__scale2_rgb
#define rad__draw          radf__draw
#define rad__hemicube_init radf__hemicube_init
#define rad__hemicube      radf__hemicube
#endif

/* Near plane of every view, in scene units: 2^-8. The depth value stored in z-buffers
 * is w = 2^30 * NEAR / d, so w <= 2^30 for every visible point. */
#if RAD_FLOAT
#define RAD__ONE  1.0f
#define RAD__NEAR (1.0f / 256.0f)
#define RAD__Q(x) ((float)(x))
#define RAD__EPS  1e-6f /* the least change that counts */
#else
#define RAD__ONE  65536
#define RAD__NEAR 256
/* Compile-time constants only: folded by the compiler, no floating point at run time. */
#define RAD__Q(x) ((rad_real_t)((x)*65536.0 + 0.5))
#define RAD__EPS  1 /* the least change that counts: one LSB */
#endif
#define RAD__DEPTH_ONE  (1u << 30)
#define RAD__FF_ONE_Q30 (1u << 30)

/* Helpers shared by the shim (scalar.c): integer ones in the fixed build, fsqrt in the twin. */
uint64_t rad__isqrt64(uint64_t v);
/* Unit vector (Q16.16) along the integer vector (x, y, z), |components| < 2^62;
 * returns its length, rounded, in the same units as the components (0: zero vector). */
uint64_t rad__unit64(int64_t x, int64_t y, int64_t z, rad_vec3_t *unit);
float rad__fsqrt(float x);

/* v / 2^n rounded to nearest (halves up), 1 <= n <= 32, |v| < 2^62: shifts v + 2^62,
 * never a negative number, and takes no branch. */
static inline int64_t rad__shr_round(int64_t v, unsigned n)
{
    uint64_t biased = (uint64_t)v + ((uint64_t)1 << 62) + ((uint64_t)1 << (n - 1));
    return (int64_t)(biased >> n) - (int64_t)((uint64_t)1 << (62 - n));
}

/* rad__shr_round for |v| < 2^30 and 1 <= n <= 30, in 32 bits (the 64-bit shift by a
 * variable is a library call on M0): the same floor((v + 2^(n-1)) / 2^n), its bias 2^30
 * a multiple of 2^n as 2^62 is. */
static inline int32_t rad__shr_round32(int32_t v, unsigned n)
{
    uint32_t biased = (uint32_t)v + (1u << 30) + (1u << (n - 1));
    return (int32_t)(biased >> n) - (int32_t)(1u << (30 - n));
}

/* Integer products, exact, in both builds. Targets without a 32 x 32 -> 64 bit
 * multiply (ARMv6-M, ARMv8-M baseline: Cortex-M0, M0+, M23 have a 32-bit MULS only)
 * build them inline from 32-bit products of 16-bit halves, instead of a call to
 * libgcc's 64 x 64 bit multiply: the same integers, so the same bits everywhere.
 * RAD__MUL_SPLIT=1 selects those forms on any target (the host tests both). */
#ifndef RAD__MUL_SPLIT
#if defined(__ARM_ARCH_6M__) || defined(__ARM_ARCH_8M_BASE__)
#define RAD__MUL_SPLIT 1
#else
#define RAD__MUL_SPLIT 0
#endif
#endif

/* The product's core, inlined into its few callers on RAD__MUL_SPLIT targets even at -Os
 * (as a call it costs the M0 more than its body). */
#if RAD__MUL_SPLIT && defined(__GNUC__)
#define RAD__ALWAYS_INLINE static inline __attribute__((always_inline))
#else
#define RAD__ALWAYS_INLINE static inline
#endif

/* Whether a 64-bit division is one instruction (64-bit targets), not a library call. */
#ifndef RAD__DIV64
#if UINTPTR_MAX > 0xFFFFFFFFu
#define RAD__DIV64 1
#else
#define RAD__DIV64 0
#endif
#endif

/* The int64 whose two's complement is U (a conversion C99 leaves to the compiler). */
static inline int64_t rad__s64(uint64_t u)
{
    return u >> 63 ? -(int64_t)~u - 1 : (int64_t)u;
}

/* a * b for any two uint32, below 2^64. */
RAD__ALWAYS_INLINE uint64_t rad__mulu32(uint32_t a, uint32_t b)
{
#if RAD__MUL_SPLIT
    /* hi 2^32 + lo from partial products of 16-bit halves: each is below 2^32, and so is
     * each with a carry of at most 2^16 - 1 added (mid, mid2: (2^16 - 1)^2 + 2^16 - 1 <
     * 2^32). */
    uint32_t lo = (a & 0xFFFFu) * (b & 0xFFFFu);
    uint32_t mid = (a >> 16) * (b & 0xFFFFu) + (lo >> 16);
    uint32_t mid2 = (a & 0xFFFFu) * (b >> 16) + (mid & 0xFFFFu);
    uint32_t hi = (a >> 16) * (b >> 16) + (mid >> 16) + (mid2 >> 16);
    return (uint64_t)hi << 32 | (mid2 << 16) | (lo & 0xFFFFu);
#else
    return (uint64_t)a * b;
#endif
}

/* a * b for any two int32: |a b| <= 2^62. */
static inline int64_t rad__mul32(int32_t a, int32_t b)
{
#if RAD__MUL_SPLIT
    /* A negative a is ua - 2^32 (b alike), so the signed product is the unsigned one
     * less ub 2^32 and ua 2^32, mod 2^64. */
    uint32_t ua = (uint32_t)a, ub = (uint32_t)b;
    uint64_t p = rad__mulu32(ua, ub);
    uint32_t hi = (uint32_t)(p >> 32) - ((a < 0 ? ub : 0u) + (b < 0 ? ua : 0u));
    return rad__s64((uint64_t)hi << 32 | (uint32_t)p);
#else
    return (int64_t)a * b;
#endif
}

/* x * m mod 2^64 for any uint64 x and uint32 m: the low word's product and the low 32
 * bits of the high word's (the rest is past 2^64). */
static inline uint64_t rad__mulu64_32(uint64_t x, uint32_t m)
{
#if RAD__MUL_SPLIT
    return rad__mulu32((uint32_t)x, m) + ((uint64_t)((uint32_t)(x >> 32) * m) << 32);
#else
    return x * m;
#endif
}

/* x * m mod 2^64 for any x and |m| < 2^16. */
static inline uint64_t rad__mulmod16(uint64_t x, int32_t m)
{
#if RAD__MUL_SPLIT
    /* x * |m| mod 2^64 from three products below 2^32 (x's low word in halves, p0 and
     * p1) and the high word's, of which only the low 32 bits reach the sum; the low
     * word's carry is rlo < p0. Then the sign. */
    uint32_t lo = (uint32_t)x, um = m < 0 ? 0u - (uint32_t)m : (uint32_t)m;
    uint32_t p0 = (lo & 0xFFFFu) * um, p1 = (lo >> 16) * um, rlo = p0 + (p1 << 16);
    uint32_t rhi = (uint32_t)(x >> 32) * um + (p1 >> 16) + (rlo < p0);
    uint64_t r = (uint64_t)rhi << 32 | rlo;
    return m < 0 ? 0u - r : r;
#else
    return x * (uint64_t)(int64_t)m;
#endif
}

/* x * m for |m| < 2^16, the product within int64 (the caller's range). */
static inline int64_t rad__mul16(int64_t x, int32_t m)
{
#if RAD__MUL_SPLIT
    return rad__s64(rad__mulmod16((uint64_t)x, m));
#else
    return x * m;
#endif
}

/* n 2^s mod 2^64, 0 <= s <= 31: in 32-bit words (a variable 64-bit shift is a library
 * call on M0). */
static inline uint64_t rad__shl64(uint64_t n, unsigned s)
{
    uint32_t hi = (uint32_t)(n >> 32), lo = (uint32_t)n;
    return (uint64_t)(s ? hi << s | lo >> (32u - s) : hi) << 32 | (uint32_t)(lo << s);
}

/* The leading zero bits of d > 0: three halvings (16, 8, 4), then the top nibble's. */
static inline unsigned rad__clz32(uint32_t d)
{
    static const unsigned char nibble[16] = {4, 3, 2, 2, 1, 1, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0};
    unsigned s = 0;
    if (d <= 0xFFFFu) {
        s = 16;
        d <<= 16;
    }
    if (d <= 0xFFFFFFu) {
        s += 8;
        d <<= 8;
    }
    if (d <= 0xFFFFFFFu) {
        s += 4;
        d <<= 4;
    }
    return s + nibble[d >> 28];
}

/* The bit length of V: 0 for 0, else 1 + the index of its highest set bit. */
static inline unsigned rad__bitlen64(uint64_t v)
{
    uint32_t hi = (uint32_t)(v >> 32), lo = (uint32_t)v;
    return hi ? 64u - rad__clz32(hi) : lo ? 32u - rad__clz32(lo) : 0u;
}

/* One 16-bit digit of rad__udiv64_32: the quotient of U * 2^16 + LO16 (U < V) by the
 * normalised V (top bit set), estimated from V's top half VN1, then corrected: the
 * estimate is at most 2 too large (Knuth, TAOCP 4.3.1, Theorem B). Leaves the
 * remainder in *U. The first test keeps q * vn0 below 2^32, the last rhat * 2^16.
 * U / VN1 itself comes from REC = floor((2^31 - 1) / VN1) < 2^16 (shared by both digits:
 * one 32-bit division, a library call on M0, instead of two): with U = 2^16 uh + ul,
 * q = floor((uh REC + floor(ul REC / 2^16)) / 2^15) (the sum below 2^32) is at most
 * U REC / 2^31 <= U / VN1, and at least U / VN1 - U / (2^31 VN1) - U / 2^31 - 2^-15 - 1
 * > U / VN1 - 4: three increments at most make it floor(U / VN1), with rhat its
 * remainder. */
static inline uint32_t rad__udigit(uint32_t *u, uint32_t lo16, uint32_t v, uint32_t rec)
{
    uint32_t vn1 = v >> 16, vn0 = v & 0xFFFFu;
    uint32_t q = ((*u >> 16) * rec + (((*u & 0xFFFFu) * rec) >> 16)) >> 15, rhat = *u - q * vn1;
    while (rhat >= vn1) {
        q++;
        rhat -= vn1;
    }
    while (q > 0xFFFFu || q * vn0 > (rhat << 16) + lo16) {
        q--;
        rhat += vn1;
        if (rhat > 0xFFFFu) break;
    }
    *u = (*u << 16) + lo16 - q * v; /* the true remainder < v, mod 2^32 */
    return q;
}

/* floor((2^31 - 1) / V) for V in [2^15, 2^16): rad__udigit's REC without a division
 * (a library call of about 100 instructions on M0). With x = V / 2^15 in [1, 2), the
 * line 24/17 - 8/17 x is 1/x within 1/17 (Chebyshev's: equal and opposite errors at 1,
 * at the middle and at 2); so y = 2^16 (24/17 - 8/17 x) = 92521 - 16/17 V is 2^31 / V
 * within 6%, and y V (2^31 within 6%) fits 32 bits. Each Newton step y += y e / 2^31,
 * e = 2^31 - y V, squares the relative error (0.0035, then 1.2e-5: within 1 of 2^31 / V
 * but for the truncations of e / 2^11 and of the product / 2^20: over every V, y ends
 * 1 below in 6,643 cases, 1 above in 641, 2 above in one); the last loops make it exact
 * (remainder 2^31 - 1 - y V in [0, V)). test_mulsplit checks every V. */
static inline uint32_t rad__rec16(uint32_t v)
{
    uint32_t y = 92521u - ((v * 61681u) >> 16), i; /* 61681 / 2^16 = 16/17 to 2^-17 */
    int32_t r;
    for (i = 0; i < 2; i++) {
        /* |e| < 2^28: the product of |e| / 2^11 and y (< 2^17) stays below 2^32 */
        int32_t e = (int32_t)(0x80000000u - y * v);
        uint32_t m = (((uint32_t)(e < 0 ? -e : e) >> 11) * y) >> 20;
        y = e < 0 ? y - m : y + m;
    }
    r = (int32_t)(0x7FFFFFFFu - y * v);
    while (r < 0) {
        y--;
        r += (int32_t)v;
    }
    while (r >= (int32_t)v) {
        y++;
        r -= (int32_t)v;
    }
    return y;
}

/* n / d for d > 0 and n / d < 2^32 (n >> 32 < d): long division by two 16-bit digits
 * (Hacker's Delight's divlu), for targets where a 64-bit division is a long library
 * call. */
static inline uint32_t rad__udiv64_32(uint64_t n, uint32_t d)
{
    unsigned s = rad__clz32(d);
    uint64_t un = rad__shl64(n, s);
    uint32_t u = (uint32_t)(un >> 32), lo = (uint32_t)un, q1, rec;
    d <<= s;
    rec = rad__rec16(d >> 16);
    q1 = rad__udigit(&u, lo >> 16, d, rec);
    return q1 << 16 | rad__udigit(&u, lo & 0xFFFFu, d, rec);
}

/* n / d for d > 0: by rad__udiv64_32 where it applies on RAD__MUL_SPLIT targets. */
static inline uint64_t rad__udiv64(uint64_t n, uint64_t d)
{
#if RAD__MUL_SPLIT
    if (d >> 32 == 0 && n >> 32 < d) return rad__udiv64_32(n, (uint32_t)d);
#endif
    return n / d;
}

/* num / den truncated toward zero, as C99's division, for den != 0 and num > INT64_MIN. */
static inline int64_t rad__sdiv64(int64_t num, int64_t den)
{
#if RAD__MUL_SPLIT
    uint64_t n = num < 0 ? (uint64_t)0 - (uint64_t)num : (uint64_t)num;
    uint64_t d = den < 0 ? (uint64_t)0 - (uint64_t)den : (uint64_t)den;
    int64_t q = (int64_t)rad__udiv64(n, d);
    return (num < 0) != (den < 0) ? -q : q;
#else
    return num / den;
#endif
}

/* num / den rounded half away from zero (C99 division truncates toward zero). */
static inline int64_t rad__div_round(int64_t num, int64_t den)
{
    int neg = (num < 0) != (den < 0);
    uint64_t n = num < 0 ? (uint64_t)0 - (uint64_t)num : (uint64_t)num;
    uint64_t d = den < 0 ? (uint64_t)0 - (uint64_t)den : (uint64_t)den;
    uint64_t q = rad__udiv64(n + d / 2u, d);
    return neg ? -(int64_t)q : (int64_t)q;
}

/* Division by an invariant: one divisor D (1 <= D < 2^32) of several quotients. On
 * RAD__MUL_SPLIT targets its reciprocal is found once (one rad__udiv64_32) and each
 * quotient then takes a product and two corrections (Moller and Granlund, "Improved
 * division by invariant integers", IEEE Trans. Computers 60(2), 2011, Algorithm 4; its
 * Theorem 2 is the proof): with D normalised to d = D 2^s (top bit set) and v =
 * floor((2^64 - 1) / d) - 2^32, the quotient of <u1, u0> = n 2^s (u1 < d) by d, which is
 * n / D, comes out exact. Elsewhere it is the plain division. NEG keeps D's sign for
 * rad__div_round_inv. */
typedef struct {
    uint32_t den; /* D */
    int neg;
#if RAD__MUL_SPLIT
    uint32_t d, v;
    unsigned s;
#endif
} rad__udiv_inv_t;

/* The divisor |DEN| (0 < |DEN| < 2^32), of DEN's sign. */
static inline rad__udiv_inv_t rad__udiv_inv_init(int64_t den)
{
    rad__udiv_inv_t r;
    r.neg = den < 0;
    r.den = (uint32_t)(den < 0 ? (uint64_t)0 - (uint64_t)den : (uint64_t)den);
#if RAD__MUL_SPLIT
    r.s = rad__clz32(r.den);
    r.d = r.den << r.s;
    /* (2^64 - 1) - 2^32 d = (2^32 - 1 - d) 2^32 + 2^32 - 1, and 2^32 - 1 - d < d */
    r.v = rad__udiv64_32((uint64_t)~r.d << 32 | 0xFFFFFFFFu, r.d);
#endif
    return r;
}

/* n / D for n / D < 2^32 (n >> 32 < D). */
static inline uint32_t rad__udiv_inv(uint64_t n, const rad__udiv_inv_t *iv)
{
#if RAD__MUL_SPLIT
    /* n 2^s < D 2^s 2^32 = d 2^32: fits, and u1 < d. <q1, q0> = (2^32 + v) u1 + u0 fits
     * 64 bits: 2^32 + v <= (2^64 - 1) / d, u1 <= d - 1 and (2^64 - 1) / d > 2^32 > u0. */
    uint64_t u = rad__shl64(n, iv->s), p = rad__mulu32(iv->v, (uint32_t)(u >> 32)) + u;
    uint32_t q1 = (uint32_t)(p >> 32) + 1u, q0 = (uint32_t)p, r = (uint32_t)u - q1 * iv->d;
    if (r > q0) { /* mod 2^32: the candidate is one too large */
        q1--;
        r += iv->d;
    }
    if (r >= iv->d) q1++; /* rare: one too small */
    return q1;
#else
    return (uint32_t)(n / iv->den);
#endif
}

/* rad__div_round(NUM, D) for |NUM| / |D| < 2^32 - 1, D's IV (rad__udiv_inv_init). */
static inline int64_t rad__div_round_inv(int64_t num, const rad__udiv_inv_t *iv)
{
    uint64_t n = num < 0 ? (uint64_t)0 - (uint64_t)num : (uint64_t)num;
    int64_t q = (int64_t)rad__udiv_inv(n + iv->den / 2u, iv);
    return (num < 0) != iv->neg ? -q : q;
}

static inline rad_vec3_t rad__sub(rad_vec3_t a, rad_vec3_t b)
{
    rad_vec3_t r;
    r.x = a.x - b.x;
    r.y = a.y - b.y;
    r.z = a.z - b.z;
    return r;
}

#if RAD_FLOAT

static inline rad_real_t rad__dot(rad_vec3_t a, rad_vec3_t b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
static inline rad_vec3_t rad__cross(rad_vec3_t a, rad_vec3_t b)
{
    rad_vec3_t r;
    r.x = a.y * b.z - a.z * b.y;
    r.y = a.z * b.x - a.x * b.z;
    r.z = a.x * b.y - a.y * b.x;
    return r;
}
static inline rad_real_t rad__mul(rad_real_t a, rad_real_t b, uint32_t *sat)
{
    (void)sat;
    return a * b;
}
static inline rad_real_t rad__div(rad_real_t a, rad_real_t b, uint32_t *sat)
{
    (void)sat;
    return a / b;
}
static inline rad_real_t rad__length(rad_vec3_t v)
{
    return rad__fsqrt(rad__dot(v, v));
}
/* The square root of A >= 0 (an area: the side of a square of that area). */
static inline rad_real_t rad__sqrt(rad_real_t a)
{
    return rad__fsqrt(a);
}
/* Unit vector of V; returns 0 for a zero vector. */
static inline int rad__normalize(rad_vec3_t v, rad_vec3_t *u)
{
    float l = rad__length(v);
    if (!(l > 0.0f)) {
        u->x = u->y = u->z = 0.0f;
        return 0;
    }
    u->x = v.x / l;
    u->y = v.y / l;
    u->z = v.z / l;
    return 1;
}
/* Half the length of D1 x D2 (the area of a triangle on D1, D2, or of a quad with
 * diagonals D1, D2) and the unit normal along D1 x D2. */
static inline rad_real_t rad__area_normal(rad_vec3_t d1, rad_vec3_t d2, rad_vec3_t *n)
{
    rad_vec3_t c = rad__cross(d1, d2);
    float l = rad__length(c);
    if (!(l > 0.0f)) {
        n->x = n->y = n->z = 0.0f;
        return 0.0f;
    }
    n->x = c.x / l;
    n->y = c.y / l;
    n->z = c.z / l;
    return 0.5f * l;
}
/* Weighted mean of K points with integer weights W summing to DEN. */
static inline rad_vec3_t rad__wavg(const rad_vec3_t *c, const uint32_t *w, unsigned k, uint32_t den)
{
    rad_vec3_t r = {0.0f, 0.0f, 0.0f};
    unsigned i;
    for (i = 0; i < k; i++) {
        float f = (float)w[i] / (float)den;
        r.x += c[i].x * f;
        r.y += c[i].y * f;
        r.z += c[i].z * f;
    }
    return r;
}
/* ceil(a / (b * m) - 1/1024), at least 1, for a > 0, b > 0, m >= 1: a length that
 * is a whole number of b * m within 0.1% (as meshes often are) gives that number in
 * both builds, whatever their last bits. */
static inline uint32_t rad__ceil_div(rad_real_t a, rad_real_t b, uint32_t m)
{
    float q = a / (b * (float)m) - 1.0f / 1024.0f;
    uint32_t n = q > 0.0f ? (uint32_t)q : 0u;
    return (float)n < q ? n + 1u : n > 0u ? n : 1u;
}
/* a + (b - a) * da / (da - db): the crossing of a clip plane, da and db of opposite sign,
 * for the CLIP of da and db (one for every coordinate of a crossing). */
typedef struct {
    rad_real_t t;
} rad__clip_t;
static inline rad__clip_t rad__clip_init(rad_real_t da, rad_real_t db)
{
    rad__clip_t c;
    c.t = da / (da - db);
    return c;
}
static inline rad_real_t rad__clip_lerp(rad_real_t a, rad_real_t b, const rad__clip_t *c)
{
    return a + (b - a) * c->t;
}
/* The reciprocal of a depth d >= RAD__NEAR, for projecting without dividing. */
typedef float rad__recip_t;
static inline rad__recip_t rad__recip(rad_real_t d)
{
    return 1.0f / d;
}
/* round(num * scale / d) for num in [0, 2 d]: a screen coordinate in subpixels. */
static inline int32_t rad__proj(rad_real_t num, rad__recip_t inv, uint32_t scale)
{
    float v = num * inv * (float)scale;
    return v > 0.0f ? (int32_t)(v + 0.5f) : 0;
}
/* The depth value w = 2^30 NEAR / d (<= 2^30). */
static inline uint32_t rad__depth(rad__recip_t inv)
{
    return (uint32_t)(1073741824.0f * RAD__NEAR * inv + 0.5f);
}
/* The distance d of depth value W > 0 (w = 2^30 NEAR / d), rounded. */
static inline rad_real_t rad__depth_d(uint32_t w)
{
    return 1073741824.0f * RAD__NEAR / (float)w;
}
static inline rad_energy_t rad__energy(rad_real_t b, rad_real_t area)
{
    return b * area;
}
static inline rad_energy_t rad__energy_ff(rad_energy_t u, rad_ff_t f)
{
    return u * f;
}
static inline rad_energy_t rad__energy_refl(rad_energy_t u, rad_real_t rho)
{
    return u * rho;
}
typedef rad_real_t rad__area_div_t;
static inline rad__area_div_t rad__area_div(rad_real_t area)
{
    return area;
}
static inline rad_real_t rad__energy_to_rad(rad_energy_t u, const rad__area_div_t *area,
                                            uint32_t *sat)
{
    (void)sat;
    return u / *area;
}
static inline rad_real_t rad__energy_ratio(rad_energy_t num, rad_energy_t den)
{
    return den > 0.0f ? num / den : 0.0f;
}
static inline rad_real_t rad__add_sat(rad_real_t a, rad_real_t b, uint32_t *sat)
{
    (void)sat;
    return a + b;
}
static inline rad_ff_t rad__ff_from_q30(uint32_t q)
{
    return (float)q * (1.0f / 1073741824.0f);
}
static inline uint32_t rad__ff_to_q30(rad_ff_t f)
{
    float v = f * 1073741824.0f + 0.5f;
    return v <= 0.0f ? 0u : v >= 4294967295.0f ? 0xFFFFFFFFu : (uint32_t)v;
}
/* Gauss-Seidel sums: a form factor times a radiosity, summed, then read as radiosity. */
typedef float rad__gsum_t;
static inline rad__gsum_t rad__gs_term(rad_ff_t g, rad_real_t b)
{
    return g * b;
}
static inline rad_real_t rad__gs_value(rad__gsum_t a, uint32_t *sat)
{
    (void)sat;
    return a;
}
/* G = F * a / b: a form factor taken to another area by reciprocity. */
static inline rad_ff_t rad__ff_scale(rad_ff_t f, rad_real_t a, rad_real_t b, uint32_t *sat)
{
    (void)sat;
    return f * (a / b);
}
/* Raster attribute (<= 2^30) of a radiosity, and back: Q16.15 in both builds. */
static inline uint32_t rad__attr(rad_real_t b)
{
    float v = b * 32768.0f;
    return v <= 0.0f ? 0u : v >= 1073741824.0f ? 1073741824u : (uint32_t)(v + 0.5f);
}
static inline rad_real_t rad__from_attr(uint32_t a)
{
    return (float)a * (1.0f / 32768.0f);
}
static inline rad_ff_t rad__vweight(rad_real_t area)
{
    return area;
}
static inline rad_real_t rad__wpart(rad_real_t b, rad_ff_t w, rad_ff_t wsum)
{
    return b * (w / wsum);
}
static inline rad_real_t rad__from_int(int32_t i)
{
    return (float)i;
}
/* floor(V M) for 0 <= V <= 2 and M <= 2^15: a fraction of a raster's width in pixels. */
static inline int32_t rad__floor_times(rad_real_t v, uint32_t m)
{
    return (int32_t)(v * (float)m);
}
/* V in [-M, M] as an integer in [-2^S, 2^S], rounded (S <= 23, M > 0), for the GRID of
 * M and S (one for every coordinate of a lattice). */
typedef struct {
    float m;
    unsigned s;
} rad__grid_t;
static inline rad__grid_t rad__grid_init(rad_real_t m, unsigned s)
{
    rad__grid_t g = {m, s};
    return g;
}
static inline int64_t rad__grid(rad_real_t v, const rad__grid_t *g)
{
    float q = v / g->m * (float)((int32_t)1 << g->s);
    return (int64_t)(q < 0 ? q - 0.5f : q + 0.5f);
}
/* V times 2^N, -31 <= N <= 31: exact (a power of two), short of float's range. */
static inline rad_real_t rad__scale2(rad_real_t v, int n, uint32_t *sat)
{
    float f = 1.0f;
    (void)sat;
    for (; n > 0; n--) f *= 2.0f;
    for (; n < 0; n++) f *= 0.5f;
    return v * f;
}
/* V times 2^-N, 0 <= N <= 16, rounded down (exact in float). */
static inline rad_real_t rad__floor2(rad_real_t v, unsigned n)
{
    return rad__scale2(v, -(int)n, 0);
}
/* Area A (units^2) times 2^(2N), -16 <= N <= 16, in energy's format (the caller's
 * area, which may pass rad_real_t's range). */
static inline rad_energy_t rad__area_scale(rad_real_t a, int n)
{
    return rad__scale2(a, 2 * n, 0);
}
/* (a U + b V) / c: U turned toward V by the angle whose cosine is a / c. */
static inline rad_vec3_t rad__turn(rad_vec3_t u, rad_vec3_t v, int a, int b, int c)
{
    rad_vec3_t r;
    r.x = ((float)a * u.x + (float)b * v.x) / (float)c;
    r.y = ((float)a * u.y + (float)b * v.y) / (float)c;
    r.z = ((float)a * u.z + (float)b * v.z) / (float)c;
    return r;
}

#else /* fixed point */

static inline rad_real_t rad__sat32(int64_t v, uint32_t *sat)
{
    if (v > INT32_MAX) {
        if (sat) (*sat)++;
        return INT32_MAX;
    }
    if (v < INT32_MIN) {
        if (sat) (*sat)++;
        return INT32_MIN;
    }
    return (rad_real_t)v;
}
/* Inputs: |a|, |b| < 2^25 (differences of in-range coordinates, or unit vectors). */
static inline rad_real_t rad__dot(rad_vec3_t a, rad_vec3_t b)
{
    int64_t s = rad__mul32(a.x, b.x) + rad__mul32(a.y, b.y) + rad__mul32(a.z, b.z);
    return (rad_real_t)rad__shr_round(s, 16);
}
/* Cross product of vectors of magnitude <= 2 (unit vectors), rounded to Q16.16. */
static inline rad_vec3_t rad__cross(rad_vec3_t a, rad_vec3_t b)
{
    rad_vec3_t r;
    r.x = (rad_real_t)rad__shr_round(rad__mul32(a.y, b.z) - rad__mul32(a.z, b.y), 16);
    r.y = (rad_real_t)rad__shr_round(rad__mul32(a.z, b.x) - rad__mul32(a.x, b.z), 16);
    r.z = (rad_real_t)rad__shr_round(rad__mul32(a.x, b.y) - rad__mul32(a.y, b.x), 16);
    return r;
}
static inline rad_real_t rad__mul(rad_real_t a, rad_real_t b, uint32_t *sat)
{
    return rad__sat32(rad__shr_round(rad__mul32(a, b), 16), sat);
}
static inline rad_real_t rad__div(rad_real_t a, rad_real_t b, uint32_t *sat)
{
    return rad__sat32(rad__div_round((int64_t)a * 65536, b), sat);
}
static inline rad_real_t rad__length(rad_vec3_t v)
{
    rad_vec3_t u;
    return (rad_real_t)rad__unit64(v.x, v.y, v.z, &u);
}
/* The square root of A >= 0 (an area: the side of a square of that area), rounded
 * down: sqrt(a / 2^16) 2^16 = sqrt(a 2^16), below 2^24 for any a < 2^31. */
static inline rad_real_t rad__sqrt(rad_real_t a)
{
    return (rad_real_t)rad__isqrt64((uint64_t)a << 16);
}
static inline int rad__normalize(rad_vec3_t v, rad_vec3_t *u)
{
    return rad__unit64(v.x, v.y, v.z, u) != 0;
}
/* Inputs: components < 2^24 (in-range coordinate differences). The cross product is
 * exact in Q32 (< 2^49); its length converts to an area in Q16.16 (< 2^31). */
static inline rad_real_t rad__area_normal(rad_vec3_t d1, rad_vec3_t d2, rad_vec3_t *n)
{
    int64_t cx = rad__mul32(d1.y, d2.z) - rad__mul32(d1.z, d2.y);
    int64_t cy = rad__mul32(d1.z, d2.x) - rad__mul32(d1.x, d2.z);
    int64_t cz = rad__mul32(d1.x, d2.y) - rad__mul32(d1.y, d2.x);
    uint64_t len = rad__unit64(cx, cy, cz, n);     /* |c| in Q32 */
    return (rad_real_t)((len + (1u << 16)) >> 17); /* |c| / 2 in Q16.16, rounded */
}
static inline rad_vec3_t rad__wavg(const rad_vec3_t *c, const uint32_t *w, unsigned k, uint32_t den)
{
    int64_t x = 0, y = 0, z = 0;
    unsigned i;
    for (i = 0; i < k; i++) {
        x += (int64_t)c[i].x * w[i];
        y += (int64_t)c[i].y * w[i];
        z += (int64_t)c[i].z * w[i];
    }
    {
        rad_vec3_t r;
        r.x = (rad_real_t)rad__div_round(x, den);
        r.y = (rad_real_t)rad__div_round(y, den);
        r.z = (rad_real_t)rad__div_round(z, den);
        return r;
    }
}
static inline uint32_t rad__ceil_div(rad_real_t a, rad_real_t b, uint32_t m)
{
    int64_t d = (int64_t)b * m, x = (int64_t)a * 1024 - d; /* 1024 (a / d - 1/1024) d */
    int64_t q = x > 0 ? (x + 1024 * d - 1) / (1024 * d) : 0;
    return q > 0 ? (uint32_t)q : 1u;
}
/* |a|, |b| < 2^26: the product fits int64 comfortably, and da - db (opposite signs, so
 * not 0) is below 2^32, as is the quotient, |b - a| at most. */
typedef struct {
    rad_real_t da;
    rad__udiv_inv_t den;
} rad__clip_t;
static inline rad__clip_t rad__clip_init(rad_real_t da, rad_real_t db)
{
    rad__clip_t c;
    c.da = da;
    c.den = rad__udiv_inv_init((int64_t)da - db);
    return c;
}
static inline rad_real_t rad__clip_lerp(rad_real_t a, rad_real_t b, const rad__clip_t *c)
{
    if (a == b) return a; /* the quotient is 0 (a hemi-cube's colours): no division */
    return a + (rad_real_t)rad__div_round_inv(rad__mul32(b - a, c->da), &c->den);
}
/* 2^46 / d for d in [RAD__NEAR, 2^26): below 2^38, with 2^-23 relative precision. */
typedef uint64_t rad__recip_t;
static inline rad__recip_t rad__recip(rad_real_t d)
{
    return rad__udiv64(((uint64_t)1 << 46) + ((uint64_t)d >> 1), (uint64_t)d);
}
/* num * scale / d for num in [0, 2 d], scale <= 2^15: num * inv <= 2^47, times scale
 * <= 2^62. */
static inline int32_t rad__proj(rad_real_t num, rad__recip_t inv, uint32_t scale)
{
    return num > 0 ? (int32_t)((rad__mulu64_32(rad__mulu64_32(inv, (uint32_t)num), scale) +
                                ((uint64_t)1 << 45)) >>
                               46)
                   : 0;
}
/* w = 2^30 NEAR / d = 2^38 / d (NEAR = 2^8 in Q16.16) = inv / 2^8. */
static inline uint32_t rad__depth(rad__recip_t inv)
{
    return (uint32_t)((inv + 128u) >> 8);
}
/* d = 2^38 / w for W > 0, rounded; past 2^31 - 1 (w < 128, d beyond 32767) that. */
static inline rad_real_t rad__depth_d(uint32_t w)
{
    uint64_t d = (((uint64_t)1 << 38) + w / 2u) / w;
    return d > 0x7FFFFFFFu ? 0x7FFFFFFF : (rad_real_t)d;
}
/* Energies are signed (overshooting owes power), but these take and give magnitudes:
 * callers carry the sign (rad__eabs), so no product or shift sees a negative value. */
/* b, area >= 0 and < 2^31: the product < 2^62. */
static inline rad_energy_t rad__energy(rad_real_t b, rad_real_t area)
{
    return (rad_energy_t)((rad__mulu32((uint32_t)b, (uint32_t)area) + 32768u) >> 16);
}
/* 0 <= u < 2^46, f <= 2^30: (u * f) >> 30 without a 128-bit product. */
static inline rad_energy_t rad__energy_ff(rad_energy_t u, rad_ff_t f)
{
    uint32_t hi = (uint32_t)((uint64_t)u >> 32), lo = (uint32_t)u;
    return (rad_energy_t)((rad__mulu32(hi, f) << 2) + ((rad__mulu32(lo, f) + (1u << 29)) >> 30));
}
static inline rad_energy_t rad__energy_refl(rad_energy_t u, rad_real_t rho)
{
    return (rad_energy_t)((rad__mulu64_32((uint64_t)u, (uint32_t)rho) + 32768u) >> 16);
}
/* An element's area as rad__energy_to_rad divides by it, prepared once for its three
 * channels: on RAD__MUL_SPLIT targets the reciprocal (rad__udiv_inv), one 64/32
 * division where each channel took one. */
typedef rad__udiv_inv_t rad__area_div_t;
static inline rad__area_div_t rad__area_div(rad_real_t area)
{
    return rad__udiv_inv_init(area > 0 ? area : 1);
}
/* Radiosity of power 0 <= U < 2^47 spread over AREA (rad__area_div's, of an area > 0),
 * rounded: (U 2^16 + A / 2) / A, whose numerator is below 2^63. A quotient of 2^32 or
 * more (n >> 32 >= A, outside rad__udiv_inv's range) saturates, as does one past
 * INT32_MAX. */
static inline rad_real_t rad__energy_to_rad(rad_energy_t u, const rad__area_div_t *area,
                                            uint32_t *sat)
{
    uint64_t n = ((uint64_t)u << 16) + (area->den >> 1);
    uint32_t q = n >> 32 < area->den ? rad__udiv_inv(n, area) : 0xFFFFFFFFu;
    if (q > (uint32_t)INT32_MAX) {
        if (sat) (*sat)++;
        return INT32_MAX;
    }
    return (rad_real_t)q;
}
/* num / den in Q16.16 for any two energies >= 0 (the larger is scaled down to fit). */
static inline rad_real_t rad__energy_ratio(rad_energy_t num, rad_energy_t den)
{
    uint64_t q, n = (uint64_t)num, d = (uint64_t)den;
    while (n >> 46) {
        n >>= 1;
        d >>= 1;
    }
    if (d == 0) return n ? INT32_MAX : 0;
    q = rad__udiv64((n << 16) + (d >> 1), d);
    return q > (uint64_t)INT32_MAX ? INT32_MAX : (rad_real_t)q;
}
static inline rad_real_t rad__add_sat(rad_real_t a, rad_real_t b, uint32_t *sat)
{
    return rad__sat32((int64_t)a + b, sat);
}
static inline rad_ff_t rad__ff_from_q30(uint32_t q)
{
    return q;
}
static inline uint32_t rad__ff_to_q30(rad_ff_t f)
{
    return f;
}
/* Gauss-Seidel sums: each term (Q2.30 * Q16.16) >> 14 < 2^49, so 2^14 patches' sum fits
 * 64 bits; the sum >> 16 is a Q16.16 radiosity. */
typedef uint64_t rad__gsum_t;
static inline rad__gsum_t rad__gs_term(rad_ff_t g, rad_real_t b)
{
    return (rad__mulu32(g, (uint32_t)(b > 0 ? b : 0)) + 8192u) >> 14;
}
static inline rad_real_t rad__gs_value(rad__gsum_t a, uint32_t *sat)
{
    uint64_t v = (a + 32768u) >> 16;
    if (v > (uint64_t)INT32_MAX) {
        if (sat) (*sat)++;
        return INT32_MAX;
    }
    return (rad_real_t)v;
}
/* G = F * a / b in Q2.30, saturating at 4.0 (F <= 2^30, a < 2^31). */
static inline rad_ff_t rad__ff_scale(rad_ff_t f, rad_real_t a, rad_real_t b, uint32_t *sat)
{
    uint64_t v =
        rad__udiv64((uint64_t)f * (uint64_t)a + (uint64_t)b / 2u, (uint64_t)(b > 0 ? b : 1));
    if (v > 0xFFFFFFFFu) {
        if (sat) (*sat)++;
        return 0xFFFFFFFFu;
    }
    return (rad_ff_t)v;
}
static inline uint32_t rad__attr(rad_real_t b)
{
    return b > 0 ? (uint32_t)b >> 1 : 0u;
}
static inline rad_real_t rad__from_attr(uint32_t a)
{
    return a >= 0x40000000u ? INT32_MAX : (rad_real_t)(a << 1);
}
/* Vertex weights: area / 4, so that six of them (the most around a vertex) fit 32 bits. */
static inline rad_ff_t rad__vweight(rad_real_t area)
{
    return area > 3 ? (uint32_t)area >> 2 : 1u;
}
static inline rad_real_t rad__wpart(rad_real_t b, rad_ff_t w, rad_ff_t wsum)
{
    return (rad_real_t)rad__udiv64(rad__mulu32((uint32_t)(b > 0 ? b : 0), w) + wsum / 2u, wsum);
}
static inline rad_real_t rad__from_int(int32_t i)
{
    return (rad_real_t)((uint32_t)i << 16);
}
static inline int32_t rad__floor_times(rad_real_t v, uint32_t m)
{
    return (int32_t)(((uint64_t)(uint32_t)v * m) >> 16);
}
/* |v| <= m: the quotient is at most 2^S + 1/2 (S <= 23). */
typedef struct {
    rad__udiv_inv_t m;
    unsigned s;
} rad__grid_t;
static inline rad__grid_t rad__grid_init(rad_real_t m, unsigned s)
{
    rad__grid_t g;
    g.m = rad__udiv_inv_init(m);
    g.s = s;
    return g;
}
static inline int64_t rad__grid(rad_real_t v, const rad__grid_t *g)
{
    return rad__div_round_inv(rad__s64(rad__shl64((uint64_t)(int64_t)v, g->s)), &g->m); /* v 2^s */
}
/* V times 2^N, -31 <= N <= 31: a shift, exact for N >= 0 (saturating, counted),
 * rounded to nearest for N < 0. */
static inline rad_real_t rad__scale2(rad_real_t v, int n, uint32_t *sat)
{
    if (n < 0) return (rad_real_t)rad__shr_round(v, (unsigned)-n);
    return rad__sat32((int64_t)v * ((int64_t)1 << n), sat);
}
/* floor(V / 2^N), 0 <= N <= 16: rounding down composes (floor(floor(v / a) / b) =
 * floor(v / ab)), so a scale reached in steps is the scale reached at once. */
static inline rad_real_t rad__floor2(rad_real_t v, unsigned n)
{
    return v >= 0 ? v >> n : -(rad_real_t)(((uint32_t) - (int64_t)v + (1u << n) - 1u) >> n);
}
/* Area A (Q16.16) times 2^(2N), -16 <= N <= 16, as Q16.16 in int64 (exact upwards,
 * rounded to nearest downwards). */
static inline rad_energy_t rad__area_scale(rad_real_t a, int n)
{
    if (n < 0) return rad__shr_round(a, (unsigned)(-2 * n));
    return (rad_energy_t)a * ((int64_t)1 << (2 * n));
}
static inline rad_vec3_t rad__turn(rad_vec3_t u, rad_vec3_t v, int a, int b, int c)
{
    rad_vec3_t r;
    r.x = (rad_real_t)rad__div_round((int64_t)a * u.x + (int64_t)b * v.x, c);
    r.y = (rad_real_t)rad__div_round((int64_t)a * u.y + (int64_t)b * v.y, c);
    r.z = (rad_real_t)rad__div_round((int64_t)a * u.z + (int64_t)b * v.z, c);
    return r;
}

#endif

#if RAD__MUL_SPLIT && !RAD_FLOAT
/* floor(V / 2^N) for |V| < 2^31 - 2^(N + 1), 1 <= N <= 16, in 32 bits: V + 2^31 is not
 * negative and below 2^32. */
static inline int32_t rad__floor_shr32(int32_t v, unsigned n)
{
    return (int32_t)(((uint32_t)v + 0x80000000u) >> n) - (int32_t)(0x80000000u >> n);
}
#endif

/* rad__dot(A, U), the same value, for components |A| <= 2^24 (differences of in-range
 * points) and |U| < 2^17 (unit vectors, rounding included). On RAD__MUL_SPLIT targets
 * in six 32-bit products, no 64-bit sum: with A = 2^12 AH + AL (AL the low 12 bits,
 * |AH| <= 2^12), H = sum AH U and L = sum AL U are below 3 2^29 in magnitude, so
 * A . U = 2^12 H + L; with H = 16 HH + HL (HL its low 4 bits) the rounded quotient
 * floor((2^12 H + L + 2^15) / 2^16) is HH + floor((2^12 HL + L + 2^15) / 2^16), and
 * that numerator is below 2^30. */
static inline rad_real_t rad__dot_unit(rad_vec3_t a, rad_vec3_t u)
{
#if RAD__MUL_SPLIT && !RAD_FLOAT
    int32_t h = rad__floor_shr32(a.x, 12) * u.x + rad__floor_shr32(a.y, 12) * u.y +
                rad__floor_shr32(a.z, 12) * u.z;
    int32_t l = (int32_t)((uint32_t)a.x & 0xFFFu) * u.x + (int32_t)((uint32_t)a.y & 0xFFFu) * u.y +
                (int32_t)((uint32_t)a.z & 0xFFFu) * u.z;
    int32_t x = (int32_t)(((uint32_t)h & 15u) << 12) + l + 32768;
    return rad__floor_shr32(h, 4) + rad__floor_shr32(x, 16);
#else
    return rad__dot(a, u);
#endif
}

/* V and C times 2^N, each component as rad__scale2 (scalar.c: not inlined, for size). */
rad_vec3_t rad__scale2_vec(rad_vec3_t v, int n, uint32_t *sat);
rad_rgb_t rad__scale2_rgb(rad_rgb_t c, int n, uint32_t *sat);

/* The magnitude of a signed energy (|u| < 2^62 in the fixed build: no overflow). */
static inline rad_energy_t rad__eabs(rad_energy_t u)
{
    return u < 0 ? -u : u;
}

/* A patch's unshot power is kept within +-RAD__EMAX (2^30 units of power: 2^46 in
 * Q16.16, the range the fixed build's products are exact in), clamped and counted past
 * it: overshooting in a scene that reflects nearly everything can owe more than that. */
#if RAD_FLOAT
#define RAD__EMAX 1073741824.0f
#define RAD__ESUM 4.6e18f
#else
#define RAD__EMAX ((rad_energy_t)1 << 46)
#define RAD__ESUM ((rad_energy_t)1 << 61)
#endif
static inline rad_energy_t rad__eclamp(rad_energy_t u, uint32_t *sat)
{
    if (u > RAD__EMAX) {
        if (sat) (*sat)++;
        return RAD__EMAX;
    }
    if (u < -RAD__EMAX) {
        if (sat) (*sat)++;
        return -RAD__EMAX;
    }
    return u;
}
/* A running sum of energies, each within +-RAD__ESUM, stopped at +-RAD__ESUM so that no
 * number of terms overflows (sums over every patch). */
static inline rad_energy_t rad__esum(rad_energy_t a, rad_energy_t b)
{
    rad_energy_t v = a + b;
    return v > RAD__ESUM ? RAD__ESUM : v < -RAD__ESUM ? -RAD__ESUM : v;
}

#endif
