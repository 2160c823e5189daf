/* SPDX-License-Identifier: MIT */
/* rad — gathering: the light arriving at any point, through a cube of its own.
 *
 * A gather is the shots' hemi-cube (hemicube.c: the same rasterizer, lattice and
 * delta form factor table) put at any point and normal, at its own resolution, with
 * each pixel weighting the radiosity of the element it sees instead of adding to the
 * element's form factor. The table sums to exactly 2^30 and every weight and shown
 * radiosity is >= 0, so the fixed sum sum F B is exact in 64 bits (< 2^61) and is
 * rounded once: in a closed scene whose elements all show B, the gather is B.
 *
 * A probe renders a whole cube (six whole faces) and projects the radiosity seen onto
 * the spherical harmonics of bands 0..2 through the moments of the direction
 * w = (a, b, 1) / r of each pixel (r^2 = a^2 + b^2 + 1, a and b the pixel centre's odd
 * lattice numbers over the resolution): its solid angle dw ~ 1 / r^3, dw w, dw w w^T. Each face's moments need six quadrant tables, by the face's
 * symmetries in a and b (c = 1 / r):
 *     T0 = c^3 (dw)    TA = c^4 a (dw w_a)    TD = c^4 (dw w_d)
 *     TAA = c^5 a^2 (dw w_a^2)    TAB = c^5 a b (dw w_a w_b)    TAD = c^5 a (dw w_a w_d)
 * w_b's tables are w_a's transposed, and dw w_d^2 = dw - dw w_a^2 - dw w_b^2. All are
 * built in integers in both builds and scaled alike so that each quadrant of T0 sums
 * to exactly 2^26: the sphere's 24 quadrants to 1.5 * 2^30, standing for 4 pi.
 * A uniform environment then has every first and mixed moment zero by the tables'
 * symmetry, and equal diagonal moments by the cube's: bands 1 and 2 vanish exactly.
 * The cube is turned by the rotation with rows (1, 2, 2) / 3, (2, 1, -2) / 3 and
 * (-2, 2, -1) / 3: no scene axis lies along a face's pixel rows or columns, where the
 * outlines of walls along the axes would alias by half a pixel over their whole length.
 * The moments turn back to the scene's axes exactly (numerators in integers, then one
 * division by 3 or 9), so a uniform environment's stay as they were.
 */
#include "internal.h"

/* The six tables of one quadrant, each q^2 entries, i across + j q. */
enum { T0, TA, TD, TAA, TAB, TAD, NTABLES };

/* Moments of one face, on its axes a, b, d. */
enum { M0, MA, MB, MD, MAA, MBB, MAB, MAD, MBD, NMOM };

static int res_ok(unsigned res)
{
    return res >= 8u && res <= RAD_MAX_RES && !(res & 1u);
}

/* x y / 2^31, rounded, for x, y < 2^32. */
static uint64_t mul31(uint64_t x, uint64_t y)
{
    return (x * y + (1u << 30)) >> 31;
}

/* Entry (i, j) of the quadrant tables before scaling, in Q31: c from c^2 = res^2 / N,
 * N = A^2 + B^2 + res^2 for the odd numbers A = 2i + 1, B = 2j + 1 (a = A / res). */
static void sphere_raw(uint32_t res, uint32_t i, uint32_t j, uint64_t *t)
{
    uint64_t aa = 2u * i + 1u, bb = 2u * j + 1u, r2 = (uint64_t)res * res;
    uint64_t n = aa * aa + bb * bb + r2;
    uint64_t c2 = (r2 << 40) / n; /* Q40, < 2^40 */
    uint64_t c = rad__isqrt64(c2 << 22), a = (aa << 31) / res, b = (bb << 31) / res;
    uint64_t c3 = mul31(mul31(c, c), c), c4 = mul31(c3, c), c5 = mul31(c4, c);
    t[T0] = c3;
    t[TA] = mul31(c4, a);
    t[TD] = c4;
    t[TAA] = mul31(c5, mul31(a, a));
    t[TAB] = mul31(c5, mul31(a, b));
    t[TAD] = mul31(c5, a);
}

