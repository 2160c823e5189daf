/* SPDX-License-Identifier: MIT */
/* rad — scene set-up: pools, validation, and meshing polygons into patches (shooters)
 * and elements (receivers) on a shared per-surface vertex grid (Cohen, Greenberg,
 * Immel & Brock 1986's patch/element substructuring).
 *
 * A quad becomes a bilinear grid of nu x nv elements grouped into pu x pv patches of
 * ku x kv elements; a triangle becomes n^2 similar triangles on a barycentric lattice,
 * grouped into np^2 patches of k^2 elements. Counts are checked against the pools
 * before anything is written, so a full pool changes nothing.
 */
#include "internal.h"

#define MIN_AREA         RAD__Q(1.0 / 4096.0)  /* smallest surface accepted, in units^2 */
#define MIN_SMALL        RAD__Q(1.0 / 65536.0) /* with RAD_SMALL_FACES, for reflectors (rad.h) */
#define MIN_ELEMENT      RAD__Q(1.0 / 65536.0) /* smallest max_element setting: 1 LSB */
#define MAX_SETTING      RAD__Q(2 * RAD_INPUT_LIMIT) /* largest max_element, max_patch */
/* Elements along a polygon's side: lattices of up to 2^15 a side keep every count of
 * rad_surface_t in 16-bit indices and the vertex count, (2^15 + 1)^2, in 32 bits. */
#define MAX_SIDE         32768u
/* The geometry's shift while it is added: down to 2^-7, for coordinates of up to
 * RAD_INPUT_LIMIT (2^13) within RAD_COORD_LIMIT (2^6). */
#define MIN_LENGTH_SHIFT (-7)
/* A group's area grows by less than MIN_AREA a join: below this it cannot overflow. */
#define MAX_GROUP_AREA   RAD__Q(16384.0)

static int in_range(rad_real_t v, rad_real_t lo, rad_real_t hi)
{
    return v >= lo && v <= hi;
}

static int rgb_ok(const rad_rgb_t *c, rad_real_t hi, int open_top)
{
    if (!c) return 1;
    if (open_top) return c->r >= 0 && c->r < hi && c->g >= 0 && c->g < hi && c->b >= 0 && c->b < hi;
    return in_range(c->r, 0, hi) && in_range(c->g, 0, hi) && in_range(c->b, 0, hi);
}

static int rgb_any(const rad_rgb_t *c)
{
    return c && (c->r > 0 || c->g > 0 || c->b > 0);
}

/* Defaults filled in and every setting checked, as rad_init and rad_plan_polygon use
 * them. Returns RAD_OK or RAD_ERR_ARG with *WHY naming the setting. */
static int resolve_config(rad_config_t *c, const char **why)
{
    if (c->res == 0) c->res = RAD_DEFAULT_RES;
    if (c->max_element == 0) c->max_element = RAD__Q(4.0);
    *why = "res not even within 8..RAD_MAX_RES";
    if (c->res < 8 || c->res > RAD_MAX_RES || (c->res & 1u)) return RAD_ERR_ARG;
    *why = "unknown flag, or band_rows with RAD_NO_BANDS";
    if (c->flags & ~(RAD_NO_OVERSHOOT | RAD_NO_BANDS | RAD_SMALL_FACES)) return RAD_ERR_ARG;
    if ((c->flags & RAD_NO_BANDS) && c->band_rows) return RAD_ERR_ARG;
    *why = "coarse negative, or coarse_res not 0 or even within 8..res";
    if (c->coarse < 0 ||
        (c->coarse_res && (c->coarse_res < 8 || c->coarse_res > c->res || (c->coarse_res & 1u))))
        return RAD_ERR_ARG;
    /* Checked before the default patch size is derived from it: 4 * max_element of an
     * out-of-range value would overflow. */
    *why = "max_element outside 2^-16..2 RAD_INPUT_LIMIT";
    if (!in_range(c->max_element, MIN_ELEMENT, MAX_SETTING)) return RAD_ERR_ARG;
    if (c->max_patch == 0)
        c->max_patch = c->max_element <= MAX_SETTING / 4 ? 4 * c->max_element : MAX_SETTING;
    *why = "max_patch outside max_element..2 RAD_INPUT_LIMIT";
    if (!in_range(c->max_patch, c->max_element, MAX_SETTING)) return RAD_ERR_ARG;
    return RAD_OK;
}

/* C99 has no alignof: a type's alignment is its offset after a char in a struct. */
typedef struct {
    char c;
    rad_surface_t t;
} align_surface_t;
typedef struct {
    char c;
    rad_patch_t t;
} align_patch_t;
typedef struct {
    char c;
    rad_element_t t;
} align_element_t;
typedef struct {
    char c;
    rad_vec3_t t;
} align_vec3_t;
typedef struct {
    char c;
    rad_rgb_t t;
} align_rgb_t;

static int aligned(const void *p, size_t a)
{
    return (uintptr_t)p % a == 0;
}

static int pools_aligned(const rad_pools_t *p)
{
    return aligned(p->surfaces, offsetof(align_surface_t, t)) &&
           aligned(p->patches, offsetof(align_patch_t, t)) &&
           aligned(p->elements, offsetof(align_element_t, t)) &&
           aligned(p->vertices, offsetof(align_vec3_t, t));
}

/* The caller's sizes and kind against the library's: a program compiled with another
 * RAD_INDEX_BITS would index the pools with other strides. Checked before S is used. */
