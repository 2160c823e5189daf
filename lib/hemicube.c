/* SPDX-License-Identifier: MIT */
/* rad — the hemi-cube: delta form factors, face passes, item-buffer accumulation.
 *
 * The hemi-cube has a top face of res x res pixels and four half side faces of
 * res x res/2. The delta form factor of a top pixel at (x, y) (face spanning -1..1) is
 * dA / (pi (x^2 + y^2 + 1)^2), of a side pixel at (x, z) z dA / (pi (x^2 + z^2 + 1)^2)
 * (Cohen & Greenberg 1985). Both are symmetric in x (and the top in y), so one quadrant
 * of each is stored. The table is built in integers in both builds and normalised so
 * that the whole hemi-cube sums to exactly 2^30 (1.0 in Q2.30).
 *
 * A cube draws every surface (but the shooter's own) once a face, and each pixel gets
 * the element of the surface under its centre from the surface's lattice (lattice.c).
 * The same cube, at any point, frame and resolution, and with a sixth face and full
 * side faces for a whole sphere, serves gathering (gather.c): rad__eye_face.
 */
#include "internal.h"

typedef struct {
    unsigned face;   /* 0 top, 1..4 sides */
    int row0, row1;  /* rows of the face this region holds */
    uint32_t offset; /* first pixel in the work buffer's face buffers */
} region_t;

/* Rows of face F of a cube of resolution RES: a hemi-cube's sides are half faces, a full
 * cube's (FULL) are whole. */
static uint32_t rows_of(uint32_t res, int full, unsigned f)
{
    return f && !full ? res / 2u : res;
}
static uint32_t face_rows(const rad_scene_t *s, unsigned f)
{
    return rows_of(s->cube_res, 0, f);
}
/* First pixel of face F when all five faces are in the buffers: the top, then the sides. */
static uint32_t face_offset(const rad_scene_t *s, unsigned f)
{
    uint32_t res = s->cube_res;
    return f ? res * res + (f - 1u) * res * (res / 2u) : 0u;
}

/* ---- the delta form factor table ----------------------------------------------- */

/* Unnormalised delta form factor of quadrant entry (i, j) of FACE, shifted right by SH:
 * with odd lattice numbers (2i+1)/res the formulas above become 2^62 / N^2 (top) and
 * 2^62 / N^2 * h / res (side), N = (2i+1)^2 + (2j+1 or h)^2 + res^2 < 3 * 2^22. */
static uint64_t raw_dff(uint32_t res, unsigned side, uint32_t i, uint32_t j, unsigned sh)
{
    uint64_t a = 2u * i + 1u, h = side ? res - 2u * j - 1u : 2u * j + 1u;
    uint64_t n = a * a + h * h + (uint64_t)res * res;
    uint64_t v = ((uint64_t)1 << 62) / (n * n);
    if (side) v = v * h / res;
    return v >> sh;
}

void rad__dff_table(uint32_t res, rad_ff_t *top, rad_ff_t *side)
{
    uint32_t q = res / 2u, n = q * q, k, extra_side, extra_top;
    unsigned sh, b = rad__bitlen64(raw_dff(res, 0, 0, 0, 0));
    uint64_t sum = 0, fsum = 0, deficit;

    /* Keep raw values below 2^32 so raw * 2^28 fits in 64 bits. */
    sh = b > 32 ? b - 32 : 0;
    for (k = 0; k < n; k++)
        sum += raw_dff(res, 0, k % q, k / q, sh) + 2u * raw_dff(res, 1, k % q, k / q, sh);
    /* The four top quadrants plus eight side quadrants sum to 2^30: one top quadrant
     * plus two side quadrants to 2^28. Floors lose less than one per entry; give the
     * deficit back one unit at a time (two per side entry), so the sum is exact. */
    for (k = 0; k < n; k++)
        fsum += (raw_dff(res, 0, k % q, k / q, sh) << 28) / sum +
                2u * ((raw_dff(res, 1, k % q, k / q, sh) << 28) / sum);
    deficit = ((uint64_t)1 << 28) - fsum;
    extra_side = (uint32_t)(deficit / 2u < n ? deficit / 2u : n);
    extra_top = (uint32_t)(deficit - 2u * (uint64_t)extra_side);
    for (k = 0; k < n; k++) {
        uint64_t t = (raw_dff(res, 0, k % q, k / q, sh) << 28) / sum + (k < extra_top);
        uint64_t d = (raw_dff(res, 1, k % q, k / q, sh) << 28) / sum + (k < extra_side);
        top[k] = rad__ff_from_q30((uint32_t)t);
        side[k] = rad__ff_from_q30((uint32_t)d);
    }
}

