/* SPDX-License-Identifier: MIT */
/* rad — lights that are not surfaces: sun, sky, point and spot (rad.h has the model).
 *
 * A light shoots once, through the one rasterizer and the element lattice, as a
 * patch's shot does: its view's item buffer gives each pixel the element it sees, the
 * pixels' weights are summed per element into s->acc (a fraction F of the power U of
 * the light's whole raster, Q2.30), and each element receives F U as from a patch
 * (rad__receive: rho F U to its radiosity over its area and to its patch's unshot
 * power).
 *
 * Point and spot: a whole cube at the light (six R x R faces, R = the light's res).
 * A pixel of a face at (a, b, 1), a and b its centre's odd lattice numbers over R,
 * has the solid angle dw ~ c^3 dA, c = 1 / sqrt(a^2 + b^2 + 1); its weight is c^3, in
 * integers in both builds, scaled so that each quadrant of a face sums to exactly 2^26
 * (a face's quadrant is 1/24 of the sphere): the sphere's 24 quadrants sum to
 * 1.5 2^30, standing for 4 pi, so U = 4 pi I / 1.5 and a pixel gives I dw. A
 * spot's pixel weighs that times its falloff at the pixel centre's direction. The
 * cube is turned by the rotation of rows (2, 3, 6) / 7, (3, -6, 2) / 7, (6, 2, -3) / 7:
 * no scene axis lies along a face's rows or columns, where walls along the axes would
 * alias by half a pixel along their whole length.
 *
 * Sun: an orthographic item buffer over the square (side 2 h) that every surface
 * corner projects into across the light's direction, in K x K tiles of W x W pixels
 * (W the scene's res, or R when smaller; K = R / W rounded up; R: ortho_res, fine
 * enough for the scene's smallest elements unless the light's res is set), each pixel of area
 * (2 h / K W)^2: U = E (2 h)^2 and a pixel's fraction 1 / (K W)^2. The rasterizer draws
 * a tile as a face whose vertices all lie at depth h / K (a / (h / K) is then the
 * place across the tile, exactly), testing depth by the nearness to the sun (frustum
 * ORTHO); the tiles' half widths times K make h, so they meet exactly. A sun with an
 * angular radius shoots 16 times, each with E / 16 from one direction of its disc
 * (a fixed pattern, symmetric about its centre), which gives shadows penumbrae.
 *
 * Sky: N = 3 m^2 sun shots over the hemisphere about "up" (sky_up). Band i (0..m-1)
 * holds the directions whose projection on the ground plane lies in the ring of radii
 * i / m .. (i + 1) / m of the unit disc, in 3 (2 i + 1) cells of equal angle about up:
 * every cell's projected area is pi / (3 m^2). A cell's shot comes along the cell's
 * vector integral of L w dw (shoot_sky), with the irradiance that the cell's sky gives
 * a plane facing up over the shot's cosine to up: the cells sum to exactly
 * pi H + 2 pi (Z - H) / 3 on a plane facing up (pi L for a uniform sky), and any plane
 * that sees a whole cell receives that cell's light exactly (grey skies).
 *
 * Gathers (gather.c) receive each light's direct light along the same directions
 * (light_dirs, rad__lights_at), its visibility read from their own cube's pixels.
 *
 * A surface turned away from a light receives nothing from it but occludes it (drawn
 * with no element, a quarter of a pixel's footprint behind: view_t), as a gather's
 * cube draws it: a one-sided roof keeps the sun out.
 *
 * Both render in bands of rows in the depth and item buffers of the work buffer, so the
 * result does not depend on the buffer's size, with the scene's row of id steps; a
 * point light's face wider than the scene's res keeps a row of its own at the depth
 * buffer's start, and its R is lowered (halved, at least the scene's res) when not
 * even one row fits beside it. Weights are worked out a pixel at a time (no table): a
 * light shoots once.
 */
#include "internal.h"

/* The most pixels along a side of a sun's or sky's raster: its tiles' side, that
 * rounded up to whole tiles (of at most RAD_MAX_RES), is below 2^13 + 2^11, so the
 * whole raster has fewer than 2^27 pixels, each at least 2^3 units of Q2.30. */
#define ORTHO_MAX_RES 8192u

/* A light's res: 0, or even within 8..RAD_MAX_RES (point, spot: one face) or
 * 8..ORTHO_MAX_RES (sun, sky: tiles). */
static int res_ok(const rad_light_t *l)
{
    const uint32_t most =
        l->type == RAD_LIGHT_SUN || l->type == RAD_LIGHT_SKY ? ORTHO_MAX_RES : RAD_MAX_RES;
    return l->res == 0 || (l->res >= 8u && l->res <= most && !(l->res & 1u));
}

/* V within +-M (written so that a NaN fails in the float twin). */
static int within(const rad_vec3_t *v, rad_real_t m)
{
    return v->x >= -m && v->x <= m && v->y >= -m && v->y <= m && v->z >= -m && v->z <= m;
}

/* In the core's scale (light_position), or a direction. */
static int vec_ok(const rad_vec3_t *v)
{
    return within(v, RAD__Q(RAD_COORD_LIMIT));
}

static int channel_ok(rad_real_t v)
{
    return v >= 0 && v <= RAD__Q(RAD_EMISSION_LIMIT);
}

static int cosine_ok(rad_real_t c)
{
    return c >= -RAD__ONE && c <= RAD__ONE;
}

/* The light's raster resolution, before the work buffer's limit: a point's or spot's
 * face; a sun's or sky's least (ortho_res may raise it for small elements). */
static uint32_t wanted_res(const rad_scene_t *s, const rad_light_t *l)
{
    uint32_t r = s->cfg.res;
    if (l->res) return l->res;
    if (l->type != RAD_LIGHT_SUN || l->dirs > 1u) return r; /* a dome's sun as a sky's */
    return 4u * r < RAD_MAX_RES ? 4u * r : RAD_MAX_RES;
}

/* Sun and sky rasters fine enough for small elements. A pixel's centre decides which
 * element it counts for, so an element of side a (a = sqrt(area)) under pixels of side
 * p is off by about p / a of its light: measured 0.85..1.1 p / a rms over the lit
 * facets of thin columns, 71% at p / a = 0.63 (a sun's 768 pixels over 51 m on
 * 0.07 x 0.16 m facets), 6.7% at p / a = 0.08. A light's default raster therefore has
 * pixels of side at most a / ORTHO_PIXELS_PER_SIDE, a the side of the smallest
 * elements (below: ortho_small), the shot's window 2 h across: R >= 2 h / p. A light
 * that shoots N times (a sun's disc: 16; a sky: its directions) spreads its light over
 * N rasters whose pixels fall differently on an element, so their errors add as
 * independent ones (sqrt N of them, each 1 / N of the light): each raster's p may be
 * sqrt N times larger for the same error. Never below wanted_res, at most
 * ORTHO_MAX_RES (then coarser than the rule). */