int rad_init_abi(rad_scene_t *s, const rad_pools_t *pools, const rad_config_t *cfg,
                 size_t scene_bytes, unsigned index_bytes, int is_float)
{
    const uint32_t lim = RAD_INDEX_NONE - 1u;
    const char *why;
    rad_scene_t z = {0};
    if (scene_bytes != sizeof(rad_scene_t) || index_bytes != sizeof(rad_index_t) ||
        is_float != RAD_FLOAT)
        return RAD_ERR_ABI;
    if (s) s->self = 0; /* refused by every call unless this succeeds */
    if (!s || !pools || !pools->surfaces || !pools->patches || !pools->elements ||
        !pools->vertices || !pools->work)
        return RAD_ERR_ARG;
    if (pools->max_surfaces > lim || pools->max_patches > lim || pools->max_elements > lim ||
        pools->max_vertices > lim)
        return RAD_ERR_ARG;
    if (!pools_aligned(pools)) return RAD_ERR_ALIGN;
    z.pools = *pools;
    if (cfg) z.cfg = *cfg;
    if (resolve_config(&z.cfg, &why) < 0) return RAD_ERR_ARG;
    {
        int rc = rad__hemicube_init(&z);
        if (rc < 0) return rc;
        if ((z.cfg.flags & RAD_NO_BANDS) && z.band_rows) return RAD_ERR_WORK;
    }
    z.shot_patch = RAD_INDEX_NONE;
    z.self = s;
    *s = z;
    return RAD_OK;
}

/* ---- validation ---------------------------------------------------------------- */

static int vec_eq(rad_vec3_t a, rad_vec3_t b)
{
    return a.x == b.x && a.y == b.y && a.z == b.z;
}

static rad_real_t larger_abs(rad_real_t m, rad_real_t v)
{
    if (v < 0) v = -v;
    return v > m ? v : m;
}

/* The largest coordinate magnitude of the N points V. */
static rad_real_t points_extent(const rad_vec3_t *v, unsigned n)
{
    rad_real_t m = 0;
    unsigned i;
    for (i = 0; i < n; i++) m = larger_abs(larger_abs(larger_abs(m, v[i].x), v[i].y), v[i].z);
    return m;
}

/* The largest shift in MIN_LENGTH_SHIFT..0 that takes magnitude M within
 * RAD_COORD_LIMIT (M <= RAD_INPUT_LIMIT). */
/* The magnitude of -M at scale 2^G <= 0 as scale_point rounds it (down: away from 0),
 * the farthest from 0 that a coordinate of magnitude M goes: rounding M itself to
 * nearest took -256 - 2^-16 to -64 at G = -2, where scale_point gives -64 - 2^-16. */
static rad_real_t farthest(rad_real_t m, int g)
{
    return g == 0 ? m : -rad__floor2(-m, (unsigned)-g);
}

static int fit_shift(rad_real_t m)
{
    int g = 0;
    while (g > MIN_LENGTH_SHIFT && farthest(m, g) > RAD__Q(RAD_COORD_LIMIT)) g--;
    return g;
}

/* Point V times 2^G: exact upwards, rounded down (rad__floor2) downwards. */
static rad_vec3_t scale_point(rad_vec3_t v, int g)
{
    if (g >= 0) return rad__scale2_vec(v, g, 0);
    v.x = rad__floor2(v.x, (unsigned)-g);
    v.y = rad__floor2(v.y, (unsigned)-g);
    v.z = rad__floor2(v.z, (unsigned)-g);
    return v;
}

/* Normal and area (at least MIN) of polygon V (3 or 4 vertices, the caller's, within
 * +-RAD_INPUT_LIMIT), measured at the polygon's own scale (its coordinates times
 * 2^fit_shift: the caller's within +-RAD_COORD_LIMIT), or a negative RAD_ERR_* with
 * *WHY. */
static int check_polygon(const rad_vec3_t *in, unsigned n, rad_real_t min, rad_vec3_t *normal,
                         rad_real_t *area, const char **why)
{
    const rad_real_t lim = RAD__Q(RAD_INPUT_LIMIT);
    rad_vec3_t v[4];
    unsigned i;
    int g;
    for (i = 0; i < n; i++) {
        *why = "coordinate beyond +-RAD_INPUT_LIMIT";
        if (!in_range(in[i].x, -lim, lim) || !in_range(in[i].y, -lim, lim) ||
            !in_range(in[i].z, -lim, lim))
            return RAD_ERR_RANGE;
    }
    g = fit_shift(points_extent(in, n));
    for (i = 0; i < n; i++) v[i] = scale_point(in[i], g);
    for (i = 0; i < n; i++) {
        *why = "two consecutive vertices equal";
        if (vec_eq(v[i], v[(i + 1) % n])) return RAD_ERR_DEGENERATE;
    }
    if (n == 3)
        *area = rad__area_normal(rad__sub(v[1], v[0]), rad__sub(v[2], v[0]), normal);
    else
        *area = rad__area_normal(rad__sub(v[2], v[0]), rad__sub(v[3], v[1]), normal);
    *why = min == MIN_AREA ? "area below 1/4096 (or vertices in a line)"
                           : "area below 2^-16 (or vertices in a line)";
    if (!(*area >= min)) return RAD_ERR_DEGENERATE;
    if (n == 4) {
        uint32_t sat = 0;
        for (i = 0; i < 4; i++) {
            rad_vec3_t nk;
            /* Planar: every corner within sqrt(area) / 64 of the plane through v0. */
            rad_real_t h = rad__dot(rad__sub(v[i], v[0]), *normal);
            *why = "quad corner farther than sqrt(area) / 64 from its plane";
            if (rad__mul(rad__mul(h, h, &sat), RAD__Q(4096.0), &sat) > *area)
                return RAD_ERR_NONPLANAR;
            /* Convex: every corner turns the same way as the whole. */
            *why = "quad with three corners in a line";
            if (rad__area_normal(rad__sub(v[(i + 1) % 4], v[i]),
                                 rad__sub(v[(i + 2) % 4], v[(i + 1) % 4]), &nk) <= 0)
                return RAD_ERR_DEGENERATE;
            *why = "quad not convex";
            if (rad__dot(nk, *normal) <= 0) return RAD_ERR_NONPLANAR;
        }
    }
    *why = "";
    return RAD_OK;
}

/* ---- meshing ------------------------------------------------------------------- */

