/* SPDX-License-Identifier: MIT */
/* rad — culling a gather's cube through a bounding volume hierarchy of the surfaces.
 *
 * The hierarchy (rad_cull_build) is a binary tree with one surface in each leaf:
 * 2 n - 1 nodes for n surfaces, laid out depth first (a node's first child follows
 * it), each with the box of its surfaces' corners (the polygon the rasterizer draws)
 * in the core's coordinates. A node splits its surfaces at the median of their box
 * centres along the axis where those centres spread most, ties to the lower surface
 * index: the same tree for the same scene, whatever the machine.
 *
 * A face of a gather's cube (rad__cull_face) is drawn in two passes.
 * 1. From the root, the child nearer the eye first, a node is skipped when its box
 *    lies wholly outside one of the face's clip planes (then each corner of each of
 *    its surfaces does: the face would not draw them), or when it is hidden: in each
 *    of the face's tiles (16 x 16 of them) its box can reach, or, when it can reach
 *    at most SMALL_REACH pixels, at each of those pixels, no point of the box inside
 *    the tile or near the pixel's centre lies nearer than the farthest depth drawn
 *    there (near a centre where nothing is drawn, none at all). The surfaces of the
 *    leaves left are drawn with their indices as ids, ties between equal depths kept
 *    by the least (rad__target_t.least).
 * 2. The face is cleared and the surfaces left in its pixels drawn again in the order
 *    of their indices, as rad__eye_face draws every surface.
 * Why the pixels are those of drawing every surface: depth only grows, so a surface S
 * of a hidden node draws, at every pixel it can reach, a depth below one a drawn
 * surface drew there in pass 1, and draws the same depth in pass 2 (a surface's depths
 * do not depend on the pass or on its ids). S is then never the nearest at any pixel,
 * nor tied for it, and a surface outside the face draws nothing: at each pixel the
 * surfaces of greatest depth were all drawn in pass 1, which keeps the greatest depth
 * and of its surfaces the least index whatever the order, the one drawing all in index
 * order keeps (rad__depth_put keeps the earlier of equal depths). Pass 2 draws that
 * surface again at each pixel, and no other there draws a greater depth, nor an equal
 * one before it in index order.
 *
 * Bounds, all conservative: a box is turned into the cube's frame as its centre and
 * its half extents along |frame|, widened by MARGIN and 1/1024 (the rounding of the
 * corners' own products is a few units in the last place); a tile's edges are taken
 * one pixel out (a polygon's pixels are those whose centres its projected, rounded
 * outline covers); a tile's farthest distance is that of its least depth, plus 1/64
 * and MARGIN (depth is rounded in projection and interpolation, and a quad is planar
 * only within rounding). Tiles keep their farthest distance as last computed (an upper
 * bound, since depth only grows) and compute it again once a surface drawn may have
 * covered them. A pixel's test takes its centre's lattice positions a quarter pixel
 * out (a polygon's rounded corners are within 1/16 pixel of the box's points) and its
 * own depth, widened as a tile's. A box within 2 NEAR of the eye is never hidden.
 */
#include "internal.h"

#define CULL_MAGIC 0x6C6C7563u /* "cull" */
#define LEAF       0x80000000u /* a node's link: a leaf's surface, else its second child */
#define TILES      16u         /* tiles along a face's width: each ceil(res / 16) pixels a side */
/* Depth of the tree: at most 1 + ceil(log2 n) <= 33 for n < 2^32, so the nodes
 * waiting while the traversal goes down (one a level) are at most 32. */
#define STACK      34u

typedef struct {
    uint32_t magic, surfaces, nodes;
    int8_t shift; /* the scene's length_shift when built */
    uint8_t pad[3];
} head_t;

typedef struct {
    rad_real_t lo[3], hi[3];
    uint32_t link;
} node_t;