int rad__hemicube_init(rad_scene_t *s)
{
    uint32_t res = s->cfg.res, q = res / 2u, k;
    uint32_t nacc = s->pools.max_elements > s->pools.max_vertices ? s->pools.max_elements
                                                                  : s->pools.max_vertices;
    uintptr_t base = (uintptr_t)s->pools.work, start = (base + 7u) & ~(uintptr_t)7u;
    size_t fixed = res * sizeof(uint32_t) + (2u * (size_t)q * q + nacc) * sizeof(rad_ff_t), avail,
           pixels, band;

    if (s->pools.work_bytes < (size_t)(start - base) + fixed) return RAD_ERR_WORK;
    avail = s->pools.work_bytes - (size_t)(start - base) - fixed;
    pixels = avail / (sizeof(uint32_t) + sizeof(rad_index_t));
    if (s->cfg.band_rows == 0 && pixels >= RAD_PIXELS_ALL(res)) {
        s->band_rows = 0;
        s->pass_pixels = RAD_PIXELS_ALL(res);
    } else {
        band = pixels / res;
        if (band > 3u * res) band = 3u * res; /* a band may span faces */
        if (s->cfg.band_rows && band > s->cfg.band_rows) band = s->cfg.band_rows;
        if (band == 0) return RAD_ERR_WORK;
        s->band_rows = (uint16_t)band;
        s->pass_pixels = (uint32_t)(band * res);
    }
    s->steps = (uint32_t *)start;
    s->dff_top = (rad_ff_t *)(void *)(s->steps + res);
    s->dff_side = s->dff_top + (size_t)q * q;
    s->acc = s->dff_side + (size_t)q * q;
    s->zbuf = (uint32_t *)(s->acc + nacc);
    s->ibuf = (rad_index_t *)(s->zbuf + s->pass_pixels);
    rad__dff_table(res, s->dff_top, s->dff_side);
    for (k = 0; k < res; k++) s->steps[k] = 0; /* once: every span leaves it zero */
    s->cube_res = s->cfg.res;
    s->cube_top = s->dff_top;
    s->cube_side = s->dff_side;
    s->cube_built = 0;
    return RAD_OK;
}

/* ---- coarse shots (rad_config_t.coarse) ---------------------------------------- */

/* A coarse cube's tables follow the pixels of a level-1 cube in the depth buffer (the
 * most any coarse cube draws): 3 res^2 / 4 words, then at most 2 (res / 4)^2 words of
 * tables, within the 3 res^2 words it holds with all faces in one pass. */
static rad_ff_t *coarse_tables(const rad_scene_t *s)
{
    return (rad_ff_t *)(void *)(s->zbuf + RAD_PIXELS_ALL(s->cfg.res / 2u));
}

/* The sums of the M x M blocks of quadrant table IN (Q x Q, row after row from the
 * cube's centre out) into OUT ((Q / M)^2, the same layout): pixel (i, j) of the cube
 * at res / M covers pixels (M i .. M i + M - 1, M j .. M j + M - 1) of the cube at
 * res, counted from the centre as both tables are. */
static void block_sums(const rad_ff_t *in, uint32_t q, uint32_t m, rad_ff_t *out)
{
    uint32_t qc = q / m, i, j, a, b;
    for (j = 0; j < qc; j++)
        for (i = 0; i < qc; i++) {
            rad_ff_t sum = 0;
            for (b = 0; b < m; b++)
                for (a = 0; a < m; a++) sum += in[(size_t)(j * m + b) * q + i * m + a];
            out[(size_t)j * qc + i] = sum;
        }
}

/* The deepest level at most LEVEL that S allows: its cube at least the floor
 * (coarse_res, else res / 4, and 8) and res / 2 made of whole 2^level blocks; 0 with
 * bands (the depth buffer holds no tail). */
static unsigned allowed_level(const rad_scene_t *s, unsigned level)
{
    uint32_t res = s->cfg.res, floor = s->cfg.coarse_res ? s->cfg.coarse_res : res / 4u;
    unsigned l;
    if (s->band_rows != 0) return 0;
    if (floor < 8u) floor = 8u;
    for (l = 0; l < level; l++)
        if ((res >> (l + 1u)) < floor || (res / 2u) % (2u << l) != 0) break;
    return l;
}

unsigned rad__cube_level(rad_scene_t *s, unsigned level)
{
    uint32_t q = s->cfg.res / 2u, m;
    level = allowed_level(s, level);
    m = 1u << level;
    s->cube_res = (uint16_t)(s->cfg.res >> level);
    if (level == 0) {
        s->cube_top = s->dff_top;
        s->cube_side = s->dff_side;
        return 0;
    }
    s->cube_top = coarse_tables(s);
    s->cube_side = s->cube_top + (size_t)(q / m) * (q / m);
    if (s->cube_built != level) {
        block_sums(s->dff_top, q, m, s->cube_top);
        block_sums(s->dff_side, q, m, s->cube_side);
        s->cube_built = (uint16_t)level;
    }
    return level;
}

/* ---- passes -------------------------------------------------------------------- */

/* The regions of rows [A, B) of the cube's rows, face after face (the top's res, then
 * the four sides' res / 2 each: 3 res rows of res pixels), into R; each region's
 * offset is its first pixel's in that layout less BASE. Returns how many (<= 5). Every
 * row falls in one region, in the layout's order. */
static unsigned row_regions(const rad_scene_t *s, uint32_t a, uint32_t b, uint32_t base,
                            region_t *r)
{
    uint32_t res = s->cube_res, g = 0, f, n = 0;
    for (f = 0; f < 5; f++) {
        uint32_t rows = face_rows(s, f), lo = a > g ? a - g : 0u, hi = b - g < rows ? b - g : rows;
        if (b > g && lo < hi && lo < rows) {
            r[n].face = f;
            r[n].row0 = (int)lo;
            r[n].row1 = (int)hi;
            r[n].offset = face_offset(s, f) + lo * res - base;
            n++;
        }
        g += rows;
    }
    return n;
}

