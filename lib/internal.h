/* SPDX-License-Identifier: MIT */
/* rad — declarations shared by lib/ files (the rad__ names), never installed. */
#ifndef RAD_INTERNAL_H
#define RAD_INTERNAL_H

#include "scalar.h"

#if RAD_FLOAT
#define rad__outcodes        radf__outcodes
#define rad__pixel           radf__pixel
#define rad__eye_pixel       radf__eye_pixel
#define rad__lights_at       radf__lights_at
#define rad__receive         radf__receive
#define rad__shoot           radf__shoot
#define rad__cube_part       radf__cube_part
#define rad__cube_merge      radf__cube_merge
#define rad__cube_list       radf__cube_list
#define rad__cube_lists      radf__cube_lists
#define rad__cube_level      radf__cube_level
#define rad__shot_cube       radf__shot_cube
#define rad__surface_corners radf__surface_corners
#define rad__lattice_init    radf__lattice_init
#define rad__lattice_face    radf__lattice_face
#define rad__lattice_span    radf__lattice_span
#define rad__dff_table       radf__dff_table
#define rad__cube_frame      radf__cube_frame
#define rad__eye_face        radf__eye_face
#define rad__eye_clear       radf__eye_clear
#define rad__eye_surface     radf__eye_surface
#define rad__cull_face       radf__cull_face
#define rad__cull_fits       radf__cull_fits
#define rad__cull_edges      radf__cull_edges
#define rad__cull_work       radf__cull_work
#define rad__cull_after      radf__cull_after
#define rad__face_axis       radf__face_axis
#define rad__face_sign       radf__face_sign
#define rad__emission        radf__emission
#define rad__scale_geometry  radf__scale_geometry
#define rad__freeze          radf__freeze
#define rad__scale_power     radf__scale_power
#define rad__ambient         radf__ambient
#define rad__patch_mean      radf__patch_mean
#define rad__lights_shoot    radf__lights_shoot
#define rad__lights_check    radf__lights_check
#define rad__lights_peak     radf__lights_peak
#define rad__lights_solve    radf__lights_solve
#endif

/* A vertex in view space before projection: a across, b up, d depth; c a colour. */
typedef struct {
    rad_real_t a, b, d;
    rad_real_t c[3];
} rad__cvert_t;

/* A view frustum of unit slopes: |a| <= d, and d >= b >= -d (or >= 0 when half is
 * set: the hemi-cube's side faces), d >= RAD__NEAR; mapped onto a WIDTH x HEIGHT
 * raster. (The camera scales its axes so that its field of view has unit slopes.)
 * ORTHO: an orthographic view (a sun's, light.c) given as vertices whose d is one
 * constant, the window's half width, so that a / d is their place across it: the
 * depth tested is then the vertex attribute c[0] (nearness, larger is nearer) in
 * place of 1 / d, and is linear on the screen as an orthographic depth is.
 * RECEDE (perspective only; 0: none): every vertex's depth w lowered by w / 2^RECEDE,
 * as if the polygon were scaled away from the eye by 1 / (1 - 2^-RECEDE) (its pixels
 * unchanged): a light's faces turned away from it, a little behind the faces it lights
 * (light.c). */
typedef struct {
    unsigned char half, ortho, recede; /* (chars: the frustum stays 12 bytes on 32-bit stacks) */
    int width, height;
} rad__frustum_t;

/* A family of lattice lines (lattice.c): line k's plane through the cube's centre has
 * normal C0 + k C1 + k^2 C2 (c[j], on the lattice's current axes: the cube's x, y, z,
 * then a face's a, -b, d), k = 0..N, with K elements to a patch across the lines. */
typedef struct {
    int64_t c[3][3];
    int64_t o[3]; /* on the current face, coefficient j's E at pixel (x, y):
                     o[j] + 2 x c[j][0] + 2 y c[j][1] */
    uint32_t n, k;
    uint32_t unit, coarse; /* quads: a fine and a coarse step's change of the element id */
    int32_t hint[2];       /* the last span's first and last cells on this face, or -1 */
    /* Spans start from a walker (lattice.c) at line WK of pixel (WX, WY), -1 before the
     * face's first span: w[0..6] are E_k, D = E_{k+1} - E_k, D2 (D's change to the
     * next k), and the changes of E and D a pixel right and a row down. */
    int64_t w[7];
    int32_t wk, wx, wy;
} rad__family_t;