/* The lattice as rad_surface_t keeps it: a quad's patches and elements per patch along
 * u and v; a triangle's patch and element subdivision levels in pu = pv, ku = kv. */
typedef struct {
    uint32_t pu, pv, ku, kv;
    uint32_t patches, elements, vertices;
} plan_t;

static rad_real_t max2(rad_real_t a, rad_real_t b)
{
    return a > b ? a : b;
}

/* Emitters shoot from every element: direct light is the largest and most visible
 * term, and shooting it from many points (each hemi-cube turned differently) averages
 * the aliasing of any one cube, which a single shot from a big light leaves as blotches.
 *
 * A triangle is cut into m^2 triangles like itself, m from its longest side l, but at
 * most from s = 2 sqrt(AREA), the side of a square of four times its area: a sliver
 * (4 mm by 4 m) cut by l alone would give (l / max_element)^2 elements for an area
 * of a few, so a wall of 2,000 of them meshed into 1.15 million. With s its elements
 * number about 4 AREA / max_element^2, as a quad's. s >= l whenever the triangle's
 * height over its longest side is at least half that side (4 AREA = 2 l h >= l^2), so
 * any triangle but a sliver is cut by l, as it always was. Returns 0 when a side would
 * need more than MAX_SIDE elements, else 1. */
static int plan_mesh(const rad_config_t *cfg, const rad_vec3_t *v, unsigned n, int emits,
                     rad_real_t area, plan_t *p)
{
    static const plan_t zero = {0, 0, 0, 0, 0, 0, 0};
    rad_real_t me = cfg->max_element, mp = emits ? me : cfg->max_patch;
    *p = zero;
    if (n == 4) {
        rad_real_t lu = max2(rad__length(rad__sub(v[1], v[0])), rad__length(rad__sub(v[2], v[3])));
        rad_real_t lv = max2(rad__length(rad__sub(v[3], v[0])), rad__length(rad__sub(v[2], v[1])));
        p->pu = rad__ceil_div(lu, mp, 1);
        p->pv = rad__ceil_div(lv, mp, 1);
        p->ku = rad__ceil_div(lu, me, p->pu);
        p->kv = rad__ceil_div(lv, me, p->pv);
        if ((uint64_t)p->pu * p->ku > MAX_SIDE || (uint64_t)p->pv * p->kv > MAX_SIDE) return 0;
        p->patches = p->pu * p->pv;
        p->elements = p->patches * p->ku * p->kv;
        p->vertices = (p->pu * p->ku + 1u) * (p->pv * p->kv + 1u);
    } else {
        rad_real_t l =
            max2(rad__length(rad__sub(v[1], v[0])),
                 max2(rad__length(rad__sub(v[2], v[1])), rad__length(rad__sub(v[0], v[2]))));
        rad_real_t s = 2 * rad__sqrt(area);
        uint32_t m;
        if (s < l) l = s;
        p->pu = p->pv = rad__ceil_div(l, mp, 1);
        p->ku = p->kv = rad__ceil_div(l, me, p->pu);
        if ((uint64_t)p->pu * p->ku > MAX_SIDE) return 0;
        m = p->pu * p->ku;
        p->patches = p->pu * p->pu;
        p->elements = m * m;
        p->vertices = (m + 1u) * (m + 2u) / 2u;
    }
    return 1;
}

static int args_ok(const rad_vec3_t *v, unsigned n)
{
    return v && (n == 3 || n == 4);
}

/* Everything rad_add_polygon decides before it writes, in its order: colours, then
 * the polygon, then the mesh's plan. Returns RAD_OK or the error with *WHY. */
static int plan_polygon(const rad_config_t *cfg, const rad_vec3_t *v, unsigned n,
                        const rad_rgb_t *reflectance, const rad_rgb_t *emission, rad_vec3_t *normal,
                        rad_real_t *area, plan_t *plan, const char **why)
{
    int rc, emits = rgb_any(emission);
    *why = "reflectance outside [0, 1)";
    if (!rgb_ok(reflectance, RAD__ONE, 1)) return RAD_ERR_RANGE;
    *why = "emission outside [0, RAD_EMISSION_LIMIT]";
    if (!rgb_ok(emission, RAD__Q(RAD_EMISSION_LIMIT), 0)) return RAD_ERR_RANGE;
    rc = check_polygon(v, n, (cfg->flags & RAD_SMALL_FACES) && !emits ? MIN_SMALL : MIN_AREA,
                       normal, area, why);
    if (rc < 0) return rc;
    *why = "more than 32768 elements along a side (max_element, max_patch)";
    if (!plan_mesh(cfg, v, n, emits, *area, plan)) return RAD_ERR_FULL;
    *why = "";
    return RAD_OK;
}

static uint32_t add_sat(uint32_t a, uint32_t b)
{
    return b > UINT32_MAX - a ? UINT32_MAX : a + b;
}

int rad_plan_polygon(const rad_config_t *cfg, const rad_vec3_t *v, unsigned n,
                     const rad_rgb_t *reflectance, const rad_rgb_t *emission, rad_plan_t *plan)
{
    rad_config_t c = {0};
    rad_vec3_t normal;
    rad_real_t area;
    plan_t p;
    int rc;
    if (!plan) return RAD_ERR_ARG;
    plan->problem = "NULL vertices, or not 3 or 4 of them";
    if (!args_ok(v, n)) return RAD_ERR_ARG;
    if (cfg) c = *cfg;
    rc = resolve_config(&c, &plan->problem);
    if (rc == RAD_OK)
        rc = plan_polygon(&c, v, n, reflectance, emission, &normal, &area, &p, &plan->problem);
    if (rc < 0) return rc;
    plan->surfaces = add_sat(plan->surfaces, 1);
    plan->patches = add_sat(plan->patches, p.patches);
    plan->elements = add_sat(plan->elements, p.elements);
    plan->vertices = add_sat(plan->vertices, p.vertices);
    return RAD_OK;
}