/* The regions rendered in pass K: all five faces at once, or band K of the layout's
 * rows (row_regions: a band may end in one face and go on in the next, so at res 16 in
 * bands of 16 rows the four half sides take two passes, not four, and the surfaces are
 * set up three times a cube instead of five); returns how many, 0 past the last pass.
 * Pixels are accumulated in the same order either way. */
static unsigned pass_regions(const rad_scene_t *s, unsigned k, region_t *r)
{
    uint32_t band = s->band_rows, res = s->cube_res, a = (uint32_t)k * band;
    if (band == 0) return k ? 0u : row_regions(s, 0, 3u * res, 0, r);
    if (a >= 3u * res) return 0;
    return row_regions(s, a, a + band < 3u * res ? a + band : 3u * res, a * res, r);
}

/* The faces look along +z, +x, -x, +y, -y (and a full cube's sixth, -z): their axes a
 * (across), b (up) and d (depth) are the cube's axes x, y, z (0, 1, 2) of
 * rad__face_axis, times rad__face_sign. */
const unsigned char rad__face_axis[6][3] = {{0, 1, 2}, {1, 2, 0}, {1, 2, 0},
                                            {0, 2, 1}, {0, 2, 1}, {0, 1, 2}};
const signed char rad__face_sign[6][3] = {{1, 1, 1}, {1, 1, 1},  {1, 1, -1},
                                          {1, 1, 1}, {1, 1, -1}, {1, 1, -1}};

static rad_real_t axis(rad_vec3_t l, unsigned face, unsigned k)
{
    unsigned a = rad__face_axis[face][k];
    rad_real_t v = a == 0 ? l.x : a == 1 ? l.y : l.z;
    return rad__face_sign[face][k] < 0 ? -v : v;
}

/* A point in the cube's frame in the face's view space. */
static void face_vertex(unsigned face, rad_vec3_t l, rad__cvert_t *c)
{
    c->a = axis(l, face, 0);
    c->b = axis(l, face, 1);
    c->d = axis(l, face, 2);
    c->c[0] = c->c[1] = c->c[2] = 0;
}

/* The outcodes of a vertex in the cube's frame for all five faces at once, bits
 * 5 f + p: plane p of face f as rad__outcodes numbers them (d < near, a > d, -a > d,
 * b > d, then -b > d on the top face or b < 0 on the sides), with slopes 1, so no
 * multiply is needed. */
static uint32_t cube_codes(rad_vec3_t l)
{
    const rad_real_t x = l.x, y = l.y, z = l.z;
    uint32_t below = (uint32_t)(z < 0) << 4;
    uint32_t top = (uint32_t)(z < RAD__NEAR) | (uint32_t)(x > z) << 1 | (uint32_t)(-x > z) << 2 |
                   (uint32_t)(y > z) << 3 | (uint32_t)(-y > z) << 4;
    uint32_t px = (uint32_t)(x < RAD__NEAR) | (uint32_t)(y > x) << 1 | (uint32_t)(-y > x) << 2 |
                  (uint32_t)(z > x) << 3 | below;
    uint32_t nx = (uint32_t)(-x < RAD__NEAR) | (uint32_t)(y > -x) << 1 | (uint32_t)(-y > -x) << 2 |
                  (uint32_t)(z > -x) << 3 | below;
    uint32_t py = (uint32_t)(y < RAD__NEAR) | (uint32_t)(x > y) << 1 | (uint32_t)(-x > y) << 2 |
                  (uint32_t)(z > y) << 3 | below;
    uint32_t ny = (uint32_t)(-y < RAD__NEAR) | (uint32_t)(x > -y) << 1 | (uint32_t)(-x > -y) << 2 |
                  (uint32_t)(z > -y) << 3 | below;
    return top | px << 5 | nx << 10 | py << 15 | ny << 20;
}

/* The same for a full cube's six faces, bits 5 f + p, whose side faces are whole (plane
 * 4 is -b > d on every face): each face's planes tested on its own axes. */
static uint32_t full_codes(rad_vec3_t l)
{
    uint32_t codes = 0;
    unsigned f;
    for (f = 0; f < 6; f++) {
        rad_real_t a = axis(l, f, 0), b = axis(l, f, 1), d = axis(l, f, 2);
        uint32_t c = (uint32_t)(d < RAD__NEAR) | (uint32_t)(a > d) << 1 | (uint32_t)(-a > d) << 2 |
                     (uint32_t)(b > d) << 3 | (uint32_t)(-b > d) << 4;
        codes |= c << (5u * f);
    }
    return codes;
}

/* Where a pass draws: the face buffers (region offsets index into them) of a cube of
 * resolution RES, a full cube (six whole faces) when FULL. */
typedef struct {
    uint32_t *z;
    rad_index_t *ids;
    uint32_t *steps;
    rad_stats_t *st;
    uint32_t res;
    int full;
} canvas_t;