/* RAD_CULL_BYTES counts 16 bytes of head and 60 a surface: two nodes and an index. */
typedef char rad__cull_sizes[sizeof(head_t) == 16u && sizeof(node_t) == 28u &&
                                     RAD_CULL_BYTES(1) == 16u + 2u * 28u + 4u
                                 ? 1
                                 : -1];

static const node_t *cull_nodes(const head_t *h)
{
    return (const node_t *)(const void *)(h + 1);
}

static rad_real_t coord(const rad_vec3_t *v, unsigned a)
{
    return a == 0 ? v->x : a == 1 ? v->y : v->z;
}

/* The box of surface K's corners. */
static void surface_box(const rad_scene_t *s, uint32_t k, rad_real_t *lo, rad_real_t *hi)
{
    uint32_t c[4];
    unsigned n = rad__surface_corners(s, &s->pools.surfaces[k], c), i, a;
    for (a = 0; a < 3; a++) lo[a] = hi[a] = coord(&s->pools.vertices[c[0]], a);
    for (i = 1; i < n; i++)
        for (a = 0; a < 3; a++) {
            rad_real_t v = coord(&s->pools.vertices[c[i]], a);
            if (v < lo[a]) lo[a] = v;
            if (v > hi[a]) hi[a] = v;
        }
}

/* ---- building --------------------------------------------------------------------- */

typedef struct {
    const rad_scene_t *s;
    node_t *nodes;
    uint32_t *idx; /* the surfaces, reordered as the leaves */
    uint32_t next; /* the next free node */
} build_t;

/* Twice surface K's box centre along axis A (no rounding). */
static rad_real_t centre2(const rad_scene_t *s, uint32_t k, unsigned a)
{
    rad_real_t lo[3], hi[3];
    surface_box(s, k, lo, hi);
    return lo[a] + hi[a];
}

/* Whether surface I (centre CI) comes before J (centre CJ): by centre, then index. */
static int before(rad_real_t ci, uint32_t i, rad_real_t cj, uint32_t j)
{
    return ci < cj || (ci == cj && i < j);
}

/* Reorders the N surfaces of V so that V[M] is the one the order of `before` along
 * axis A puts there, those before it below and the rest above (Hoare's selection,
 * the middle of three as the pivot: deterministic). */
static void select_nth(const rad_scene_t *s, uint32_t *v, int32_t n, int32_t m, unsigned a)
{
    int32_t lo = 0, hi = n - 1;
    while (hi > lo) {
        int32_t i = lo, j = hi, mid = lo + (hi - lo) / 2;
        uint32_t t3[3] = {v[lo], v[mid], v[hi]}, p;
        rad_real_t c3[3], cp;
        unsigned x;
        for (x = 0; x < 3; x++) c3[x] = centre2(s, t3[x], a);
        /* the middle of the three */
        x = before(c3[0], t3[0], c3[1], t3[1]) ? (before(c3[1], t3[1], c3[2], t3[2])   ? 1u
                                                  : before(c3[0], t3[0], c3[2], t3[2]) ? 2u
                                                                                       : 0u)
                                               : (before(c3[0], t3[0], c3[2], t3[2])   ? 0u
                                                  : before(c3[1], t3[1], c3[2], t3[2]) ? 2u
                                                                                       : 1u);
        p = t3[x];
        cp = c3[x];
        while (i <= j) {
            uint32_t t;
            while (before(centre2(s, v[i], a), v[i], cp, p)) i++;
            while (before(cp, p, centre2(s, v[j], a), v[j])) j--;
            if (i <= j) {
                t = v[i];
                v[i] = v[j];
                v[j] = t;
                i++;
                j--;
            }
        }
        /* now v[lo..j] come before the rest, v[i..hi] after, and j < i */
        if (m <= j)
            hi = j;
        else if (m >= i)
            lo = i;
        else
            break;
    }
}

/* The axis along which the centres of surfaces V[0..N), N >= 1, spread most (the
 * lowest of equal spreads). */