static int fits(uint32_t used, uint32_t want, uint32_t max)
{
    return want <= max - used;
}

static void set_area(rad_element_t *el, const rad_vec3_t *vt)
{
    rad_vec3_t nrm;
    if (el->v[3] == RAD_INDEX_NONE)
        el->area = rad__area_normal(rad__sub(vt[el->v[1]], vt[el->v[0]]),
                                    rad__sub(vt[el->v[2]], vt[el->v[0]]), &nrm);
    else
        el->area = rad__area_normal(rad__sub(vt[el->v[2]], vt[el->v[0]]),
                                    rad__sub(vt[el->v[3]], vt[el->v[1]]), &nrm);
    if (!(el->area > 0)) el->area = RAD__Q(1.0 / 65536.0); /* a sliver: never divide by 0 */
}

/* Appends an element on vertices A, B, C (, D) to patch P, returning its area. */
static rad_real_t add_element(rad_scene_t *s, uint32_t surf, uint32_t p, uint32_t a, uint32_t b,
                              uint32_t c, uint32_t d)
{
    rad_element_t *el = &s->pools.elements[s->n_elements++];
    el->v[0] = (rad_index_t)a;
    el->v[1] = (rad_index_t)b;
    el->v[2] = (rad_index_t)c;
    el->v[3] = (rad_index_t)d;
    el->surface = (rad_index_t)surf;
    el->patch = (rad_index_t)p;
    set_area(el, s->pools.vertices);
    return el->area;
}

static rad_patch_t *new_patch(rad_scene_t *s, uint32_t surf, rad_vec3_t center)
{
    rad_patch_t *pt = &s->pools.patches[s->n_patches];
    pt->center = center;
    pt->surface = (rad_index_t)surf;
    pt->first_element = (rad_index_t)s->n_elements;
    pt->area = 0;
    return pt;
}

static void close_patch(rad_scene_t *s, rad_patch_t *pt)
{
    pt->n_elements = (rad_index_t)(s->n_elements - pt->first_element);
    s->n_patches++;
}

static void mesh_quad(rad_scene_t *s, uint32_t surf, const rad_vec3_t *c, const plan_t *p)
{
    uint32_t nu = p->pu * p->ku, nv = p->pv * p->kv, v0 = s->n_vertices, i, j, pi, pj, a, b;
    for (j = 0; j <= nv; j++)
        for (i = 0; i <= nu; i++) {
            uint32_t w[4];
            w[0] = (nu - i) * (nv - j);
            w[1] = i * (nv - j);
            w[2] = i * j;
            w[3] = (nu - i) * j;
            s->pools.vertices[s->n_vertices++] = rad__wavg(c, w, 4, nu * nv);
        }
#define G(ii, jj) (v0 + (jj) * (nu + 1u) + (ii))
    for (pj = 0; pj < p->pv; pj++)
        for (pi = 0; pi < p->pu; pi++) {
            /* The centre on the doubled lattice: (2 pi ku + ku, 2 pj kv + kv). */
            uint32_t ci = (2u * pi + 1u) * p->ku, cj = (2u * pj + 1u) * p->kv, w[4];
            rad_patch_t *pt;
            w[0] = (2u * nu - ci) * (2u * nv - cj);
            w[1] = ci * (2u * nv - cj);
            w[2] = ci * cj;
            w[3] = (2u * nu - ci) * cj;
            pt = new_patch(s, surf, rad__wavg(c, w, 4, 4u * nu * nv));
            for (b = 0; b < p->kv; b++)
                for (a = 0; a < p->ku; a++) {
                    uint32_t ii = pi * p->ku + a, jj = pj * p->kv + b;
                    pt->area += add_element(s, surf, s->n_patches, G(ii, jj), G(ii + 1u, jj),
                                            G(ii + 1u, jj + 1u), G(ii, jj + 1u));
                }
            close_patch(s, pt);
        }
#undef G
}

/* The corners of surface SF's vertex lattice, as mesh_quad and mesh_tri lay it out:
 * quads G(0,0), G(nu,0), G(nu,nv), G(0,nv); triangles T(0,0), T(m,0), T(0,m). */
unsigned rad__surface_corners(const rad_scene_t *s, const rad_surface_t *sf, uint32_t *k)
{
    uint32_t v0 = sf->first_vertex, last = v0 + sf->n_vertices - 1u, nu = (uint32_t)sf->pu * sf->ku;
    k[0] = v0;
    k[1] = v0 + nu;
    k[2] = last;
    if (s->pools.elements[sf->first_element].v[3] == RAD_INDEX_NONE) return 3;
    k[3] = last - nu;
    return 4;
}

/* Index of lattice point (i, j), i + j <= m, of a triangle's vertex block at V0. */
static uint32_t tri_index(uint32_t v0, uint32_t m, uint32_t i, uint32_t j)
{
    return v0 + j * (m + 1u) - j * (j - 1u) / 2u + i; /* rows shrink by one point each */
}