/* One pass of a cube: its centre C and frame, the regions drawn, and the surface not
 * drawn (the shooter's own; any value past the last surface: none), nor those joined
 * to patch GROUP (the shooter's group, rad_join_polygon, which stands for one flat
 * patch: from its centre off a curved group's faces it would light itself). BACKS:
 * surfaces seen from behind are drawn as occluders that show nothing (a gather's
 * cube), else left out (a shot's). */
typedef struct {
    rad_vec3_t c;
    const rad_vec3_t *frame;
    const region_t *reg;
    unsigned nreg;
    uint32_t skip, group;
    int backs, by_index; /* BY_INDEX: every surface drawn by its index (rad__eye_surface) */
} pass_t;

/* The frustum of region R's face and the target of its rows. */
static void region_view(const canvas_t *cv, const region_t *r, rad__frustum_t *f, rad__target_t *t)
{
    f->half = r->face != 0 && !cv->full;
    f->ortho = 0;
    f->recede = 0;
    f->width = (int)cv->res;
    f->height = (int)rows_of(cv->res, cv->full, r->face);
    t->z = cv->z + r->offset;
    t->ids = cv->ids + r->offset;
    t->rgb = 0;
    t->lat = 0;
    t->steps = cv->steps;
    t->width = (int)cv->res;
    t->row0 = r->row0;
    t->row1 = r->row1;
    t->least = 0;
}

/* Surface SF into the pass's regions: its outline drawn once a face, each pixel given
 * the element of its lattice it sees (one element: that one). */
static void render_surface(const rad_scene_t *s, const canvas_t *cv, const pass_t *ps,
                           const rad_surface_t *sf)
{
    uint32_t k[4], all = cv->full ? 0x3FFFFFFFu : 0x1FFFFFFu, any = 0;
    rad_vec3_t loc[4];
    rad__cvert_t cvt[4];
    rad__lattice_t lat;
    unsigned i, r, n = rad__surface_corners(s, sf, k), grid, front = 0;
    rad_index_t id;

    /* Facing away at every corner (a quad may be planar only within rounding): seen
     * from behind. Radiosity is one-sided, so its back is black; a gather's cube draws
     * it as an opaque occluder showing nothing (ids RAD_INDEX_NONE), so that a point
     * under a panel lit from above is in its shadow as the lamp's shots left it. */
    for (i = 0; i < n; i++)
        front |= rad__dot_unit(rad__sub(ps->c, s->pools.vertices[k[i]]), sf->normal) > 0;
    if (!front && !ps->backs) return;
    if (ps->by_index) front = 0; /* its depths alone, whichever side */
    grid = front && sf->n_elements > 1;
    id = front ? (rad_index_t)rad__group_element(s, sf, sf->first_element) : RAD_INDEX_NONE;
    if (ps->by_index) id = (rad_index_t)(sf - s->pools.surfaces); /* < max_surfaces < NONE */
    for (i = 0; i < n; i++) {
        rad_vec3_t d = rad__sub(s->pools.vertices[k[i]], ps->c);
        uint32_t code;
        loc[i].x = rad__dot_unit(d, ps->frame[0]);
        loc[i].y = rad__dot_unit(d, ps->frame[1]);
        loc[i].z = rad__dot_unit(d, ps->frame[2]);
        code = cv->full ? full_codes(loc[i]) : cube_codes(loc[i]);
        all &= code;
        any |= code;
    }
    for (r = 0; r < ps->nreg; r++) {
        unsigned f = ps->reg[r].face;
        rad__frustum_t fr;
        rad__target_t t;
        if ((all >> (5 * f)) & 0x1F) continue; /* wholly outside this face */
        region_view(cv, &ps->reg[r], &fr, &t);
        t.least = ps->by_index;
        if (grid) {
            /* set up on the first face that draws it */
            if (grid == 1) rad__lattice_init(&lat, sf, loc, n, (int32_t)cv->res);
            grid = 2;
            rad__lattice_face(&lat, rad__face_axis[f], rad__face_sign[f]);
            t.lat = &lat;
        }
        for (i = 0; i < n; i++) face_vertex(f, loc[i], &cvt[i]);
        rad__draw(cv->st, &t, &fr, cvt, n, (any >> (5 * f)) & 0x1F, id);
    }
}

/* Whether half row H (its first pixel / (res / 2), over the layout of all five faces)
 * may hold an element of [E0, E0 + N): by its smallest and largest id in BOUNDS, or
 * always (BOUNDS null). */
static int half_row_has(const uint32_t *bounds, uint32_t h, uint32_t e0, uint32_t n)
{
    return !bounds || (bounds[2u * h + 1u] >= e0 && bounds[2u * h] < e0 + n);
}

/* Adds each pixel's delta form factor in region REG of the item buffer IBUF (laid out
 * as the work buffer's) to its element's sum in ACC (a parameter, not s->acc: a store
 * through it cannot change it), for the elements [E0, E0 + N), skipping
 * the half rows BOUNDS rules out (see half_row_has). */