/* The probe's tables: each entry times 2^26 / (the quadrant's sum of T0), rounded down,
 * and T0's deficit given back one unit an entry, so each T0 quadrant sums to 2^26. */
static void sphere_tables(uint32_t res, rad_ff_t *table)
{
    uint32_t q = res / 2u, n = q * q, k, m;
    uint64_t sum = 0, got = 0, t[NTABLES];
    for (k = 0; k < n; k++) {
        sphere_raw(res, k % q, k / q, t);
        sum += t[T0];
    }
    for (k = 0; k < n; k++) {
        sphere_raw(res, k % q, k / q, t);
        got += (t[T0] << 26) / sum;
    }
    for (k = 0; k < n; k++) {
        sphere_raw(res, k % q, k / q, t);
        for (m = 0; m < NTABLES; m++) {
            uint64_t v = (t[m] << 26) / sum + (m == T0 && k < ((uint64_t)1 << 26) - got);
            table[(size_t)m * n + k] = rad__ff_from_q30((uint32_t)v);
        }
    }
}

int rad_gather_init(rad_gather_t *g, unsigned res, unsigned flags, void *work, size_t bytes)
{
    static const rad_stats_t zero = {0};
    uintptr_t base = (uintptr_t)work, start = (base + 7u) & ~(uintptr_t)7u;
    size_t q = res / 2u, tables = (flags & RAD_GATHER_SH) ? 6u * q * q : 2u * q * q;
    size_t need;
    uint32_t k;
    if (!g || !work || !res_ok(res) || (flags & ~RAD_GATHER_SH)) return RAD_ERR_ARG;
    need = (size_t)(start - base) + tables * sizeof(rad_ff_t) + res * sizeof(uint32_t) +
           (size_t)res * res * (sizeof(uint32_t) + sizeof(rad_index_t));
    if (bytes < need) return RAD_ERR_WORK;
    g->res = (uint16_t)res;
    g->sh = (uint16_t)(flags & RAD_GATHER_SH);
    g->turn = 0;
    g->table = (rad_ff_t *)start;
    g->steps = (uint32_t *)(void *)(g->table + tables);
    g->zbuf = g->steps + res;
    g->ibuf = (rad_index_t *)(void *)(g->zbuf + (size_t)res * res);
    g->stats = zero;
    g->cull = 0;
    g->cull_work = 0;
    for (k = 0; k < res; k++) g->steps[k] = 0; /* once: every span leaves it zero */
    if (g->sh)
        sphere_tables(res, g->table);
    else
        rad__dff_table(res, g->table, g->table + q * q);
    return RAD_OK;
}

static int in_range(const rad_vec3_t *v)
{
    const rad_real_t m = RAD__Q(RAD_COORD_LIMIT);
    /* written so that a NaN fails in the float twin */
    return v->x >= -m && v->x <= m && v->y >= -m && v->y <= m && v->z >= -m && v->z <= m;
}

/* The checks shared by both gathers, and the cube's fixed fields: POINT in the core's
 * scale (the caller's times 2^length_shift, exact). */
static int eye_setup(const rad_scene_t *s, rad_gather_t *g, const rad_vec3_t *point, uint32_t skip,
                     int sh, int flags, rad__eye_t *e)
{
    uint32_t sat = 0;
    RAD__CHECK_SCENE(s);
    if (!g || !point || (int)g->sh != sh ||
        (flags &
         ~(RAD_SHADE_AMBIENT | RAD_SHADE_SCALED | (sh ? 0 : RAD_SHADE_SOFT | RAD_SHADE_SKIES))) ||
        (flags & (RAD_SHADE_SOFT | RAD_SHADE_SKIES)) == RAD_SHADE_SKIES)
        return RAD_ERR_ARG;
    if (!s->solving || (g->cull && !rad__cull_fits(s, g->cull))) return RAD_ERR_STATE;
    e->c = rad__scale2_vec(*point, s->length_shift, &sat);
    if (sat || !in_range(&e->c)) return RAD_ERR_RANGE;
    e->res = g->res;
    e->skip = skip;
    e->group = UINT32_MAX;
    e->full = sh;
    e->backs = 1;
    e->z = g->zbuf;
    e->steps = g->steps;
    e->ids = g->ibuf;
    e->st = &g->stats;
    e->cull = g->cull;
    e->cwork = g->cull_work;
    return RAD_OK;
}