#define ORTHO_PIXELS_PER_SIDE 16u
#define ORTHO_PERCENT         1u /* the smallest elements: the smallest 1% of them */

/* 2^15 times the area below which the smallest ORTHO_PERCENT of the elements lie, to a
 * power of two (the lower end of its octave: areas by bit length, in Q15 units as
 * rad__attr gives them alike in both builds), or 0 with no elements. */
static uint64_t ortho_small(const rad_scene_t *s)
{
    uint32_t bins[32] = {0}, e, want, got = 0, a;
    unsigned b;
    if (s->n_elements == 0) return 0;
    for (e = 0; e < s->n_elements; e++) { /* a <= 2^30: a bit length of at most 31 */
        a = rad__attr(s->pools.elements[e].area);
        bins[a ? 32u - rad__clz32(a) : 0u]++;
    }
    want = s->n_elements / (100u / ORTHO_PERCENT);
    if (want == 0) want = 1;
    for (b = 0; b < 31u && (got += bins[b]) < want; b++) {}
    return (uint64_t)1 << (b + 14u); /* bin b: areas of Q15 2^(b-1) .. 2^b, times 2^15 */
}

/* The rule's divisor for light L of SHOTS shots: sqrt(SMALL N), SMALL = ortho_small (so
 * SMALL N < 2^46 2^10); 0 for a light whose res is set, or no elements (then every
 * raster is wanted_res). */
static uint32_t ortho_den(const rad_scene_t *s, const rad_light_t *l, uint32_t shots)
{
    return l->res ? 0u : (uint32_t)rad__isqrt64(ortho_small(s) * shots);
}

/* A sun's or sky's raster side R for the window of half width HW (the core's units):
 * the rule above with DEN (ortho_den), at least FLOOR. */
static uint32_t ortho_res(rad_real_t hw, uint32_t den, uint32_t floor)
{
    uint64_t r;
    if (!den) return floor;
    /* R = 2 hw / p, p = a sqrt(N) / PPS: with hw = H / 2^15 (H = rad__attr(hw)) and
     * a sqrt(N) = sqrt(SMALL N) / 2^15, R = 2 PPS H / DEN, rounded up */
    r = (2u * (uint64_t)ORTHO_PIXELS_PER_SIDE * rad__attr(hw) + den - 1u) / den;
    r += r & 1u;
    return r < floor ? floor : r > ORTHO_MAX_RES ? ORTHO_MAX_RES : (uint32_t)r;
}

/* Words of the depth buffer a raster of resolution R takes before its first row: a
 * row of id steps when the scene's (res entries) is too short. */
static uint32_t head_words(const rad_scene_t *s, uint32_t r)
{
    return r > s->cfg.res ? r : 0u;
}

/* R, halved (kept even, at least the scene's res, which always fits) until its head
 * and one row fit the buffers. */
static uint32_t fitted_res(const rad_scene_t *s, uint32_t r)
{
    while (r > s->cfg.res && head_words(s, r) + r > s->pass_pixels)
        r = r / 4u * 2u < s->cfg.res ? s->cfg.res : r / 4u * 2u;
    return r;
}

/* Point and spot lights have a position; suns and skies only directions. */
static int is_point(const rad_light_t *l)
{
    return l->type == RAD_LIGHT_POINT || l->type == RAD_LIGHT_SPOT;
}

/* A sun's or spot's direction, a sky's up (zero: +y). */
static rad_vec3_t sky_up(const rad_light_t *l)
{
    rad_vec3_t u = l->direction;
    if (l->type == RAD_LIGHT_SKY && u.x == 0 && u.y == 0 && u.z == 0) u.y = RAD__ONE;
    return u;
}

/* A sky's bands m: its count of directions rounded down to 3 m^2 (0: the default). */
#define SKY_MAX_DIRS     768u /* 3 x 16^2 */
#define SKY_DEFAULT_DIRS 192u
static uint32_t sky_bands(const rad_light_t *l)
{
    uint32_t n = l->dirs ? l->dirs : SKY_DEFAULT_DIRS, m = 1;
    while (3u * (m + 1u) * (m + 1u) <= n) m++;
    return m;
}

int rad_use_lights(rad_scene_t *s, rad_light_t *lights, uint32_t max)
{
    RAD__CHECK_SCENE(s);
    if (!lights || max == 0) return RAD_ERR_ARG;
    if (s->lights || s->solving) return RAD_ERR_STATE;
    s->lights = lights;
    s->max_lights = (uint16_t)(max < 65535u ? max : 65535u); /* more than 65535: as many */
    s->n_lights = 0;
    s->lights_shot = 0;
    return RAD_OK;
}

/* RAD_OK for a light rad_add_light takes, else its error but RAD_ERR_STATE. */
static int light_ok(const rad_light_t *l)
{
    rad_vec3_t u;
    if (!l || l->type < RAD_LIGHT_SUN || l->type > RAD_LIGHT_SKY || !res_ok(l)) return RAD_ERR_ARG;
    if (l->type == RAD_LIGHT_SKY && (l->dirs > SKY_MAX_DIRS || (l->dirs && l->dirs < 3u)))
        return RAD_ERR_ARG;
    if (l->type == RAD_LIGHT_SUN && l->dirs > SKY_MAX_DIRS) return RAD_ERR_ARG;
    if (!channel_ok(l->intensity.r) || !channel_ok(l->intensity.g) || !channel_ok(l->intensity.b))
        return RAD_ERR_RANGE;
    if (l->type == RAD_LIGHT_SKY &&
        !(channel_ok(l->horizon.r) && channel_ok(l->horizon.g) && channel_ok(l->horizon.b)))
        return RAD_ERR_RANGE;
    if (is_point(l) && !within(&l->position, RAD__Q(RAD_INPUT_LIMIT))) return RAD_ERR_RANGE;
    if (l->type != RAD_LIGHT_POINT) {
        if (!vec_ok(&l->direction)) return RAD_ERR_RANGE;
        if (!rad__normalize(sky_up(l), &u)) return RAD_ERR_ARG;
    }
    if (l->type == RAD_LIGHT_SPOT &&
        !(cosine_ok(l->cos_outer) && cosine_ok(l->cos_inner) && l->cos_outer <= l->cos_inner))
        return RAD_ERR_RANGE;
    if (l->type == RAD_LIGHT_SUN && !(l->radius >= 0 && l->radius <= RAD__Q(0.25)))
        return RAD_ERR_RANGE;
    return RAD_OK;
}

int rad_add_light(rad_scene_t *s, const rad_light_t *l)
{
    int rc;
    RAD__CHECK_SCENE(s);
    rc = light_ok(l);
    if (rc == RAD_ERR_ARG) return rc; /* bad arguments first, then state, then ranges */
    if (!s->lights || s->solving) return RAD_ERR_STATE;
    if (rc < 0) return rc;
    if (s->n_lights >= s->max_lights) return RAD_ERR_FULL;
    s->lights[s->n_lights] = *l;
    return (int)s->n_lights++;
}