static void accumulate(const rad_scene_t *s, rad_ff_t *acc, const rad_index_t *ibuf,
                       const region_t *reg, uint32_t e0, uint32_t n, const uint32_t *bounds)
{
    uint32_t res = s->cube_res, q = res / 2u, i, h;
    int r;
    if (q == 0) return; /* rad_init keeps res >= 8: for the analyzer, which cannot see it */
    /* h, the row's first half row: offsets are whole rows, so each row adds two */
    for (r = reg->row0, h = reg->offset / q; r < reg->row1; r++, h += 2u) {
        uint32_t px = reg->offset + (uint32_t)(r - reg->row0) * res;
        const rad_index_t *ids = ibuf + px;
        const rad_ff_t *row = rad__dff_row(s->cube_top, s->cube_side, res, reg->face, (uint32_t)r);
        /* ids[i] - e0 wraps past N below E0 (and RAD_INDEX_NONE is above every range) */
        if (half_row_has(bounds, h, e0, n))
            for (i = 0; i < q; i++)
                if ((uint32_t)(ids[i] - e0) < n) acc[ids[i]] += row[q - 1u - i];
        if (half_row_has(bounds, h + 1u, e0, n))
            for (i = q; i < res; i++)
                if ((uint32_t)(ids[i] - e0) < n) acc[ids[i]] += row[i - q];
    }
}

/* The smallest and largest element id of each half row of region REG of the item
 * buffer IDS into BOUNDS (two per half row, indexed as in half_row_has; an empty half
 * row gets smallest > largest). Skipping the half rows without its elements, a merge
 * of a run of elements reads little more than its own pixels. */
static void half_row_bounds(const rad_scene_t *s, const rad_index_t *ids, const region_t *reg,
                            uint32_t *bounds)
{
    uint32_t q = s->cube_res / 2u, n = s->n_elements, px, i, h;
    uint32_t end = reg->offset + (uint32_t)(reg->row1 - reg->row0) * s->cube_res;
    if (q == 0) return; /* as in accumulate */
    for (px = reg->offset, h = reg->offset / q; px < end; px += q, h++) {
        uint32_t lo = 0xFFFFFFFFu, hi = 0;
        for (i = px; i < px + q; i++) {
            uint32_t id = ids[i];
            if (id < n) {
                lo = id < lo ? id : lo;
                hi = id > hi ? id : hi;
            }
        }
        bounds[2u * h] = lo;
        bounds[2u * h + 1u] = hi;
    }
}

static void clear_region(const canvas_t *cv, const region_t *reg)
{
    uint32_t i, n = (uint32_t)(reg->row1 - reg->row0) * cv->res;
    uint32_t *z = cv->z + reg->offset;
    rad_index_t *ids = cv->ids + reg->offset;
    /* Eight at a time, which compilers turn into wide stores. */
    for (i = 0; i + 8u <= n; i += 8u) {
        z[i] = z[i + 1] = z[i + 2] = z[i + 3] = z[i + 4] = z[i + 5] = z[i + 6] = z[i + 7] = 0;
        ids[i] = ids[i + 1] = ids[i + 2] = ids[i + 3] = RAD_INDEX_NONE;
        ids[i + 4] = ids[i + 5] = ids[i + 6] = ids[i + 7] = RAD_INDEX_NONE;
    }
    for (; i < n; i++) {
        z[i] = 0;
        ids[i] = RAD_INDEX_NONE;
    }
}

/* Turns of the hemi-cube about its normal, as exact rational rotations (Pythagorean
 * triples a^2 + b^2 = c^2). Polygon edges parallel to the pixel grid alias by up to
 * half a pixel column along their whole length; turning the cube by an odd angle, and
 * by a different one for neighbouring shooters, spreads that error so it averages out.
 * The turn depends on the patch alone, not on when it shoots, so the result does not
 * depend on the order of shots among patches of equal power. */
static const uint8_t spins[8][3] = {{3, 4, 5},    {12, 5, 13},  {8, 15, 17}, {24, 7, 25},
                                    {20, 21, 29}, {35, 12, 37}, {9, 40, 41}, {45, 28, 53}};

void rad__cube_frame(rad_vec3_t n, unsigned spin, rad_vec3_t *frame)
{
    rad_vec3_t helper = {0, 0, 0}, u0, v0;
    const uint8_t *t = spins[spin % 8u];
    /* A tangent frame from the axis least aligned with the normal, then turned. */
    if ((n.x < 0 ? -n.x : n.x) < RAD__Q(0.57))
        helper.x = RAD__ONE;
    else
        helper.y = RAD__ONE;
    rad__normalize(rad__cross(n, helper), &u0);
    v0 = rad__cross(n, u0);
    frame[0] = rad__turn(u0, v0, t[0], t[1], t[2]);
    frame[1] = rad__cross(n, frame[0]);
    frame[2] = n;
}

/* Surface K into PS's regions unless it is PS's skipped one or joined to its group. */
static void render_one(const rad_scene_t *s, const canvas_t *cv, const pass_t *ps, uint32_t k)
{
    const rad_surface_t *sf = &s->pools.surfaces[k];
    if (k != ps->skip && (sf->n_patches != 0 || sf->first_patch != ps->group))
        render_surface(s, cv, ps, sf);
}

/* Every surface but PS's skipped one into PS's regions. */
static void render_view(const rad_scene_t *s, const canvas_t *cv, const pass_t *ps)
{
    uint32_t k;
    for (k = 0; k < s->n_surfaces; k++) render_one(s, cv, ps, k);
}