/* Face F of E's cube: through its hierarchy when it has one (the same pixels). */
static void eye_face(const rad_scene_t *s, const rad__eye_t *e, unsigned f)
{
    if (e->cull)
        rad__cull_face(s, e, f);
    else
        rad__eye_face(s, e, f);
}

/* The ambient term in the core's scale into AMB when FLAGS ask for it (a pass over the
 * patches), else null. */
static const rad_rgb_t *gather_ambient(const rad_scene_t *s, rad_gather_t *g, int flags,
                                       rad_rgb_t *amb)
{
    rad_real_t a[3];
    if (!(flags & RAD_SHADE_AMBIENT)) return 0;
    rad__ambient(s, a, &g->stats.saturations);
    amb->r = a[0];
    amb->g = a[1];
    amb->b = a[2];
    return amb;
}

/* V from the core's scale to the caller's, unless FLAGS keep the core's. */
static rad_rgb_t gather_out(const rad_scene_t *s, int flags, rad_rgb_t v, uint32_t *sat)
{
    if (flags & RAD_SHADE_SCALED) return v;
    return rad__scale2_rgb(v, -s->power_shift, sat);
}

/* SUM (per channel) plus E times COSINE, saturating. */
static void add_cos(rad_real_t sum[3], const rad_rgb_t *e, rad_real_t cosine, uint32_t *sat)
{
    unsigned c;
    for (c = 0; c < 3; c++)
        sum[c] = rad__add_sat(sum[c], rad__mul(rad__channel(e, c), cosine, sat), sat);
}

/* ---- the lights' direct light ---------------------------------------------------- */

/* Moments of the whole sphere: M0, then x, y, z, then xx, yy, zz, xy, yz, xz; per
 * channel; on the cube's axes, then on the scene's. */
typedef struct {
    rad__msum_t m[10][3];
} sphere_t;
/* The second moments' places in sphere_t by axis pair. */
static const unsigned char second[3][3] = {{4, 7, 9}, {7, 5, 8}, {9, 8, 6}};

/* A gather's view of the lights on the face just drawn (rad__lights_at): a direction
 * on it reaches the point when its pixel shows nothing (a sun's or sky's) or nothing
 * nearer than the light (a point's), seen as the cube sees the scene: a pixel's centre
 * decides, and a face seen from behind occludes. The hemisphere sums E cos t per
 * channel (its normal the cube's third axis); the sphere adds each direction's
 * moments (MOM, on the cube's axes, Q20 as add_face's). The first face keeps the
 * directions, each with the face and pixel it meets (working a sky's out is most of
 * their cost), for the others when they
 * fit in LIT_KEEP (2.5 KB of stack: a sun's disc and a sky of 48 directions fit),
 * else every face works them out again. */
#define LIT_KEEP 64
typedef struct {
    uint32_t face, px, depth; /* where the direction meets the cube (rad__eye_pixel) */
    int point;
    rad_real_t l[3]; /* its unit on the cube's axes */
    rad_rgb_t e;
} lit_dir_t;
typedef struct {
    const rad__eye_t *e;
    unsigned face;
    rad_real_t sum[3];
    rad__msum_t (*mom)[3];
    uint32_t *sat;
    lit_dir_t kept[LIT_KEEP];
    uint32_t n_kept;
    int keep, more; /* KEEP: the first face's pass; MORE: some did not fit */
    unsigned types; /* the lights' types counted (rad__lights_at) */
} lit_t;