static unsigned split_axis(const rad_scene_t *s, const uint32_t *v, uint32_t n)
{
    rad_real_t lo[3], hi[3], blo[3], bhi[3], best = 0;
    uint32_t k;
    unsigned a, axis = 0;
    surface_box(s, v[0], blo, bhi);
    for (a = 0; a < 3; a++) lo[a] = hi[a] = blo[a] + bhi[a];
    for (k = 1; k < n; k++) {
        surface_box(s, v[k], blo, bhi);
        for (a = 0; a < 3; a++) {
            rad_real_t c = blo[a] + bhi[a];
            if (c < lo[a]) lo[a] = c;
            if (c > hi[a]) hi[a] = c;
        }
    }
    for (a = 0; a < 3; a++)
        if (hi[a] - lo[a] > best) {
            best = hi[a] - lo[a];
            axis = a;
        }
    return axis;
}

/* The subtree of surfaces idx[FIRST .. FIRST + N), N >= 1; returns its root. Recursion
 * as deep as the tree (at most 33). */
static uint32_t build_node(build_t *b, uint32_t first, uint32_t n)
{
    uint32_t at = b->next++, left, right;
    node_t *nd = &b->nodes[at];
    unsigned a;
    if (n == 1) {
        surface_box(b->s, b->idx[first], nd->lo, nd->hi);
        nd->link = LEAF | b->idx[first];
        return at;
    }
    select_nth(b->s, b->idx + first, (int32_t)n, (int32_t)(n / 2u),
               split_axis(b->s, b->idx + first, n));
    left = build_node(b, first, n / 2u);
    right = build_node(b, first + n / 2u, n - n / 2u);
    for (a = 0; a < 3; a++) {
        const node_t *l = &b->nodes[left], *r = &b->nodes[right];
        nd->lo[a] = l->lo[a] < r->lo[a] ? l->lo[a] : r->lo[a];
        nd->hi[a] = l->hi[a] > r->hi[a] ? l->hi[a] : r->hi[a];
    }
    nd->link = right;
    return at;
}

int rad_cull_build(const rad_scene_t *s, void *buf, size_t bytes)
{
    head_t *h = (head_t *)buf;
    build_t b;
    uint32_t n, k;
    RAD__CHECK_SCENE(s);
    if (!buf) return RAD_ERR_ARG;
    if ((uintptr_t)buf & 3u) return RAD_ERR_ALIGN;
    if (!s->solving) return RAD_ERR_STATE;
    n = s->n_surfaces;
    /* the nodes' count must fit the int returned, and a surface index the link */
    if (n >= 0x40000000u || bytes < RAD_CULL_BYTES(n)) return RAD_ERR_WORK;
    b.s = s;
    b.nodes = (node_t *)(void *)(h + 1);
    b.idx = (uint32_t *)(void *)(b.nodes + 2u * (size_t)n);
    b.next = 0;
    for (k = 0; k < n; k++) b.idx[k] = k;
    if (n) build_node(&b, 0, n);
    h->magic = CULL_MAGIC;
    h->surfaces = n;
    h->nodes = b.next;
    h->shift = s->length_shift;
    h->pad[0] = h->pad[1] = h->pad[2] = 0;
    return (int)b.next;
}

/* The lattice positions of pixel column X's centre, (2 X + 1 - RES) / RES, less and
 * plus a quarter pixel (1 / (2 RES)), into EDGES[X] and EDGES[RES + X]. A row Y's are
 * the column Y's negated: b / d = 1 - 2 y / res. */
void rad__cull_edges(uint32_t res, uint32_t *cwork)
{
    rad_real_t *edges = (rad_real_t *)(void *)cwork;
    const rad_real_t twice = rad__from_int(2 * (int32_t)res);
    uint32_t sat = 0, x; /* quotients within +-1 */
    for (x = 0; x < res; x++) {
        int32_t u = 4 * (int32_t)x + 2 - 2 * (int32_t)res;
        edges[x] = rad__div(rad__from_int(u - 1), twice, &sat);
        edges[res + x] = rad__div(rad__from_int(u + 1), twice, &sat);
    }
}