/* A surface's lattice: 2 families (quad columns, rows) or 3 (triangle i, j, i + j);
 * element ids from FIRST, PU patches across a quad (a triangle's patch levels); seen
 * on a face of resolution RES whose axes a, -b, d are the cube's AXIS (0 x, 1 y, 2 z)
 * times SIGN (the cube's own axes before the first face); from SF and its NCORNER
 * corners CORNER (READY: 1 the families set up, 2 and the face's coefficients). */
typedef struct {
    rad__family_t fam[3];
    unsigned nfam, ncorner, ready;
    int32_t res;
    uint32_t first, pu;
    const rad_surface_t *sf;
    const rad_vec3_t *corner;
    unsigned char axis[3];
    signed char sign[3];
} rad__lattice_t;

/* The lattice of surface SF from its N corners (rad__surface_corners' order) relative
 * to the centre of a cube of resolution RES, on the cube's axes. (Set up here, not at
 * the first span: there the set-up's frames would sit under the rasterizer's, and the
 * Cortex-M0 port has no stack to spare.) */
void rad__lattice_init(rad__lattice_t *lt, const rad_surface_t *sf, const rad_vec3_t *corner,
                       unsigned n, int32_t res);
/* LT seen on a face whose axes a, b, d are the cube's AXIS times SIGN (+-1). */
void rad__lattice_face(rad__lattice_t *lt, const unsigned char *axis, const signed char *sign);
/* Pixels XS..XE-1 of row Y of an item buffer: depth W (* 2^16) stepping by DW, ids
 * the elements of LT under each pixel. STEPS: XE - XS entries, zero, left zero. */
void rad__lattice_span(rad__lattice_t *lt, int32_t y, int32_t xs, int32_t xe, uint32_t *z,
                       rad_index_t *ids, uint64_t w, uint64_t dw, uint32_t *steps);

/* Where the rasterizer writes: rows row0..row1-1 of a WIDTH-wide raster; buffers hold
 * just those rows. One of ids and rgb is set: with rgb, colours are interpolated; with
 * ids, every pixel gets the polygon's id, or with LAT the id of its lattice element
 * (STEPS: WIDTH entries of zero for rad__lattice_span). LEAST (ids without LAT): of
 * equal depths a pixel keeps the least id, not the earlier drawn, so that what a
 * pixel ends with does not depend on the order of drawing (cull.c). */
typedef struct {
    uint32_t *z;
    rad_index_t *ids;
    rad_rgb_t *rgb;
    rad__lattice_t *lat;
    uint32_t *steps;
    int width, row0, row1, least;
} rad__target_t;

/* Outcodes of polygon IN against frustum F: returns the OR of the vertices' outside
 * bits (bit p: outside plane p), or RAD__CULLED when all are outside one plane. */
#define RAD__CULLED 0x100u
unsigned rad__outcodes(const rad__frustum_t *f, const rad__cvert_t *in, unsigned n);
/* The pixel (column *X, row *Y) of frustum F's raster that point C projects into, and
 * its depth value *W, as the rasterizer projects a vertex: 1, or 0 when C lies
 * outside F. */
int rad__pixel(const rad__frustum_t *f, const rad__cvert_t *c, uint32_t *x, uint32_t *y,
               uint32_t *w);

/* Pixel X of a row of an item buffer gets depth D and ID if D is nearer than Z's (depth
 * is 1/distance: larger is nearer), without a branch (an element's run in a row is
 * under two pixels on average at res 128: too short for a branch to be predicted). */
static inline void rad__depth_put(uint32_t *z, rad_index_t *ids, int32_t x, uint32_t d, uint32_t id)
{
    uint32_t old = z[x];
    rad_index_t keep = ids[x];
    z[x] = d > old ? d : old;
    ids[x] = d > old ? (rad_index_t)id : keep;
}

/* Clips the convex polygon IN (N <= 4 vertices) against the planes in ANY (from
 * rad__outcodes, or an equal test of the caller's), projects it and rasterizes it
 * into T with item id ID. */