int rad_set_light(rad_scene_t *s, uint32_t k, const rad_light_t *l)
{
    int rc;
    RAD__CHECK_SCENE(s);
    if (!l || k >= s->n_lights) return RAD_ERR_ARG;
    if ((rc = light_ok(l)) < 0) return rc;
    if (!s->solving || !rad__lights_pending(s)) {
        s->lights[k] = *l; /* read by the next solve's shots and power scale */
        return RAD_OK;
    }
    /* A solve with lights still to shoot would shoot this one at the scale chosen
     * without it: refused once anything has shot; before (rows computed, frozen) the
     * scale is chosen again at once. */
    if (s->lights_shot || s->stats.shots) return RAD_ERR_STATE;
    s->lights[k] = *l;
    return rad_restart(s);
}

/* A light all of whose channels are 0 (a light group's others, rad.h) sends nothing:
 * its shot is not rendered. */
static int dark(const rad_light_t *l)
{
    const rad_rgb_t *i = &l->intensity, *h = &l->horizon;
    return !(i->r > 0 || i->g > 0 || i->b > 0) &&
           (l->type != RAD_LIGHT_SKY || !(h->r > 0 || h->g > 0 || h->b > 0));
}

/* ---- the view --------------------------------------------------------------------- */

/* What a light's raster draws: its kind, resolution R and frame (rows: the view's
 * axes on the scene's), and
 *   point, spot: the position C (the core's scale) and the face drawn;
 *   sun: the window's centre (U0, V0) and half width H across the direction, and the
 *        largest depth FAR along it, from which nearness is measured. */
typedef struct {
    const rad_light_t *l;
    rad_vec3_t dir; /* sun: the direction of this shot (one of its disc's, radius > 0) */
    int ortho;
    uint32_t res;
    rad_vec3_t c, frame[3];
    rad_real_t u0, v0, h, far;
    rad_real_t uc, vc, hw; /* sun: the whole window's centre and half width */
    rad_ff_t wz, wh;       /* sky: this direction's E over the zenith's and horizon's L */
    uint32_t tiles;        /* sun: the window in TILES x TILES squares of res pixels */
    uint32_t want, den;    /* sun: the least raster side (wanted_res), ortho_den's */
    unsigned face;
    uint64_t sum;     /* point: a quadrant's sum of c^3 (pixel_weight) */
    uint32_t deficit; /* and the units its entries' rounding down lost */
    /* How far behind the faces the light reaches its back faces are drawn: a quarter
     * of a pixel's footprint. A face's depth at a pixel comes from a plane through
     * its corners placed to 1/32 pixel (1/16, rounded), and inside its outline (or
     * its fan's other half, reached with weights in [-1, 2]) is off by at most its
     * depth step over a pixel times 3 sqrt 2 / 32 < 0.14. Two faces back to back
     * share their corners' places, so their planes are the same; a lit face and a
     * back face that meet (a solid's silhouette edge) share the edge's places, where
     * they agree, and part as they leave it. A quarter footprint keeps a lit face in
     * front wherever the two errors' sum stays below it: faces whose depth steps over
     * a pixel sum to 1.8 footprints (two faces at 42 degrees to the raster) even in
     * the worst case. What it lets through: light reaching a surface less than a
     * quarter footprint behind a back face, along contact edges (at most a row of
     * pixels along each).
     *   sun: BIAS, a quarter of a pixel's side 2 h / res, added to the nearness of
     *   lit faces; point, spot: RECEDE, w lowered by 2^-recede <= 1 / (2 res): a face
     *   pixel at depth d spans 2 d / res across (rad__frustum_t). */
    rad_real_t bias;
    unsigned char recede;
} view_t;

/* The buffers of a band: id steps (R, zero), the rows' depths and ids. */
typedef struct {
    uint32_t *steps, *z;
    rad_index_t *ids;
    uint32_t rows;
} bufs_t;

static rad_real_t comp(rad_vec3_t v, unsigned k)
{
    return k == 0 ? v.x : k == 1 ? v.y : v.z;
}

/* V's coordinates on the view's axes. */
static rad_vec3_t on_frame(const view_t *v, rad_vec3_t d)
{
    rad_vec3_t r;
    r.x = rad__dot_unit(d, v->frame[0]);
    r.y = rad__dot_unit(d, v->frame[1]);
    r.z = rad__dot_unit(d, v->frame[2]);
    return r;
}

/* Whether surface SF, of corners K (N), turns its front to the light: a sun's
 * direction against its normal; a point in front of it at some corner (a quad may be
 * planar only within rounding), as the hemi-cube's test. */
static int faces_light(const rad_scene_t *s, const view_t *v, const rad_surface_t *sf,
                       const uint32_t *k, unsigned n)
{
    unsigned i;
    if (v->ortho) return rad__dot(sf->normal, v->frame[2]) < 0;
    for (i = 0; i < n; i++)
        if (rad__dot_unit(rad__sub(v->c, s->pools.vertices[k[i]]), sf->normal) > 0) return 1;
    return 0;
}

/* Surface SF into target T of frustum FR: its outline once, each pixel given the
 * element of its lattice it sees; a surface turned away from the light as an occluder
 * that shows nothing (ids RAD_INDEX_NONE: it receives nothing, as a gather's cube
 * draws it), a little behind the surfaces the light reaches (view_t: bias, recede) so
 * that a lit face is not shadowed by a back face that meets it or lies on it. */