size_t rad__cull_work(const void *cull, uint32_t res)
{
    return RAD_GATHER_CULL_BYTES(res, ((const head_t *)cull)->surfaces) - 3u;
}

int rad_gather_cull(rad_gather_t *g, const void *cull, void *work, size_t bytes)
{
    const head_t *h = (const head_t *)cull;
    uintptr_t base = (uintptr_t)work, start = (base + 3u) & ~(uintptr_t)3u;
    if (!g) return RAD_ERR_ARG;
    if (!cull) {
        g->cull = 0;
        g->cull_work = 0;
        return RAD_OK;
    }
    if (!work || ((uintptr_t)cull & 3u) || h->magic != CULL_MAGIC) return RAD_ERR_ARG;
    if (bytes < rad__cull_work(cull, g->res) + (size_t)(start - base)) return RAD_ERR_WORK;
    g->cull = cull;
    g->cull_work = (uint32_t *)start;
    rad__cull_edges(g->res, g->cull_work);
    return RAD_OK;
}

int rad_shoot_cull(rad_scene_t *s, const void *cull)
{
    const head_t *h = (const head_t *)cull;
    RAD__CHECK_SCENE(s);
    if (cull && (((uintptr_t)cull & 3u) || h->magic != CULL_MAGIC)) return RAD_ERR_ARG;
    s->cull = cull;
    s->cull_wait = 0;
    return RAD_OK;
}

int rad__cull_fits(const rad_scene_t *s, const void *cull)
{
    const head_t *h = (const head_t *)cull;
    return h->surfaces == s->n_surfaces && h->shift == s->length_shift;
}

/* ---- drawing a face through it ------------------------------------------------------ */

/* One face being drawn: the eye, the face's axes, its size in pixels and tiles, the
 * tiles' farthest distances (FAR: d of their least depth, widened; negative when a
 * pixel shows nothing) and their flags (1: to compute again), the marks, and the
 * tiles' edges, one pixel out, as lattice positions: a / d from ULO[tx] to UHI[tx]
 * and b / d from VLO[ty] to VHI[ty]. */
typedef struct {
    const rad_scene_t *s;
    const rad__eye_t *e;
    unsigned face, ax[3];
    int neg[3]; /* the face's axis k is the cube's ax[k], negated */
    rad_vec3_t absf[3];
    uint32_t res, rows, tile, tw, th; /* TILE pixels a side, TW x TH of them */
    int half;
    const rad_real_t *edge; /* pixel columns' edges, a quarter pixel out (rad__cull_edges) */
    rad_real_t *far;
    uint32_t *marks;
    unsigned char *stale;
    uint32_t tests; /* nodes tested */
    rad_real_t ulo[TILES], uhi[TILES], vlo[TILES], vhi[TILES];
} face_t;

/* What a node's box is on a face: where its pixels can be (x0..x1, y0..y1), and
 * whether it can be hidden at all (HIDABLE 0 when the box comes near the eye). */
typedef struct {
    int32_t x0, x1, y0, y1;
    int hidable;
} reach_t;

/* Widening of a box for the rounding of corners' products: 2^-12 of a unit. */
#define MARGIN RAD__Q(1.0 / 4096.0)

static rad_real_t absr(rad_real_t v)
{
    return v < 0 ? -v : v;
}

/* The middle of ND's box (rounded down in the fixed build: its half extents, HI less
 * it, reach LO). */
static rad_vec3_t box_mid(const node_t *nd)
{
    rad_vec3_t m;
    m.x = nd->lo[0] + (nd->hi[0] - nd->lo[0]) / 2;
    m.y = nd->lo[1] + (nd->hi[1] - nd->lo[1]) / 2;
    m.z = nd->lo[2] + (nd->hi[2] - nd->lo[2]) / 2;
    return m;
}

