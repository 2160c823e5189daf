/* SPDX-License-Identifier: MIT */
/* libFuzzer harness: the core's public API (lib/) driven by arbitrary bytes, in both
 * builds. This file is compiled twice, like tools/host/scene.c: with RAD_FLOAT=0 it
 * defines fuzz_core_fixed() and the libFuzzer entry point, with RAD_FLOAT=1
 * fuzz_core_float(); every input runs through both cores.
 *
 * The input is read as a little program (a reader that runs dry gives zeros):
 *   configuration  pools (sizes, sometimes NULL, oversized counts, a misaligned or
 *                  short work buffer), rad_config_t (any max_patch / max_element / res /
 *                  band_rows, valid or not)
 *   operations     add_polygon (0..5 vertices from grids, boundary values, raw bits,
 *                  copies of earlier vertices: coincident, degenerate, straddling the
 *                  hemi-cube's eye, tiny, huge; any reflectance and emission, or NULL),
 *                  set_surface, restart, shoot, unshot_fraction, ambient,
 *                  element_radiosity, shade_vertices, render (small views, any camera),
 *                  form_factors, the threaded shot (shot_begin / shot_part / shot_end),
 *                  stored rows (rows_compute / rows_shoot / rows_gauss_seidel), mix,
 *                  ff_from_code, strerror; the work buffer is exact, short, or has
 *                  bytes to spare.
 * Values come in Q16.16 for the fixed core; the float core gets the same numbers as
 * floats, or (selector bit 3) raw float bits: NaN, infinities, denormals, 1e38.
 *
 * Checked after every call: the return value is >= 0 or one of the RAD_ERR_* codes;
 * after an error the scene structure and the used part of every pool are bit-for-bit
 * unchanged; after success the counts grow as documented, the mesh is consistent
 * (indices in range, patches and surfaces cover their elements), displayed radiosity
 * is never negative, a form factor row sums to at most 1; shooting plainly
 * (RAD_NO_OVERSHOOT, selector bit 6), the partial radiosities and the ambient term are
 * never negative either and unshot power never exceeds what was emitted (overshooting
 * owes power for a while: then only displayed values are bounded). Every buffer is allocated at its exact size, so AddressSanitizer sees any
 * access past it; UndefinedBehaviorSanitizer sees overflows and bad conversions.
 */
#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rad/rad.h"

#if RAD_FLOAT
#define FUZZ_FN fuzz_core_float
#define BUILD   "float"
#else
#define FUZZ_FN fuzz_core_fixed
#define BUILD   "fixed"
#endif