static void draw_surface(rad_scene_t *s, const view_t *v, const rad__target_t *t,
                         const rad__frustum_t *fr, const rad_surface_t *sf)
{
    static const unsigned char same_axis[3] = {0, 1, 2};
    static const signed char same_sign[3] = {1, 1, 1};
    uint32_t k[4];
    rad_vec3_t lc[4];
    rad__cvert_t cv[4];
    rad__lattice_t lat;
    rad__target_t tl = *t;
    rad__frustum_t fb = *fr;
    unsigned i, j, any, n = rad__surface_corners(s, sf, k);
    const int front = faces_light(s, v, sf, k, n);
    for (i = 0; i < n; i++) {
        const rad_vec3_t p = s->pools.vertices[k[i]];
        rad_vec3_t l = on_frame(v, v->ortho ? p : rad__sub(p, v->c));
        cv[i].c[0] = cv[i].c[1] = cv[i].c[2] = 0;
        if (v->ortho) {
            cv[i].a = l.x - v->u0;
            cv[i].b = l.y - v->v0;
            cv[i].d = v->h;
            cv[i].c[0] = v->far - l.z + RAD__ONE + (front ? v->bias : 0); /* nearness >= 1 */
            lc[i].x = cv[i].a;
            lc[i].y = cv[i].b;
            lc[i].z = cv[i].d;
        } else {
            const unsigned char *ax = rad__face_axis[v->face];
            const signed char *sg = rad__face_sign[v->face];
            rad_real_t f[3];
            for (j = 0; j < 3; j++) f[j] = sg[j] < 0 ? -comp(l, ax[j]) : comp(l, ax[j]);
            cv[i].a = f[0];
            cv[i].b = f[1];
            cv[i].d = f[2];
            lc[i] = l;
        }
    }
    any = rad__outcodes(fr, cv, n);
    if (any & RAD__CULLED) return;
    if (!front) {
        fb.recede = v->recede;
        rad__draw(&s->stats, t, &fb, cv, n, any, RAD_INDEX_NONE);
        return;
    }
    if (sf->n_elements > 1) {
        rad__lattice_init(&lat, sf, lc, n, (int32_t)v->res);
        if (v->ortho)
            rad__lattice_face(&lat, same_axis, same_sign);
        else
            rad__lattice_face(&lat, rad__face_axis[v->face], rad__face_sign[v->face]);
        tl.lat = &lat;
    }
    rad__draw(&s->stats, &tl, fr, cv, n, any,
              (rad_index_t)rad__group_element(s, sf, sf->first_element));
}

/* The spot's falloff at cosine C of the angle to its axis (rad.h). */
static rad_real_t falloff(const rad_light_t *l, rad_real_t c)
{
    rad_real_t t;
    if (c >= l->cos_inner) return RAD__ONE;
    if (c <= l->cos_outer) return 0;
    t = rad__div(c - l->cos_outer, l->cos_inner - l->cos_outer, 0);
    return rad__mul(t, t, 0);
}

/* c^3 of quadrant pixel (I, J) of a face of resolution R, c = R / sqrt(A^2 + B^2 + R^2)
 * for its centre's odd numbers A = 2 I + 1, B = 2 J + 1: in Q31, c from c^2 in Q40. */
static uint64_t pixel_c3(uint32_t r, uint32_t i, uint32_t j)
{
    uint64_t a = 2u * i + 1u, b = 2u * j + 1u, r2 = (uint64_t)r * r;
    uint64_t c = rad__isqrt64(((r2 << 40) / (a * a + b * b + r2)) << 22);
    return (((c * c) >> 31) * c) >> 31;
}

/* The point light's weights: entry k = j q + i of a quadrant is c^3 times 2^26 over the
 * quadrant's sum, rounded down, plus 1 for the first DEFICIT entries, so that each
 * quadrant sums to exactly 2^26 (Q2.30), in both builds. */
static void weight_sums(view_t *v)
{
    uint32_t q = v->res / 2u, n = q * q, k;
    uint64_t got = 0;
    v->sum = 0;
    for (k = 0; k < n; k++) v->sum += pixel_c3(v->res, k % q, k / q);
    for (k = 0; k < n; k++) got += (pixel_c3(v->res, k % q, k / q) << 26) / v->sum;
    v->deficit = (uint32_t)(((uint64_t)1 << 26) - got);
}

static rad_ff_t pixel_weight(const view_t *v, uint32_t i, uint32_t j)
{
    uint32_t k = j * (v->res / 2u) + i;
    return rad__ff_from_q30((uint32_t)((pixel_c3(v->res, i, j) << 26) / v->sum + (k < v->deficit)));
}

/* The weight of pixel (X, Y) of the face drawn: a sun's one count, a point's solid
 * angle, a spot's that times its falloff toward the pixel centre (AXIS: the spot's
 * axis on the face's axes a, b, d). */
static rad_ff_t weight(const view_t *v, const rad_vec3_t *axis, uint32_t x, uint32_t y)
{
    const int32_t r = (int32_t)v->res;
    uint32_t q = v->res / 2u, i = x < q ? q - 1u - x : x - q, j = y < q ? q - 1u - y : y - q;
    rad_ff_t w;
    rad_vec3_t d;
    if (v->ortho) return rad__ff_from_q30(1u);
    w = pixel_weight(v, i, j);
    if (v->l->type != RAD_LIGHT_SPOT) return w;
    d.x = rad__div(rad__from_int(2 * (int32_t)x + 1 - r), rad__from_int(r), 0);
    d.y = rad__div(rad__from_int(r - 1 - 2 * (int32_t)y), rad__from_int(r), 0);
    d.z = RAD__ONE;
    return rad__ff_scale(w, falloff(v->l, rad__div(rad__dot(d, *axis), rad__length(d), 0)),
                         RAD__ONE, 0);
}

/* Rows Y0..Y1-1 of the face drawn: cleared, every surface drawn, each pixel's weight
 * added to the sum of the element it sees. */
static void band(rad_scene_t *s, const view_t *v, const bufs_t *b, const rad_vec3_t *axis,
                 uint32_t y0, uint32_t y1)
{
    const uint32_t r = v->res, npix = (y1 - y0) * r;
    rad__frustum_t fr;
    rad__target_t t;
    uint32_t i, x, y;
    for (i = 0; i < npix; i++) {
        b->z[i] = 0;
        b->ids[i] = RAD_INDEX_NONE;
    }
    fr.half = 0;
    fr.ortho = v->ortho;
    fr.recede = 0;
    fr.width = fr.height = (int)r;
    t.z = b->z;
    t.ids = b->ids;
    t.rgb = 0;
    t.lat = 0;
    t.steps = b->steps;
    t.width = (int)r;
    t.row0 = (int)y0;
    t.row1 = (int)y1;
    t.least = 0;
    for (i = 0; i < s->n_surfaces; i++) draw_surface(s, v, &t, &fr, &s->pools.surfaces[i]);
    for (y = y0, i = 0; y < y1; y++)
        for (x = 0; x < r; x++, i++)
            if (b->ids[i] < s->n_elements) s->acc[b->ids[i]] += weight(v, axis, x, y);
}

/* The sun's frame (its direction the third axis, turned as a patch's cube) and
 * window: the square about the centre of the corners' projections, of half width HW
 * (the tiles' half width times their count, so that the tiles meet exactly; at least
 * RAD__NEAR a tile: the frustum's near plane), its tiles (ortho_res's raster over
 * res), and the largest depth. */