static void mesh_tri(rad_scene_t *s, uint32_t surf, const rad_vec3_t *c, const plan_t *p)
{
    uint32_t np = p->pu, k = p->ku, m = np * k, v0 = s->n_vertices, i, j, I, J, a, b, down;
    for (j = 0; j <= m; j++)
        for (i = 0; i + j <= m; i++) {
            uint32_t w[3];
            w[0] = m - i - j;
            w[1] = i;
            w[2] = j;
            s->pools.vertices[s->n_vertices++] = rad__wavg(c, w, 3, m);
        }
#define T(ii, jj) tri_index(v0, m, (ii), (jj))
    for (down = 0; down < 2; down++)
        for (J = 0; J < np; J++)
            for (I = 0; I + J + down < np; I++) {
                /* Coarse triangle: up (I,J),(I+1,J),(I,J+1); down is its point reflection
                 * about corner (I+1,J+1). Centroid weights on a 3np lattice. */
                uint32_t ci = 3u * I + (down ? 2u : 1u), cj = 3u * J + (down ? 2u : 1u), w[3];
                rad_patch_t *pt;
                w[0] = 3u * np - ci - cj;
                w[1] = ci;
                w[2] = cj;
                pt = new_patch(s, surf, rad__wavg(c, w, 3, 3u * np));
                for (b = 0; b < k; b++)
                    for (a = 0; a + b < k; a++) {
                        uint32_t P = s->n_patches;
                        if (!down) {
                            uint32_t x = k * I + a, y = k * J + b;
                            pt->area += add_element(s, surf, P, T(x, y), T(x + 1u, y), T(x, y + 1u),
                                                    RAD_INDEX_NONE);
                            if (a + b + 1u < k)
                                pt->area += add_element(s, surf, P, T(x + 1u, y), T(x + 1u, y + 1u),
                                                        T(x, y + 1u), RAD_INDEX_NONE);
                        } else {
                            /* Reflected: local up (a,b) is a fine down triangle and vice versa. */
                            uint32_t cx = k * (I + 1u), cy = k * (J + 1u);
                            pt->area +=
                                add_element(s, surf, P, T(cx - a, cy - b - 1u), T(cx - a, cy - b),
                                            T(cx - a - 1u, cy - b), RAD_INDEX_NONE);
                            if (a + b + 1u < k)
                                pt->area += add_element(s, surf, P, T(cx - a - 1u, cy - b - 1u),
                                                        T(cx - a, cy - b - 1u),
                                                        T(cx - a - 1u, cy - b), RAD_INDEX_NONE);
                        }
                    }
                close_patch(s, pt);
            }
#undef T
}

/* Patch PT's shooting point: the mean of its elements' vertices (a group's centre;
 * rad_join_polygon). Offsets by RAD_COORD_LIMIT keep the sums non-negative; a sum of at
 * most 2^20 vertices of at most 2^23 fits the ratio's 2^46 without a shift. */
static rad_vec3_t group_center(const rad_scene_t *s, const rad_patch_t *pt)
{
    const rad_real_t lim = RAD__Q(RAD_COORD_LIMIT);
    rad_energy_t x = 0, y = 0, z = 0, cnt = 0;
    rad_vec3_t c;
    uint32_t e, k;
    for (e = pt->first_element; e < (uint32_t)pt->first_element + pt->n_elements; e++) {
        const rad_element_t *el = &s->pools.elements[e];
        for (k = 0; k < rad__nverts(el); k++) {
            const rad_vec3_t *v = &s->pools.vertices[el->v[k]];
            x += v->x + lim;
            y += v->y + lim;
            z += v->z + lim;
            cnt += RAD__ONE;
        }
    }
    c.x = rad__energy_ratio(x, cnt) - lim;
    c.y = rad__energy_ratio(y, cnt) - lim;
    c.z = rad__energy_ratio(z, cnt) - lim;
    return c;
}

/* Polygon C (N corners) as one element of patch P: the vertices of a lattice of one (a
 * triangle's T(0,0), T(1,0), T(0,1); a quad's G(0,0), G(1,0), G(0,1), G(1,1)), as
 * mesh_tri and mesh_quad lay them out. Its pixels go to P's first element, the group's
 * receiver (rad__group_element), so that the group's power is rounded once a shot, not
 * once a face (a face's share of a pixel is often below the 2^-16 a power keeps): that
 * element's area, P's area and count grow by the polygon's, and P's centre moves. */
static void mesh_joined(rad_scene_t *s, uint32_t surf, const rad_vec3_t *c, unsigned n, uint32_t p)
{
    rad_patch_t *pt = &s->pools.patches[p];
    rad_real_t a;
    uint32_t v0 = s->n_vertices;
    s->pools.vertices[s->n_vertices++] = c[0];
    s->pools.vertices[s->n_vertices++] = c[1];
    s->pools.vertices[s->n_vertices++] = c[n - 1];
    if (n == 4) s->pools.vertices[s->n_vertices++] = c[2];
    a = add_element(s, surf, p, v0, v0 + 1u, n == 4 ? v0 + 3u : v0 + 2u,
                    n == 4 ? v0 + 2u : RAD_INDEX_NONE);
    pt->area += a;
    s->pools.elements[pt->first_element].area += a;
    pt->n_elements++;
    pt->center = group_center(s, pt);
}

static void mesh_surface(rad_scene_t *s, uint32_t surf, const rad_vec3_t *c, unsigned n,
                         const plan_t *p)
{
    if (n == 4)
        mesh_quad(s, surf, c, p);
    else
        mesh_tri(s, surf, c, p);
}

rad_rgb_t rad__emission(rad_scene_t *s, const rad_surface_t *sf)
{
    return rad__scale2_rgb(sf->emission, s->power_shift, &s->stats.saturations);
}

/* Emission as the solution's starting point: radiosity E, unshot power E * area. */
static void start_surface(rad_scene_t *s, uint32_t surf)
{
    const rad_surface_t *sf = &s->pools.surfaces[surf];
    rad_rgb_t em = rad__emission(s, sf);
    uint32_t i;
    for (i = 0; i < sf->n_elements; i++) s->pools.elements[sf->first_element + i].radiosity = em;
    for (i = 0; i < sf->n_patches; i++) {
        rad_patch_t *pt = &s->pools.patches[sf->first_patch + i];
        pt->unshot[0] = rad__energy(em.r, pt->area);
        pt->unshot[1] = rad__energy(em.g, pt->area);
        pt->unshot[2] = rad__energy(em.b, pt->area);
        s->emitted = rad__esum(s->emitted, pt->unshot[0] + pt->unshot[1] + pt->unshot[2]);
    }
}

static int rgb_eq(const rad_rgb_t *a, const rad_rgb_t *b)
{
    return a->r == b->r && a->g == b->g && a->b == b->b;
}