/* Every surface but the shooter's own into the regions, seen from patch P's centre
 * through its cube's frame. */
static void render_scene(const rad_scene_t *s, const canvas_t *cv, const region_t *reg,
                         unsigned nreg, uint32_t p)
{
    const rad_patch_t *pt = &s->pools.patches[p];
    rad_vec3_t frame[3];
    pass_t ps;
    rad__cube_frame(s->pools.surfaces[pt->surface].normal, p, frame);
    ps.c = pt->center;
    ps.frame = frame;
    ps.reg = reg;
    ps.nreg = nreg;
    ps.skip = pt->surface;
    ps.group = p;
    ps.backs = 0;
    ps.by_index = 0;
    render_view(s, cv, &ps);
}

/* The scene's own cube's canvas over face buffers Z, IDS and a row of STEPS. */
static canvas_t scene_canvas(const rad_scene_t *s, uint32_t *z, rad_index_t *ids, uint32_t *steps,
                             rad_stats_t *st)
{
    canvas_t cv;
    cv.z = z;
    cv.ids = ids;
    cv.steps = steps;
    cv.st = st;
    cv.res = s->cube_res;
    cv.full = 0;
    return cv;
}

/* Face FACE of E's cube as a canvas, its one region and a pass (BY_INDEX as pass_t's). */
static void eye_pass(const rad__eye_t *e, unsigned face, int by_index, canvas_t *cv, region_t *reg,
                     pass_t *ps)
{
    cv->z = e->z;
    cv->ids = e->ids;
    cv->steps = e->steps;
    cv->st = e->st;
    cv->res = e->res;
    cv->full = e->full;
    reg->face = face;
    reg->row0 = 0;
    reg->row1 = (int)rows_of(e->res, e->full, face);
    reg->offset = 0;
    ps->c = e->c;
    ps->frame = e->frame;
    ps->reg = reg;
    ps->nreg = 1;
    ps->skip = e->skip;
    ps->group = e->group;
    ps->backs = e->backs;
    ps->by_index = by_index;
}

void rad__eye_clear(const rad__eye_t *e, unsigned face)
{
    canvas_t cv;
    region_t reg;
    pass_t ps;
    eye_pass(e, face, 0, &cv, &reg, &ps);
    clear_region(&cv, &reg);
}

void rad__eye_surface(const rad_scene_t *s, const rad__eye_t *e, unsigned face, uint32_t k,
                      int by_index)
{
    canvas_t cv;
    region_t reg;
    pass_t ps;
    eye_pass(e, face, by_index, &cv, &reg, &ps);
    render_one(s, &cv, &ps, k);
}

void rad__eye_face(const rad_scene_t *s, const rad__eye_t *e, unsigned face)
{
    canvas_t cv;
    region_t reg;
    pass_t ps;
    eye_pass(e, face, 0, &cv, &reg, &ps);
    clear_region(&cv, &reg);
    render_view(s, &cv, &ps);
}

int rad__eye_pixel(const rad__eye_t *e, rad_vec3_t w, uint32_t *face, uint32_t *px, uint32_t *depth)
{
    rad_vec3_t l;
    rad_real_t m[3], lk;
    rad__cvert_t c;
    rad__frustum_t f;
    uint32_t x, y;
    unsigned k = 0, f0;
    l.x = rad__dot_unit(w, e->frame[0]);
    l.y = rad__dot_unit(w, e->frame[1]);
    l.z = rad__dot_unit(w, e->frame[2]);
    m[0] = l.x < 0 ? -l.x : l.x;
    m[1] = l.y < 0 ? -l.y : l.y;
    m[2] = l.z < 0 ? -l.z : l.z;
    /* the face whose axis is the largest component's (ties: the lower axis) */
    if (m[1] > m[k]) k = 1;
    if (m[2] > m[k]) k = 2;
    lk = k == 0 ? l.x : k == 1 ? l.y : l.z;
    for (f0 = 0; f0 < 6; f0++)
        if (rad__face_axis[f0][2] == k && (rad__face_sign[f0][2] < 0) == (lk < 0)) break;
    if (f0 == 5 && !e->full) return 0;
    face_vertex(f0, l, &c);
    f.half = f0 != 0 && !e->full;
    f.ortho = 0;
    f.recede = 0;
    f.width = (int)e->res;
    f.height = (int)rows_of(e->res, e->full, f0);
    if (!rad__pixel(&f, &c, &x, &y, depth)) return 0;
    *face = f0;
    *px = y * e->res + x;
    return 1;
}

/* Patch P's cube into the five faces of canvas CV (laid out as all five: face_offset)
 * through the scene's hierarchy (rad_shoot_cull), WORK (BYTES long, 4-aligned) the
 * culling's: the nodes it tested, or RAD__DRAWN_ALL without drawing when there is no
 * hierarchy, it was built for another scene, WORK is too small or the shots wait
 * (cull_wait). Face after face, as a gather's cube: the pixels of render_scene over
 * the five regions (the lattice and depths of a surface do not depend on the faces
 * drawn with it). */