void rad__draw(rad_stats_t *st, const rad__target_t *t, const rad__frustum_t *f,
               const rad__cvert_t *in, unsigned n, unsigned any, rad_index_t id);

/* Work buffer layout and delta form factor table (hemicube.c). */
int rad__hemicube_init(rad_scene_t *s);
/* The delta form factor table of a hemi-cube of resolution RES: TOP and SIDE quadrants
 * of (RES/2)^2 entries each, summing over the whole cube to exactly 2^30 (Q2.30). */
void rad__dff_table(uint32_t res, rad_ff_t *top, rad_ff_t *side);
/* Row R of face FACE's delta form factors: the quadrant row it mirrors, entry i for
 * the pixels q + i and q - 1 - i (q = RES/2). */
static inline const rad_ff_t *rad__dff_row(const rad_ff_t *top, const rad_ff_t *side, uint32_t res,
                                           unsigned face, uint32_t r)
{
    uint32_t q = res / 2u;
    if (face == 0) return top + (size_t)(r < q ? q - 1u - r : r - q) * q;
    return side + (size_t)r * q;
}
/* The frame (x, y, z = N, unit) of a cube at a point of unit normal N, turned by the
 * SPIN-th (mod 8) of its rational turns about N. */
void rad__cube_frame(rad_vec3_t n, unsigned spin, rad_vec3_t *frame);
/* The axes a, b, d of face F (0 +z, 1 +x, 2 -x, 3 +y, 4 -y, 5 -z) are the cube's axes
 * rad__face_axis[F] times rad__face_sign[F]. */
extern const unsigned char rad__face_axis[6][3];
extern const signed char rad__face_sign[6][3];

/* A cube at any point (gather.c): centre C, FRAME, resolution RES, a hemi-cube (five
 * faces, half sides) or, FULL, a whole cube (six whole faces); surface SKIP not drawn
 * (past the last: none), nor those joined to patch GROUP (a shot's, pass_t's); BACKS:
 * surfaces seen from behind drawn as occluders showing nothing (a gather's), else left
 * out (a shot's). Buffers of one face: Z and IDS of RES^2 pixels, STEPS of RES entries,
 * zero. CULL: a hierarchy (rad_cull_build) to draw through, with its work CWORK
 * (rad__cull_work bytes, its pixel edges by rad__cull_edges), or null: every surface
 * drawn. */
typedef struct {
    rad_vec3_t c, frame[3];
    uint32_t res, skip, group;
    int full, backs;
    uint32_t *z, *steps;
    rad_index_t *ids;
    rad_stats_t *st;
    const void *cull;
    uint32_t *cwork;
} rad__eye_t;
/* Face FACE of E's cube into its buffers: cleared, then every surface drawn (rows 0 at
 * the face's top, b = +1, as the hemi-cube's). */
void rad__eye_face(const rad_scene_t *s, const rad__eye_t *e, unsigned face);
/* Where direction W (the scene's axes, from E's centre; any length above RAD__NEAR)
 * meets E's cube: 1, with *FACE the face it lies on (each direction on one), *PX its
 * pixel's index in that face's buffers and *DEPTH its depth value there for a point at
 * W (as the rasterizer's); 0 below a hemi-cube's horizon. */
int rad__eye_pixel(const rad__eye_t *e, rad_vec3_t w, uint32_t *face, uint32_t *px,
                   uint32_t *depth);
/* Face FACE of E's buffers cleared; surface K drawn into them, as rad__eye_face draws it
 * (nothing when it is E's skipped one), or with BY_INDEX by its index K at every pixel,
 * front or back, ties kept by the least id (rad__target_t.least): the same depths. */
void rad__eye_clear(const rad__eye_t *e, unsigned face);
void rad__eye_surface(const rad_scene_t *s, const rad__eye_t *e, unsigned face, uint32_t k,
                      int by_index);
/* rad__eye_face through E's hierarchy (cull.c): the same pixels, bit for bit. Returns
 * the hierarchy's nodes it tested. */