/* Direction D when it lies on the face just drawn and reaches the point. */
static void lit_one(lit_t *t, const lit_dir_t *d)
{
    uint32_t z = t->e->z[d->px];
    unsigned c, k, m;
    if (d->face != t->face || (d->point ? z > d->depth : z != 0)) return;
    if (!t->mom) {
        if (d->l[2] > 0) add_cos(t->sum, &d->e, d->l[2], t->sat);
        return;
    }
    for (c = 0; c < 3; c++) {
        rad_real_t v = rad__channel(&d->e, c);
        t->mom[0][c] += rad__msum_light(v, RAD__ONE, RAD__ONE);
        for (k = 0; k < 3; k++) {
            t->mom[1 + k][c] += rad__msum_light(v, d->l[k], RAD__ONE);
            for (m = k; m < 3; m++) t->mom[second[k][m]][c] += rad__msum_light(v, d->l[k], d->l[m]);
        }
    }
}

/* A direction from rad__lights_at: its face and pixel found once, kept on the first
 * face's pass. */
static void lit_dir(void *ctx, uint32_t light, const rad_vec3_t *w, const rad_vec3_t *u, int point,
                    const rad_rgb_t *e)
{
    lit_t *t = ctx;
    lit_dir_t d;
    unsigned k;
    (void)light;
    if (!rad__eye_pixel(t->e, *w, &d.face, &d.px, &d.depth)) return;
    for (k = 0; k < 3; k++) d.l[k] = rad__dot_unit(*u, t->e->frame[k]);
    d.e = *e;
    d.point = point;
    if (t->keep && t->n_kept < LIT_KEEP)
        t->kept[t->n_kept++] = d;
    else if (t->keep)
        t->more = 1;
    lit_one(t, &d);
}

/* The lights seen on face F of E's cube, just drawn, into T (F 0 first). */
static void lit_face(const rad_scene_t *s, const rad__eye_t *e, unsigned f, lit_t *t)
{
    uint32_t k;
    if (!s->n_lights) return;
    t->e = e;
    t->face = f;
    t->keep = f == 0;
    if (f == 0) {
        t->n_kept = 0;
        t->more = 0;
    }
    if (f == 0 || t->more) {
        rad__lights_at(s, e->c, t->types, lit_dir, t, t->sat);
        return;
    }
    for (k = 0; k < t->n_kept; k++) lit_one(t, &t->kept[k]);
}

/* ---- a hemisphere --------------------------------------------------------------- */

/* Element ID's shown radiosity into B; 0 when ID is past the last (none seen). */
static inline int run_shown(const rad_scene_t *s, const rad_rgb_t *amb, uint32_t id, uint32_t *sat,
                            rad_rgb_t *b)
{
    if (id >= s->n_elements) return 0;
    *b = rad__shown(s, id, amb, sat);
    return 1;
}

/* Adds a run of element ID's pixels (ID past the last: none seen), the sums W[k] of
 * their NW weights, times its shown radiosity, to ACC[k]. Summing the weights first
 * is exact in the fixed build (a run's weights sum to less than 2^30) and looks B up
 * once a run; saturations are counted a run. */
static void add_run(const rad_scene_t *s, rad_gather_t *g, const rad_rgb_t *amb, uint32_t id,
                    const rad_ff_t *w, unsigned nw, rad__wsum_t (*acc)[3])
{
    rad_rgb_t b;
    unsigned k;
    if (!run_shown(s, amb, id, &g->stats.saturations, &b)) return;
    for (k = 0; k < nw; k++) {
        acc[k][0] += rad__wterm(w[k], b.r);
        acc[k][1] += rad__wterm(w[k], b.g);
        acc[k][2] += rad__wterm(w[k], b.b);
    }
}

/* The ambient part (rad__ambient_part) of the last surface a hemisphere's run met, and
 * the saturations computing it counted: neighbouring runs are mostly of one surface. */
typedef struct {
    const rad_rgb_t *amb;
    uint32_t surface, sat;
    rad_rgb_t part;
} part_cache_t;

/* rad__shown of element ID through cache C, the same values and count of saturations;
 * 0 when ID is past the last. */