/* ND's box on face F's axes a, b, d: centre C, half extents H, widened. */
static void face_box(const face_t *f, const node_t *nd, rad_real_t *c, rad_real_t *h)
{
    rad_vec3_t mid = box_mid(nd), half, rel;
    rad_real_t cc[3], hh[3];
    unsigned k;
    half.x = nd->hi[0] - mid.x;
    half.y = nd->hi[1] - mid.y;
    half.z = nd->hi[2] - mid.z;
    rel = rad__sub(mid, f->e->c);
    for (k = 0; k < 3; k++) {
        cc[k] = rad__dot_unit(rel, f->e->frame[k]);
        hh[k] = rad__dot_unit(half, f->absf[k]);
        hh[k] += hh[k] / 1024 + MARGIN;
    }
    for (k = 0; k < 3; k++) {
        c[k] = f->neg[k] ? -cc[f->ax[k]] : cc[f->ax[k]];
        h[k] = hh[f->ax[k]];
    }
}

/* Whether box C +- H lies wholly outside one of the face's clip planes (rad__outcodes'
 * planes: d >= NEAR, d >= a, d >= -a, d >= b, and b >= 0 on a half face, else
 * d >= -b): the greatest value of the plane's side over the box is negative. */
static int outside(const face_t *f, const rad_real_t *c, const rad_real_t *h)
{
    rad_real_t a = c[0], b = c[1], d = c[2], ab = h[0] + h[2], bb = h[1] + h[2];
    if (d + h[2] < RAD__NEAR) return 1;
    if (d - a + ab < 0 || d + a + ab < 0 || d - b + bb < 0) return 1;
    return f->half ? b + h[1] < 0 : d + b + bb < 0;
}

/* The pixel column of the lattice position V / d, clamped to the face (-1..1):
 * floor((1 + V / d) res / 2) or one more or less, with the projection's arithmetic
 * (INV = rad__recip(D), D > 0): its position rounded to 1/16 pixel, then the whole
 * pixels of that. */
static int32_t column(const face_t *f, rad_real_t v, rad_real_t d, rad__recip_t inv)
{
    if (v < -d) v = -d;
    if (v > d) v = d;
    return rad__proj(v + d, inv, f->res * 8u) / 16;
}

/* The least and greatest of V / d over d in [D0, D1] (0 < D0 <= D1, their reciprocals
 * I0, I1) and V in [V0, V1], clamped to -1..1, as columns, widened by one. Wide enough:
 * a column k holds a polygon's pixel only if its centre k + 1/2 lies within 1/16 pixel
 * of the box's projection [x, ...], k + 1/2 >= x - 1/16, and the lower column is at
 * most floor(x + 1/32) - 1, which is below that for every x (likewise the upper). */
static void span(const face_t *f, rad_real_t v0, rad_real_t v1, rad_real_t d0, rad_real_t d1,
                 rad__recip_t i0, rad__recip_t i1, int32_t *lo, int32_t *hi)
{
    *lo = column(f, v0, v0 < 0 ? d0 : d1, v0 < 0 ? i0 : i1) - 1;
    *hi = column(f, v1, v1 > 0 ? d0 : d1, v1 > 0 ? i0 : i1) + 1;
}

static int32_t clampi(int32_t v, int32_t lo, int32_t hi)
{
    return v < lo ? lo : v > hi ? hi : v;
}

/* Box C +- H's reach on the face (see reach_t); pixel rows go down as b goes up:
 * y = (1 - b / d) res / 2 on every face. */