uint32_t rad__cull_face(const rad_scene_t *s, const rad__eye_t *e, unsigned face);
/* A shot's cube drawn without its hierarchy (hemicube.c); and after a shot, or a batch
 * of CUBES, whether they were CULLED (all or none: cull_wait is the batch's) and the
 * nodes they TESTED in all: whether the next shots draw every surface (s->cull_wait). */
#define RAD__DRAWN_ALL 0xFFFFFFFFu
void rad__cull_after(rad_scene_t *s, int culled, uint64_t tests, uint32_t cubes);
/* Whether hierarchy CULL was built for S as it stands (its surfaces and scale). */
int rad__cull_fits(const rad_scene_t *s, const void *cull);
/* The bytes of a cube's culling work at resolution RES through hierarchy CULL (4-aligned
 * work: RAD_GATHER_CULL_BYTES less its 3 of alignment), and its first part, the pixel
 * edges, written into CWORK. */
size_t rad__cull_work(const void *cull, uint32_t res);
void rad__cull_edges(uint32_t res, uint32_t *cwork);
/* Form factors from patch P's centre to every element, into s->acc, at res. */
void rad__hemicube(rad_scene_t *s, uint32_t p);
/* The shot's cube at coarse level LEVEL (0: res; rad_config_t.coarse) or the deepest
 * the scene allows: sets s->cube_res and the cube's tables (block sums of the res
 * table, built when the level changes). Returns the level set. */
unsigned rad__cube_level(rad_scene_t *s, unsigned level);
/* rad__hemicube at the level rad__cube_level set. */
void rad__shot_cube(rad_scene_t *s, uint32_t p);

/* Element E receives power F * U (three channels) from a shooter; its patch's unshot
 * power grows by what it reflects (solve.c). */
void rad__receive(rad_scene_t *s, const rad_energy_t *u, uint32_t e, rad_ff_t f);
/* Lights (light.c): whether some have not shot since the solution started; shooting
 * up to MAX of them (returns how many, or RAD_ERR_RANGE with none shot when a point
 * or spot light lies outside the core's range); and their brightest irradiance on
 * any surface, in the caller's units, for the power shift. */
static inline int rad__lights_pending(const rad_scene_t *s)
{
    return s->lights_shot < s->n_lights;
}
int rad__lights_shoot(rad_scene_t *s, uint32_t max);
/* RAD_ERR_RANGE when a point or spot light from index FIRST on lies beyond the core's
 * range (rad__lights_shoot would refuse), else RAD_OK. */
int rad__lights_check(const rad_scene_t *s, uint32_t first);
rad_real_t rad__lights_peak(const rad_scene_t *s);
/* The direct light of S's lights that have shot whose types (RAD_LIGHT_*) are in the
 * mask TYPES (bit 1 << type), at point C (the core's scale), a direction at a time: FN
 * gets the light's index K, the vector W from C toward the light (a sun's or sky's
 * direction: unit; a point's or spot's: to its position), its unit U, whether the
 * light is a point (at W's end) or at infinity, and the irradiance E it gives a plane
 * facing U there (per channel, the core's scale and power shift, >= 0; a spot's
 * falloff applied), in a fixed order. Counts saturations in SAT. */
typedef void rad__light_fn(void *ctx, uint32_t k, const rad_vec3_t *w, const rad_vec3_t *u,
                           int point, const rad_rgb_t *e);
#define RAD__LIGHTS_ALL   0xffffu
#define RAD__LIGHTS_SKIES (1u << RAD_LIGHT_SKY)
void rad__lights_at(const rad_scene_t *s, rad_vec3_t c, unsigned types, rad__light_fn *fn,
                    void *ctx, uint32_t *sat);
/* rad_shoot (ROWS null) or rad_rows_shoot while lights are pending: they shoot (each
 * a shot of MAX_SHOTS), then patches as rad__shoot (returns the shots, or the error). */
int rad__lights_solve(rad_scene_t *s, const rad_rows_t *rows, uint32_t max_shots, rad_real_t tol);

/* Progressive refinement through hemi-cubes (ROWS null) or stored rows. */
int rad__shoot(rad_scene_t *s, const rad_rows_t *rows, uint32_t max_shots, rad_real_t tol);

/* The 16-bit code of a stored form factor (Q2.30 in): 5-bit exponent, 11-bit mantissa,
 * rounded to nearest; relative error below 2^-11, exact below 2^11. */
