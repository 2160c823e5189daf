/* SPDX-License-Identifier: MIT */
/* rad — the one rasterizer: clip, project, and fill triangles into an integer
 * z-buffer with an item buffer (hemi-cube faces) or interpolated colours (the camera).
 *
 * Integer ranges: screen positions are in 1/16 pixel (4 subpixel bits) and lie within
 * [0, 16 * 2048] = [0, 2^15] after clipping, so edge functions stay below 2^32 and are
 * kept in int64. Attributes (depth w, colours) are <= 2^30; their plane gradients, in
 * attribute units * 2^16 per subpixel, have numerators below 2 * 2^30 * 2^15 * 2^16 =
 * 2^62. Values are stepped across the bounding box in uint64 (modular, so stepping
 * over pixels outside the triangle cannot overflow) and read only inside it.
 * A pixel is covered when its centre is inside; centres on an edge belong to exactly
 * one of the two triangles sharing it, so shared edges neither leak nor double count.
 */
#include "internal.h"

#define SUB 16 /* subpixels per pixel */

/* A projected vertex: position in 1/16 pixel, depth w = 2^30 NEAR / d (at[0]; ortho:
 * the attribute c[0]) and colour (at[1..3], used by colour targets only). */
typedef struct {
    int32_t x, y;
    uint32_t at[4];
} pvert_t;

/* ---- clipping ------------------------------------------------------------------ */

/* Signed distance of V inside clip plane P (>= 0: inside). */
static rad_real_t plane_dist(const rad__frustum_t *f, const rad__cvert_t *v, unsigned p)
{
    switch (p) {
    case 0: return v->d - RAD__NEAR;
    case 1: return v->d - v->a;
    case 2: return v->d + v->a;
    case 3: return v->d - v->b;
    default: return f->half ? v->b : v->d + v->b;
    }
}

unsigned rad__outcodes(const rad__frustum_t *f, const rad__cvert_t *in, unsigned n)
{
    unsigned i, p, all = 0x1F, any = 0;
    for (i = 0; i < n; i++) {
        unsigned code = 0;
        for (p = 0; p < 5; p++)
            if (plane_dist(f, &in[i], p) < 0) code |= 1u << p;
        all &= code;
        any |= code;
    }
    return all ? RAD__CULLED : any;
}

/* The point where edge IN-OUT crosses the plane, always interpolated from the inside
 * end, so the two elements sharing an edge compute the same point. */
static void crossing(const rad__cvert_t *in, const rad__cvert_t *out, rad_real_t din,
                     rad_real_t dout, rad__cvert_t *r)
{
    const rad__clip_t c = rad__clip_init(din, dout);
    unsigned k;
    r->a = rad__clip_lerp(in->a, out->a, &c);
    r->b = rad__clip_lerp(in->b, out->b, &c);
    r->d = rad__clip_lerp(in->d, out->d, &c);
    for (k = 0; k < 3; k++) r->c[k] = rad__clip_lerp(in->c[k], out->c[k], &c);
}

/* Sutherland-Hodgman against plane P: N vertices of SRC into DST; returns the count. */
static unsigned clip_plane(const rad__frustum_t *f, unsigned p, const rad__cvert_t *src, unsigned n,
                           rad__cvert_t *dst)
{
    unsigned i, m = 0;
    for (i = 0; i < n; i++) {
        const rad__cvert_t *a = &src[i],
                           *b = &src[i + 1 < n ? i + 1 : 0]; /* no modulo: a call on M0 */
        rad_real_t da = plane_dist(f, a, p), db = plane_dist(f, b, p);
        if (da >= 0) dst[m++] = *a;
        if ((da >= 0) != (db >= 0)) {
            if (da >= 0)
                crossing(a, b, da, db, &dst[m++]);
            else
                crossing(b, a, db, da, &dst[m++]);
        }
    }
    return m;
}

/* ---- convex polygons ------------------------------------------------------------- */

typedef struct {
    int64_t e, dx, dy; /* value at the first pixel centre, steps per pixel in x and y */
} edge_t;

static void edge_setup(edge_t *ed, const pvert_t *a, const pvert_t *b, int32_t px, int32_t py,
                       int flip)
{
    /* Positions within [0, 2^15] (centres within 2^15 + 8): differences fit int32. */
    int32_t ex = b->x - a->x, ey = b->y - a->y;
    int owned;
    if (flip) {
        ex = -ex;
        ey = -ey;
        a = b;
    }
    /* Half-open ownership: of the two directions along a shared edge, exactly one
     * (pointing down, or right when horizontal) includes centres lying on it. */
    owned = ey > 0 || (ey == 0 && ex > 0);
    ed->e = rad__mul32(ex, py - a->y) - rad__mul32(ey, px - a->x) - (owned ? 0 : 1);
    ed->dx = (int64_t)-ey * SUB;
    ed->dy = (int64_t)ex * SUB;
}