int fuzz_core_fixed(const uint8_t *data, size_t size);
int fuzz_core_float(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define CHECK(c)                                                                              \
    do {                                                                                      \
        if (!(c)) {                                                                           \
            fprintf(stderr, "fuzz_core(" BUILD "): check failed: %s (%s:%d)\n", #c, __FILE__, \
                    __LINE__);                                                                \
            abort();                                                                          \
        }                                                                                     \
    } while (0)

#define MAX_OPS  48
#define MAX_VIEW 24

/* ---- reading the input ----------------------------------------------------------- */

typedef struct {
    const uint8_t *p;
    size_t n, pos;
    rad_vec3_t hist[16]; /* earlier vertices, for coincident and shared corners */
    unsigned nhist;
    rad_real_t last;
    int nonfinite; /* the float core got a NaN or an infinity somewhere */
} reader_t;

static uint8_t u8(reader_t *r)
{
    return r->pos < r->n ? r->p[r->pos++] : 0;
}
static uint16_t u16(reader_t *r)
{
    uint16_t v = u8(r);
    return (uint16_t)(v | (uint16_t)u8(r) << 8);
}
static uint32_t u32(reader_t *r)
{
    uint32_t v = u16(r);
    return v | (uint32_t)u16(r) << 16;
}

/* Boundary values in Q16.16; the float core also sees the special ones. */
static const int32_t palette_q[] = {
    0,
    1,
    -1,
    65536,
    -65536,
    64 << 16,
    -(64 << 16),
    (64 << 16) + 1,
    -(64 << 16) - 1,
    INT32_MAX,
    INT32_MIN,
    16,
    15,
    65535,
    256,
    255,
    128 << 16,
    256 << 16,
    (256 << 16) + 1,
    -(256 << 16) - 1,
    1024 << 16,
    4096 << 16,
    (4096 << 16) + 1,
    16 << 16,
    4096,
    1 << 30,
    32767 << 16,
    3,
    17,
    0x7FFF0000,
    -(1 << 30),
    2,
};
#define NPAL (sizeof palette_q / sizeof palette_q[0])

static rad_real_t from_q(int32_t q)
{
#if RAD_FLOAT
    return (float)q / 65536.0f;
#else
    return q;
#endif
}

#if RAD_FLOAT
static float special(reader_t *r, unsigned k)
{
    static const float sp[] = {0.0f,   -0.0f,       1e38f,     -1e38f,     FLT_MAX,    FLT_MIN,
                               1e-45f, 0.99999994f, 64.00001f, -64.00001f, 4096.0005f, 1e30f,
                               1e-30f, 3.4e38f,     0.5f,      1.0f};
    unsigned i = k % 20u;
    if (i == 16) {
        r->nonfinite = 1;
        return NAN;
    }
    if (i == 17) {
        r->nonfinite = 1;
        return INFINITY;
    }
    if (i == 18) {
        r->nonfinite = 1;
        return -INFINITY;
    }
    if (i == 19) {
        uint32_t b = u32(r);
        float f;
        memcpy(&f, &b, sizeof f);
        if (!isfinite(f)) r->nonfinite = 1;
        return f;
    }
    return sp[i];
}
#endif

/* One real: the selector's low 3 bits pick the kind, bit 3 (float core only) swaps in
 * a special float, the upper bits index the palette or scale. */
static rad_real_t real(reader_t *r)
{
    uint8_t sel = u8(r);
    rad_real_t v;
#if RAD_FLOAT
    if (sel & 8) {
        uint8_t k = u8(r);
        v = special(r, k);
        r->last = v;
        return v;
    }
#endif
    switch (sel & 7u) {
    case 0: v = from_q((int32_t)u32(r)); break;                /* raw bits */
    case 1: v = from_q((int32_t)(int8_t)u8(r) * 16384); break; /* quarter units, +-32 */
    case 2: v = from_q(palette_q[u8(r) % NPAL]); break;        /* boundaries */
    case 3: { /* a hair from the last */ int32_t d = (int8_t)u8(r);
#if RAD_FLOAT
        v = r->last + (float)d / 65536.0f;
#else
        v = (int32_t)((uint32_t)r->last + (uint32_t)d);
#endif
        break;
    }
    case 4: v = from_q((int32_t)(int16_t)u16(r) * 256); break; /* +-128 units, 1/256 */
    case 5: v = from_q((int32_t)(int16_t)u16(r)); break;       /* +-0.5 unit, tiny */
    default: v = from_q((int32_t)(int8_t)u8(r) * 8192); break; /* eighth units, +-16 */
    }
    r->last = v;
    return v;
}

static rad_vec3_t vertex(reader_t *r)
{
    rad_vec3_t v;
    uint8_t k = u8(r);
    if ((k & 7u) == 7u && r->nhist) {
        v = r->hist[(k >> 3) % (r->nhist < 16u ? r->nhist : 16u)]; /* a shared corner */
    } else {
        v.x = real(r);
        v.y = real(r);
        v.z = real(r);
    }
    r->hist[r->nhist++ % 16u] = v;
    if (r->nhist >= 32u) r->nhist = 16u;
    return v;
}

static rad_rgb_t colour(reader_t *r)
{
    rad_rgb_t c;
    c.r = real(r);
    c.g = real(r);
    c.b = real(r);
    return c;
}

/* ---- snapshots: after an error nothing may have changed ----------------------------- */

typedef struct {
    rad_scene_t s;
    void *surf, *patch, *elem, *vert;
} snap_t;

static void *dup(const void *p, size_t n)
{
    void *q = malloc(n ? n : 1);
    CHECK(q != NULL);
    if (n) memcpy(q, p, n);
    return q;
}

static void snap_take(snap_t *sn, const rad_scene_t *s)
{
    sn->s = *s;
    sn->surf = dup(s->pools.surfaces, s->n_surfaces * sizeof(rad_surface_t));
    sn->patch = dup(s->pools.patches, s->n_patches * sizeof(rad_patch_t));
    sn->elem = dup(s->pools.elements, s->n_elements * sizeof(rad_element_t));
    sn->vert = dup(s->pools.vertices, s->n_vertices * sizeof(rad_vec3_t));
}

static void snap_same(const snap_t *sn, const rad_scene_t *s)
{
    CHECK(memcmp(&sn->s, s, sizeof *s) == 0);
    CHECK(memcmp(sn->surf, s->pools.surfaces, s->n_surfaces * sizeof(rad_surface_t)) == 0);
    CHECK(memcmp(sn->patch, s->pools.patches, s->n_patches * sizeof(rad_patch_t)) == 0);
    CHECK(memcmp(sn->elem, s->pools.elements, s->n_elements * sizeof(rad_element_t)) == 0);
    CHECK(memcmp(sn->vert, s->pools.vertices, s->n_vertices * sizeof(rad_vec3_t)) == 0);
}

static void snap_free(snap_t *sn)
{
    free(sn->surf);
    free(sn->patch);
    free(sn->elem);
    free(sn->vert);
}

static int is_err(int rc)
{
    return rc == RAD_ERR_ARG || rc == RAD_ERR_FULL || rc == RAD_ERR_RANGE ||
           rc == RAD_ERR_DEGENERATE || rc == RAD_ERR_NONPLANAR || rc == RAD_ERR_STATE ||
           rc == RAD_ERR_WORK || rc == RAD_ERR_ALIGN || rc == RAD_ERR_ABI;
}

/* ---- invariants -------------------------------------------------------------------- */

static int nonneg(rad_real_t v)
{
#if RAD_FLOAT
    return !(v < 0.0f);
#else
    return v >= 0;
#endif
}

static void check_mesh(const rad_scene_t *s, int finite)
{
    const rad_pools_t *p = &s->pools;
    uint32_t i, k;
    CHECK(s->n_surfaces <= p->max_surfaces && s->n_patches <= p->max_patches);
    CHECK(s->n_elements <= p->max_elements && s->n_vertices <= p->max_vertices);
    for (i = 0; i < s->n_surfaces; i++) {
        const rad_surface_t *sf = &p->surfaces[i];
        CHECK((uint32_t)sf->first_patch + sf->n_patches <= s->n_patches && sf->n_patches > 0);
        CHECK((uint32_t)sf->first_element + sf->n_elements <= s->n_elements && sf->n_elements > 0);
        CHECK((uint32_t)sf->first_vertex + sf->n_vertices <= s->n_vertices && sf->n_vertices >= 3);
    }
    for (i = 0; i < s->n_patches; i++) {
        const rad_patch_t *pt = &p->patches[i];
        const rad_surface_t *sf;
        CHECK(pt->surface < s->n_surfaces);
        sf = &p->surfaces[pt->surface];
        CHECK(pt->first_element >= sf->first_element && pt->n_elements > 0 &&
              (uint32_t)pt->first_element + pt->n_elements <=
                  (uint32_t)sf->first_element + sf->n_elements);
        CHECK(nonneg(pt->area));
    }
    for (i = 0; i < s->n_elements; i++) {
        const rad_element_t *el = &p->elements[i];
        const rad_surface_t *sf;
        unsigned nv = el->v[3] == RAD_INDEX_NONE ? 3u : 4u;
        CHECK(el->surface < s->n_surfaces && el->patch < s->n_patches);
        sf = &p->surfaces[el->surface];
        CHECK(i >= sf->first_element && i < (uint32_t)sf->first_element + sf->n_elements);
        CHECK(p->patches[el->patch].surface == el->surface);
        for (k = 0; k < nv; k++)
            CHECK(el->v[k] >= sf->first_vertex &&
                  el->v[k] < (uint32_t)sf->first_vertex + sf->n_vertices);
        CHECK(nonneg(el->area) && el->area != 0);
        if (s->cfg.flags & RAD_NO_OVERSHOOT)
            CHECK(nonneg(el->radiosity.r) && nonneg(el->radiosity.g) && nonneg(el->radiosity.b));
#if RAD_FLOAT
        if (finite)
            CHECK(isfinite(el->radiosity.r) && isfinite(el->radiosity.g) &&
                  isfinite(el->radiosity.b));
#endif
    }
    for (i = 0; i < s->n_vertices; i++) {
        const rad_real_t lim = from_q(64 << 16);
        const rad_vec3_t *v = &p->vertices[i];
        CHECK(v->x >= -lim && v->x <= lim && v->y >= -lim && v->y <= lim && v->z >= -lim &&
              v->z <= lim);
    }
    (void)finite;
}

static void check_unshot(const rad_scene_t *s)
{
    rad_real_t f = rad_unshot_fraction(s);
    int plain = (s->cfg.flags & RAD_NO_OVERSHOOT) != 0;
#if RAD_FLOAT
    CHECK(!(f < 0.0f) && !(plain && f > 1.001f));
#else
    CHECK(f >= 0 && !(plain && f > 65536 + 66)); /* at most 1, give or take rounding */
#endif
}

/* ---- the program --------------------------------------------------------------------- */

typedef struct {
    rad_scene_t s;
    rad_pools_t pools;
    unsigned char *work_block;
    void *blocks[4]; /* the pools as allocated (setup may hide one from rad_init) */
    rad_rows_t rows; /* stored form factors, once an op asks for them */
} ctx_t;

static void *alloc_exact(size_t n)
{
    return malloc(n ? n : 1);
}

static int setup(reader_t *r, ctx_t *c)
{
    static const uint16_t resv[] = {8, 10, 16, 32,   12,   64,    20,   0,
                                    6, 7,  9,  1026, 2048, 65534, 1024, 2};
    rad_config_t cfg = {.res = 0}; /* every field not set below is 0, its default */
    uint8_t f = u8(r);
    uint16_t res;
    size_t pixels, misalign, need, n;
    rad_scene_t before;
    int rc;

    memset(c, 0, sizeof *c);
    c->pools.max_surfaces = u8(r) % 12u;
    c->pools.max_patches = u8(r) % 96u;
    c->pools.max_elements = u16(r) % 640u;
    c->pools.max_vertices = u16(r) % 1100u;
    cfg.max_patch = (f & 1) ? real(r) : 0;
    cfg.max_element = (f & 2) ? real(r) : 0;
    res = resv[u8(r) % 16u];
    cfg.res = res;
    cfg.band_rows = (f & 4) ? (uint16_t)(u8(r) % 40u) : 0;
    cfg.flags = (f & 0x40) ? RAD_NO_OVERSHOOT : 0u;
    if (f & 0x80) { /* coarse shots, valid or not */
        cfg.coarse = real(r);
        cfg.coarse_res = (uint16_t)(u8(r) & 0xFEu);
    }
    c->pools.surfaces = alloc_exact(c->pools.max_surfaces * sizeof(rad_surface_t));
    c->pools.patches = alloc_exact(c->pools.max_patches * sizeof(rad_patch_t));
    c->pools.elements = alloc_exact(c->pools.max_elements * sizeof(rad_element_t));
    c->pools.vertices = alloc_exact(c->pools.max_vertices * sizeof(rad_vec3_t));
    CHECK(c->pools.surfaces && c->pools.patches && c->pools.elements && c->pools.vertices);
    c->blocks[0] = c->pools.surfaces;
    c->blocks[1] = c->pools.patches;
    c->blocks[2] = c->pools.elements;
    c->blocks[3] = c->pools.vertices;
    /* The work buffer: all faces, some rows, or a little short; at any alignment. */
    {
        uint16_t rr = res ? res : 64;
        uint32_t nacc = c->pools.max_elements > c->pools.max_vertices ? c->pools.max_elements
                                                                      : c->pools.max_vertices;
        uint8_t w = u8(r);
        if (rr > 2048) rr = 2048;
        switch (w & 3u) {
        case 0: pixels = RAD_PIXELS_ALL(rr); break;
        case 1: pixels = (size_t)rr * (1u + (w >> 2) % 8u); break;
        case 2: pixels = 0; break;
        default: pixels = RAD_PIXELS_ALL(rr) - 1u; break;
        }
        if (rr >= 1024 && pixels > (size_t)rr * 8u) pixels = (size_t)rr * 2u; /* keep it small */
        need = RAD_WORK_BYTES(rr, pixels, nacc);
        n = (w & 0x80) ? need - (w >> 4 & 7u) * 3u : need;
        misalign = u8(r);
        if (misalign & 8u) n += 1u + (misalign >> 4) * 97u; /* bytes to spare */
        misalign %= 8u;
        c->work_block = malloc(n + misalign);
        CHECK(c->work_block != NULL);
        c->pools.work = c->work_block + misalign;
        c->pools.work_bytes = n;
    }
    /* Oversized counts and missing pools must be refused before anything is touched. */
    if (f & 0x10) c->pools.max_elements = (f & 0x20) ? 0xFFFFFFFFu : (uint32_t)RAD_INDEX_NONE;
    if ((f & 0xC0) == 0xC0) c->pools.vertices = NULL;
    memset(&c->s, 0x5A, sizeof c->s);
    before = c->s;
    rc = rad_init(&c->s, &c->pools, (f & 8) ? NULL : &cfg);
    CHECK(rc == RAD_OK || is_err(rc));
    if (rc != RAD_OK) {
        before.self = 0; /* a failed rad_init clears the marker alone (rad.h) */
        CHECK(memcmp(&before, &c->s, sizeof before) == 0);
        return -1;
    }
    CHECK(c->s.n_surfaces == 0 && c->s.n_elements == 0 && c->s.cfg.res >= 8 &&
          c->s.cfg.res <= RAD_MAX_RES);
    return 0;
}

static void op_add(reader_t *r, ctx_t *c)
{
    static const unsigned counts[] = {3, 4, 3, 4, 3, 4, 0, 1, 2, 5, 3, 4, 3, 4, 3, 4};
    uint8_t f = u8(r);
    unsigned n = counts[f % 16u], i, na = n ? n : 1u;
    rad_vec3_t *v = malloc(na * sizeof *v);
    rad_rgb_t rho, em;
    uint32_t ns = c->s.n_surfaces, np = c->s.n_patches, ne = c->s.n_elements, nv = c->s.n_vertices;
    snap_t sn;
    int rc;
    CHECK(v != NULL);
    for (i = 0; i < n; i++) v[i] = vertex(r);
    if (f & 0x10) rho = colour(r);
    if (f & 0x20) em = colour(r);
    snap_take(&sn, &c->s);
    rc = rad_add_polygon(&c->s, (f & 0xC0) == 0xC0 ? NULL : v, n, (f & 0x10) ? &rho : NULL,
                         (f & 0x20) ? &em : NULL);
    if (rc < 0) {
        CHECK(is_err(rc));
        snap_same(&sn, &c->s);
    } else {
        const rad_surface_t *sf = &c->s.pools.surfaces[rc];
        CHECK((uint32_t)rc == ns && c->s.n_surfaces == ns + 1);
        CHECK(c->s.n_patches > np && c->s.n_elements > ne && c->s.n_vertices > nv);
        CHECK(sf->first_patch == np && sf->first_element == ne && sf->first_vertex == nv);
        CHECK(!c->s.solving);
    }
    snap_free(&sn);
    free(v);
}

static void op_set_surface(reader_t *r, ctx_t *c)
{
    uint8_t f = u8(r);
    uint32_t surf = (f & 1) ? u32(r) : u8(r) % (c->s.n_surfaces + 1u);
    rad_rgb_t rho, em;
    snap_t sn;
    int rc;
    if (f & 0x10) rho = colour(r);
    if (f & 0x20) em = colour(r);
    snap_take(&sn, &c->s);
    rc = rad_set_surface(&c->s, surf, (f & 0x10) ? &rho : NULL, (f & 0x20) ? &em : NULL);
    if (rc < 0) {
        CHECK(is_err(rc));
        snap_same(&sn, &c->s);
    } else {
        CHECK(rc == RAD_OK && surf < c->s.n_surfaces);
    }
    snap_free(&sn);
}

static void op_shoot(reader_t *r, ctx_t *c)
{
    uint32_t shots = u8(r) % 4u;
    rad_real_t tol = real(r);
    uint32_t before = c->s.stats.shots;
    int rc;
    if (c->s.cfg.res > 64) return; /* a shot at 1024 x 1024 is too slow to fuzz */
    rc = rad_shoot(&c->s, shots, tol);
    CHECK(rc >= 0 && (uint32_t)rc <= shots);
    CHECK(c->s.stats.shots == before + (uint32_t)rc);
    CHECK(c->s.solving || c->s.emitted == 0); /* nothing emitting: the scene stays open */
    check_unshot(&c->s);
}

static void op_element(reader_t *r, ctx_t *c)
{
    uint8_t f = u8(r);
    uint32_t e = (f & 1) ? u32(r) : u8(r) % (c->s.n_elements + 1u);
    rad_rgb_t out;
    snap_t sn;
    int rc;
    snap_take(&sn, &c->s);
    rc = rad_element_radiosity(&c->s, e, (int)(int8_t)u8(r), (f & 2) ? NULL : &out);
    if (rc < 0) {
        CHECK(rc == RAD_ERR_ARG);
        snap_same(&sn, &c->s);
    } else {
        CHECK(rc == RAD_OK && e < c->s.n_elements);
        CHECK(nonneg(out.r) && nonneg(out.g) && nonneg(out.b));
    }
    snap_free(&sn);
}

static void op_ambient(reader_t *r, ctx_t *c)
{
    rad_rgb_t out;
    int rc = rad_ambient(&c->s, (u8(r) & 1) ? NULL : &out);
    if (rc < 0)
        CHECK(rc == RAD_ERR_ARG);
    else
        CHECK(rc == RAD_OK && (!(c->s.cfg.flags & RAD_NO_OVERSHOOT) ||
                               (nonneg(out.r) && nonneg(out.g) && nonneg(out.b))));
}

static void op_shade(reader_t *r, ctx_t *c)
{
    uint8_t f = u8(r);
    uint32_t n = c->s.n_vertices, k;
    rad_rgb_t *out;
    snap_t sn;
    int rc;
    if (f & 1)
        n = n ? n - 1u : 0u; /* one short */
    else if (f & 2)
        n += u8(r) % 5u; /* room to spare */
    out = alloc_exact(n * sizeof *out);
    CHECK(out != NULL);
    snap_take(&sn, &c->s);
    rc = rad_shade_vertices(&c->s, (int)(int8_t)u8(r), (f & 4) ? NULL : out, n);
    if (rc < 0) {
        CHECK(rc == RAD_ERR_ARG);
        snap_same(&sn, &c->s);
    } else {
        CHECK((uint32_t)rc == c->s.n_vertices);
        for (k = 0; k < (uint32_t)rc; k++)
            CHECK(nonneg(out[k].r) && nonneg(out[k].g) && nonneg(out[k].b));
    }
    snap_free(&sn);
    free(out);
}

static void op_render(reader_t *r, ctx_t *c)
{
    static const unsigned bad[] = {0, RAD_MAX_RASTER + 1u, 0xFFFFFFFFu, 65536u};
    uint8_t f = u8(r);
    unsigned w = 1u + u8(r) % MAX_VIEW, h = 1u + u8(r) % MAX_VIEW;
    size_t npix, i;
    rad_camera_t cam;
    rad_rgb_t *vrgb, *fb;
    uint32_t *z, nv = c->s.n_vertices;
    snap_t sn;
    int rc, sized;
    if (f & 1) w = bad[u8(r) % 4u];
    if (f & 2) h = bad[u8(r) % 4u];
    if ((f & 0x30) == 0x30) {
        w = RAD_MAX_RASTER;
        h = 1u + u8(r) % 2u;
    } /* widest aspect */
    sized = w >= 1 && h >= 1 && w <= RAD_MAX_RASTER && h <= RAD_MAX_RASTER;
    npix = sized ? (size_t)w * h : 1u;
    cam.eye = vertex(r);
    cam.target = vertex(r);
    if (f & 4) {
        cam.up.x = real(r);
        cam.up.y = real(r);
        cam.up.z = real(r);
    } else {
        cam.up.x = 0;
        cam.up.y = from_q(65536);
        cam.up.z = 0;
    }
    cam.tan_half_fov = (f & 8) ? real(r) : from_q(27146); /* tan 22.5 degrees */
    /* Vertex colours: zeros, or the solution's (what rad_render documents). */
    vrgb = alloc_exact(nv * sizeof *vrgb);
    CHECK(vrgb != NULL);
    if (nv) {
        CHECK(rad_shade_vertices(&c->s, 1, vrgb, nv) == (int)nv);
    }
    fb = alloc_exact(npix * sizeof *fb);
    z = alloc_exact(npix * sizeof *z);
    CHECK(fb && z);
    snap_take(&sn, &c->s);
    rc = rad_render(&c->s, (f & 0x40) ? NULL : vrgb, &cam, fb, z, w, h);
    if (rc < 0) {
        CHECK(rc == RAD_ERR_ARG);
        snap_same(&sn, &c->s);
    } else {
        CHECK(sized);
        CHECK((uint32_t)rc <= 16u * 7u * c->s.n_elements + 0u);
        for (i = 0; i < npix; i++) CHECK(nonneg(fb[i].r) && nonneg(fb[i].g) && nonneg(fb[i].b));
        snap_same(&sn, &c->s); /* rendering changes nothing in the scene */
    }
    snap_free(&sn);
    free(vrgb);
    free(fb);
    free(z);
}

static void op_form_factors(reader_t *r, ctx_t *c)
{
    uint8_t f = u8(r);
    uint32_t p = (f & 1) ? u32(r) : u8(r) % (c->s.n_patches + 1u), ne = c->s.n_elements, e;
    rad_ff_t *out = alloc_exact(ne * sizeof *out);
    int rc;
    CHECK(out != NULL);
    if (c->s.cfg.res > 64) {
        free(out);
        return;
    }
    rc = rad_form_factors(&c->s, p, (f & 2) ? NULL : out);
    if (rc < 0) {
        CHECK(rc == RAD_ERR_ARG);
    } else {
#if RAD_FLOAT
        double sum = 0;
        for (e = 0; e < ne; e++) {
            CHECK(!(out[e] < 0));
            sum += out[e];
        }
        CHECK(sum <= 1.001);
#else
        uint64_t sum = 0;
        for (e = 0; e < ne; e++) sum += out[e];
        CHECK(sum <= (1u << 30)); /* disjoint pixels of a table summing to exactly 2^30 */
#endif
        CHECK((uint32_t)rc == ne && p < c->s.n_patches);
    }
    free(out);
}

/* The threaded shot: begin, NPARTS parts into their own buffers, end. */
static void op_parallel(reader_t *r, ctx_t *c)
{
    uint8_t f = u8(r);
    rad_real_t tol = real(r);
    unsigned nparts = 1u + u8(r) % 4u, k, ok = 1;
    uint32_t patch = 0xDEADBEEFu, shots = c->s.stats.shots;
    size_t bytes;
    void *bufs[4] = {0, 0, 0, 0};
    unsigned char *blk[4] = {0, 0, 0, 0};
    snap_t sn;
    int rc, short_buf = (f & 1) && !(f & 0x20);
    if (c->s.cfg.res > 64) return;
    /* One byte short of a part, or bytes to spare. */
    bytes = RAD_PART_BYTES(c->s.cfg.res) - (short_buf ? 1u : 0u);
    if (f & 0x20) bytes += (f & 0x80) ? 1u : 4096u;
    snap_take(&sn, &c->s);
    rc = rad_shot_begin(&c->s, tol, (f & 0x40) ? NULL : &patch);
    if (rc < 0) {
        CHECK(is_err(rc));
        snap_same(&sn, &c->s);
    }
    snap_free(&sn);
    if (rc != 1) {
        CHECK(rc != 0 || patch == 0xDEADBEEFu);
        return;
    }
    CHECK(patch < c->s.n_patches && c->s.band_rows == 0);
    if (f & 2) patch = (f & 4) ? u32(r) : patch + u8(r) % 3u; /* maybe another, maybe none */
    for (k = 0; k < nparts; k++) {
        blk[k] = malloc(bytes + 8u);
        CHECK(blk[k] != NULL);
        bufs[k] = (f & 8) ? blk[k] + 4 : blk[k]; /* misaligned: refused */
        snap_take(&sn, &c->s);
        rc = rad_shot_part(&c->s, patch, k, nparts, bufs[k], bytes);
        snap_same(&sn, &c->s); /* parts only read the scene */
        snap_free(&sn);
        /* short or misaligned: RAD_ERR_ARG; another patch than the one begun: _STATE */
        if (rc < 0) {
            CHECK(rc == RAD_ERR_ARG || rc == RAD_ERR_STATE);
            ok = 0;
        } else
            CHECK(!short_buf && !(f & 8) && patch == c->s.shot_patch);
    }
    if (ok) {
        unsigned n = (f & 0x10) ? 1u + u8(r) % nparts : nparts;
        snap_take(&sn, &c->s);
        rc = rad_shot_end(&c->s, patch, bufs, n);
        if (rc < 0) {
            CHECK(rc == RAD_ERR_STATE && n != nparts); /* fewer parts than rendered */
            snap_same(&sn, &c->s);
        } else {
            CHECK(rc == 1 && c->s.stats.shots == shots + 1u);
            check_unshot(&c->s);
        }
        snap_free(&sn);
    }
    for (k = 0; k < nparts; k++) free(blk[k]);
}

static void rows_free(rad_rows_t *rows)
{
    free(rows->start);
    free(rows->ids);
    free(rows->ffs);
    memset(rows, 0, sizeof *rows);
}

/* Stored rows: (re)allocate, compute some, shoot through them, or Gauss-Seidel. */
static void op_rows(reader_t *r, ctx_t *c)
{
    uint8_t f = u8(r);
    rad_rows_t *rows = &c->rows;
    uint32_t i;
    int rc;
    if (c->s.cfg.res > 64) return;
    if (!rows->start || (f & 3) == 3) {
        rows_free(rows);
        rows->max_rows = c->s.n_patches + (uint32_t)(int8_t)(u8(r) % 3u) - 1u; /* -1, 0, +1 */
        if (rows->max_rows == 0xFFFFFFFFu) rows->max_rows = 0;
        rows->max_entries = u16(r) % 6000u;
        rows->start = alloc_exact(((size_t)rows->max_rows + 1u) * sizeof *rows->start);
        rows->ids = alloc_exact(rows->max_entries * sizeof *rows->ids);
        rows->ffs = alloc_exact(rows->max_entries * sizeof *rows->ffs);
        CHECK(rows->start && rows->ids && rows->ffs);
        rows->n_rows = 0;
    }
    switch ((f >> 2) & 3u) {
    case 0:
    case 1: {
        uint32_t before = rows->n_rows, ns = c->s.n_surfaces, ne = c->s.n_elements;
        rc = rad_rows_compute(&c->s, rows, u8(r) % 8u);
        if (rc < 0) {
            CHECK(rc == RAD_ERR_ARG || rc == RAD_ERR_FULL);
            CHECK(rows->n_rows == before);
        } else {
            CHECK(rows->n_rows == before + (uint32_t)rc && rows->n_rows <= c->s.n_patches);
        }
        CHECK(c->s.n_surfaces == ns && c->s.n_elements == ne);
        if (rows->n_rows) CHECK(rows->start[0] == 0);
        for (i = 0; i < rows->n_rows; i++) {
            uint32_t k;
            CHECK(rows->start[i] <= rows->start[i + 1] && rows->start[i + 1] <= rows->max_entries);
            for (k = rows->start[i]; k < rows->start[i + 1]; k++)
                CHECK(rows->ids[k] < c->s.n_elements);
        }
        break;
    }
    case 2: {
        uint32_t shots = u8(r) % 4u;
        rc = rad_rows_shoot(&c->s, rows, shots, real(r));
        if (rc < 0)
            CHECK(rc == RAD_ERR_STATE || rc == RAD_ERR_ARG);
        else {
            CHECK((uint32_t)rc <= shots);
            check_unshot(&c->s);
        }
        break;
    }
    default: {
        size_t entries = RAD_GS_ENTRIES(c->s.n_patches);
        if ((f & 0x10) && entries) entries--; /* one short: refused */
        rad_ff_t *m = alloc_exact(entries * sizeof *m);
        uint32_t iters = u8(r) % 6u;
        CHECK(m != NULL);
        rc = rad_rows_gauss_seidel(&c->s, rows, m, entries, iters, real(r));
        if (rc < 0)
            CHECK(rc == RAD_ERR_ARG || rc == RAD_ERR_STATE);
        else
            CHECK((uint32_t)rc <= iters);
        free(m);
        break;
    }
    }
}

/* Light groups: any mix of any radiosities, saturating. */
static void op_mix(reader_t *r, ctx_t *c)
{
    uint8_t f = u8(r);
    uint32_t ng = f % 4u, ne = c->s.n_elements, g, e;
    rad_rgb_t *grp[3] = {0, 0, 0}, inten[3], *out = alloc_exact(ne * sizeof *out);
    const rad_rgb_t *cg[3];
    snap_t sn;
    int rc;
    CHECK(out != NULL);
    for (g = 0; g < ng; g++) {
        rad_rgb_t fill = colour(r);
        grp[g] = alloc_exact(ne * sizeof(rad_rgb_t));
        CHECK(grp[g] != NULL);
        for (e = 0; e < ne; e++) grp[g][e] = (f & 0x10) ? c->s.pools.elements[e].radiosity : fill;
        inten[g] = colour(r);
        cg[g] = (f & 0x20) && g == ng - 1u ? NULL : grp[g];
    }
    snap_take(&sn, &c->s);
    rc = rad_mix(&c->s, cg, inten, ng, (f & 0x40) ? NULL : out);
    if (rc < 0) {
        CHECK(rc == RAD_ERR_ARG);
        snap_same(&sn, &c->s);
    } else {
        CHECK(rc == RAD_OK);
    }
    snap_free(&sn);
    for (g = 0; g < ng; g++) free(grp[g]);
    free(out);
}

static void op_code(reader_t *r)
{
    uint16_t code = u16(r), e = (uint16_t)(code >> 11), m = (uint16_t)(code & 2047u);
    uint16_t next = m == 2047u ? (uint16_t)((e + 1u) << 11 | 1024u) : (uint16_t)(code + 1u);
    rad_ff_t f = rad_ff_from_code(code), g = rad_ff_from_code(next);
#if RAD_FLOAT
    CHECK(!(f < 0.0f) && f <= 4.0f);
#endif
    /* Over the codes rad_rows_compute makes (normalised: mantissa >= 1024 unless the
     * exponent is 0; form factors up to 2^30: exponents up to 19), decoding is monotone
     * and exact to 11 bits. */
    if (e <= 19u && (e == 0u || m >= 1024u)) CHECK(g > f);
}

int FUZZ_FN(const uint8_t *data, size_t size)
{
    reader_t r;
    ctx_t c;
    unsigned ops;
    memset(&r, 0, sizeof r);
    r.p = data;
    r.n = size;
    if (setup(&r, &c) == 0) {
        for (ops = 0; ops < MAX_OPS && r.pos < r.n; ops++) {
            uint8_t op = u8(&r);
            switch (op % 17u) {
            case 0:
            case 1:
            case 2: op_add(&r, &c); break;
            case 3: op_set_surface(&r, &c); break;
            case 4:
                CHECK(rad_restart(&c.s) == RAD_OK && c.s.stats.shots == 0 && !c.s.solving);
                break;
            case 5:
            case 6: op_shoot(&r, &c); break;
            case 7: check_unshot(&c.s); break;
            case 8: op_ambient(&r, &c); break;
            case 9: op_element(&r, &c); break;
            case 10: op_shade(&r, &c); break;
            case 11: op_render(&r, &c); break;
            case 12: op_form_factors(&r, &c); break;
            case 13: op_parallel(&r, &c); break;
            case 14: op_rows(&r, &c); break;
            case 15: op_mix(&r, &c); break;
            default: op_code(&r); break;
            }
            check_mesh(&c.s, !r.nonfinite);
        }
        /* NULL scenes are refused everywhere. */
        CHECK(rad_add_polygon(NULL, NULL, 3, NULL, NULL) == RAD_ERR_ARG);
        CHECK(rad_shoot(NULL, 1, 0) == RAD_ERR_ARG);
        CHECK(rad_restart(NULL) == RAD_ERR_ARG);
        CHECK(rad_ambient(NULL, NULL) == RAD_ERR_ARG);
    }
    {
        int e = (int)(int32_t)(r.pos < r.n ? u32(&r) : 0x80000000u);
        CHECK(rad_strerror(e) != NULL && rad_strerror(e)[0] != '\0');
    }
    free(c.blocks[0]);
    free(c.blocks[1]);
    free(c.blocks[2]);
    free(c.blocks[3]);
    free(c.work_block);
    rows_free(&c.rows);
    return 0;
}

#if !RAD_FLOAT
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_core_fixed(data, size);
    fuzz_core_float(data, size);
    return 0;
}
#endif