static void box_reach(const face_t *f, const rad_real_t *c, const rad_real_t *h, reach_t *r)
{
    rad_real_t d0 = c[2] - h[2], d1 = c[2] + h[2];
    r->x0 = r->y0 = 0;
    r->x1 = (int32_t)f->res - 1;
    r->y1 = (int32_t)f->rows - 1;
    r->hidable = d0 >= 2 * RAD__NEAR;
    if (r->hidable) {
        rad__recip_t i0 = rad__recip(d0), i1 = rad__recip(d1);
        int32_t x0, x1, y0, y1;
        span(f, c[0] - h[0], c[0] + h[0], d0, d1, i0, i1, &x0, &x1);
        span(f, -c[1] - h[1], -c[1] + h[1], d0, d1, i0, i1, &y0, &y1);
        r->x0 = clampi(x0, 0, r->x1);
        r->x1 = clampi(x1, 0, r->x1);
        r->y0 = clampi(y0, 0, r->y1);
        r->y1 = clampi(y1, 0, r->y1);
    }
}

/* Beyond this a tile's distance is not used (products with it stay in range). */
#define FAR_LIMIT RAD__Q(16384.0)

/* The farthest distance in tile (TX, TY) of the face's depth buffer: d of its least
 * depth, plus 1/64 and MARGIN (depth is rounded in projection and interpolation, and
 * a quad is planar only within rounding); -1 when a pixel shows nothing or lies past
 * FAR_LIMIT. */
static rad_real_t tile_far(const face_t *f, uint32_t tx, uint32_t ty)
{
    rad_real_t d;
    uint32_t x0 = tx * f->tile, y0 = ty * f->tile, x1 = x0 + f->tile, y1 = y0 + f->tile, x, y,
             m = 0xFFFFFFFFu;
    if (x1 > f->res) x1 = f->res;
    if (y1 > f->rows) y1 = f->rows;
    for (y = y0; y < y1; y++) {
        const uint32_t *z = f->e->z + (size_t)y * f->res;
        for (x = x0; x < x1; x++) m = z[x] < m ? z[x] : m;
    }
    if (m == 0) return -1;
    d = rad__depth_d(m);
    return d > FAR_LIMIT ? -1 : d + d / 64 + MARGIN;
}

/* Whether the box's extent C +- H along one axis misses U0 d..U1 d for every d in
 * [D0, D] (see box_misses). */
static int axis_misses(rad_real_t c, rad_real_t h, rad_real_t u0, rad_real_t u1, rad_real_t d0,
                       rad_real_t d)
{
    uint32_t sat = 0; /* |u| < 2, d < FAR_LIMIT: none */
    return c - h > rad__mul(u1, u1 > 0 ? d : d0, &sat) ||
           c + h < rad__mul(u0, u0 < 0 ? d : d0, &sat);
}

/* Whether box C +- H misses the pyramid of lattice positions U0..U1 across and V0..V1
 * up within distance D >= 0: no point of the box within D lies inside those edges. Of
 * the points with d in [d0, D], the greatest u d over the pyramid is u1 D (u1 > 0) or
 * u1 d0, the least u0 d0 (u0 >= 0) or u0 D: a box wholly beyond one of them, or past
 * D, misses it. */
static int box_misses(const rad_real_t *c, const rad_real_t *h, rad_real_t u0, rad_real_t u1,
                      rad_real_t v0, rad_real_t v1, rad_real_t d)
{
    rad_real_t d0 = c[2] - h[2];
    return d0 > d || axis_misses(c[0], h[0], u0, u1, d0, d) ||
           axis_misses(c[1], h[1], v0, v1, d0, d);
}

/* Reaches of at most this many pixels are tested pixel by pixel (a box under a pixel
 * reaches 3 x 3: span widens by one). */
#define SMALL_REACH 25

/* Whether box C +- H is hidden at pixel (X, Y), whose column and row it meets (the
 * first step of `hidden`): no point of it within a quarter pixel of the centre lies
 * nearer than the depth drawn there, widened as a tile's. A polygon covers the pixel
 * only if its projected, rounded outline covers the centre, and the outline's corners
 * are the box's points (within its widening) rounded to 1/16 pixel: a polygon that
 * covers it has a point of the box within 1/16 pixel of the centre. Where nothing is
 * drawn, or the depth drawn lies beyond the box, that is the column's and row's test
 * again: not hidden. */