/* a / b for a >= 0, b > 0: in 32 bits when both fit (most rows: 64-bit division is a
 * long library call on targets without a divider), the same quotient either way. */
static int64_t udiv(int64_t a, int64_t b)
{
    if (((uint64_t)a | (uint64_t)b) >> 32 == 0) return (int64_t)((uint32_t)a / (uint32_t)b);
    return (int64_t)rad__udiv64((uint64_t)a, (uint64_t)b);
}

/* Narrows pixels LO..HI of a row (from the bounding box's first) to those where edge
 * ED, E + t DX at pixel t, is >= 0: exact integer bounds, the same pixels as testing
 * each one. */
static void span_edge(const edge_t *ed, int32_t *lo, int32_t *hi)
{
    int64_t e = ed->e, dx = ed->dx;
    if (dx > 0) {
        if (e < 0) {
            int64_t t = udiv(-e + dx - 1, dx);
            if (t > *lo) *lo = t > *hi ? *hi + 1 : (int32_t)t;
        }
    } else if (e < 0) {
        *hi = -1;
    } else if (dx < 0) {
        int64_t t = udiv(e, -dx);
        if (t < *hi) *hi = (int32_t)t;
    }
}

/* Twice the signed area of triangle A, B, C in subpixels^2. */
static int64_t area2(const pvert_t *a, const pvert_t *b, const pvert_t *c)
{
    return rad__mul32(b->x - a->x, c->y - a->y) - rad__mul32(c->x - a->x, b->y - a->y);
}

/* Plane of attribute K through triangle V0, V1, V2 (twice its area AR): the value at
 * the first pixel centre and its steps, all * 2^16, modulo 2^64. */
static void attr_setup(const pvert_t *v0, const pvert_t *v1, const pvert_t *v2, unsigned k,
                       int64_t ar, int32_t px, int32_t py, uint64_t *val, uint64_t *sx,
                       uint64_t *sy)
{
    /* Attributes <= 2^30 and positions within [0, 2^15]: differences fit int32. */
    int32_t d1 = (int32_t)v1->at[k] - (int32_t)v0->at[k];
    int32_t d2 = (int32_t)v2->at[k] - (int32_t)v0->at[k];
    int32_t x1 = v1->x - v0->x, y1 = v1->y - v0->y;
    int32_t x2 = v2->x - v0->x, y2 = v2->y - v0->y;
    int64_t gx = rad__sdiv64((rad__mul32(d1, y2) - rad__mul32(d2, y1)) * 65536, ar);
    int64_t gy = rad__sdiv64((rad__mul32(d2, x1) - rad__mul32(d1, x2)) * 65536, ar);
    /* px - x0 and py - y0 within +-(2^15 + 8): rad__mulmod16's range */
    *val = ((uint64_t)v0->at[k] << 16) + rad__mulmod16((uint64_t)gx, px - v0->x) +
           rad__mulmod16((uint64_t)gy, py - v0->y);
    *sx = (uint64_t)gx * SUB;
    *sy = (uint64_t)gy * SUB;
}

/* An attribute read inside the polygon: there its value is within rounding of the
 * vertices' (>= 0), so the modular sum holds the true value. */
static uint32_t attr_value(uint64_t v)
{
    if (v >> 63) return 0; /* a rounding step below zero */
    v = (v + 32768u) >> 16;
    return v > 0xFFFFFFFFu ? 0xFFFFFFFFu : (uint32_t)v;
}

/* Pixels XS..XE-1 of a row of an item buffer: depth W (* 2^16) stepping by DW, id ID;
 * with LEAST, of equal depths the least id is kept (rad__target_t.least). Inside,
 * depth is within rounding of the vertices' (>= 2^22 / 554). */
static void fill_ids(uint32_t *z, rad_index_t *ids, int32_t xs, int32_t xe, uint64_t w, uint64_t dw,
                     rad_index_t id, int least)
{
    int32_t x;
    if (!least) {
        for (x = xs; x < xe; x++, w += dw) rad__depth_put(z, ids, x, (uint32_t)(w >> 16), id);
        return;
    }
    for (x = xs; x < xe; x++, w += dw) {
        uint32_t d = (uint32_t)(w >> 16);
        if (d > z[x] || (d == z[x] && id < ids[x])) {
            z[x] = d;
            ids[x] = id;
        }
    }
}