static inline int run_shown_cached(const rad_scene_t *s, part_cache_t *c, uint32_t id,
                                   uint32_t *sat, rad_rgb_t *b)
{
    const rad_element_t *el;
    if (id >= s->n_elements) return 0;
    el = &s->pools.elements[id];
    if (!c->amb || s->element_rho) { /* nothing to cache per surface */
        *b = rad__shown(s, id, c->amb, sat);
        return 1;
    }
    if (el->surface != c->surface) {
        c->surface = el->surface;
        c->sat = 0;
        c->part = rad__ambient_part(&s->pools.surfaces[el->surface].reflectance, c->amb, &c->sat);
    }
    *sat += c->sat;
    *b = rad__shown_plus(el->radiosity, &c->part, sat);
    return 1;
}

/* A run of one element in a row of a hemisphere's face: its id and weight so far, and
 * the row's sums. */
typedef struct {
    uint32_t id;
    rad_ff_t w;
    rad__wsum_t acc[3];
} run_t;

/* Ends R's run (add_run's sum for one weight, inline: the hemisphere's hot loop) and
 * starts one of element ID. */
static inline void run_next(const rad_scene_t *s, part_cache_t *pc, uint32_t *sat, run_t *r,
                            uint32_t id)
{
    rad_rgb_t b;
    if (run_shown_cached(s, pc, r->id, sat, &b)) {
        r->acc[0] += rad__wterm(r->w, b.r);
        r->acc[1] += rad__wterm(r->w, b.g);
        r->acc[2] += rad__wterm(r->w, b.b);
    }
    r->id = id;
    r->w = 0;
}

/* Adds face FACE's sum of F B, per channel, to SUM. Row by row, so that the twin's
 * float sums add at most res terms at a time; a run goes on across the row's centre,
 * where the weights' mirrored halves meet. Saturations are counted here and added to
 * the gatherer's once. */
static void face_sum(const rad_scene_t *s, rad_gather_t *g, const rad_rgb_t *amb, unsigned face,
                     rad__wsum_t *sum)
{
    uint32_t res = g->res, q = res / 2u, rows = face ? q : res, r, x, c, sat = 0;
    const rad_ff_t *top = g->table, *side = g->table + (size_t)q * q;
    part_cache_t pc = {0, 0xFFFFFFFFu, 0, {0, 0, 0}}; /* no surface's index */
    pc.amb = amb;
    for (r = 0; r < rows; r++) {
        const rad_index_t *ids = g->ibuf + (size_t)r * res;
        const rad_ff_t *row = rad__dff_row(top, side, res, face, r);
        run_t run = {RAD_INDEX_NONE, 0, {0, 0, 0}};
        for (x = 0; x < q; x++) {
            if (ids[x] != run.id) run_next(s, &pc, &sat, &run, ids[x]);
            run.w += row[q - 1u - x];
        }
        for (; x < res; x++) {
            if (ids[x] != run.id) run_next(s, &pc, &sat, &run, ids[x]);
            run.w += row[x - q];
        }
        run_next(s, &pc, &sat, &run, RAD_INDEX_NONE);
        for (c = 0; c < 3; c++) sum[c] += run.acc[c];
    }
    g->stats.saturations += sat;
}