static void sun_view(const rad_scene_t *s, view_t *v)
{
    rad_vec3_t dir, lo = {0, 0, 0}, hi = {0, 0, 0};
    rad_real_t du, dv, ht;
    uint32_t i;
    dir = v->dir;
    rad__cube_frame(dir, 0, v->frame);
    for (i = 0; i < s->n_vertices; i++) {
        rad_vec3_t p = on_frame(v, s->pools.vertices[i]);
        if (i == 0 || p.x < lo.x) lo.x = p.x;
        if (i == 0 || p.y < lo.y) lo.y = p.y;
        if (i == 0 || p.z < lo.z) lo.z = p.z;
        if (i == 0 || p.x > hi.x) hi.x = p.x;
        if (i == 0 || p.y > hi.y) hi.y = p.y;
        if (i == 0 || p.z > hi.z) hi.z = p.z;
    }
    v->uc = lo.x + (hi.x - lo.x) / 2;
    v->vc = lo.y + (hi.y - lo.y) / 2;
    du = hi.x - v->uc;
    dv = hi.y - v->vc;
    v->tiles = (ortho_res(du > dv ? du : dv, v->den, v->want) + v->res - 1u) / v->res;
    /* a tile's half width, rounded up (the centre's rounding, the division's) */
    ht = rad__div(du > dv ? du : dv, rad__from_int((int32_t)v->tiles), 0) + 4 * RAD__EPS;
    v->h = ht < RAD__NEAR ? RAD__NEAR : ht;
    v->bias = rad__div(v->h, rad__from_int(2 * (int32_t)v->res), 0);
    v->hw = rad__mul(v->h, rad__from_int((int32_t)v->tiles), 0); /* exact: under 2^7 units */
    v->far = hi.z;
}

/* Tile T of the sun's window (row after row from its top left) as the view drawn. */
static void sun_tile(view_t *v, uint32_t t)
{
    int32_t tu = (int32_t)(t % v->tiles), tv = (int32_t)(t / v->tiles);
    v->u0 = v->uc - v->hw + rad__mul(v->h, rad__from_int(2 * tu + 1), 0); /* exact, as hw */
    v->v0 = v->vc + v->hw - rad__mul(v->h, rad__from_int(2 * tv + 1), 0);
}

/* Every face of V's view (a sun's tiles, a point's six faces) in bands of B's rows. */
static void render(rad_scene_t *s, view_t *v, const bufs_t *b)
{
    unsigned nface = v->ortho ? 1u : 6u, k;
    uint32_t y, t, ntiles = v->ortho ? v->tiles * v->tiles : 1u;
    rad_vec3_t axis = {0, 0, 0}, ax;
    if (v->l->type == RAD_LIGHT_SPOT) {
        rad__normalize(v->l->direction, &ax);
        ax = on_frame(v, ax);
    }
    for (v->face = 0; v->face < nface; v->face++) {
        if (v->l->type == RAD_LIGHT_SPOT) { /* the axis on this face's a, b, d */
            rad_real_t f[3];
            for (k = 0; k < 3; k++) {
                rad_real_t c = comp(ax, rad__face_axis[v->face][k]);
                f[k] = rad__face_sign[v->face][k] < 0 ? -c : c;
            }
            axis.x = f[0];
            axis.y = f[1];
            axis.z = f[2];
        }
        for (t = 0; t < ntiles; t++) {
            if (v->ortho) sun_tile(v, t);
            for (y = 0; y < v->res; y += b->rows)
                band(s, v, b, &axis, y, y + b->rows < v->res ? y + b->rows : v->res);
        }
    }
}

/* ---- shooting --------------------------------------------------------------------- */

/* E >= 0 times 2^N, stopped at RAD__EMAX (counted in SAT); N < 0 (a scene the core
 * scaled down: rad.h, any units) halves, rounding down in the fixed build (a unit of
 * the last place a halving, against powers of many thousand units). */
static rad_energy_t energy_shift(rad_energy_t e, int n, uint32_t *sat)
{
    for (; n > 0; n--) {
        if (e > RAD__EMAX / 2) {
            (*sat)++;
            return RAD__EMAX;
        }
        e += e;
    }
    for (; n < 0; n++) e = e / 2;
    return e;
}

/* 4 pi / 1.5: the power of unit intensity over the cube's weights (1.5 2^30 in all). */
#define SPHERE_POWER RAD__Q(8.377580409572781)

/* The power of light L's whole raster per channel, in the core's scale, into U. */
static void light_power(rad_scene_t *s, const view_t *v, rad_energy_t *u)
{
    const rad_light_t *l = v->l;
    unsigned c;
    for (c = 0; c < 3; c++) {
        rad_real_t i = rad__channel(&l->intensity, c);
        if (v->ortho) { /* E (2 hw)^2, hw below 2^7: (2 hw)^2 as a product of energies */
            rad_energy_t e = rad__energy_refl(rad__energy(i, 2 * v->hw), 2 * v->hw);
            if (l->type == RAD_LIGHT_SKY) { /* Z wz + H wh, then (2 hw)^2 */
                rad_energy_t h = rad__energy(rad__channel(&l->horizon, c), 2 * v->hw);
                e = rad__energy_ff(e, v->wz) +
                    rad__energy_ff(rad__energy_refl(h, 2 * v->hw), v->wh);
            }
            u[c] = energy_shift(e, s->power_shift, &s->stats.saturations);
        } else { /* lengths scale by 2^length_shift, so I by its square: E stays */
            u[c] = energy_shift(rad__energy(i, SPHERE_POWER), 2 * s->length_shift + s->power_shift,
                                &s->stats.saturations);
        }
    }
}

/* A point's position in the core's scale into C: 0 when beyond the core's range. */
static int light_position(const rad_scene_t *s, const rad_light_t *l, rad_vec3_t *c)
{
    uint32_t sat = 0;
    *c = rad__scale2_vec(l->position, s->length_shift, &sat);
    return !sat && vec_ok(c);
}

/* The sun's disc: 8 points of Vogel's spiral over the unit disc (radius
 * sqrt((k + 1/2) / 8), angle k times the golden angle) and their opposites, in Q16. */
#define SUN_SAMPLES 16u
static const int32_t disc[8][2] = {{16384, 0},      {-20925, 19169}, {3203, -36495},
                                   {26375, 34401},  {-48401, -8561}, {45849, -29166},
                                   {-15336, 57048}, {-29247, -56313}};

/* View V's shot, each channel's power divided by PARTS: its raster's weights into
 * s->acc, then every element that sees it receives its share, and the power arriving
 * joins the emitted power. */
static void shoot_view(rad_scene_t *s, view_t *v, const bufs_t *b, uint32_t parts)
{
    rad_energy_t u[3], got = 0;
    uint32_t e, c, nn;
    if (v->ortho) sun_view(s, v);
    nn = v->res * v->tiles * v->res * v->tiles;
    for (e = 0; e < s->n_elements; e++) s->acc[e] = 0;
    render(s, v, b);
    light_power(s, v, u);
    for (c = 0; c < 3; c++) u[c] /= (rad_energy_t)parts;
    for (e = 0; e < s->n_elements; e++) {
        rad_ff_t f = s->acc[e];
        if (!(f > 0)) continue;
        if (v->ortho) /* the pixel count over all the tiles' (< 2^27), in Q2.30 */
            f = rad__ff_from_q30((uint32_t)((((uint64_t)rad__ff_to_q30(f) << 30) + nn / 2u) / nn));
        rad__receive(s, u, e, f);
        got = rad__esum(got, rad__energy_ff(u[0], f) + rad__energy_ff(u[1], f) +
                                 rad__energy_ff(u[2], f));
    }
    s->emitted = rad__esum(s->emitted, got);
}