/* fill_ids for a colour raster; VAL are the attributes at the row's first pixel of
 * the bounding box, SKIP pixels before XS. */
static void fill_rgb(uint32_t *z, rad_rgb_t *rgb, int32_t xs, int32_t xe, uint64_t w,
                     const uint64_t *val, const uint64_t *sx, int32_t skip)
{
    int32_t x;
    uint64_t c[3];
    unsigned k;
    for (k = 0; k < 3; k++) c[k] = val[k + 1] + sx[k + 1] * (uint64_t)skip;
    for (x = xs; x < xe; x++, w += sx[0]) {
        uint32_t d = (uint32_t)(w >> 16);
        if (d > z[x]) {
            z[x] = d;
            rgb[x].r = rad__from_attr(attr_value(c[0]));
            rgb[x].g = rad__from_attr(attr_value(c[1]));
            rgb[x].b = rad__from_attr(attr_value(c[2]));
        }
        for (k = 0; k < 3; k++) c[k] += sx[k + 1];
    }
}

static int32_t clampi(int32_t v, int32_t lo, int32_t hi)
{
    return v < lo ? lo : v > hi ? hi : v;
}

/* Fills the convex polygon V of N = 3 or 4 vertices (either winding). Attributes are
 * interpolated on the plane of the wider of its two fan triangles: exact for a planar
 * polygon's depth; callers with colours pass triangles. A triangle's fourth edge
 * repeats its first, so one loop with four edges in registers serves both. */
static void raster_piece(rad_stats_t *st, const rad__target_t *t, const pvert_t *v, unsigned n,
                         rad_index_t id)
{
    edge_t ed[4];
    uint64_t val[4], sx[4], sy[4], pixels = 0;
    int64_t a1 = area2(&v[0], &v[1], &v[2]), a2 = n == 4 ? area2(&v[0], &v[2], &v[3]) : 0;
    int64_t best = (a2 < 0 ? -a2 : a2) > (a1 < 0 ? -a1 : a1) ? a2 : a1;
    int32_t x0, x1, y0, y1, px, py, y;
    unsigned k, b = best == a1 ? 1u : 2u, nat = t->rgb ? 4u : 1u;

    if (best == 0) return;
    st->raster_calls++;

    /* Pixels whose centres (16 p + 8) lie within the bounding box, inside the target. */
    x0 = x1 = v[0].x;
    y0 = y1 = v[0].y;
    for (k = 1; k < n; k++) {
        if (v[k].x < x0) x0 = v[k].x;
        if (v[k].x > x1) x1 = v[k].x;
        if (v[k].y < y0) y0 = v[k].y;
        if (v[k].y > y1) y1 = v[k].y;
    }
    x0 = clampi((x0 + 7) / SUB, 0, t->width);
    x1 = clampi((x1 + 8) / SUB - 1, -1, t->width - 1);
    y0 = clampi((y0 + 7) / SUB, t->row0, t->row1);
    y1 = clampi((y1 + 8) / SUB - 1, t->row0 - 1, t->row1 - 1);
    if (x0 > x1 || y0 > y1) return;

    px = x0 * SUB + SUB / 2;
    py = y0 * SUB + SUB / 2;
    for (k = 0; k < n; k++)
        edge_setup(&ed[k], &v[k], &v[k + 1 < n ? k + 1 : 0], px, py, a1 + a2 < 0);
    if (n == 3) ed[3] = ed[0];
    for (k = 0; k < nat; k++)
        attr_setup(&v[0], &v[b], &v[b + 1], k, best, px, py, &val[k], &sx[k], &sy[k]);

    for (y = y0; y <= y1; y++) {
        /* Convex: the span is where every edge's value, linear along the row, is >= 0. */
        int32_t lo = 0, hi = x1 - x0;
        size_t row = (size_t)(y - t->row0) * (size_t)t->width;
        uint64_t w;
        for (k = 0; k < 4; k++) span_edge(&ed[k], &lo, &hi);
        if (lo <= hi) {
            int32_t xs = x0 + lo, xe = x0 + hi + 1;
            w = val[0] + rad__mulmod16(sx[0], lo); /* lo < 2^11 */
            pixels += (uint64_t)(xe - xs);
            if (t->rgb)
                fill_rgb(t->z + row, t->rgb + row, xs, xe, w, val, sx, lo);
            else if (t->lat)
                rad__lattice_span(t->lat, y, xs, xe, t->z + row, t->ids + row, w, sx[0], t->steps);
            else
                fill_ids(t->z + row, t->ids + row, xs, xe, w, sx[0], id, t->least);
        }
        for (k = 0; k < 4; k++) ed[k].e += ed[k].dy;
        for (k = 0; k < nat; k++) val[k] += sy[k];
    }
    st->raster_pixels += pixels;
}