/* Sum over the patch's elements of rho_e A_e over the sum of A_e, per channel, each
 * product rounded once (|error| <= n / 2 LSB of power over >= n LSB of area: below 1
 * LSB of the ratio); a mean rounding up to 1 (only from elements all within a few LSB
 * of it) is kept at the largest value below. The elements of a group's other surfaces
 * are skipped: their power goes to the receiver, the patch's first element, whose
 * area is the group's. Elements that all agree give their value exactly. */
void rad__patch_mean(rad_scene_t *s, uint32_t p)
{
    const rad_patch_t *pt = &s->pools.patches[p];
    const rad_rgb_t *rho = s->element_rho, *first = &rho[pt->first_element];
    rad_energy_t area = 0, sum[3] = {0, 0, 0};
    uint32_t e, end = (uint32_t)pt->first_element + pt->n_elements;
    rad_rgb_t *m = &s->element_rho[s->pools.max_elements + p];
    int same = 1;
    s->amb_ok = 0;
    for (e = pt->first_element; e < end; e++) {
        const rad_element_t *el = &s->pools.elements[e];
        if (el->surface != pt->surface) continue;
        same = same && rgb_eq(&rho[e], first);
        area = rad__esum(area, rad__energy(RAD__ONE, el->area));
        sum[0] = rad__esum(sum[0], rad__energy(rho[e].r, el->area));
        sum[1] = rad__esum(sum[1], rad__energy(rho[e].g, el->area));
        sum[2] = rad__esum(sum[2], rad__energy(rho[e].b, el->area));
    }
    if (same) {
        *m = *first;
        return;
    }
    m->r = rad__energy_ratio(sum[0], area);
    m->g = rad__energy_ratio(sum[1], area);
    m->b = rad__energy_ratio(sum[2], area);
    if (m->r >= RAD__ONE) m->r = RAD__ONE - RAD__EPS;
    if (m->g >= RAD__ONE) m->g = RAD__ONE - RAD__EPS;
    if (m->b >= RAD__ONE) m->b = RAD__ONE - RAD__EPS;
}

/* Every element and patch of surface SF reflects as SF, when elements have
 * reflectances of their own (rad_use_element_reflectance). */
static void element_rho_reset(rad_scene_t *s, const rad_surface_t *sf)
{
    uint32_t i;
    if (!s->element_rho) return;
    for (i = 0; i < sf->n_elements; i++) s->element_rho[sf->first_element + i] = sf->reflectance;
    for (i = 0; i < sf->n_patches; i++)
        s->element_rho[s->pools.max_elements + sf->first_patch + i] = sf->reflectance;
}

static void start_all(rad_scene_t *s)
{
    uint32_t i;
    s->emitted = 0;
    s->lights_shot = 0; /* lights shoot again (light.c) */
    for (i = 0; i < s->n_surfaces; i++) start_surface(s, i);
}

/* ---- the core's scale (rad.h) ---------------------------------------------------- */

#define SCALE_HALF       RAD__Q(RAD_COORD_LIMIT / 2.0) /* the largest coordinate into (16, 32] */
#define SCALE_PEAK       RAD__Q(256.0)                 /* the brightest emission into (128, 256] */
#define SMALL_AREA       RAD__Q(1.0 / 64.0)            /* 2^10 LSB: rounding 2^-11 of the area */
#define MAX_LENGTH_SHIFT 15 /* for a scene within 2^-10: smaller than any polygon accepted */
/* Emission scales up only: outputs come back in the caller's Q16.16, whose range a
 * smaller scale would not widen, while it would round away the low bits of emissions. */
#define MIN_POWER_SHIFT  0
#define MAX_POWER_SHIFT  24 /* 2^-16 to 256 */

/* The N in LO..HI that takes V > 0 into (TARGET / 2, TARGET] times 2^N, or the bound
 * nearest it (0 for V = 0). */
static int pick_shift(rad_real_t v, rad_real_t target, int lo, int hi)
{
    int n = 0;
    if (!(v > 0)) return 0;
    while (n > lo && rad__scale2(v, n, 0) > target) n--;
    while (n < hi && rad__scale2(v, n + 1, 0) <= target) n++;
    return n;
}

/* The largest coordinate magnitude, in the caller's units: every vertex is a convex
 * combination of its surface's corners, which are the caller's own vertices times
 * 2^length_shift exactly (the lattice's weights at a corner are den, 0, 0...). */
static rad_real_t extent(const rad_scene_t *s)
{
    rad_real_t m = 0;
    uint32_t i, k[4];
    unsigned j, n;
    for (i = 0; i < s->n_surfaces; i++) {
        n = rad__surface_corners(s, &s->pools.surfaces[i], k);
        for (j = 0; j < n; j++) {
            const rad_vec3_t *v = &s->pools.vertices[k[j]];
            m = larger_abs(larger_abs(larger_abs(m, v->x), v->y), v->z);
        }
    }
    return rad__scale2(m, -s->length_shift, 0); /* exact: a multiple of 2^length_shift */
}

/* The brightest emission channel of any surface, or irradiance of any light, in the
 * caller's units. */
static rad_real_t peak(const rad_scene_t *s)
{
    rad_real_t m = 0;
    uint32_t i;
    for (i = 0; i < s->n_surfaces; i++) {
        const rad_rgb_t *e = &s->pools.surfaces[i].emission;
        m = larger_abs(larger_abs(larger_abs(m, e->r), e->g), e->b);
    }
    return larger_abs(m, rad__lights_peak(s));
}

/* Meshes every surface again, in place, from its corners at length shift G: the same
 * lattice (the plan is kept in the surface), vertices, centres and areas rounded at the
 * new scale as if the caller had given the scaled polygons. The corners scale exactly
 * (up by 2^(G - length_shift), or back down: they are multiples of 2^length_shift). */