#define HALF_PI_Q30 1686629713u /* pi / 2 in Q30, 2 pi in Q28 */

/* sin(2 pi NUM / DEN) in Q30 (DEN > 0), in integers: the angle reduced to a quarter
 * turn's fraction F, then x = F pi / 2 < 2^31 in Q30 and Taylor's series to x^17 / 17!
 * (its remainder below 2e-12 at pi / 2). */
static int64_t sin_q30(uint32_t num, uint32_t den)
{
    const uint64_t q4 = 4u * (uint64_t)num;
    const uint32_t quarter = (uint32_t)((q4 / den) % 4u);
    const int64_t x = (int64_t)(((q4 % den) * HALF_PI_Q30) / den);
    const int64_t x2 = (x * x) >> 30;
    int64_t term = quarter & 1u ? (int64_t)1 << 30 : x, sum = term; /* cos or sin of x */
    unsigned k;
    for (k = quarter & 1u ? 1u : 2u; k < 18u; k += 2u) {
        term = -((term * x2) >> 30) / (int64_t)(k * (k + 1u));
        sum += term;
    }
    return quarter >= 2u ? -sum : sum;
}

static rad_real_t real_q30(int64_t q)
{
    return RAD_REAL_RATIO(q, 1073741824);
}

/* Q30 a^3 for A in Q30, A <= 1. */
static uint64_t cube_q30(uint64_t a)
{
    return (((a * a) >> 30) * a) >> 30;
}

/* A sky band's edge: sqrt(m^2 - i^2) / m in Q30 (m <= 16: m^2 - i^2 < 2^9), the root
 * in Q27 (off by less than 2^-27). */
static uint64_t edge_q30(uint64_t m, uint64_t i)
{
    return (rad__isqrt64((m * m - i * i) << 54) << 3) / m;
}

/* atan(X) in Q30 for X >= 0 in Q30 (below 2^32): X halved twice by atan x =
 * 2 atan(x / (1 + sqrt(1 + x^2))), to at most tan(pi / 8) = 0.41, then Taylor's series
 * to x^41 (its remainder below 2e-17). */
static uint64_t atan_q30(uint64_t x)
{
    const uint64_t one = (uint64_t)1 << 30;
    int64_t term, sum, x2;
    unsigned k;
    for (k = 0; k < 2u; k++) x = (x << 30) / (one + rad__isqrt64((one + ((x * x) >> 30)) << 30));
    x2 = (int64_t)((x * x) >> 30);
    term = (int64_t)x;
    sum = term;
    for (k = 3; k < 42u; k += 2u) {
        term = -((term * x2) >> 30); /* (-1)^(k/2) x^k */
        sum += term / (int64_t)k;
    }
    return (uint64_t)sum * 4u;
}

/* The sum of a colour's channels as an integer (Q16), alike in both builds. */
static uint64_t grey_q16(const rad_rgb_t *c)
{
#if RAD_FLOAT
    return (uint64_t)((c->r + c->g + c->b) * 65536.0f + 0.5f);
#else
    return (uint64_t)c->r + (uint64_t)c->g + (uint64_t)c->b;
#endif
}

/* One of a sun's or sky's directions: the way its light travels (unit) and the
 * irradiance it gives a plane facing it: a sun's E over PARTS, a sky's WZ times its
 * zenith's radiance Z plus WH times its horizon's H. */
typedef struct {
    rad_vec3_t dir;
    rad_ff_t wz, wh;
    uint32_t parts;
} dir_t;
typedef void dir_fn(void *ctx, const dir_t *d);

/* The sky's 3 m^2 directions (the top of the file) to FN, all in integers, as both
 * builds' must agree. Band i between r1 = i / m and r2 = (i + 1) / m on the disc
 * (c^2 = 1 - r^2, dw = r dr dphi / c) has, per unit of angle, the integrals
 *   Au = int c dw = (r2^2 - r1^2) / 2,        Ac = int c^2 dw = (c1^3 - c2^3) / 3,
 *   Bu = int s dw = (asin r - r c) / 2 |r1..r2, Bc = int c s dw = (r2^3 - r1^3) / 3
 * (s = r the sine of the zenith angle). A cell's light of L = H (1 - c) + Z c has the
 * vector integral of L w dw with the vertical part A = H (Au - Ac) + Z Ac and the
 * horizontal part B = H (Bu - Bc) + Z Bc times sin(pi / n) / (pi / n) toward the
 * cell's middle angle: its shot comes along that vector (for Z and H the sums of the
 * channels), so a plane that sees the whole cell in front of it receives the cell's
 * light exactly (for a grey sky); each channel's E is its own 2 pi A / n over the
 * shot's cosine c to up, so a plane facing up receives exactly pi H + 2 pi (Z - H) / 3.
 * In Q30: the edges c1, c2 (edge_q30), the integrals, the cosine and sine of the shot
 * (c, sn), the weights WZ = 2 pi Ac / (n c), WH = 2 pi (Au - Ac) / (n c) (at most 2 pi
 * / 3); 2 pi in Q28; A and B (Q16 radiance times Q30) shifted below 2^31 for their
 * length. */