static inline uint16_t rad__ff_code(uint32_t q)
{
    unsigned e = 0;
    uint32_t m;
    while ((q >> e) >= 2048u) e++;
    m = e ? (q + (1u << (e - 1))) >> e : q;
    if (m == 2048u) {
        m = 1024u;
        e++;
    }
    return (uint16_t)(e << 11 | m);
}
static inline uint32_t rad__ff_decode(uint16_t c)
{
    return (uint32_t)(c & 2047u) << (c >> 11);
}

/* The head of a part buffer (RAD_PART_BYTES): the part's raster counts (rad_shot_part),
 * then the shot as rad_shot_aim set it up (its power U, the same in every part) and
 * the saturations of the part's receiving. STATE: RAD__PART_RENDERED, _AIMED, _RECEIVED
 * or _SHOT, in that order. */
typedef struct {
    uint32_t calls, state;
    uint64_t pixels;
    rad_energy_t u[3];
    uint32_t saturations;
    uint32_t shot;         /* rad_scene_t.shot_serial of the shot it was rendered for */
    uint32_t part, nparts; /* rad_shot_part's; a batch's cube: its shooter K of N */
    uint32_t patch;        /* a batch's cube: the patch it was rendered for, */
    uint32_t seen;         /* how many elements it sees (rad__cube_list), */
    uint32_t tests;        /* the hierarchy's nodes its culling tested, or RAD__DRAWN_ALL */
    uint32_t rparts;       /* the parts of the receipts when this is one (rad_batch_receive_part) */
    rad_energy_t left[3];  /* and what its patch is left owing when it shoots */
} rad__part_head_t;
#define RAD__PART_HEAD     96u /* RAD_PART_BYTES's head: sizeof(rad__part_head_t) (hemicube.c) */
/* States are words a zeroed or unwritten buffer is unlikely to hold, so that a part
 * never rendered is told from one rendered (rad_shot_end returns RAD_ERR_STATE). */
#define RAD__PART_RENDERED 0x72610001u
#define RAD__PART_AIMED    0x72610002u
#define RAD__PART_RECEIVED 0x72610003u
#define RAD__PART_SHOT     0x72610004u
#define RAD__CUBE_RENDERED 0x72610005u /* a batch's cube: rendered (rad_batch_render), */
#define RAD__CUBE_AIMED    0x72610006u /* aimed (rad_batch_aim), its part of the receipts */
#define RAD__CUBE_RECEIVED 0x72610007u /* done (rad_batch_receive_part); then _PART_SHOT */

/* One shot's cube in parts (hemicube.c): part PART of NPARTS renders its run of the
 * cube's rows into BUF (RAD_PART_BYTES); merging the elements [E0, E1) fills s->acc
 * there as rad__hemicube would, bit for bit: each sum takes its pixels in the serial
 * pass's order, whatever the range. Needs all five faces in one pass (band_rows 0). */
int rad__cube_part(const rad_scene_t *s, uint32_t p, unsigned part, unsigned nparts, void *buf);
void rad__cube_merge(rad_scene_t *s, void *const *bufs, unsigned nparts, uint32_t e0, uint32_t e1);
/* A batch's cube (solve.c): patch P's whole cube rendered into BUF (RAD_PART_BYTES),
 * its pixels summed per element into ACC (n_elements entries, as rad__hemicube sums
 * them into s->acc, bit for bit), then the elements of sum above 0 listed in BUF in
 * order, with their sums: rad__cube_lists points at the two lists. Returns how many. */
uint32_t rad__cube_list(const rad_scene_t *s, uint32_t p, void *buf, rad_ff_t *acc);
void rad__cube_lists(const rad_scene_t *s, void *buf, rad_index_t **ids, rad_ff_t **ffs);

/* The 3 or 4 corners of surface SF's vertex lattice (mesh.c): every vertex of the
 * surface is a rounded convex combination of them. Returns how many, indices in K. */
unsigned rad__surface_corners(const rad_scene_t *s, const rad_surface_t *sf, uint32_t *k);