static int pixel_hides(const face_t *f, const rad_real_t *c, const rad_real_t *h, int32_t x,
                       int32_t y)
{
    uint32_t z = f->e->z[(size_t)y * f->res + (uint32_t)x];
    rad_real_t d;
    if (z == 0) return 0;
    d = rad__depth_d(z);
    if (d > FAR_LIMIT) return 0;
    d += d / 64 + MARGIN;
    if (d >= c[2] + h[2]) return 0;
    return box_misses(c, h, f->edge[x], f->edge[f->res + (uint32_t)x],
                      -f->edge[f->res + (uint32_t)y], -f->edge[y], d);
}

/* Whether box C +- H (reach R) is hidden in every pixel it can reach when R is small,
 * else in every tile R reaches: wherever it could draw, a nearer depth is drawn
 * already. */
static int hidden(const face_t *f, const rad_real_t *c, const rad_real_t *h, const reach_t *r)
{
    uint32_t tx, ty;
    int32_t x, y;
    if (!r->hidable) return 0;
    if ((r->x1 - r->x0 + 1) * (r->y1 - r->y0 + 1) <= SMALL_REACH) {
        /* first the columns and rows the box can meet at all (bits from x0, y0: at most
         * SMALL_REACH of them), then their pixels with the depth drawn */
        rad_real_t d0 = c[2] - h[2], d1 = c[2] + h[2];
        uint32_t cols = 0, rows = 0;
        for (x = r->x0; x <= r->x1; x++)
            if (!axis_misses(c[0], h[0], f->edge[x], f->edge[f->res + (uint32_t)x], d0, d1))
                cols |= 1u << (x - r->x0);
        for (y = r->y0; y <= r->y1 && cols; y++)
            if (!axis_misses(c[1], h[1], -f->edge[f->res + (uint32_t)y], -f->edge[y], d0, d1))
                rows |= 1u << (y - r->y0);
        for (y = r->y0; y <= r->y1; y++)
            for (x = r->x0; x <= r->x1; x++)
                if ((rows >> (y - r->y0)) & (cols >> (x - r->x0)) & 1u &&
                    !pixel_hides(f, c, h, x, y))
                    return 0;
        return 1;
    }
    for (ty = (uint32_t)r->y0 / f->tile; ty <= (uint32_t)r->y1 / f->tile; ty++)
        for (tx = (uint32_t)r->x0 / f->tile; tx <= (uint32_t)r->x1 / f->tile; tx++) {
            uint32_t t = ty * f->tw + tx;
            if (f->stale[t]) {
                f->far[t] = tile_far(f, tx, ty);
                f->stale[t] = 0;
            }
            if (f->far[t] < 0 ||
                !box_misses(c, h, f->ulo[tx], f->uhi[tx], f->vlo[ty], f->vhi[ty], f->far[t]))
                return 0;
        }
    return 1;
}

/* The tiles R reaches may hold new depths. */
static void touch(const face_t *f, const reach_t *r)
{
    uint32_t tx, ty;
    for (ty = (uint32_t)r->y0 / f->tile; ty <= (uint32_t)r->y1 / f->tile; ty++)
        for (tx = (uint32_t)r->x0 / f->tile; tx <= (uint32_t)r->x1 / f->tile; tx++)
            f->stale[ty * f->tw + tx] = 1;
}

/* How far ND's box is from the eye, along the farthest axis (0 with the eye inside):
 * which child is nearer, whatever the face. */
static rad_real_t box_distance(const face_t *f, const node_t *nd)
{
    rad_real_t m = 0;
    unsigned a;
    for (a = 0; a < 3; a++) {
        rad_real_t e = coord(&f->e->c, a),
                   out = nd->lo[a] - e > e - nd->hi[a] ? nd->lo[a] - e : e - nd->hi[a];
        if (out > m) m = out;
    }
    return m;
}

/* Pass 1: the tree from the root, nearest child first, drawing the leaves' surfaces by
 * their indices; F's tests counted. */