static uint32_t cull_scene(const rad_scene_t *s, const canvas_t *cv, uint32_t p, uint32_t *work,
                           size_t bytes)
{
    const rad_patch_t *pt = &s->pools.patches[p];
    rad__eye_t e;
    uint64_t tests = 0;
    unsigned f;
    if (!s->cull || s->cull_wait || !rad__cull_fits(s, s->cull) ||
        bytes < rad__cull_work(s->cull, cv->res))
        return RAD__DRAWN_ALL;
    rad__cube_frame(s->pools.surfaces[pt->surface].normal, p, e.frame);
    e.c = pt->center;
    e.res = cv->res;
    e.skip = pt->surface;
    e.group = p;
    e.full = 0;
    e.backs = 0;
    e.steps = cv->steps;
    e.st = cv->st;
    e.cull = s->cull;
    e.cwork = work;
    rad__cull_edges(cv->res, work);
    for (f = 0; f < 5; f++) {
        e.z = cv->z + face_offset(s, f);
        e.ids = cv->ids + face_offset(s, f);
        tests += rad__cull_face(s, &e, f);
    }
    return tests < RAD__DRAWN_ALL ? (uint32_t)tests : RAD__DRAWN_ALL - 1u;
}

/* When to draw every surface again. Drawing all costs in proportion to the surfaces,
 * culling to the nodes tested: on the level of rad_bench --level (62,296 surfaces, res
 * 48 and 96, x86-64) its shots 300 to 3,300, culled, tested 30,652 nodes a cube and
 * took 5.8 ms a shot, against 4.2 ms drawing all (1.4 times as long: 189 ns a node
 * tested, 67 a surface drawn all); its first 300 (roofs under the sky) tested 979 and
 * took 0.76 ms against 3.1. So a culled cube that tested more nodes than a third of the
 * surfaces' count cost more than drawing all would have: CULL_WAIT shots then draw
 * every surface before one tries the hierarchy again. In grids of closed rooms a cube
 * tests 500 to 900 nodes, whatever the rooms' count. */
#define CULL_SHARE 3u
#define CULL_WAIT  16u

void rad__cull_after(rad_scene_t *s, int culled, uint64_t tests, uint32_t cubes)
{
    if (!culled)
        s->cull_wait = (uint16_t)(s->cull_wait > cubes ? s->cull_wait - cubes : 0u);
    else if (tests * CULL_SHARE > (uint64_t)cubes * s->n_surfaces)
        s->cull_wait = CULL_WAIT;
}

void rad__shot_cube(rad_scene_t *s, uint32_t p)
{
    region_t reg[5];
    canvas_t cv = scene_canvas(s, s->zbuf, s->ibuf, s->steps, &s->stats);
    unsigned k, nreg, r;
    uint32_t e, tests = RAD__DRAWN_ALL;

    /* A cube at res draws over a coarse cube's tables. */
    if (s->cube_res == s->cfg.res) s->cube_built = 0;
    /* all five faces in one pass, the form factor sums the culling's work till then */
    if (s->band_rows == 0)
        tests = cull_scene(s, &cv, p, (uint32_t *)(void *)s->acc,
                           (size_t)s->n_elements * sizeof *s->acc);
    rad__cull_after(s, tests != RAD__DRAWN_ALL, tests, 1);
    for (e = 0; e < s->n_elements; e++) s->acc[e] = 0;
    for (k = 0; (nreg = pass_regions(s, k, reg)) != 0; k++) {
        if (tests == RAD__DRAWN_ALL) {
            for (r = 0; r < nreg; r++) clear_region(&cv, &reg[r]);
            render_scene(s, &cv, reg, nreg, p);
        }
        for (r = 0; r < nreg; r++) accumulate(s, s->acc, s->ibuf, &reg[r], 0, s->n_elements, 0);
    }
}

void rad__hemicube(rad_scene_t *s, uint32_t p)
{
    rad__cube_level(s, 0);
    rad__shot_cube(s, p);
}

/* ---- one shot's hemi-cube in parts, for threads in the caller ------------------ */

/* A part's buffer: its head, a row of id steps, then depth and ids laid out as all
 * five faces. RAD_PART_BYTES counts RAD__PART_HEAD bytes for the head. */
typedef char rad__part_head_fits[sizeof(rad__part_head_t) <= RAD__PART_HEAD &&
                                         RAD__PART_HEAD % 8u == 0 &&
                                         RAD_PART_BYTES(0) == RAD__PART_HEAD
                                     ? 1
                                     : -1];

static uint32_t *part_steps(void *buf)
{
    return (uint32_t *)(void *)((unsigned char *)buf + RAD__PART_HEAD);
}
static uint32_t *part_z(const rad_scene_t *s, void *buf)
{
    return (uint32_t *)(void *)(part_steps(buf) + s->cfg.res);
}
static rad_index_t *part_ids(const rad_scene_t *s, void *buf)
{
    return (rad_index_t *)(void *)(part_z(s, buf) + RAD_PIXELS_ALL(s->cube_res));
}

/* The part's canvas in BUF, its steps zeroed. */
static canvas_t part_canvas(const rad_scene_t *s, void *buf)
{
    canvas_t cv = scene_canvas(s, part_z(s, buf), part_ids(s, buf), part_steps(buf), 0);
    uint32_t i;
    for (i = 0; i < s->cube_res; i++) cv.steps[i] = 0;
    return cv;
}