/* The core's scale (mesh.c; rad.h has the rules). rad__scale_geometry re-meshes the
 * scene at the length shift its extent calls for (a no-op once it is there) and counts
 * small elements; rad__scale_power picks the power shift for the emissions as they
 * stand; rad__freeze, before a solve, does both and sets s->solving (a no-op while
 * solving). Each restarts the solution when a shift changes: call them only before a
 * solve, or (Gauss-Seidel) where the solution is replaced anyway. */
void rad__scale_geometry(rad_scene_t *s);
void rad__scale_power(rad_scene_t *s);
void rad__freeze(rad_scene_t *s);
/* Surface SF's emission in the core's scale (saturations counted). */
rad_rgb_t rad__emission(rad_scene_t *s, const rad_surface_t *sf);
/* The ambient radiosity per channel in the core's scale (solve.c). */
void rad__ambient(const rad_scene_t *s, rad_real_t *amb, uint32_t *sat);

/* Whether rad_init set S up: its self is its own address (no zeroed or copied
 * struct, and no garbage short of its own address, holds that). */
static inline int rad__live(const rad_scene_t *s)
{
    return s->self == (const void *)s;
}
/* The first check of every public call taking scene S: RAD_ERR_ARG when S is null,
 * RAD_ERR_STATE when rad_init has not set it up. */
#define RAD__CHECK_SCENE(s)                      \
    do {                                         \
        if (!(s)) return RAD_ERR_ARG;            \
        if (!rad__live(s)) return RAD_ERR_STATE; \
    } while (0)

/* Channel K (0 r, 1 g, 2 b) of C. */
static inline rad_real_t rad__channel(const rad_rgb_t *c, unsigned k)
{
    return k == 0 ? c->r : k == 1 ? c->g : c->b;
}

/* Element E's reflectance: its own (rad_use_element_reflectance) or its surface's. */
static inline const rad_rgb_t *rad__element_rho(const rad_scene_t *s, uint32_t e)
{
    if (s->element_rho) return &s->element_rho[e];
    return &s->pools.surfaces[s->pools.elements[e].surface].reflectance;
}

/* Patch P's reflectance: its surface's, or with per-element reflectances the mean the
 * array keeps after the elements' (rad__patch_mean). */
static inline const rad_rgb_t *rad__patch_rho(const rad_scene_t *s, uint32_t p)
{
    if (s->element_rho) return &s->element_rho[s->pools.max_elements + p];
    return &s->pools.surfaces[s->pools.patches[p].surface].reflectance;
}

/* Sets patch P's entry of the array to the area-weighted mean of its elements' (mesh.c). */
void rad__patch_mean(rad_scene_t *s, uint32_t p);

/* What the ambient term AMB adds to the shown radiosity of a surface of reflectance R. */
static inline rad_rgb_t rad__ambient_part(const rad_rgb_t *r, const rad_rgb_t *amb, uint32_t *sat)
{
    rad_rgb_t a;
    a.r = rad__mul(r->r, amb->r, sat);
    a.g = rad__mul(r->g, amb->g, sat);
    a.b = rad__mul(r->b, amb->b, sat);
    return a;
}

/* Radiosity B as shown: plus the ambient part A when A is given, and at least 0 (while
 * overshooting, power owed can make either negative for a while). */
static inline rad_rgb_t rad__shown_plus(rad_rgb_t b, const rad_rgb_t *a, uint32_t *sat)
{
    if (a) {
        b.r = rad__add_sat(b.r, a->r, sat);
        b.g = rad__add_sat(b.g, a->g, sat);
        b.b = rad__add_sat(b.b, a->b, sat);
    }
    if (b.r < 0) b.r = 0;
    if (b.g < 0) b.g = 0;
    if (b.b < 0) b.b = 0;
    return b;
}

/* Element E's radiosity as shown: plus reflectance times AMB when AMB is given, and at
 * least 0. Saturations are counted in SAT. */
static inline rad_rgb_t rad__shown(const rad_scene_t *s, uint32_t e, const rad_rgb_t *amb,
                                   uint32_t *sat)
{
    const rad_element_t *el = &s->pools.elements[e];
    rad_rgb_t a;
    if (!amb) return rad__shown_plus(el->radiosity, 0, sat);
    a = rad__ambient_part(rad__element_rho(s, e), amb, sat);
    return rad__shown_plus(el->radiosity, &a, sat);
}