int rad_gather(const rad_scene_t *s, rad_gather_t *g, const rad_vec3_t *point,
               const rad_vec3_t *normal, uint32_t skip, int flags, rad_rgb_t *out)
{
    rad__eye_t e;
    rad_vec3_t n;
    rad_rgb_t amb, v;
    const rad_rgb_t *ap;
    rad__wsum_t sum[3] = {0, 0, 0};
    lit_t lit;
    unsigned f;
    int rc = normal && out ? eye_setup(s, g, point, skip, 0, flags, &e) : RAD_ERR_ARG;
    if (rc < 0) return rc;
    if (!in_range(normal)) return RAD_ERR_RANGE;
    if (!rad__normalize(*normal, &n)) return RAD_ERR_ARG;
    rad__cube_frame(n, g->turn, e.frame);
    ap = gather_ambient(s, g, flags, &amb);
    lit.mom = 0;
    lit.sat = &g->stats.saturations;
    lit.types = !(flags & RAD_SHADE_SOFT)   ? RAD__LIGHTS_ALL
                : (flags & RAD_SHADE_SKIES) ? 0u
                                            : RAD__LIGHTS_SKIES;
    lit.sum[0] = lit.sum[1] = lit.sum[2] = 0;
    for (f = 0; f < 5; f++) {
        eye_face(s, &e, f);
        face_sum(s, g, ap, f, sum);
        lit_face(s, &e, f, &lit);
    }
    v.r = rad__add_sat(rad__wvalue(sum[0], lit.sat), lit.sum[0], lit.sat);
    v.g = rad__add_sat(rad__wvalue(sum[1], lit.sat), lit.sum[1], lit.sat);
    v.b = rad__add_sat(rad__wvalue(sum[2], lit.sat), lit.sum[2], lit.sat);
    *out = gather_out(s, flags, v, &g->stats.saturations);
    return RAD_OK;
}

/* ---- the sharp lights at a point, visibility the caller's ------------------------ */

typedef struct {
    rad_vec3_t n; /* the surface's unit normal */
    rad_visible_fn *vis;
    void *ctx;
    rad_real_t sum[3];
    uint32_t *sat;
} direct_t;

static void direct_one(void *ctx, uint32_t light, const rad_vec3_t *w, const rad_vec3_t *u,
                       int point, const rad_rgb_t *e)
{
    direct_t *d = ctx;
    rad_real_t cosine = rad__dot_unit(*u, d->n);
    (void)w;
    (void)point;
    if (cosine > 0 && d->vis(d->ctx, light, u)) add_cos(d->sum, e, cosine, d->sat);
}

int rad_direct(const rad_scene_t *s, const rad_vec3_t *point, const rad_vec3_t *normal, int flags,
               rad_visible_fn *vis, void *ctx, rad_rgb_t *out)
{
    direct_t d;
    rad_vec3_t c;
    rad_rgb_t v;
    uint32_t sat = 0;
    RAD__CHECK_SCENE(s);
    if (!point || !normal || !vis || !out || (flags & ~(RAD_SHADE_SCALED | RAD_SHADE_SKIES)))
        return RAD_ERR_ARG;
    c = rad__scale2_vec(*point, s->length_shift, &sat);
    if (sat || !in_range(&c) || !in_range(normal)) return RAD_ERR_RANGE;
    if (!rad__normalize(*normal, &d.n)) return RAD_ERR_ARG;
    d.vis = vis;
    d.ctx = ctx;
    d.sat = &sat;
    d.sum[0] = d.sum[1] = d.sum[2] = 0;
    rad__lights_at(s, c, RAD__LIGHTS_ALL & ((flags & RAD_SHADE_SKIES) ? ~0u : ~RAD__LIGHTS_SKIES),
                   direct_one, &d, &sat);
    v.r = d.sum[0];
    v.g = d.sum[1];
    v.b = d.sum[2];
    *out = gather_out(s, flags, v, &sat);
    return RAD_OK;
}

/* ---- a sphere, in spherical harmonics ------------------------------------------- */

/* Row R's moments (per channel) into face sums FS: the pixels left of the centre have
 * a < 0, those of the rows below it b < 0; a run ends at the centre too. */