static void sky_dirs(const rad_light_t *l, dir_fn *fn, void *ctx)
{
    const uint64_t two_pi = HALF_PI_Q30; /* 2 pi in Q28 */
    const uint32_t m = sky_bands(l);
    const uint64_t mm = (uint64_t)m * m;
    uint64_t zs = grey_q16(&l->intensity), hs = grey_q16(&l->horizon), asin1 = 0;
    rad_vec3_t up, f[3];
    dir_t d;
    uint32_t i, j;
    d.parts = 1;
    rad__normalize(sky_up(l), &up);
    rad__cube_frame(up, 0, f);
    if (zs + hs == 0) zs = hs = 1; /* a black sky: any directions */
    for (i = 0; i < m; i++) {
        const uint32_t n = 3u * (2u * i + 1u);
        const uint64_t c1 = edge_q30(m, i), c2 = edge_q30(m, i + 1u);
        const uint64_t r1 = ((uint64_t)i << 30) / m, r2 = ((uint64_t)(i + 1u) << 30) / m;
        const uint64_t asin2 = c2 ? atan_q30((r2 << 30) / c2) : HALF_PI_Q30;
        const uint64_t au = (((uint64_t)2u * i + 1u) << 30) / (2u * mm);
        const uint64_t ac = (cube_q30(c1) - cube_q30(c2)) / 3u;
        const uint64_t bu = (asin2 - asin1 - ((r2 * c2) >> 30) + ((r1 * c1) >> 30)) / 2u;
        const uint64_t bc = (((uint64_t)3u * i * i + 3u * i + 1u) << 30) / (3u * mm * m);
        const uint64_t sinc = (((uint64_t)n * (uint64_t)sin_q30(1u, 2u * n)) << 28) / two_pi * 2u;
        uint64_t va = hs * (au > ac ? au - ac : 0) + zs * ac;
        uint64_t vb = ((hs * (bu > bc ? bu - bc : 0) + zs * bc) >> 30) * sinc, len, c, sn;
        while (va >= ((uint64_t)1 << 31) || vb >= ((uint64_t)1 << 31)) {
            va >>= 1;
            vb >>= 1;
        }
        len = rad__isqrt64(va * va + vb * vb);
        c = (va << 30) / len;
        sn = (vb << 30) / len;
        asin1 = asin2;
        d.wz = rad__ff_from_q30((uint32_t)(((((ac * two_pi) >> 28) / n) << 30) / c));
        d.wh = rad__ff_from_q30(
            (uint32_t)((((((au > ac ? au - ac : 0) * two_pi) >> 28) / n) << 30) / c));
        for (j = 0; j < n; j++) { /* the light travels down: -(c up + sn (cos f0 + sin f1)) */
            const rad_real_t a0 = real_q30(((int64_t)sn * sin_q30(4u * j + 2u + n, 4u * n)) >> 30);
            const rad_real_t a1 = real_q30(((int64_t)sn * sin_q30(2u * j + 1u, 2u * n)) >> 30);
            const rad_real_t cr = real_q30((int64_t)c);
            rad_vec3_t t;
            t.x = -(rad__mul(cr, up.x, 0) + rad__mul(a0, f[0].x, 0) + rad__mul(a1, f[1].x, 0));
            t.y = -(rad__mul(cr, up.y, 0) + rad__mul(a0, f[0].y, 0) + rad__mul(a1, f[1].y, 0));
            t.z = -(rad__mul(cr, up.z, 0) + rad__mul(a0, f[0].z, 0) + rad__mul(a1, f[1].z, 0));
            rad__normalize(t, &d.dir);
            fn(ctx, &d);
        }
    }
}

/* Sun or sky L's directions, in a fixed order, to FN: a sky's (sky_dirs), a sun's one,
 * or the 16 of its disc when it has a radius. */
static void light_dirs(const rad_light_t *l, dir_fn *fn, void *ctx)
{
    dir_t d;
    d.wz = d.wh = 0;
    if (l->type == RAD_LIGHT_SKY) {
        sky_dirs(l, fn, ctx);
    } else if (l->radius == 0) {
        rad__normalize(l->direction, &d.dir);
        d.parts = 1;
        fn(ctx, &d);
    } else {
        rad_vec3_t d0, f[3];
        uint32_t k;
        rad__normalize(l->direction, &d0);
        rad__cube_frame(d0, 0, f);
        d.parts = SUN_SAMPLES;
        for (k = 0; k < SUN_SAMPLES; k++) { /* d0 + radius (x f0 + y f1) */
            const int32_t sg = k < SUN_SAMPLES / 2u ? 1 : -1;
            rad_real_t x = rad__mul(l->radius, RAD_REAL_RATIO(sg * disc[k % 8u][0], 65536), 0);
            rad_real_t y = rad__mul(l->radius, RAD_REAL_RATIO(sg * disc[k % 8u][1], 65536), 0);
            rad_vec3_t t;
            t.x = d0.x + rad__mul(x, f[0].x, 0) + rad__mul(y, f[1].x, 0);
            t.y = d0.y + rad__mul(x, f[0].y, 0) + rad__mul(y, f[1].y, 0);
            t.z = d0.z + rad__mul(x, f[0].z, 0) + rad__mul(y, f[1].z, 0);
            rad__normalize(t, &d.dir);
            fn(ctx, &d);
        }
    }
}

/* A sun's or sky's shot along one of its directions. */
typedef struct {
    rad_scene_t *s;
    view_t *v;
    const bufs_t *b;
} shot_t;

static void shoot_dir(void *ctx, const dir_t *d)
{
    shot_t *sh = ctx;
    sh->v->dir = d->dir;
    sh->v->wz = d->wz;
    sh->v->wh = d->wh;
    shoot_view(sh->s, sh->v, sh->b, d->parts);
}

/* Light L's shot (a sun of some radius: one a direction of its disc). */
static void shoot_light(rad_scene_t *s, const rad_light_t *l)
{
    view_t v = {0};
    bufs_t b = {0};
    uint32_t e, head;
    v.l = l;
    v.ortho = !is_point(l);
    v.res = v.ortho ? s->cfg.res : fitted_res(s, wanted_res(s, l));
    v.tiles = 1;
    if (v.ortho) {
        v.want = wanted_res(s, l);
        if (v.want < v.res) v.res = v.want;
        v.den = ortho_den(s, l,
                          l->type == RAD_LIGHT_SKY
                              ? 3u * sky_bands(l) * sky_bands(l)
                              /* a disc's samples, times a dome's suns */
                              : (l->radius > 0 ? SUN_SAMPLES : 1u) * (l->dirs > 1u ? l->dirs : 1u));
    }
    head = head_words(s, v.res);
    b.steps = head ? s->zbuf : s->steps;
    b.z = s->zbuf + head;
    b.ids = s->ibuf;
    b.rows = (s->pass_pixels - head) / v.res;
    for (e = 0; e < head; e++) b.steps[e] = 0; /* every span leaves it zero */
    if (!v.ortho) {
        static const signed char turn7[3][3] = {{2, 3, 6}, {3, -6, 2}, {6, 2, -3}};
        unsigned k;
        light_position(s, l, &v.c);
        for (k = 0; k < 3; k++) {
            v.frame[k].x = RAD_REAL_RATIO(turn7[k][0], 7);
            v.frame[k].y = RAD_REAL_RATIO(turn7[k][1], 7);
            v.frame[k].z = RAD_REAL_RATIO(turn7[k][2], 7);
        }
        weight_sums(&v);
        for (v.recede = 1; (1u << v.recede) < 2u * v.res; v.recede++) {} /* 2^recede >= 2 res */
        shoot_view(s, &v, &b, 1);
    } else {
        shot_t sh;
        sh.s = s;
        sh.v = &v;
        sh.b = &b;
        light_dirs(l, shoot_dir, &sh);
    }
    s->cube_built = 0; /* a coarse cube's tables lay in the depth buffer */
}

int rad__lights_check(const rad_scene_t *s, uint32_t first)
{
    uint32_t k;
    rad_vec3_t c;
    for (k = first; k < s->n_lights; k++)
        if (is_point(&s->lights[k]) && !light_position(s, &s->lights[k], &c)) return RAD_ERR_RANGE;
    return RAD_OK;
}