/* Gather sums (gather.c): weights (Q2.30) times shown radiosities (Q16.16, >= 0), over
 * pixels whose weights sum to at most 2^30: below 2^61, exact in uint64 (WSUM). Signed
 * sums of them (MSUM, int64) stay below 2^62; a moment is one read in Q20 (units of
 * 2^-20 radiosity times the weights' sum as a fraction of 2^30). The twin sums floats
 * (its weights are fractions already). */
#if RAD_FLOAT
typedef float rad__wsum_t;
typedef float rad__msum_t;
static inline rad__wsum_t rad__wterm(rad_ff_t w, rad_real_t b)
{
    return w * b;
}
static inline rad_real_t rad__wvalue(rad__wsum_t a, uint32_t *sat)
{
    (void)sat;
    return a;
}
static inline rad__msum_t rad__msum_q20(rad__msum_t v)
{
    return v;
}
static inline rad__msum_t rad__msum_div(rad__msum_t v, int d)
{
    return v / (float)d;
}
/* The moment of a light of irradiance E arriving along unit u, times the components
 * A and B of u (1: none): E pi / (4 pi / 1.5) A B, the sphere's 4 pi standing for 1.5. */
static inline rad__msum_t rad__msum_light(rad_real_t e, rad_real_t a, rad_real_t b)
{
    return 0.375f * e * a * b;
}
/* M times the constant K (the float value of the fixed build's Q28 integer). */
static inline rad_real_t rad__mscale(rad__msum_t m, float k, uint32_t *sat)
{
    (void)sat;
    return m * k;
}
#else
typedef uint64_t rad__wsum_t;
typedef int64_t rad__msum_t;
static inline rad__wsum_t rad__wterm(rad_ff_t w, rad_real_t b)
{
    return (uint64_t)w * (uint32_t)b;
}
/* A sum of weights of at most 2^30 in all, read as Q16.16 radiosity. */
static inline rad_real_t rad__wvalue(rad__wsum_t a, uint32_t *sat)
{
    return rad__sat32((int64_t)((a + (1u << 29)) >> 30), sat);
}
static inline rad__msum_t rad__msum_q20(rad__msum_t v)
{
    return rad__shr_round(v, 26);
}
static inline rad__msum_t rad__msum_div(rad__msum_t v, int d)
{
    return rad__div_round(v, d);
}
/* As the twin's, in Q20: E (Q16.16) times 2^4 3 / 8 = 6, then A and B (Q16.16,
 * |A|, |B| <= 1) each rounded in: below 6 2^31 2^16 < 2^50. */
static inline rad__msum_t rad__msum_light(rad_real_t e, rad_real_t a, rad_real_t b)
{
    int64_t v = rad__shr_round((int64_t)6 * e * a, 16);
    return rad__shr_round(v * b, 16);
}
/* round(M K / 2^32) for a moment |M| < 2^38 (Q20) and a constant K (Q28, < 2^32): a
 * Q16.16 value. M = hi 2^16 + lo keeps both partial products below 2^54. */
static inline rad_real_t rad__mscale(rad__msum_t m, uint32_t k, uint32_t *sat)
{
    uint64_t a = m < 0 ? (uint64_t)0 - (uint64_t)m : (uint64_t)m;
    uint64_t t = (a >> 16) * k + (((a & 0xFFFFu) * k + 32768u) >> 16);
    int64_t v = (int64_t)((t + 32768u) >> 16);
    return rad__sat32(m < 0 ? -v : v, sat);
}
#endif

/* The element that element E's surface SF shows and whose id its pixels carry: E
 * itself, or for a surface joined to a group (rad_join_polygon: no patch of its own)
 * the group's receiver, its patch's first element, whose area is the group's. */
static inline uint32_t rad__group_element(const rad_scene_t *s, const rad_surface_t *sf, uint32_t e)
{
    return sf->n_patches ? e : s->pools.patches[sf->first_patch].first_element;
}

/* Number of vertices of element E (3 or 4). */
static inline unsigned rad__nverts(const rad_element_t *e)
{
    return e->v[3] == RAD_INDEX_NONE ? 3u : 4u;
}

#endif