static void row_moments(const rad_scene_t *s, rad_gather_t *g, const rad_rgb_t *amb, uint32_t r,
                        rad__msum_t (*fs)[3])
{
    static const signed char odd_a[NMOM] = {0, 1, 0, 0, 0, 0, 1, 1, 0};
    static const signed char odd_b[NMOM] = {0, 0, 1, 0, 0, 0, 1, 0, 1};
    uint32_t res = g->res, q = res / 2u, n = q * q, j = r < q ? q - 1u - r : r - q, x, m, c;
    uint32_t id = RAD_INDEX_NONE;
    const rad_index_t *ids = g->ibuf + (size_t)r * res;
    const rad_ff_t *t = g->table;
    rad__wsum_t half[2][NMOM][3] = {{{0, 0, 0}}};
    rad_ff_t w[NMOM] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    for (x = 0; x < res; x++) {
        uint32_t i = x < q ? q - 1u - x : x - q, ij = j * q + i, ji = i * q + j;
        if (ids[x] != id || x == q) {
            add_run(s, g, amb, id, w, NMOM, half[x > q]);
            id = ids[x];
            for (m = 0; m < NMOM; m++) w[m] = 0;
        }
        w[M0] += t[T0 * n + ij];
        w[MA] += t[TA * n + ij];
        w[MB] += t[TA * n + ji];
        w[MD] += t[TD * n + ij];
        w[MAA] += t[TAA * n + ij];
        w[MBB] += t[TAA * n + ji];
        w[MAB] += t[TAB * n + ij];
        w[MAD] += t[TAD * n + ij];
        w[MBD] += t[TAD * n + ji];
    }
    add_run(s, g, amb, id, w, NMOM, half[1]);
    for (m = 0; m < NMOM; m++)
        for (c = 0; c < 3; c++) {
            rad__msum_t right = (rad__msum_t)half[1][m][c], left = (rad__msum_t)half[0][m][c];
            rad__msum_t v = odd_a[m] ? right - left : right + left;
            fs[m][c] += odd_b[m] && r >= q ? -v : v;
        }
}

/* Face F's moments, on its own axes, onto the cube's: its axis k is the cube's axis
 * rad__face_axis[F][k] times rad__face_sign[F][k]. */
static void add_face(unsigned f, rad__msum_t (*fs)[3], sphere_t *sp)
{
    static const unsigned char first[3] = {MA, MB, MD};
    static const unsigned char pair[3][3] = {{MAA, MAB, MAD}, {MAB, MBB, MBD}, {MAD, MBD, 0}};
    const unsigned char *ax = rad__face_axis[f];
    const signed char *sg = rad__face_sign[f];
    unsigned c, k, l;
    for (c = 0; c < 3; c++) {
        rad__msum_t v[NMOM], dd;
        for (k = 0; k < NMOM; k++) v[k] = rad__msum_q20(fs[k][c]);
        dd = v[M0] - v[MAA] - v[MBB]; /* w_d^2 = 1 - w_a^2 - w_b^2 */
        sp->m[0][c] += v[M0];
        for (k = 0; k < 3; k++) {
            sp->m[1 + ax[k]][c] += sg[k] < 0 ? -v[first[k]] : v[first[k]];
            for (l = k; l < 3; l++) {
                rad__msum_t w = k == 2 && l == 2 ? dd : v[pair[k][l]];
                sp->m[second[ax[k]][ax[l]]][c] += sg[k] * sg[l] < 0 ? -w : w;
            }
        }
    }
}

/* The probe's turn: row k, over 3, is the cube's axis k on the scene's axes. */
static const signed char turn3[3][3] = {{1, 2, 2}, {2, 1, -2}, {-2, 2, -1}};

static void probe_frame(rad_vec3_t *frame)
{
    unsigned k;
    for (k = 0; k < 3; k++) {
        frame[k].x = rad__div(rad__from_int(turn3[k][0]), rad__from_int(3), 0);
        frame[k].y = rad__div(rad__from_int(turn3[k][1]), rad__from_int(3), 0);
        frame[k].z = rad__div(rad__from_int(turn3[k][2]), rad__from_int(3), 0);
    }
}

/* CUBE's moments on the scene's axes: m_i = sum_k R_ki m_k, m_ij = sum_kl R_ki R_lj m_kl
 * for the rotation R = turn3 / 3. */