static void remesh(rad_scene_t *s, int g)
{
    uint32_t np = s->n_patches, ne = s->n_elements, nv = s->n_vertices, i, k[4];
    int d = g - s->length_shift;
    for (i = 0; i < s->n_surfaces; i++) {
        const rad_surface_t *sf = &s->pools.surfaces[i];
        plan_t p = {0, 0, 0, 0, 0, 0, 0};
        rad_vec3_t c[4];
        unsigned j, n = rad__surface_corners(s, sf, k);
        for (j = 0; j < n; j++) c[j] = scale_point(s->pools.vertices[k[j]], d);
        p.pu = sf->pu;
        p.pv = sf->pv;
        p.ku = sf->ku;
        p.kv = sf->kv;
        s->n_elements = sf->first_element;
        s->n_vertices = sf->first_vertex;
        if (sf->n_patches == 0) { /* joined to a patch meshed before it */
            mesh_joined(s, i, c, n, sf->first_patch);
            continue;
        }
        s->n_patches = sf->first_patch;
        mesh_surface(s, i, c, n, &p);
    }
    s->n_patches = np;
    s->n_elements = ne;
    s->n_vertices = nv;
    s->length_shift = (int8_t)g;
}

/* The core's scale at length shift G and power shift P, and the start state at it;
 * nothing changes when both stand (only ever called before a solve). */
static void set_scale(rad_scene_t *s, int g, int p)
{
    if (g == s->length_shift && p == s->power_shift) return;
    if (g != s->length_shift) remesh(s, g);
    s->power_shift = (int8_t)p;
    start_all(s);
}

static int pick_power_shift(const rad_scene_t *s)
{
    return pick_shift(peak(s), SCALE_PEAK, MIN_POWER_SHIFT, MAX_POWER_SHIFT);
}

void rad__scale_geometry(rad_scene_t *s)
{
    uint32_t e, small = 0;
    /* a scene beyond +-RAD_COORD_LIMIT was fitted within it as it was added */
    int g = s->length_shift < 0 ? s->length_shift
                                : pick_shift(extent(s), SCALE_HALF, 0, MAX_LENGTH_SHIFT);
    set_scale(s, g, s->power_shift);
    for (e = 0; e < s->n_elements; e++) small += s->pools.elements[e].area < SMALL_AREA;
    s->stats.small_elements = small;
}

void rad__scale_power(rad_scene_t *s)
{
    set_scale(s, s->length_shift, pick_power_shift(s));
}

void rad__freeze(rad_scene_t *s)
{
    uint32_t p;
    if (s->solving) return;
    rad__scale_geometry(s);
    rad__scale_power(s);
    /* the patches' means over their elements' areas at this scale */
    for (p = 0; s->element_rho && p < s->n_patches; p++) rad__patch_mean(s, p);
    s->amb_ok = 0;
    s->solving = 1;
}

/* The length shift for adding polygon V (N vertices) to S: the scene's while it is
 * below 0 (the scene fitted within +-RAD_COORD_LIMIT as it was added), else 0 (the
 * caller's units, as the scene was added), and lower where V needs it (fit_shift).
 * The shift only falls while polygons are added, and coordinates scale down by
 * rounding down, so the geometry does not depend on the order of the polygons. */
static int add_shift(const rad_scene_t *s, const rad_vec3_t *v, unsigned n)
{
    int g = fit_shift(points_extent(v, n));
    return s->length_shift < g ? s->length_shift : g;
}

int rad_add_polygon(rad_scene_t *s, const rad_vec3_t *v, unsigned n, const rad_rgb_t *reflectance,
                    const rad_rgb_t *emission)
{
    static const rad_rgb_t black = {0, 0, 0};
    rad_surface_t *sf;
    rad_vec3_t normal, c[4];
    rad_real_t area;
    plan_t plan;
    const char *why;
    unsigned k;
    int rc, g;

    RAD__CHECK_SCENE(s);
    if (!args_ok(v, n)) return RAD_ERR_ARG;
    if (s->solving) return RAD_ERR_STATE;
    rc = plan_polygon(&s->cfg, v, n, reflectance, emission, &normal, &area, &plan, &why);
    if (rc < 0) return rc;
    if (!fits(s->n_surfaces, 1, s->pools.max_surfaces) ||
        !fits(s->n_patches, plan.patches, s->pools.max_patches) ||
        !fits(s->n_elements, plan.elements, s->pools.max_elements) ||
        !fits(s->n_vertices, plan.vertices, s->pools.max_vertices))
        return RAD_ERR_FULL;

    g = add_shift(s, v, n);
    set_scale(s, g, 0);
    for (k = 0; k < n; k++) c[k] = scale_point(v[k], g);
    sf = &s->pools.surfaces[s->n_surfaces];
    sf->normal = normal;
    sf->reflectance = reflectance ? *reflectance : black;
    sf->emission = emission ? *emission : black;
    sf->first_patch = (rad_index_t)s->n_patches;
    sf->first_element = (rad_index_t)s->n_elements;
    sf->first_vertex = (rad_index_t)s->n_vertices;
    sf->pu = (rad_index_t)plan.pu;
    sf->pv = (rad_index_t)plan.pv;
    sf->ku = (rad_index_t)plan.ku;
    sf->kv = (rad_index_t)plan.kv;
    mesh_surface(s, s->n_surfaces, c, n, &plan);
    sf->n_patches = (rad_index_t)(s->n_patches - sf->first_patch);
    sf->n_elements = (rad_index_t)(s->n_elements - sf->first_element);
    sf->n_vertices = (rad_index_t)(s->n_vertices - sf->first_vertex);
    element_rho_reset(s, sf);
    start_surface(s, s->n_surfaces);
    return (int)s->n_surfaces++;
}