/* Rendering cost of a row of the top face and of a side face, relative: a top row costs
 * about 1.6 side rows, as measured from two parts' processor times on the bundled box
 * and CornellBox-Original (commit 3d127f3 has the figures). The weights only balance
 * the parts' work: where the cut falls never changes a bit. */
#define TOP_ROW_COST  16u
#define SIDE_ROW_COST 10u

/* The row (of the 3 res, face after face) where cut K of NPARTS falls: at equal shares
 * of the rows' cost. */
static uint32_t part_cut(uint32_t res, unsigned k, unsigned nparts)
{
    uint64_t top = (uint64_t)TOP_ROW_COST * res, total = top + (uint64_t)SIDE_ROW_COST * 2u * res;
    uint64_t x = total * k / nparts;
    return (uint32_t)(x <= top ? x / TOP_ROW_COST : res + (x - top) / SIDE_ROW_COST);
}

/* The regions of part PART of NPARTS: the cube's rows cut into NPARTS runs of equal
 * cost (part_cut: 0 and 3 res at the ends, in order), laid out as all five faces.
 * Every pixel belongs to one part, and accumulating the parts in order adds in the
 * serial pass's order. */
static unsigned part_regions(const rad_scene_t *s, unsigned part, unsigned nparts, region_t *r)
{
    uint32_t res = s->cube_res;
    return row_regions(s, part_cut(res, part, nparts), part_cut(res, part + 1u, nparts), 0, r);
}

int rad__cube_part(const rad_scene_t *s, uint32_t p, unsigned part, unsigned nparts, void *buf)
{
    region_t reg[5];
    rad_stats_t st = {0};
    canvas_t cv = part_canvas(s, buf);
    rad__part_head_t *h = (rad__part_head_t *)buf;
    unsigned r, nreg = part_regions(s, part, nparts, reg);

    cv.st = &st;
    for (r = 0; r < nreg; r++) clear_region(&cv, &reg[r]);
    if (nreg) render_scene(s, &cv, reg, nreg, p);
    /* The depth buffer is done with: it keeps the bounds (12 res words of 3 res^2). */
    for (r = 0; r < nreg; r++) half_row_bounds(s, cv.ids, &reg[r], cv.z);
    h->calls = st.raster_calls;
    h->pixels = st.raster_pixels;
    h->shot = s->shot_serial;
    h->part = part;
    h->nparts = nparts;
    h->state = RAD__PART_RENDERED;
    return (int)st.raster_calls;
}

void rad__cube_merge(rad_scene_t *s, void *const *bufs, unsigned nparts, uint32_t e0, uint32_t e1)
{
    region_t reg[5];
    uint32_t e;
    unsigned k, r, nreg;
    for (e = e0; e < e1; e++) s->acc[e] = 0;
    for (k = 0; k < nparts; k++) {
        nreg = part_regions(s, k, nparts, reg);
        for (r = 0; r < nreg; r++)
            accumulate(s, s->acc, part_ids(s, bufs[k]), &reg[r], e0, e1 - e0, part_z(s, bufs[k]));
    }
}

/* ---- a batch's cube (rad_batch_render) ----------------------------------------- */

void rad__cube_lists(const rad_scene_t *s, void *buf, rad_index_t **ids, rad_ff_t **ffs)
{
    *ids = part_ids(s, buf);
    *ffs = (rad_ff_t *)(void *)part_z(s, buf);
}

uint32_t rad__cube_list(const rad_scene_t *s, uint32_t p, void *buf, rad_ff_t *acc)
{
    region_t reg[5];
    rad_stats_t st = {0};
    canvas_t cv = part_canvas(s, buf);
    rad__part_head_t *h = (rad__part_head_t *)buf;
    unsigned r, nreg = part_regions(s, 0, 1, reg);
    uint32_t e, n = 0, cap = RAD_PIXELS_ALL(s->cube_res);
    rad_index_t *ids;
    rad_ff_t *ffs;

    cv.st = &st;
    /* ACC the culling's work till the sums begin */
    h->tests = cull_scene(s, &cv, p, (uint32_t *)(void *)acc, (size_t)s->n_elements * sizeof *acc);
    if (h->tests == RAD__DRAWN_ALL) {
        for (r = 0; r < nreg; r++) clear_region(&cv, &reg[r]);
        render_scene(s, &cv, reg, nreg, p);
    }
    for (e = 0; e < s->n_elements; e++) acc[e] = 0;
    for (r = 0; r < nreg; r++) accumulate(s, acc, cv.ids, &reg[r], 0, s->n_elements, 0);
    /* The pixels are done with. Each element listed covers a pixel at least, so the
     * list fits in the item buffer (ids) and the depth buffer (sums, a word each). */
    rad__cube_lists(s, buf, &ids, &ffs);
    /* Without a branch (which elements a cube sees is a coin's toss to the predictor):
     * each element is written at N and kept by counting it. N < CAP while an element is
     * written; at CAP every pixel's element is listed, none is left. */
    for (e = 0; e < s->n_elements && n < cap; e++) {
        ids[n] = (rad_index_t)e;
        ffs[n] = acc[e];
        n += acc[e] > 0;
    }
    h->calls = st.raster_calls;
    h->pixels = st.raster_pixels;
    h->shot = s->shot_serial;
    return n;
}