static void pass_near(face_t *f, const node_t *nodes)
{
    uint32_t stack[STACK], top = 0, at = 0;
    for (;;) {
        const node_t *nd = &nodes[at];
        rad_real_t c[3], h[3];
        reach_t r;
        face_box(f, nd, c, h);
        f->tests++;
        if (!outside(f, c, h)) {
            box_reach(f, c, h, &r);
            if (!hidden(f, c, h, &r)) {
                if (nd->link & LEAF) {
                    uint32_t k = nd->link & ~LEAF;
                    rad__eye_surface(f->s, f->e, f->face, k, 1);
                    touch(f, &r);
                } else {
                    uint32_t near = at + 1u, far = nd->link, t;
                    if (box_distance(f, &nodes[far]) < box_distance(f, &nodes[near])) {
                        t = near;
                        near = far;
                        far = t;
                    }
                    stack[top++] = far; /* top < STACK: see STACK */
                    at = near;
                    continue;
                }
            }
        }
        if (top == 0) break;
        at = stack[--top];
    }
}

uint32_t rad__cull_face(const rad_scene_t *s, const rad__eye_t *e, unsigned face)
{
    const head_t *h = (const head_t *)e->cull;
    face_t f;
    uint32_t words = (h->surfaces + 31u) / 32u, tiles, k, w;
    f.s = s;
    f.e = e;
    f.face = face;
    for (k = 0; k < 3; k++) {
        const rad_vec3_t *u = &e->frame[k];
        f.ax[k] = rad__face_axis[face][k];
        f.neg[k] = rad__face_sign[face][k] < 0;
        f.absf[k].x = absr(u->x);
        f.absf[k].y = absr(u->y);
        f.absf[k].z = absr(u->z);
    }
    f.res = e->res;
    f.tests = 0;
    f.half = face != 0 && !e->full;
    f.rows = f.half ? e->res / 2u : e->res;
    f.tile = (f.res + TILES - 1u) / TILES;
    f.tw = (f.res + f.tile - 1u) / f.tile;
    f.th = (f.rows + f.tile - 1u) / f.tile;
    tiles = f.tw * f.th;
    for (k = 0; k < TILES; k++) { /* all TILES: tw, th <= TILES, and no entry unset */
        uint32_t sat = 0;
        rad_real_t res = rad__from_int((int32_t)f.res);
        int32_t lo = (int32_t)(k * f.tile) - 1, hi = (int32_t)((k + 1u) * f.tile) + 1;
        f.ulo[k] = rad__div(rad__from_int(2 * lo - (int32_t)f.res), res, &sat);
        f.uhi[k] = rad__div(rad__from_int(2 * hi - (int32_t)f.res), res, &sat);
        f.vhi[k] = -f.ulo[k]; /* b / d = 1 - 2 y / res */
        f.vlo[k] = -f.uhi[k];
    }
    f.edge = (const rad_real_t *)(const void *)e->cwork;
    f.marks = e->cwork + 2u * f.res;
    f.far = (rad_real_t *)(void *)(f.marks + words);
    f.stale = (unsigned char *)(f.far + tiles);
    for (k = 0; k < words; k++) f.marks[k] = 0;
    for (k = 0; k < tiles; k++) {
        f.far[k] = -1;
        f.stale[k] = 0;
    }
    rad__eye_clear(e, face);
    if (h->nodes) pass_near(&f, cull_nodes(h));
    for (k = 0; k < f.rows * f.res; k++) { /* the surfaces left in the pixels */
        uint32_t id = e->ids[k];
        if (id != RAD_INDEX_NONE) f.marks[id / 32u] |= 1u << (id % 32u);
    }
    rad__eye_clear(e, face);
    for (w = 0; w < words; w++) {
        uint32_t m = f.marks[w], b;
        for (b = 0; m; b++, m >>= 1)
            if (m & 1u) rad__eye_surface(s, e, face, w * 32u + b, 0);
    }
    return f.tests;
}