/* ---- polygons ------------------------------------------------------------------ */

/* Screen position in subpixels and depth of the clipped vertex C, inside frustum F:
 * one reciprocal of its depth, then multiplies. */
static void project(const rad__frustum_t *f, const rad__cvert_t *c, pvert_t *r)
{
    rad__recip_t inv = rad__recip(c->d);
    int32_t w16 = f->width * SUB, h16 = f->height * SUB;
    r->x = clampi(rad__proj(c->a + c->d, inv, (uint32_t)(w16 / 2)), 0, w16);
    r->y = clampi(rad__proj(c->d - c->b, inv, (uint32_t)(f->half ? h16 : h16 / 2)), 0, h16);
    r->at[0] = f->ortho ? rad__attr(c->c[0]) : rad__depth(inv);
    if (f->recede) r->at[0] -= r->at[0] >> f->recede;
    r->at[1] = rad__attr(c->c[0]);
    r->at[2] = rad__attr(c->c[1]);
    r->at[3] = rad__attr(c->c[2]);
}

int rad__pixel(const rad__frustum_t *f, const rad__cvert_t *c, uint32_t *x, uint32_t *y,
               uint32_t *w)
{
    pvert_t p;
    if (rad__outcodes(f, c, 1u)) return 0;
    project(f, c, &p);
    /* a point on the raster's far edge (x = width) belongs to its last pixel */
    *x = (uint32_t)(p.x / SUB < f->width ? p.x / SUB : f->width - 1);
    *y = (uint32_t)(p.y / SUB < f->height ? p.y / SUB : f->height - 1);
    *w = p.at[0];
    return 1;
}

/* Rasterizes the convex polygon PV of N projected vertices (either winding; PV is
 * rewritten) into T with item id ID. */
static void fill(rad_stats_t *st, const rad__target_t *t, pvert_t *pv, unsigned n, rad_index_t id)
{
    unsigned i, m;
    /* Vertices that clipping or projection made equal would leave an edge with no
     * direction, which owns no pixel and would reject them all: drop them. */
    for (i = 1, m = 1; i < n; i++)
        if (pv[i].x != pv[m - 1].x || pv[i].y != pv[m - 1].y) pv[m++] = pv[i];
    if (m > 1 && pv[m - 1].x == pv[0].x && pv[m - 1].y == pv[0].y) m--;
    if (m < 3) return;
    /* A fan from PV[0]: each piece's first vertex is copied over the one before its
     * others, which no later piece uses, so every piece is four (or three) in a row. */
    if (!t->rgb) {
        /* Quads (and a last triangle): pieces share edges, which the ownership rule
         * keeps watertight. */
        for (i = 1; i + 1 < m; i += 2) {
            pv[i - 1] = pv[0];
            raster_piece(st, t, &pv[i - 1], i + 2 < m ? 4u : 3u, id);
        }
        return;
    }
    /* Colours vary over a quad bilinearly, not on one plane: a fan of triangles. */
    for (i = 1; i + 1 < m; i++) {
        pv[i - 1] = pv[0];
        raster_piece(st, t, &pv[i - 1], 3, id);
    }
}

void rad__draw(rad_stats_t *st, const rad__target_t *t, const rad__frustum_t *f,
               const rad__cvert_t *in, unsigned n, unsigned any, rad_index_t id)
{
    /* Each plane adds at most one vertex: 4 + 5 = 9. The projected vertices go to the
     * buffer the last clip did not write (stack is scarce on small targets). */
    union {
        rad__cvert_t c[9];
        pvert_t p[9];
    } buf[2];
    const rad__cvert_t *cur = in;
    unsigned i, p, flip = 0;

    if (any & RAD__CULLED) return;
    for (p = 0; p < 5 && n >= 3; p++) {
        if (!(any & (1u << p))) continue;
        n = clip_plane(f, p, cur, n, buf[flip].c);
        cur = buf[flip].c;
        flip ^= 1u;
    }
    if (n < 3) return;
    for (i = 0; i < n; i++) project(f, &cur[i], &buf[flip].p[i]);
    fill(st, t, buf[flip].p, n, id);
}