int rad_join_polygon(rad_scene_t *s, const rad_vec3_t *v, unsigned n, const rad_rgb_t *reflectance)
{
    static const rad_rgb_t black = {0, 0, 0};
    rad_surface_t *sf, *first;
    rad_vec3_t normal, c[4];
    rad_real_t area;
    plan_t plan;
    const char *why;
    uint32_t p;
    unsigned k;
    int rc, g;

    RAD__CHECK_SCENE(s);
    if (!args_ok(v, n) || !(s->cfg.flags & RAD_SMALL_FACES)) return RAD_ERR_ARG;
    if (s->solving || s->n_patches == 0) return RAD_ERR_STATE;
    p = s->n_patches - 1u;
    first = &s->pools.surfaces[s->pools.patches[p].surface];
    if (rgb_any(&first->emission)) return RAD_ERR_STATE;
    rc = plan_polygon(&s->cfg, v, n, reflectance, NULL, &normal, &area, &plan, &why);
    if (rc < 0) return rc;
    if (plan.elements != 1 || !(area < MIN_AREA) || s->pools.patches[p].area > MAX_GROUP_AREA)
        return RAD_ERR_ARG;
    if (!fits(s->n_surfaces, 1, s->pools.max_surfaces) ||
        !fits(s->n_elements, 1, s->pools.max_elements) ||
        !fits(s->n_vertices, n, s->pools.max_vertices))
        return RAD_ERR_FULL;

    g = add_shift(s, v, n); /* as rad_add_polygon */
    set_scale(s, g, 0);
    for (k = 0; k < n; k++) c[k] = scale_point(v[k], g);
    sf = &s->pools.surfaces[s->n_surfaces];
    sf->normal = normal;
    sf->reflectance = reflectance ? *reflectance : black;
    sf->emission = black;
    sf->first_patch = (rad_index_t)p;
    sf->n_patches = 0;
    sf->first_element = (rad_index_t)s->n_elements;
    sf->first_vertex = (rad_index_t)s->n_vertices;
    sf->pu = sf->pv = sf->ku = sf->kv = 1;
    mesh_joined(s, s->n_surfaces, c, n, p);
    sf->n_elements = 1;
    sf->n_vertices = (rad_index_t)n;
    element_rho_reset(s, sf);
    start_surface(s, s->n_surfaces);
    return (int)s->n_surfaces++;
}

/* Surface SURF shares a patch with another (rad_join_polygon): either joined or the
 * first of a group. Such a patch's power is E A over the whole group: none may emit. */
static int grouped(const rad_scene_t *s, uint32_t surf)
{
    const rad_surface_t *sf = &s->pools.surfaces[surf];
    const rad_patch_t *pt;
    if (sf->n_patches == 0) return 1;
    pt = &s->pools.patches[sf->first_patch + sf->n_patches - 1u];
    return (uint32_t)pt->first_element + pt->n_elements !=
           (uint32_t)sf->first_element + sf->n_elements;
}

int rad_set_surface(rad_scene_t *s, uint32_t surf, const rad_rgb_t *reflectance,
                    const rad_rgb_t *emission)
{
    RAD__CHECK_SCENE(s);
    if (surf >= s->n_surfaces) return RAD_ERR_ARG;
    if (!rgb_ok(reflectance, RAD__ONE, 1) || !rgb_ok(emission, RAD__Q(RAD_EMISSION_LIMIT), 0))
        return RAD_ERR_RANGE;
    if (rgb_any(emission) && grouped(s, surf)) return RAD_ERR_RANGE;
    if (reflectance) {
        s->amb_ok = 0;
        s->pools.surfaces[surf].reflectance = *reflectance;
        element_rho_reset(s, &s->pools.surfaces[surf]);
    }
    if (emission) s->pools.surfaces[surf].emission = *emission;
    return RAD_OK;
}

int rad_use_element_reflectance(rad_scene_t *s, rad_rgb_t *rho)
{
    uint32_t i;
    RAD__CHECK_SCENE(s);
    if (!rho) return RAD_ERR_ARG;
    if (!aligned(rho, offsetof(align_rgb_t, t))) return RAD_ERR_ALIGN;
    if (s->solving || s->element_rho) return RAD_ERR_STATE;
    s->element_rho = rho;
    for (i = 0; i < s->n_surfaces; i++) element_rho_reset(s, &s->pools.surfaces[i]);
    return RAD_OK;
}

int rad_set_element_reflectance(rad_scene_t *s, uint32_t e, const rad_rgb_t *reflectance)
{
    RAD__CHECK_SCENE(s);
    if (!reflectance || e >= s->n_elements) return RAD_ERR_ARG;
    if (!rgb_ok(reflectance, RAD__ONE, 1)) return RAD_ERR_RANGE;
    if (!s->element_rho) return RAD_ERR_STATE;
    s->element_rho[e] = *reflectance;
    rad__patch_mean(s, s->pools.elements[e].patch);
    return RAD_OK;
}

int rad_restart(rad_scene_t *s)
{
    RAD__CHECK_SCENE(s);
    s->shot_patch = RAD_INDEX_NONE;
    s->power_shift = (int8_t)pick_power_shift(s); /* new emissions may need another */
    start_all(s);
    s->solving = 0;
    s->stats.shots = 0;
    return RAD_OK;
}

rad_real_t rad_real_from_q16(int32_t q)
{
#if RAD_FLOAT
    return (float)q * (1.0f / 65536.0f);
#else
    return q;
#endif
}

const char *rad_strerror(int err)
{
    switch (err) {
    case RAD_OK: return "success";
    case RAD_ERR_ARG: return "invalid argument";
    case RAD_ERR_FULL: return "pool full";
    case RAD_ERR_RANGE:
        return "coordinate, reflectance or emission out of range (rad_plan_polygon names which)";
    case RAD_ERR_DEGENERATE: return "degenerate polygon";
    case RAD_ERR_NONPLANAR: return "quad not planar or not convex";
    case RAD_ERR_STATE: return "call out of order";
    case RAD_ERR_WORK: return "work buffer too small";
    case RAD_ERR_ALIGN: return "pool not aligned for its type";
    case RAD_ERR_ABI:
        return "program compiled with another rad.h layout (RAD_INDEX_BITS or RAD_FLOAT)";
    default: return err > 0 ? "success" : "unknown error";
    }
}