int rad__lights_shoot(rad_scene_t *s, uint32_t max)
{
    uint32_t n = 0;
    if (rad__lights_check(s, s->lights_shot) < 0) return RAD_ERR_RANGE;
    for (; n < max && rad__lights_pending(s); n++, s->lights_shot++)
        if (!dark(&s->lights[s->lights_shot])) shoot_light(s, &s->lights[s->lights_shot]);
    return (int)n;
}

int rad__lights_solve(rad_scene_t *s, const rad_rows_t *rows, uint32_t max_shots, rad_real_t tol)
{
    int lit, rest;
    rad__freeze(s);
    lit = rad__lights_shoot(s, max_shots); /* before any patch: their power joins emitted */
    if (lit < 0 || (uint32_t)lit >= max_shots) return lit;
    rest = rad__shoot(s, rows, max_shots - (uint32_t)lit, tol);
    return rest < 0 ? rest : lit + rest;
}

/* The irradiance of point light L at the nearest plane of a surface it faces, in the
 * caller's units (the core's lengths are the caller's times 2^length_shift): at least
 * that of any point of the scene. 0 when it faces none. */
static rad_real_t brightest(const rad_rgb_t *c)
{
    rad_real_t m = c->r > c->g ? c->r : c->g;
    return m > c->b ? m : c->b;
}

static rad_real_t point_peak(const rad_scene_t *s, const rad_light_t *l)
{
    rad_real_t dmin = -1, d2;
    rad_vec3_t c;
    uint32_t k[4], sat = 0, j;
    view_t v;
    if (!light_position(s, l, &c)) return 0; /* rad_shoot refuses it */
    v.ortho = 0;
    v.c = c;
    for (j = 0; j < s->n_surfaces; j++) {
        const rad_surface_t *sf = &s->pools.surfaces[j];
        unsigned n = rad__surface_corners(s, sf, k);
        rad_real_t d;
        if (!faces_light(s, &v, sf, k, n)) continue;
        d = rad__dot_unit(rad__sub(c, s->pools.vertices[k[0]]), sf->normal);
        if (d < 0) d = -d;
        if (dmin < 0 || d < dmin) dmin = d;
    }
    if (dmin < 0) return 0;
    d2 = rad__scale2(rad__mul(dmin, dmin, &sat), -2 * s->length_shift, &sat);
    if (!(d2 > 0)) return RAD__Q(32767.0);
    return rad__div(brightest(&l->intensity), d2, &sat);
}

rad_real_t rad__lights_peak(const rad_scene_t *s)
{
    rad_real_t m = 0, p;
    uint32_t k;
    for (k = 0; k < s->n_lights; k++) {
        const rad_light_t *l = &s->lights[k];
        if (l->type == RAD_LIGHT_SKY) /* at most pi times its brightest radiance */
            p = rad__mul(RAD__Q(3.14159265),
                         brightest(&l->intensity) > brightest(&l->horizon)
                             ? brightest(&l->intensity)
                             : brightest(&l->horizon),
                         0);
        else
            p = l->type == RAD_LIGHT_SUN ? brightest(&l->intensity) : point_peak(s, l);
        if (p > m) m = p;
    }
    return m;
}

/* ---- the direct light at a point (gathers) ------------------------------------------- */

/* What rad__lights_at passes on for one light. */
typedef struct {
    const rad_scene_t *s;
    const rad_light_t *l;
    uint32_t k; /* its index */
    rad__light_fn *fn;
    void *ctx;
    uint32_t *sat;
} arrive_t;

/* Channel C of a direction's irradiance in the core's scale: a sun's E / parts, a sky's
 * Z wz + H wh (rad__wterm, rounded once), then the power shift. */
static rad_real_t dir_channel(const arrive_t *a, const dir_t *d, unsigned c)
{
    rad_real_t i = rad__channel(&a->l->intensity, c), e;
    if (a->l->type == RAD_LIGHT_SKY)
        e = rad__wvalue(rad__wterm(d->wz, i) + rad__wterm(d->wh, rad__channel(&a->l->horizon, c)),
                        a->sat);
    else
        e = i / (rad_real_t)d->parts;
    return rad__scale2(e, a->s->power_shift, a->sat);
}

static void arrive_dir(void *ctx, const dir_t *d)
{
    const arrive_t *a = ctx;
    rad_vec3_t u;
    rad_rgb_t e;
    u.x = -d->dir.x;
    u.y = -d->dir.y;
    u.z = -d->dir.z;
    e.r = dir_channel(a, d, 0);
    e.g = dir_channel(a, d, 1);
    e.b = dir_channel(a, d, 2);
    a->fn(a->ctx, a->k, &u, &u, 0, &e);
}

/* Point or spot A->l seen from C: I / r^2 per channel, with I in the core's scale
 * (2^(2 length_shift + power_shift) of the caller's, as light_power's) over r^2 in the
 * core's lengths, as a ratio of energies (no Q16.16 square to overflow), times the
 * spot's falloff. */
static void arrive_point(const arrive_t *a, rad_vec3_t c)
{
    const rad_light_t *l = a->l;
    rad_vec3_t p, w, u, axis;
    rad_real_t r, k = RAD__ONE, v[3];
    rad_energy_t r2;
    rad_rgb_t e;
    unsigned ch;
    if (!light_position(a->s, l, &p)) return;
    w = rad__sub(p, c);
    r = rad__length(w);
    if (!(r > RAD__NEAR) || !rad__normalize(w, &u)) return; /* at the point: no direction */
    if (l->type == RAD_LIGHT_SPOT) {
        rad__normalize(l->direction, &axis);
        k = falloff(l, -rad__dot(u, axis));
        if (!(k > 0)) return;
    }
    r2 = rad__energy(r, r);
    for (ch = 0; ch < 3; ch++) {
        rad_energy_t i = energy_shift(rad__energy(rad__channel(&l->intensity, ch), RAD__ONE),
                                      2 * a->s->length_shift + a->s->power_shift, a->sat);
        v[ch] = rad__mul(rad__energy_ratio(i, r2), k, a->sat);
    }
    e.r = v[0];
    e.g = v[1];
    e.b = v[2];
    a->fn(a->ctx, a->k, &w, &u, 1, &e);
}

void rad__lights_at(const rad_scene_t *s, rad_vec3_t c, unsigned types, rad__light_fn *fn,
                    void *ctx, uint32_t *sat)
{
    arrive_t a;
    uint32_t k;
    a.s = s;
    a.fn = fn;
    a.ctx = ctx;
    a.sat = sat;
    for (k = 0; k < s->lights_shot && k < s->n_lights; k++) {
        a.l = &s->lights[k];
        a.k = k;
        if (dark(a.l) || !(types & (1u << a.l->type))) continue;
        if (is_point(a.l))
            arrive_point(&a, c);
        else
            light_dirs(a.l, arrive_dir, &a);
    }
}