static void to_scene(const sphere_t *cube, sphere_t *sp)
{
    static const unsigned char ii[6] = {0, 1, 2, 0, 1, 0}, jj[6] = {0, 1, 2, 1, 2, 2};
    unsigned c, i, k, l;
    for (c = 0; c < 3; c++) {
        sp->m[0][c] = cube->m[0][c];
        for (i = 0; i < 3; i++) {
            rad__msum_t v = 0;
            for (k = 0; k < 3; k++) v += (rad__msum_t)turn3[k][i] * cube->m[1 + k][c];
            sp->m[1 + i][c] = rad__msum_div(v, 3);
        }
        for (i = 0; i < 6; i++) {
            rad__msum_t v = 0;
            for (k = 0; k < 3; k++)
                for (l = 0; l < 3; l++)
                    v +=
                        (rad__msum_t)(turn3[k][ii[i]] * turn3[l][jj[i]]) * cube->m[second[k][l]][c];
            sp->m[4 + i][c] = rad__msum_div(v, 9);
        }
    }
}

/* Y_lm times 4 pi / 1.5 (the tables' 1.5 * 2^30 is the sphere's 4 pi): Q28 integers in
 * the fixed build. Y00 = 1 / (2 sqrt pi), Y1 = sqrt 3 / (2 sqrt pi) (x, y, z),
 * Y2 = sqrt 15 / (2 sqrt pi) (xy, yz, xz), Y20 = sqrt 5 / (4 sqrt pi) (3z^2 - 1),
 * Y22 = sqrt 15 / (4 sqrt pi) (x^2 - y^2). */
#if RAD_FLOAT
static const float sh_k[5] = {2.36327180f, 4.09330683f, 9.15291233f, 2.64221820f, 4.57645616f};
#else
static const uint32_t sh_k[5] = {634385944u, 1098788686u, 2456966195u, 709265047u, 1228483097u};
#endif

int rad_gather_sh(const rad_scene_t *s, rad_gather_t *g, const rad_vec3_t *point, uint32_t skip,
                  int flags, rad_rgb_t *sh)
{
    rad__eye_t e;
    sphere_t cube = {{{0, 0, 0}}}, sp;
    lit_t lit;
    rad_rgb_t amb;
    const rad_rgb_t *ap;
    uint32_t *sat;
    unsigned f, r, c, k;
    int rc = sh ? eye_setup(s, g, point, skip, 1, flags, &e) : RAD_ERR_ARG;
    if (rc < 0) return rc;
    sat = &g->stats.saturations;
    probe_frame(e.frame);
    ap = gather_ambient(s, g, flags, &amb);
    lit.mom = cube.m;
    lit.sat = sat;
    lit.types = RAD__LIGHTS_ALL;
    for (f = 0; f < 6; f++) {
        rad__msum_t fs[NMOM][3] = {{0, 0, 0}};
        eye_face(s, &e, f);
        for (r = 0; r < g->res; r++) row_moments(s, g, ap, r, fs);
        add_face(f, fs, &cube);
        lit_face(s, &e, f, &lit);
    }
    to_scene(&cube, &sp);
    for (c = 0; c < 3; c++) {
        rad_real_t v[9];
        v[0] = rad__mscale(sp.m[0][c], sh_k[0], sat);
        v[1] = rad__mscale(sp.m[2][c], sh_k[1], sat);
        v[2] = rad__mscale(sp.m[3][c], sh_k[1], sat);
        v[3] = rad__mscale(sp.m[1][c], sh_k[1], sat);
        v[4] = rad__mscale(sp.m[7][c], sh_k[2], sat);
        v[5] = rad__mscale(sp.m[8][c], sh_k[2], sat);
        v[6] = rad__mscale(3 * sp.m[6][c] - sp.m[0][c], sh_k[3], sat);
        v[7] = rad__mscale(sp.m[9][c], sh_k[2], sat);
        v[8] = rad__mscale(sp.m[4][c] - sp.m[5][c], sh_k[4], sat);
        for (k = 0; k < 9; k++) {
            if (c == 0) sh[k].r = v[k];
            if (c == 1) sh[k].g = v[k];
            if (c == 2) sh[k].b = v[k];
        }
    }
    for (k = 0; k < 9; k++) sh[k] = gather_out(s, flags, sh[k], sat);
    return RAD_OK;
}
