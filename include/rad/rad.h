/* SPDX-License-Identifier: MIT */
/* rad — hemi-cube radiosity in fixed point, with progressive refinement.
 *
 * Cohen & Greenberg, "The Hemi-Cube", SIGGRAPH 1985; Cohen, Chen, Wallace & Greenberg,
 * "A Progressive Refinement Approach to Fast Radiosity Image Generation", SIGGRAPH 1988.
 *
 * The core allocates nothing: the caller hands rad_init() pools of surfaces, patches,
 * elements and vertices and one work buffer (sizes: RAD_WORK_BYTES below). It calls no
 * libc, no libm and no stdio, and in its fixed build (the default) uses no floating
 * point, giving the same bits on every CPU.
 *
 * Numbers (fixed build; the float twin, RAD_FLOAT=1, uses float for each):
 *   rad_real_t    Q16.16 in int32: coordinates, lengths, areas, reflectance, radiosity.
 *                 The caller's coordinates lie within +-RAD_INPUT_LIMIT (8192.0), in any
 *                 unit; the core keeps them within +-RAD_COORD_LIMIT (64.0), where every
 *                 area (<= 128^2 * sqrt 2 = 23170) and every difference fits.
 *                 Reflectance in [0, 1) (at most 65535/65536). Emission in
 *                 [0, RAD_EMISSION_LIMIT] (4096.0). Radiosity saturates at 32767.99:
 *                 every clamp is counted in rad_scene_t.stats.saturations.
 *   rad_energy_t  Q16.16 in int64: radiosity times area (power). A patch's unshot
 *                 power stays below 2^30 units in magnitude (clamped and counted past
 *                 it). Signed: overshooting (rad_config_t.flags) leaves a shooter
 *                 owing power, which its later receipts pay back.
 *   form factors  Q2.30 in uint32 (internal): the delta form factor table of a
 *                 hemi-cube sums to exactly 2^30.
 * Rounding is to nearest everywhere but where coordinates scale down (below: rounded
 * down); no operation relies on signed overflow or on right shifts of negative numbers.
 *
 * Scale: results do not depend on the caller's units or emission scale. A scene beyond
 * +-RAD_COORD_LIMIT is kept at 2^length_shift of the caller's coordinates (-7..-1, the
 * largest that fits it within the limit, rounded down: a scene of 500 units, as a room
 * in centimetres, at 2^-3), lowered as polygons that need it are added (each polygon
 * is checked at its own such scale: degenerate, planar, area at least 1/4096 there;
 * rounding down composes, so the order of the polygons does not matter). Otherwise,
 * when the geometry is first used (the first shot, rad_rows_compute, rad_form_factors), the core
 * re-meshes it with coordinates times 2^length_shift (the largest into (16, 32]), and
 * when a solve starts it scales radiosity and power by 2^power_shift (a brightest
 * emission channel below 128 into (128, 256]): powers of two, so coordinates scale
 * exactly. Radiosity does not depend on geometry scale and is linear in emission, so
 * outputs (rad_element_radiosity, rad_shade_vertices, rad_ambient) come back in the
 * caller's units, and rad_render and rad_gather take points in them; RAD_SHADE_SCALED
 * keeps the core's scale (a dim scene's solution with all 16 fraction bits). The pools'
 * geometry (vertices, patch centres, areas) and rad_element_t.radiosity are in the
 * core's scale; rad_element_geometry gives an element's centre and area in the
 * caller's units. stats.small_elements counts the elements whose area stays small even
 * so. Limits: the caller's coordinates within +-8192 units, kept to 2^-16 of a unit
 * below +-64 and to 2^-16 of (the scene's extent / 64) above it (a room of 5000 mm: to
 * 1/512 mm), and a polygon's area at least 1/4096 at its own scale (at 8192 units out:
 * 4 square units, 2^-24 of the extent squared).
 *
 * Every function returns int: 0 or a non-negative count on success, a negative
 * RAD_ERR_* on failure. After any error the scene is unchanged and still valid.
 */
#ifndef RAD_H
#define RAD_H

#include <stddef.h>
#include <stdint.h>
#include "rad_config.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The float twin's functions are named radf_ (it links beside the fixed library). */
#if RAD_FLOAT
#include "rad_float_names.h"
#endif

/* ---- version ------------------------------------------------------------------- */
#define RAD_VERSION_MAJOR 0
#define RAD_VERSION_MINOR 9
#define RAD_VERSION_PATCH 0
#define RAD__STR_(x)      #x
#define RAD__STR(x)       RAD__STR_(x)
#define RAD_VERSION \
    RAD__STR(RAD_VERSION_MAJOR) "." RAD__STR(RAD_VERSION_MINOR) "." RAD__STR(RAD_VERSION_PATCH)
/* One number for #if tests: 10000 major + 100 minor + patch. */
#define RAD_VERSION_NUMBER (RAD_VERSION_MAJOR * 10000 + RAD_VERSION_MINOR * 100 + RAD_VERSION_PATCH)

/* ---- scalar types -------------------------------------------------------------- */
#if RAD_FLOAT
typedef float rad_real_t;
typedef float rad_energy_t;
typedef float rad_ff_t;
#define RAD_REAL(x)              ((rad_real_t)(x))
#define RAD_REAL_RATIO(num, den) ((rad_real_t)(num) / (rad_real_t)(den))
#define RAD_TO_DOUBLE(r)         ((double)(r))
#define RAD_FF_TO_DOUBLE(f)      ((double)(f))
#else
typedef int32_t rad_real_t;
typedef int64_t rad_energy_t;
typedef uint32_t rad_ff_t;
/* For host code only: converts a double constant or variable, rounding to nearest. */
#define RAD_REAL(x) ((rad_real_t)((x)*65536.0 + ((x) < 0 ? -0.5 : 0.5)))
/* NUM / DEN for integers (DEN > 0, |NUM| < 2^46, |NUM / DEN| < 32768) in integer
 * arithmetic only, so firmware without an FPU or soft float can use it (a constant
 * expression: static initialisers fold it at compile time). Rounds half away from zero,
 * as RAD_REAL does, and equals RAD_REAL((double)NUM / DEN) for DEN < 2^20: a tie is a
 * multiple of 2^-17, which a double holds exactly, and any other value lies at least
 * 1 / (2 DEN) ulp from a tie, more than a double's rounding (2^-21 ulp below 32768). */
#define RAD_REAL_RATIO(num, den)                                                             \
    ((rad_real_t)(((int64_t)(num)*131072 + ((num) < 0 ? -(int64_t)(den) : (int64_t)(den))) / \
                  (2 * (int64_t)(den))))
#define RAD_TO_DOUBLE(r)    ((double)(r) / 65536.0)
#define RAD_FF_TO_DOUBLE(f) ((double)(f) / 1073741824.0)
#endif

#if RAD_INDEX_BITS == 16
typedef uint16_t rad_index_t;
#define RAD_INDEX_NONE 0xFFFFu
#else
typedef uint32_t rad_index_t;
#define RAD_INDEX_NONE 0xFFFFFFFFu
#endif

#define RAD_COORD_LIMIT    64   /* |coordinate| <= 64.0 units at the core's scale */
#define RAD_INPUT_LIMIT    8192 /* |coordinate| <= 8192.0 of the caller's units */
#define RAD_EMISSION_LIMIT 4096 /* emission <= 4096.0 per channel */

typedef struct {
    rad_real_t x, y, z;
} rad_vec3_t;
typedef struct {
    rad_real_t r, g, b;
} rad_rgb_t;

/* ---- errors -------------------------------------------------------------------- */
#define RAD_OK             0
#define RAD_ERR_ARG        (-1) /* NULL pointer or an argument outside its domain */
#define RAD_ERR_FULL       (-2) /* a pool is full: nothing was added */
#define RAD_ERR_RANGE      (-3) /* coordinate, reflectance or emission out of range */
#define RAD_ERR_DEGENERATE (-4) /* zero or tiny area, collinear or repeated vertices */
#define RAD_ERR_NONPLANAR  (-5) /* a quad that is not planar or not convex */
#define RAD_ERR_STATE \
    (-6)                   /* call out of order (e.g. adding after shooting), or a
                                   * scene rad_init has not set up (rad_scene_t.self) */
#define RAD_ERR_WORK  (-7) /* work buffer too small for this configuration */
#define RAD_ERR_ALIGN (-8) /* a pool not aligned for its type (rad_pools_t) */
#define RAD_ERR_ABI   (-9) /* caller compiled with another rad.h layout (rad_init) */

/* ---- pools --------------------------------------------------------------------- */
/* A polygon as given (3 or 4 vertices), meshed into a grid of patches and elements. */
typedef struct {
    rad_vec3_t normal; /* unit normal, right-handed from the vertex order */
    rad_rgb_t reflectance;
    rad_rgb_t emission;
    rad_index_t first_patch, n_patches;
    rad_index_t first_element, n_elements;
    rad_index_t first_vertex, n_vertices;
    /* the lattice: a quad has pu x pv patches of ku x kv elements; a triangle pu = pv
     * patch levels of ku = kv element levels each (its sides cut in pu ku) */
    rad_index_t pu, pv, ku, kv;
} rad_surface_t;

/* A shooter: a block of elements whose hemi-cube sits at its centre. */
typedef struct {
    rad_vec3_t center;
    rad_real_t area;
    rad_energy_t unshot[3]; /* unshot power (radiosity times area) per channel */
    rad_index_t surface;
    rad_index_t first_element, n_elements;
} rad_patch_t;

/* A receiver: a triangle or planar quad of shared surface vertices. */
typedef struct {
    rad_index_t v[4]; /* v[3] == RAD_INDEX_NONE for a triangle */
    rad_index_t surface, patch;
    rad_real_t area;
    rad_rgb_t radiosity; /* the solution so far (without the ambient term), in the
                          * core's scale: the caller's radiosity times 2^power_shift */
} rad_element_t;

/* The caller's memory. Each pool is an array of its type, aligned as the compiler
 * aligns that type (any array, static or from malloc, is): rad_init refuses another
 * address with RAD_ERR_ALIGN. The work buffer may start at any address: the core
 * starts its tables at the next multiple of 8, and RAD_WORK_BYTES counts the bytes
 * that may cost. Bytes per entry: sizeof(rad_surface_t) etc., which depend on
 * RAD_INDEX_BITS (ports/README.md has them for 16-bit indices on 32-bit targets). */
typedef struct {
    rad_surface_t *surfaces;
    uint32_t max_surfaces;
    rad_patch_t *patches;
    uint32_t max_patches;
    rad_element_t *elements;
    uint32_t max_elements;
    rad_vec3_t *vertices;
    uint32_t max_vertices;
    void *work;
    size_t work_bytes;
} rad_pools_t;

/* Work buffer bytes for hemi-cube resolution RES rendering PIXELS pixels per pass, with
 * room for N per-element (or per-vertex) accumulators, N = max(elements, vertices), and
 * one row of RES 32-bit id steps (a surface's elements along a row of pixels).
 * All five faces at once:  PIXELS = RAD_PIXELS_ALL(RES) = 3 RES^2 (top + 4 half sides).
 * One band of ROWS rows:   PIXELS = RES * ROWS (RAM for time: each band re-renders).   */
#define RAD_PIXELS_ALL(res) (3u * (uint32_t)(res) * (uint32_t)(res))
#define RAD_WORK_BYTES(res, pixels, n)                                     \
    (2u * ((size_t)(res) / 2u) * ((size_t)(res) / 2u) * sizeof(rad_ff_t) + \
     (size_t)(n) * sizeof(rad_ff_t) + (size_t)(res) * sizeof(uint32_t) +   \
     (size_t)(pixels) * (sizeof(uint32_t) + sizeof(rad_index_t)) + 16u)

/* ---- configuration (zero means default) ---------------------------------------- */
#define RAD_DEFAULT_RES 64 /* rad_config_t.res when 0 */
typedef struct {
    rad_real_t max_patch;   /* longest patch edge, in the caller's units: max_element..
                             * 2 RAD_INPUT_LIMIT; default 4 max_element (at most that) */
    rad_real_t max_element; /* longest element edge, in the caller's units: 2^-16..
                             * 2 RAD_INPUT_LIMIT; default 4.0 (set it for the scene's
                             * units: a polygon's lattice has at most 32768 a side) */
    uint16_t res;           /* hemi-cube resolution, even, 8..RAD_MAX_RES; 0: RAD_DEFAULT_RES */
    uint16_t band_rows;     /* rows per pass, 0 = as many as the work buffer holds */
    uint16_t flags;         /* RAD_NO_OVERSHOOT, RAD_NO_BANDS, RAD_SMALL_FACES, or 0 */
    uint16_t coarse_res;    /* least resolution of a coarse shot (below); 0: res / 4 */
    rad_real_t coarse;      /* unshot fraction below which shots coarsen; 0: never */
} rad_config_t;

/* Coarse shots: the first shots (the emitters', the first bounces') carry most of the
 * light, the late ones little, so a late shot's cube may be coarser. Once the unshot
 * fraction (rad_unshot_fraction) at a shot is at most COARSE, that shot renders its
 * cube at res / 2, at most COARSE / 8 at res / 4, and so on (each level an eighth of
 * the last), never below COARSE_RES (even, 8..res; res / 4 when 0) nor where res / 2
 * is not made of whole 2^level x 2^level blocks. A patch shooting its own emission
 * (its unshot power at least half its emitted power: the direct light) stays at res.
 * A coarse cube's delta form factors are the block sums of the res table, so they
 * still sum to exactly 2^30, and the light shot after the switch is what was unshot
 * then: the error coarse shots add is bounded by that share. Raising res with
 * COARSE = 1 puts the direct light at the finer res and everything else coarser
 * (docs/library.md: Coarse shots). Needs all five faces in the work buffer (band_rows 0):
 * with bands every shot is at res. Stored rows and rad_form_factors are always at
 * res. 0 (the default) keeps every shot at res: the same bits as without the field. */

/* A work buffer too small for all five faces renders the cube in bands of rows (the
 * same bits, more passes); rad_scene_t.band_rows tells which was chosen (0: all faces
 * at once). RAD_NO_BANDS refuses bands instead: rad_init returns RAD_ERR_WORK unless
 * the buffer holds all five faces (a buffer sized for fewer accumulators than the
 * pools need does not then slow every shot down unnoticed). */
#define RAD_NO_BANDS 8u

/* Shooting (see rad_shoot) overshoots by default: a patch shoots its unshot power plus
 * the power it will receive back, estimated from the ambient term (Feda & Purgathofer,
 * "Accelerating radiosity by overshooting", 1992). The estimate is left owing, as
 * negative unshot power, and paid back as the real power arrives; the solution is the
 * same, reached in fewer shots (`make bench` counts them). RAD_NO_OVERSHOOT shoots the
 * unshot power alone, as Cohen et al. 1988: then the unshot total never grows. The
 * estimate assumes that every reflection stays in the scene; where it proves too high
 * (light escaping a bright open scene: the net unshot power swings beyond twice the
 * emitted, or a value saturates), the overshoot is halved, down to plain shooting after
 * 16 halvings, and where the unshot total stops falling (4 shots a patch + 64 without a
 * new lowest), shots are plain from then on; each counted in rad_stats_t.backoffs. */
#define RAD_NO_OVERSHOOT 1u

/* Polygons that reflect (no emission) are accepted down to an area of 2^-16 square
 * units (one LSB; by default 1/4096), so that detail too small for the core's
 * precision still occludes in every hemi-cube and passes on the power it receives:
 * power reaches an element and its patch as rho F U whatever the element's area, so
 * the energy carried is exact, while the element's own radiosity, that power over an
 * area rounded to 2^-16 (a relative error up to 2^-17 / area) and from the few pixels
 * it covers in each shot, is imprecise: shade such faces from the solution around them
 * (rad_gather at the face). An emitter still needs 1/4096: its power is its emission
 * times its area (an emission given later by rad_set_surface carries that rounding). */
#define RAD_SMALL_FACES 64u

typedef struct {
    uint32_t shots;         /* patches shot */
    uint32_t saturations;   /* values clamped to their format's range */
    uint32_t raster_calls;  /* polygons rasterized: hemi-cube surface pieces */
    uint64_t raster_pixels; /* pixels covered (before the depth test) */
    /* Precision at risk: elements whose area at the core's scale is below 1/64 (2^10
     * LSB, a rounding of 2^-11 = 0.05% of it), counted when the geometry freezes. The
     * core scales every scene to one size, so these are elements small against their
     * scene (a square of side 1/8: 1/512 of a scene 64 units across): mesh coarser. */
    uint32_t small_elements;
    uint32_t backoffs;     /* overshoot halvings (see RAD_NO_OVERSHOOT): the estimate
                               of the power coming back proved too high */
    uint32_t coarse_shots; /* shots whose cube was coarser than res (rad_config_t.coarse) */
} rad_stats_t;

/* A light (rad_add_light; defined with the light functions at the end). */
typedef struct rad_light_s rad_light_t;

/* The solver. Fields are read-only for the caller; set them only through the API. */
typedef struct {
    rad_config_t cfg;
    rad_pools_t pools;
    rad_rgb_t *element_rho; /* rad_use_element_reflectance's array, or NULL */
    uint32_t n_surfaces, n_patches, n_elements, n_vertices;
    uint16_t solving; /* set by the first shot: geometry is frozen */
    /* the shot between rad_shot_begin and rad_shot_end: its serial number, which part
     * buffers record, and its patch (RAD_INDEX_NONE: no shot begun) */
    uint16_t shot_serial;
    uint32_t shot_patch;
    rad_energy_t emitted; /* total emitted power, all channels */
    /* The core's scale (see the top of this file): coordinates are the caller's times
     * 2^length_shift (0..15), radiosity and power the caller's times 2^power_shift
     * (0..24); both 0 for a scene within +-32 whose brightest emission is 256. */
    int8_t length_shift, power_shift;
    /* lights (rad_use_lights): the caller's array of max_lights, n_lights added; the
     * first lights_shot of them have shot since the solution last started */
    uint16_t n_lights, max_lights, lights_shot;
    uint16_t cull_wait; /* shots left before the hierarchy is tried again (rad_shoot_cull) */
    rad_light_t *lights;
    /* The scene's own address, set by a successful rad_init (cleared first). Every call
     * refuses (RAD_ERR_STATE) a scene without it: never initialised, its rad_init
     * failed, or a copy at another address. */
    const void *self;
    const void *cull; /* the hierarchy shots draw through (rad_shoot_cull), or NULL */
    rad_stats_t stats;
    /* work buffer layout */
    rad_ff_t *dff_top, *dff_side; /* (res/2)^2 each: one quadrant, by symmetry */
    rad_ff_t *acc;                /* per-element form factor sums */
    uint32_t *steps;              /* res: a row's element id steps (zero between spans) */
    uint32_t *zbuf;
    rad_index_t *ibuf;
    uint32_t pass_pixels; /* pixels the face buffers hold */
    uint16_t band_rows;   /* rows per band, or 0: all faces in one pass */
    uint16_t amb_ok;      /* (see amb_area) */
    /* the shot's cube: its resolution and delta form factor tables (cfg.res and the
     * dff tables but for a coarse shot, whose tables follow its depth buffer) */
    rad_ff_t *cube_top, *cube_side;
    uint16_t cube_res;
    uint16_t cube_built; /* the coarse level whose tables are built, 0: none */
    /* (amb_ok and amb_max_area belong with the ambient sums below: they fill gaps of
     * the layout here, as the lights' and shot fields do above; a Cortex-M0's 16 KB has
     * no room for a larger scene) */
    rad_real_t amb_max_area;
    /* overshooting's back-off (lib/solve.c), reset before the first shot */
    rad_energy_t over_low;  /* lowest unshot total since the last back-off */
    rad_energy_t over_net;  /* net unshot power (channels' signed sums) allowed twice */
    uint32_t over_wait;     /* shooter selections since over_low was lowered */
    uint32_t over_sat;      /* stats.saturations at the last selection */
    uint32_t over_halvings; /* the overshoot is scaled by 2^-over_halvings */
    /* the batch between rad_batch_begin and rad_batch_end (lib/solve.c): its count of
     * shooters (0: none begun) and a check word of their patches in order (here, in
     * the gap before the next 8-aligned field: a Cortex-M0's 16 KB has no room) */
    uint16_t batch_n, batch_check;
    /* the ambient term's sums over the patches of area and of reflectance times area,
     * and the largest patch area (amb_max_area, above), valid while solving when amb_ok
     * (above): cleared by the freeze and by every change of a patch's reflectance */
    rad_energy_t amb_area, amb_rho[3];
} rad_scene_t;

/* ---- building a scene ---------------------------------------------------------- */

/* Prepares S over the caller's pools with configuration CFG (NULL: defaults), and builds
 * the delta form factor table in the work buffer. Returns RAD_OK, RAD_ERR_ARG for NULL
 * or invalid settings, RAD_ERR_ALIGN for a misaligned pool, RAD_ERR_WORK when the work
 * buffer cannot hold the table, the accumulators and at least one row of a face (or all
 * five faces, with RAD_NO_BANDS), RAD_ERR_ABI when the caller was compiled with another
 * layout than the library: another RAD_INDEX_BITS or RAD_FLOAT, or a rad.h whose
 * rad_scene_t differs (the macro passes what the caller's compiler saw, so a program
 * that would index its pools with the wrong strides gets an error code, not a crash).
 * On any other error only S's marker (rad_scene_t.self) is written: cleared, so that
 * every call refuses S (RAD_ERR_STATE) until a rad_init succeeds. */
#define rad_init(s, pools, cfg) \
    rad_init_abi((s), (pools), (cfg), sizeof(rad_scene_t), (unsigned)sizeof(rad_index_t), RAD_FLOAT)
int rad_init_abi(rad_scene_t *s, const rad_pools_t *pools, const rad_config_t *cfg,
                 size_t scene_bytes, unsigned index_bytes, int is_float);

/* Sizing before adding: what a polygon will take of each pool. */
typedef struct {
    uint32_t surfaces, patches, elements, vertices; /* summed over the planned polygons */
    const char *problem; /* after an error: what is wrong, in a few words */
} rad_plan_t;

/* Adds to PLAN the surfaces, patches, elements and vertices rad_add_polygon would take
 * for this polygon under configuration CFG (NULL: defaults), through the same code that
 * meshes, so a caller can sum a scene's polygons and size the pools and RAD_WORK_BYTES
 * (n = max(elements, vertices)) before rad_init. Counts saturate at UINT32_MAX. Returns
 * RAD_OK, or the error rad_add_polygon would return for it (RAD_ERR_ARG, RAD_ERR_RANGE,
 * RAD_ERR_DEGENERATE, RAD_ERR_NONPLANAR) with the counts unchanged and PLAN->problem
 * naming the cause (e.g. "emission outside [0, RAD_EMISSION_LIMIT]"; RAD_ERR_FULL for
 * a lattice of more than 32768 elements a side): after
 * rad_add_polygon fails, the same call tells which value was out of range. */
int rad_plan_polygon(const rad_config_t *cfg, const rad_vec3_t *v, unsigned n,
                     const rad_rgb_t *reflectance, const rad_rgb_t *emission, rad_plan_t *plan);

/* Adds a convex planar polygon of N = 3 or 4 vertices V (counter-clockwise seen from
 * the lit side) with REFLECTANCE and EMISSION (NULL: black), meshed at once into
 * patches and elements. Returns the new surface's index, or RAD_ERR_ARG, RAD_ERR_RANGE,
 * RAD_ERR_DEGENERATE, RAD_ERR_NONPLANAR (split such a quad into triangles),
 * RAD_ERR_FULL (no pool changed) or RAD_ERR_STATE after shooting started. */
int rad_add_polygon(rad_scene_t *s, const rad_vec3_t *v, unsigned n, const rad_rgb_t *reflectance,
                    const rad_rgb_t *emission);

/* Adds polygon V (N = 3 or 4 vertices, as rad_add_polygon; area below 1/4096, one
 * element) as a surface of its own that joins the last patch added, with REFLECTANCE
 * (NULL: black) and no emission (RAD_SMALL_FACES). Faces too small for a patch each,
 * grouped by the caller (nearby, facing about the same way), then act as one patch of
 * their size: drawn one by one in every cube, but their pixels count for the group's
 * first element, its receiver, whose area becomes the group's (a face's own share of
 * a shot is often below the 2^-16 a power keeps); the group shoots from the patch's
 * centre (the mean of its elements' vertices) on its first surface's normal, and every
 * face of it shows the group's radiosity (rad_element_radiosity, rad_shade_vertices).
 * Each join is a pass over the patch's elements. A group's surfaces cannot emit
 * (rad_set_surface refuses it); its overshoot, ambient share and Gauss-Seidel row take
 * its first surface's reflectance. Takes 1 surface, no patch, 1 element and N
 * vertices. Returns the new surface's index, or RAD_ERR_ARG (no RAD_SMALL_FACES, a
 * polygon of 1/4096 or more or longer than max_element, a group of 16384 units^2),
 * RAD_ERR_STATE (after shooting started, no patch yet, or the last patch emits),
 * RAD_ERR_RANGE, RAD_ERR_DEGENERATE, RAD_ERR_NONPLANAR or RAD_ERR_FULL as
 * rad_add_polygon. */
int rad_join_polygon(rad_scene_t *s, const rad_vec3_t *v, unsigned n, const rad_rgb_t *reflectance);

/* Changes the reflectance and emission of surface SURF (either may be NULL to keep it);
 * a reflectance is also set on each of its elements' own entries, if they have them
 * (rad_use_element_reflectance). Takes effect on the next rad_restart(). Returns
 * RAD_OK, RAD_ERR_ARG or RAD_ERR_RANGE (also: an emission for a surface of a group,
 * rad_join_polygon). */
int rad_set_surface(rad_scene_t *s, uint32_t surf, const rad_rgb_t *reflectance,
                    const rad_rgb_t *emission);

/* Reflectance per element, for a surface whose colour varies across it (a texture's
 * mean over each element's footprint). RHO is the caller's array of
 * RAD_ELEMENT_RHO_ENTRIES(max_elements, max_patches) rad_rgb_t (12 bytes each in the
 * fixed build; aligned as rad_rgb_t), kept by the scene from then on: the elements'
 * reflectances, then each patch's, which the core keeps. The elements already added
 * get their surface's reflectance, those added later too, rad_set_surface sets its
 * elements' again, and rad_set_element_reflectance one. Without this call (the
 * default) every element reflects as its surface and rad_element_t does not grow:
 * firmware that does not use it pays nothing. The core reads an element's entry
 * wherever it reflects: receiving, its shown ambient part (RAD_SHADE_AMBIENT,
 * gathers); a patch's reflectance (overshooting, the ambient term's mean, a
 * Gauss-Seidel row) is the area-weighted mean of its elements' (kept up to date; a
 * patch whose elements share one value takes it exactly, so a scene without differing
 * elements gives the bits of one without the call; for a group, its receiver's).
 * Returns RAD_OK, RAD_ERR_ARG (NULL), RAD_ERR_ALIGN, or RAD_ERR_STATE (the geometry
 * is frozen, or an array is in use already). */
#define RAD_ELEMENT_RHO_ENTRIES(max_elements, max_patches) \
    ((size_t)(max_elements) + (size_t)(max_patches))
int rad_use_element_reflectance(rad_scene_t *s, rad_rgb_t *rho);

/* Sets element E's own reflectance (rad_use_element_reflectance) to REFLECTANCE, each
 * channel in [0, 1). Takes effect on the next rad_restart(), as rad_set_surface; an
 * element joined to a group (rad_join_polygon) reflects as the group's receiver (its
 * patch's first element), so set that one. Returns RAD_OK, RAD_ERR_ARG (NULL, E
 * beyond the elements added), RAD_ERR_RANGE or RAD_ERR_STATE (no array in use). */
int rad_set_element_reflectance(rad_scene_t *s, uint32_t e, const rad_rgb_t *reflectance);

/* Resets the solution to the emission alone (the geometry stays), so the scene can be
 * solved again after rad_set_surface(). Returns RAD_OK or RAD_ERR_ARG. */
int rad_restart(rad_scene_t *s);

/* ---- solving ------------------------------------------------------------------- */

/* Shoots up to MAX_SHOTS patches, each time the one whose shot moves the most power
 * (its unshot power, plus the overshoot unless RAD_NO_OVERSHOOT; in magnitude, summed
 * over channels), and stops early once the unshot fraction is at most TOL. A call while
 * something emits freezes the geometry (rad_add_polygon then returns RAD_ERR_STATE);
 * while nothing emits no shot is possible, and the scene stays open. Lights that have
 * not shot (rad_add_light) shoot first, one a step, each counted as a shot. Returns
 * the number of patches and lights shot (0: already converged or nothing emits),
 * RAD_ERR_ARG, or RAD_ERR_RANGE when a point or spot light lies beyond
 * +-RAD_COORD_LIMIT in the core's scale (farther out than about twice the scene's
 * extent; nothing shot). */
int rad_shoot(rad_scene_t *s, uint32_t max_shots, rad_real_t tol);

/* One shot in parts, for threads of the caller's (the core has none): rad_shot_begin
 * picks the shooter (returns 1, or 0 once the unshot fraction is at most TOL);
 * rad_shot_part renders part PART of NPARTS of its hemi-cube (a run of the cube's
 * rows, face after face: every surface clipped to them) into BUF, reading the scene
 * only, so parts may run at once; rad_shot_end sums the parts' pixels in order and
 * shoots. The result is bit for bit that of rad_shoot, in both builds. Needs the work
 * buffer to hold all five faces (band_rows 0): else RAD_ERR_STATE. BUF: 8-aligned,
 * RAD_PART_BYTES(res). Each returns RAD_ERR_ARG on a bad argument, and RAD_ERR_STATE
 * for a PATCH other than the one rad_shot_begin picked (none once the shot ended or the
 * scene was shot, restarted or solved otherwise since), or for BUFS that are not its
 * NPARTS parts, each rendered by rad_shot_part for this shot as part K of NPARTS at
 * BUFS[K] (a buffer records its shot, part and count). */
#define RAD_PART_BYTES(res)                   \
    (96u + (size_t)(res) * sizeof(uint32_t) + \
     (size_t)RAD_PIXELS_ALL(res) * (sizeof(uint32_t) + sizeof(rad_index_t)))
int rad_shot_begin(rad_scene_t *s, rad_real_t tol, uint32_t *patch);
int rad_shot_part(const rad_scene_t *s, uint32_t patch, unsigned part, unsigned nparts, void *buf,
                  size_t bytes);
int rad_shot_end(rad_scene_t *s, uint32_t patch, void *const *bufs, unsigned nparts);
/* rad_shot_end in parts, for the same threads: rad_shot_aim (one thread, after every
 * rad_shot_part) counts the parts, takes the shooter's power and writes it to every
 * buffer; then rad_shot_receive_part, PART of NPARTS at once on any threads, sums the
 * pixels of every buffer for its own run of whole patches' elements and has them
 * receive (returns how many did); rad_shot_end, after all of them, counts the parts'
 * saturations. rad_shot_end does whatever was not done, so calling it alone is the
 * serial shot. The result is bit for bit the same: each element's sum takes its
 * pixels in order, and each patch's unshot power its elements in order. A call out of
 * that order returns RAD_ERR_STATE. */
int rad_shot_aim(rad_scene_t *s, uint32_t patch, void *const *bufs, unsigned nparts);
int rad_shot_receive_part(rad_scene_t *s, uint32_t patch, void *const *bufs, unsigned nparts,
                          unsigned part);

/* Batch shooting, for threads of the caller's: K shots whose hemi-cubes render at once,
 * each whole on any thread. rad_batch_begin picks the batch: the K patches whose shots
 * move the most power (the rule of rad_shoot, ranked; ties to the lower index), into
 * PATCHES in that order (K entries, 1..RAD_BATCH_MAX), and returns how many it found
 * (fewer when fewer patches hold power; 0 once the unshot fraction is at most TOL).
 * rad_batch_render renders the hemi-cube of PATCH, the batch's shooter K, into BUF
 * (8-aligned, RAD_BATCH_BYTES(res, n_elements) bytes: a part buffer, then a form
 * factor sum per element), sums its pixels per element and lists the elements it
 * sees, reading the scene only, so a batch's cubes may render at once in any order
 * and the merging is done on their threads too. rad_batch_end, after every cube,
 * shoots the
 * batch's patches one after the other in the order picked, each with its unshot power
 * as the shots before it left it, through the cube in BUFS[K]; returns the shots (N,
 * all of them). A cube depends on the geometry
 * and its patch alone, so the result is the same bits whatever thread rendered which
 * cube and whenever, in both builds; and K = 1 is rad_shoot's shot bit for bit. A
 * batch's cubes share one resolution: the finest of its shots' coarse levels
 * (rad_config_t.coarse). Needs band_rows 0, as rad_shot_begin. rad_batch_render
 * returns RAD_ERR_ARG on a bad argument and RAD_ERR_STATE with no batch begun or K past
 * its count; rad_batch_end returns RAD_ERR_ARG on a bad argument and RAD_ERR_STATE,
 * shooting nothing, unless BUFS are the N = rad_batch_begin's count buffers, BUFS[K]
 * rendered for this batch as shooter K of its patch. A batch ends with rad_batch_end
 * and is void once the scene is shot, restarted or solved otherwise. */
#define RAD_BATCH_MAX                  32
#define RAD_BATCH_BYTES(res, elements) (RAD_PART_BYTES(res) + (size_t)(elements) * sizeof(rad_ff_t))
int rad_batch_begin(rad_scene_t *s, rad_real_t tol, unsigned k, uint32_t *patches);
int rad_batch_render(const rad_scene_t *s, uint32_t patch, unsigned k, void *buf, size_t bytes);
int rad_batch_end(rad_scene_t *s, void *const *bufs, unsigned n);
/* rad_batch_end in parts, for the same threads, as rad_shot_aim and _receive_part:
 * rad_batch_aim (one thread, after every cube) works out every shot's power in order;
 * then rad_batch_receive_part, PART of NPARTS (1..N) at once on any threads, has the
 * elements of its run of whole patches receive the batch's shots in order (records
 * its saturations in BUFS[PART]); rad_batch_end, after all of them, counts them and
 * ends the batch. rad_batch_end does whatever was not done, so calling it alone is the
 * serial batch; the result is bit for bit the same. Each returns N, or RAD_ERR_ARG,
 * or RAD_ERR_STATE for a call out of that order (a part done twice, another NPARTS).
 * A batch's shots take the ambient term (the overshoot's) at its start: for K = 1,
 * its shot's own. */
int rad_batch_aim(rad_scene_t *s, void *const *bufs, unsigned n);
int rad_batch_receive_part(rad_scene_t *s, void *const *bufs, unsigned n, unsigned part,
                           unsigned nparts);

/* Unshot power as a fraction of the emitted power (0 when nothing emits): the sum of
 * every patch's channels in magnitude, so power owed counts as much as power held. */
rad_real_t rad_unshot_fraction(const rad_scene_t *s);

/* The ambient term of Cohen et al. 1988: unshot power spread over the scene, times the
 * mean inter-reflection factor 1 / (1 - mean reflectance). Writes it to OUT, in the
 * caller's units; returns RAD_OK or RAD_ERR_ARG. While overshooting, the power owed can
 * outweigh the power held: then the term is negative, and displayed radiosities
 * (rad_element_radiosity, rad_shade_vertices) are clamped at zero. */
int rad_ambient(rad_scene_t *s, rad_rgb_t *out);

#define RAD_SHADE_AMBIENT 1 /* add reflectance times the ambient term */
#define RAD_SHADE_SCALED  2 /* in the core's scale: the caller's times 2^power_shift */
#define RAD_SHADE_SOFT    4 /* rad_gather: the direct light of skies alone (rad_direct) */
#define RAD_SHADE_SKIES   8 /* rad_direct: skies' too; rad_gather (with SOFT only): no light's */

/* Radiosity of element E (with FLAGS as above) into OUT, in the caller's units unless
 * RAD_SHADE_SCALED. Returns RAD_OK or RAD_ERR_ARG. */
int rad_element_radiosity(rad_scene_t *s, uint32_t e, int flags, rad_rgb_t *out);

/* Element E's centre (the mean of its vertices) into CENTRE and its area into AREA
 * (as rad_energy_t: Q16.16 in int64 in the fixed build, so that the caller's area may
 * pass 32768 square units), both in the caller's units, converted from the core's
 * scale (exact where the core scaled up; to within the core's rounding, 2^-16 of a
 * unit at its scale, where it scaled down). Either may be NULL. Returns RAD_OK or
 * RAD_ERR_ARG. */
int rad_element_geometry(rad_scene_t *s, uint32_t e, rad_vec3_t *centre, rad_energy_t *area);

/* Every element's radiosity, rad_element_radiosity's values bit for bit, into OUT
 * (N >= n_elements entries) with the ambient term computed once: O(elements + patches)
 * where a call per element is O(elements x patches). Returns the number of elements
 * written, or RAD_ERR_ARG. */
int rad_shade_elements(rad_scene_t *s, int flags, rad_rgb_t *out, uint32_t n);

/* Vertex radiosity for Gouraud shading: each vertex gets the area-weighted mean of the
 * elements of its surface that share it, in the caller's units unless RAD_SHADE_SCALED.
 * OUT holds N >= n_vertices entries. Uses the work buffer's accumulators as scratch.
 * Returns the number of vertices written, or RAD_ERR_ARG. */
int rad_shade_vertices(rad_scene_t *s, int flags, rad_rgb_t *out, uint32_t n);

/* ---- viewing ------------------------------------------------------------------- */
typedef struct {
    rad_vec3_t eye, target, up;
    rad_real_t tan_half_fov; /* tangent of half the vertical field of view, 1/16..16 */
} rad_camera_t;

/* Renders the scene from CAM (in the caller's units) with vertex colours VRGB (from
 * rad_shade_vertices, in either scale: FB gets the same) into FB (W*H linear
 * radiosity, row 0 at the top), using ZBUF (W*H) as the depth buffer, through the same
 * rasterizer as the hemi-cube. Pixels no surface covers are black. Returns the number
 * of triangles drawn, or RAD_ERR_ARG (sizes above RAD_MAX_RASTER, a degenerate camera,
 * an eye or target beyond 4 * RAD_COORD_LIMIT in the core's scale, tan_half_fov or
 * tan_half_fov * W / H outside 1/16..16). */
int rad_render(rad_scene_t *s, const rad_rgb_t *vrgb, const rad_camera_t *cam, rad_rgb_t *fb,
               uint32_t *zbuf, unsigned w, unsigned h);

/* Form factors from the centre of patch P to every element, written to OUT (one per
 * element, summing to 1 in a closed scene): the hemi-cube row the solver uses when P
 * shoots (the cube's turn about the normal depends on P alone; the geometry takes the
 * core's scale first, which restarts a scene not yet solving).
 * Returns the number of elements, or RAD_ERR_ARG. */
int rad_form_factors(rad_scene_t *s, uint32_t p, rad_ff_t *out);

/* ---- stored form factors: relighting without new visibility -------------------- */
/* Cohen & Greenberg's form factors do not depend on light or colour, so once every
 * patch's hemi-cube row is stored, emissions, reflectances and lights can change
 * (rad_set_surface, rad_set_light, rad_restart) and the scene be solved again with no
 * hemi-cube rendered (lights render their direct shots again: rad_rows_shoot).
 * An entry keeps an element id and a 16-bit code of its form factor (5-bit exponent,
 * 11-bit mantissa of the Q2.30 value): relative error below 2^-11 = 0.05% per entry,
 * so a solution from stored rows is within about 0.05% of one from hemi-cubes.
 * Memory: (max_rows + 1) * 4 + entries * (sizeof(rad_index_t) + 2) bytes, entries
 * being about the number of elements each patch sees, summed over patches. */
typedef struct {
    uint32_t *start;  /* max_rows + 1 offsets: row p is entries start[p]..start[p+1]-1 */
    rad_index_t *ids; /* max_entries element ids */
    uint16_t *ffs;    /* max_entries coded form factors */
    uint32_t max_rows, max_entries;
    uint32_t n_rows; /* rows stored so far: patches 0..n_rows-1 */
} rad_rows_t;

/* Stores the rows of up to COUNT more patches (spread the work over frames by calling
 * again); freezes the geometry. Set n_rows = 0 before the first call. Returns the
 * number of rows added (0 once every patch has its row), RAD_ERR_FULL when the next
 * row does not fit (nothing of it is kept), RAD_ERR_ARG (max_rows < patches, or rows
 * stored so far that rad_rows_shoot would refuse). */
int rad_rows_compute(rad_scene_t *s, rad_rows_t *rows, uint32_t count);

/* rad_shoot through the stored rows instead of hemi-cubes. Lights (rad_add_light)
 * shoot first as in rad_shoot, rendered: a light's direct light is its first shot,
 * which rows of patches do not hold, and storing it would take a row of up to every
 * element per light (a sky's dome turns with its colours) for a handful of renders;
 * so the direct light is the very bits rad_shoot gives, and lights may change in any
 * way between solves (rad_set_light). Returns the shots (lights included, as
 * rad_shoot), or RAD_ERR_STATE when not every patch has its row yet, or RAD_ERR_ARG
 * for rows that are not this scene's (offsets not rising within max_entries, an
 * element id beyond the scene's elements: checked in a pass over the entries before
 * anything changes), or RAD_ERR_RANGE for a point light beyond range (as rad_shoot). */
int rad_rows_shoot(rad_scene_t *s, const rad_rows_t *rows, uint32_t max_shots, rad_real_t tol);

/* The 1985 paper's full-matrix solve: Gauss-Seidel on the patch radiosities
 * B_k = E_k + rho_k sum_m G_mk B_m, with G_mk = (A_m / A_k) * (form factor from patch m
 * to patch k's elements) assembled from the stored rows -- the very system
 * progressive refinement solves, so both converge to one solution -- then one pass
 * gives every element its radiosity. Sweeps until no patch's radiosity changes by
 * more than TOL of itself (plus one LSB), or MAX_ITER sweeps. Lights (rad_add_light)
 * shoot first, every one (a scene with lights restarts: the solve starts from the
 * emissions alone, as without), rendered as rad_rows_shoot's: each element keeps its
 * direct light, and a patch's source E_k is its emission plus the direct light it
 * reflects (its power received times rho over its area). MATRIX holds
 * RAD_GS_ENTRIES(patches) entries; at most 16384 patches. Returns the sweeps done, or
 * RAD_ERR_ARG (matrix too small, too many patches, rows as rad_rows_shoot refuses),
 * RAD_ERR_STATE (rows missing) or RAD_ERR_RANGE (a point light beyond range, as
 * rad_shoot; nothing changed). */
#define RAD_GS_ENTRIES(patches) ((size_t)(patches) * (patches) + 3u * (size_t)(patches))
int rad_rows_gauss_seidel(rad_scene_t *s, const rad_rows_t *rows, rad_ff_t *matrix, size_t entries,
                          uint32_t max_iter, rad_real_t tol);

/* Light groups: radiosity is linear in emission, so solve once per group of lights
 * (the others dark: emitting surfaces through rad_set_surface, lights through
 * rad_set_light with all channels 0, then rad_restart) and keep each solution's
 * element radiosities; then any mix is
 * OUT[e] = sum_g INTENSITY[g] * GROUPS[g][e] per channel, for n_elements elements.
 * OUT is in the groups' unit: keep them in the caller's (rad_element_radiosity without
 * RAD_SHADE_SCALED), since each solve has the power shift of its own lights.
 * Saturations are counted in s->stats. Returns RAD_OK or RAD_ERR_ARG. */
int rad_mix(rad_scene_t *s, const rad_rgb_t *const *groups, const rad_rgb_t *intensity,
            uint32_t n_groups, rad_rgb_t *out);

/* The form factor a stored code stands for (Q2.30 in the fixed build). */
rad_ff_t rad_ff_from_code(uint16_t code);

/* Converts a Q16.16 value (as int32) to rad_real_t: identity in the fixed build. */
rad_real_t rad_real_from_q16(int32_t q);

/* A short English description of an RAD_ERR_* code, naming what to check. */
const char *rad_strerror(int err);

/* ---- gathering: the light arriving at any point --------------------------------- */
/* A gather renders a cube of its own resolution at any point over the current
 * solution, through the same rasterizer and element lattice as the shots, and sums
 * what its pixels see: the way to take the solution to a lightmap's texels, a mesh's
 * own vertices, or light probes (a gather is one call: bake a few a frame).
 * A gatherer (rad_gather_t) is the caller's work buffer laid out by rad_gather_init:
 * its delta form factor (or solid angle) tables and one face's buffers, as big as
 * RAD_GATHER_BYTES(res) for hemispheres or RAD_GATHER_SH_BYTES(res) for spheres. A
 * gather only reads the scene, so each thread may gather with a gatherer of its own.
 * Needs frozen geometry: after the first shot, rad_rows_compute or rad_form_factors. */
#define RAD_GATHER__BUFS(res)           \
    ((size_t)(res) * sizeof(uint32_t) + \
     (size_t)(res) * (res) * (sizeof(uint32_t) + sizeof(rad_index_t)) + 16u)
#define RAD_GATHER_BYTES(res) \
    (2u * ((size_t)(res) / 2u) * ((size_t)(res) / 2u) * sizeof(rad_ff_t) + RAD_GATHER__BUFS(res))
#define RAD_GATHER_SH_BYTES(res) \
    (6u * ((size_t)(res) / 2u) * ((size_t)(res) / 2u) * sizeof(rad_ff_t) + RAD_GATHER__BUFS(res))
#define RAD_GATHER_SH 1u /* rad_gather_init: a sphere gatherer (rad_gather_sh) */

typedef struct {
    uint16_t res;      /* cube resolution, even, 8..RAD_MAX_RES */
    uint16_t sh;       /* 1: a sphere gatherer (six whole faces), 0: a hemisphere's */
    uint32_t turn;     /* the hemi-cube's turn about the normal, set by the caller (0
                        * after init): patch P's own cube has turn P */
    rad_ff_t *table;   /* quadrant tables (see gather.c) */
    uint32_t *steps;   /* res: a row's element id steps */
    uint32_t *zbuf;    /* res^2: one face */
    rad_index_t *ibuf; /* res^2 */
    rad_stats_t stats; /* this gatherer's raster calls, pixels and saturations */
    const void *cull;  /* the hierarchy it draws through (rad_gather_cull), or NULL */
    uint32_t *cull_work;
} rad_gather_t;

/* Lays a gatherer of resolution RES out in WORK (BYTES long; FLAGS 0 or RAD_GATHER_SH)
 * and builds its tables. Returns RAD_OK, RAD_ERR_ARG (NULL, RES odd or outside
 * 8..RAD_MAX_RES, unknown flags) or RAD_ERR_WORK (BYTES below the macro's size). */
int rad_gather_init(rad_gather_t *g, unsigned res, unsigned flags, void *work, size_t bytes);

/* The radiosity arriving at POINT on a surface of normal NORMAL (any length; the side
 * it points to is gathered), E = sum over the cube's pixels of F * B: the delta form
 * factor F of each pixel (summing to exactly 1 over the cube) times the radiosity B of
 * the element it sees (rad_element_radiosity's value with FLAGS: RAD_SHADE_AMBIENT
 * adds reflectance times the ambient term, worked out on each call, a pass over the
 * patches; at least 0), with no element seen counting as black and a surface seen
 * from behind drawn as an opaque black occluder (radiosity is one-sided), plus the
 * direct light of the scene's lights that have shot (rad_add_light): E cos t from each
 * of a sun's or sky's directions (those it shoots along) whose pixel in the cube shows
 * nothing, and I cos t / r^2 (a spot's falloff applied) from a point or spot light
 * whose pixel shows nothing nearer than it: the light's visibility is the cube's, a
 * pixel's centre deciding, as the solve's shots decide it by their pixels (with
 * RAD_SHADE_SOFT, a sky's alone: rad_direct gives the others; with RAD_SHADE_SOFT |
 * RAD_SHADE_SKIES, no light's: rad_direct with RAD_SHADE_SKIES gives them all). An element of
 * reflectance rho at POINT would have radiosity rho E + its emission: E is irradiance
 * over pi, in radiosity units (Q16.16 in the fixed build, rounded once from an exact
 * sum in the core's scale), the caller's unless RAD_SHADE_SCALED. POINT is in the
 * caller's units. Surface SKIP is not drawn (the one POINT lies on; RAD_INDEX_NONE:
 * none). Writes OUT; returns RAD_OK, RAD_ERR_ARG (NULL, a zero normal, a sphere
 * gatherer, unknown flags, RAD_SHADE_SKIES without RAD_SHADE_SOFT), RAD_ERR_RANGE (POINT beyond +-RAD_COORD_LIMIT in the
 * core's scale, NORMAL beyond it), RAD_ERR_STATE (geometry not frozen). */
int rad_gather(const rad_scene_t *s, rad_gather_t *g, const rad_vec3_t *point,
               const rad_vec3_t *normal, uint32_t skip, int flags, rad_rgb_t *out);

/* Whether the light with index LIGHT (rad_add_light's) reaches the point along unit
 * DIR (on the scene's axes, toward the light): nonzero when nothing occludes it, up
 * to the light's position for a point or spot. */
typedef int rad_visible_fn(void *ctx, uint32_t light, const rad_vec3_t *dir);

/* The direct light at POINT (the caller's units) on a surface of normal NORMAL (any
 * length) of the suns, point lights and spots that have shot, with visibility the
 * caller's: for each of their directions that faces the surface (a sun's disc has
 * 16), VIS decides, and a visible one adds what rad_gather adds for it, E cos t or
 * I cos t / r^2 with a spot's falloff (skies are left out). With RAD_SHADE_SOFT,
 * rad_gather leaves out exactly these: the sum of the two is rad_gather's value but
 * for visibility, decided by the caller's ray per point rather than by a cube's pixel
 * (a lightmap's texels then keep sharp shadows however their soft light is
 * interpolated). With RAD_SHADE_SKIES, the skies' directions too (each cell's, a ray
 * each), and rad_gather with RAD_SHADE_SOFT | RAD_SHADE_SKIES leaves out every light's
 * direct light: again the two sum to rad_gather's. FLAGS: RAD_SHADE_SCALED,
 * RAD_SHADE_SKIES. Writes OUT; returns RAD_OK, RAD_ERR_ARG
 * (NULL, a zero normal, unknown flags) or RAD_ERR_RANGE (as rad_gather). */
int rad_direct(const rad_scene_t *s, const rad_vec3_t *point, const rad_vec3_t *normal, int flags,
               rad_visible_fn *vis, void *ctx, rad_rgb_t *out);

/* A light probe: the radiosity seen from POINT in every direction w, B(w) (as
 * rad_gather's B, with FLAGS; a light's direction that rad_gather counts gives
 * B = pi E there alone), projected onto the nine real spherical harmonics of
 * bands 0..2, SH[k] = integral of B(w) Y_k(w) dw over the sphere (w on the scene's own
 * axes), in the order Y00; Y1-1 (y), Y10 (z), Y11 (x); Y2-2 (xy), Y2-1 (yz),
 * Y20 (3z^2 - 1), Y21 (xz), Y22 (x^2 - y^2). A uniform environment B gives
 * SH[0] = B sqrt(4 pi) and zeros. The radiosity arriving on a normal n is then
 * sum_k A_l SH[k] Y_k(n) / pi with A_0 = pi, A_1 = 2 pi / 3, A_2 = pi / 4 (Ramamoorthi
 * & Hanrahan 2001). Values past 32767.99 in the core's scale saturate (counted).
 * Returns as rad_gather (RAD_ERR_ARG for a hemisphere gatherer). */
int rad_gather_sh(const rad_scene_t *s, rad_gather_t *g, const rad_vec3_t *point, uint32_t skip,
                  int flags, rad_rgb_t *sh);

/* ---- culling: a gather's cost that does not grow with the scene ------------------ */
/* A gather draws every surface on each face of its cube. Through a bounding volume
 * hierarchy over the surfaces (integer boxes in the core's coordinates: Q16.16 in the
 * fixed build), a face draws only the surfaces in its frustum whose boxes the depth
 * already drawn (nearest first) does not hide, tiles or, for small boxes, pixels at a
 * time, then draws again, in the order of their indices, those left nearest at a
 * pixel: the same pixels, bit for bit, as drawing them all (ties between equal depths
 * go to the lower surface index either way). Only stats.raster_calls and
 * raster_pixels differ. RAD_CULL_BYTES(surfaces): the hierarchy's buffer, 4-aligned;
 * RAD_GATHER_CULL_BYTES(res, surfaces): a gatherer's work for it, any alignment. */
#define RAD_CULL_BYTES(surfaces)             (16u + (size_t)(surfaces)*60u)
#define RAD_GATHER_CULL_BYTES(res, surfaces) /* 16 x 16 tiles, a pixel column's edges */ \
    (((size_t)(surfaces) + 31u) / 32u * 4u + 5u * 256u + 8u * (size_t)(res) + 3u)

/* Builds the hierarchy over S's surfaces into BUF (BYTES long, 4-aligned): the same
 * for the same scene every time. Needs frozen geometry (as rad_gather); a scene whose
 * surfaces or scale change after it (a new solve after rad_restart re-meshing) needs
 * a new one. Returns its number of nodes (2 surfaces - 1, 0 without surfaces),
 * RAD_ERR_ARG (NULL), RAD_ERR_ALIGN, RAD_ERR_STATE (geometry not frozen) or
 * RAD_ERR_WORK (BYTES below RAD_CULL_BYTES(s->n_surfaces)). */
int rad_cull_build(const rad_scene_t *s, void *buf, size_t bytes);

/* Makes G's gathers (rad_gather, rad_gather_sh) draw through hierarchy CULL (built by
 * rad_cull_build, read only: many gatherers may share it), with WORK (BYTES long, at
 * least RAD_GATHER_CULL_BYTES(G's res, the hierarchy's surfaces)) its own; CULL NULL
 * (or rad_gather_init): every surface drawn again. A gather over a scene the hierarchy was not built for
 * (another surface count or scale) returns RAD_ERR_STATE. Returns RAD_OK, RAD_ERR_ARG
 * (NULL G or WORK, CULL not a hierarchy) or RAD_ERR_WORK. */
int rad_gather_cull(rad_gather_t *g, const void *cull, void *work, size_t bytes);

/* Makes S's shots (rad_shoot, rad_batch_render, rad_form_factors) draw their cubes
 * through hierarchy CULL (rad_cull_build, read only; NULL: every surface drawn), as
 * gathers do: the same pixels and solution, bit for bit; stats.raster_calls and
 * raster_pixels differ. Where the hierarchy hides little (an open courtyard under the
 * sky) a culled cube costs more than drawing every surface: after one that tested more
 * of its nodes than a third of the surfaces' count, the next 16 shots draw every
 * surface (cull_wait), then one tries again. A shot needs no memory for it: the
 * culling works in the shot's form factor sums before they are summed, so it is used
 * only when those hold RAD_GATHER_CULL_BYTES(cube res, surfaces) - 3 bytes
 * (n_elements * sizeof(rad_ff_t): 704 elements and one per 32 surfaces at res 192,
 * 384 and one per 32 at res 32), when the whole cube is drawn at once (band_rows 0;
 * rad_batch_render always) and while CULL fits S (its surface count and scale:
 * rebuild it after re-meshing); other shots, and those in parts (rad_shot_part), draw
 * every surface. Returns RAD_OK or RAD_ERR_ARG (CULL not a hierarchy). */
int rad_shoot_cull(rad_scene_t *s, const void *cull);

/* ---- lights: sun, sky, point and spot (lib/light.c) ----------------------------- */
/* Lights that are not surfaces: each shoots once, at the start of a solve (the first
 * rad_shoot steps, one light a step, before any patch), giving every element it
 * reaches its direct light: power P on an element of area A and reflectance rho adds
 * rho P / A to its radiosity and rho P to its patch's unshot power, which progressive
 * refinement then bounces as any other. A light itself is never seen (it has no area).
 * Shadows come from the same rasterizer and element lattice as the shots:
 *   - a point or spot light renders a whole cube (six faces of RES^2 pixels) at its
 *     position; a pixel of solid angle dw (its delta solid angle, the cube's quadrant
 *     sums exact) gives the element it sees I dw of power (times the spot's falloff);
 *   - a sun renders an orthographic item buffer of about RES x RES pixels (in tiles
 *     of the scene's res; by default with pixels of at most 1/16 the side of the
 *     scene's smallest elements: res below) over the square that the scene's corners project to,
 *     across its direction; a pixel of area a (perpendicular to the light) gives the
 *     element it sees E a;
 *   - a sky is a fixed dome of N = 3 m^2 such suns over the hemisphere about its up
 *     (lib/light.c has the dome): rings of equal width on the unit disc that the
 *     hemisphere projects to, ring i (0..m-1) in 3 (2 i + 1) cells of equal angle (each
 *     of projected area pi / N), each cell's sun along the cell's irradiance vector
 *     (the integral of L w dw over it, for the channels' sum) with the irradiance that
 *     the cell's sky gives a plane facing up, over its cosine to up. Light enters
 *     through openings as a sun's does. Its radiance at zenith angle t is
 *     L(t) = H + (Z - H) cos t (Z at the zenith, H at the horizon; H = Z: uniform), so a
 *     plane facing up under an open sky receives E = pi H + 2 pi (Z - H) / 3 exactly
 *     (pi L for a uniform sky), and a plane that sees whole cells their light exactly
 *     (a grey sky); a vertical wall, whose plane cuts cells, receives
 *     (pi / 2 - 2 / 3) H + 2 Z / 3 within 0.3% at 192 directions. Each direction is
 *     a sun's shot of one raster over the whole scene (RES; by default as a sun's,
 *     each of the N rasters sqrt N times coarser: their errors average).
 * Surfaces are one-sided: an element receives only on its front (the side its normal
 * points to), but a face turned away from the light shadows as any other (a one-sided
 * roof facing into a room keeps the sun out), drawn a quarter of a pixel's footprint
 * behind the faces the light reaches so that it never shadows a lit face it meets or
 * lies on (what lies less than that behind it, along contact edges, may be lit: at
 * most a row of pixels along each). Units are
 * the scene's: a point light of intensity I (per channel) at distance r from a plane
 * whose normal makes angle t with the direction to it gives irradiance E = I cos t /
 * r^2 and radiosity B = rho E; a sun of E gives a plane at angle t to it E cos t, and
 * B = rho E cos t: the emission units of rad_add_polygon (a surface emitting B of them
 * is a light of radiosity B). Lights count in the power shift (rad.h: Scale) through
 * their brightest irradiance on any surface (a point light's I / d^2 at the nearest
 * plane it faces), and their power reaching the surfaces joins the emitted power
 * (rad_unshot_fraction, which is 1 while a light has not shot). */
#define RAD_LIGHT_SUN   1 /* directional: irradiance E on a plane facing it */
#define RAD_LIGHT_POINT 2 /* intensity I in every direction */
#define RAD_LIGHT_SPOT  3 /* intensity I inside a cone, 0 outside */
#define RAD_LIGHT_SKY   4 /* radiance from every direction above the horizon */
struct rad_light_s {
    uint16_t type;        /* RAD_LIGHT_* */
    uint16_t res;         /* 0: default (point, spot: the scene's res; sun, sky: pixels of
                    * at most 1/16 the side (square root of the area) of the smallest
                    * 1% of the elements, to a power of two in area, each of a light's
                    * N rasters (a sun's disc: 16; a sky's directions; dirs below)
                    * sqrt N times coarser, within 4 res (sky, dome sun: res)..8192: a pixel's
                    * centre decides which element it counts for, so an element of side
                    * a gets about p / a of its light wrong, p the pixel's side); else
                    * even, 8..RAD_MAX_RES (sun, sky: 8..8192). A sun's raster is
                    * K x K tiles of the scene's res, K = RES / res rounded up; a point
                    * light's face above the scene's res needs 2 RES pixels a pass in
                    * the work buffer (rad_scene_t.pass_pixels), else RES is halved
                    * down to res */
    rad_vec3_t position;  /* point, spot: where it is, within +-RAD_INPUT_LIMIT in the
                           * caller's units and +-RAD_COORD_LIMIT in the core's scale
                           * (checked by rad_shoot) */
    rad_vec3_t direction; /* sun, spot: the way its light travels (a sun straight
                           * overhead: (0, -1, 0) with y up); any length above 0.
                           * sky: its up, the zenith's direction (0: +y) */
    rad_rgb_t intensity;  /* point, spot: I (per unit solid angle); sun: E; sky: the
                           * zenith's radiance Z; each channel in
                           * [0, RAD_EMISSION_LIMIT] */
    /* spot: the cosines of the cone's half angle (0 beyond it) and of the inner half
     * angle (full intensity within it), cos_outer <= cos_inner, both in [-1, 1];
     * between them I times s^2, s = (cos a - cos_outer) / (cos_inner - cos_outer)
     * (glTF's KHR_lights_punctual falloff); equal cosines: a hard edge */
    rad_real_t cos_outer, cos_inner;
    /* sun: the tangent of its angular radius, in [0, 1/4] (0: a point; the real sun's
     * is 0.0047): its light then comes from 16 directions over its disc (8 of
     * Vogel's spiral and their opposites, fixed), each an orthographic shot of E / 16,
     * so that shadows have penumbrae */
    rad_real_t radius;
    rad_rgb_t horizon; /* sky: the horizon's radiance H, each channel in
                        * [0, RAD_EMISSION_LIMIT] (equal to intensity: a uniform sky;
                        * a light zeroed then filled in has H = 0: L = Z cos t) */
    uint32_t dirs;     /* sky: its count of directions, rounded down to 3 m^2
                        * (3, 12, 27, 48, 75, ...), 3..768; 0: the default, 192.
                        * sun: 0..768, the count of suns it is one of (a sky dome
                        * built of suns), whose rasters' errors average: its default
                        * raster is sqrt(dirs) times coarser (res above); 0, 1: alone */
};

/* Hands S an array LIGHTS of MAX entries for rad_add_light (kept by the scene from then
 * on; at most 65535 are used). Returns RAD_OK, RAD_ERR_ARG (NULL, MAX 0) or
 * RAD_ERR_STATE (an array is in use already, or shooting started). */
int rad_use_lights(rad_scene_t *s, rad_light_t *lights, uint32_t max);

/* Adds a copy of LIGHT to the scene's array; it shoots at the start of the next solve
 * (the one that rad_restart starts, once solving). Returns its index, or RAD_ERR_ARG
 * (NULL, an unknown type or res, a zero direction), RAD_ERR_RANGE (a position,
 * intensity or cosine out of range), RAD_ERR_FULL (the array is full) or
 * RAD_ERR_STATE (no array, or shooting started: rad_restart first); a sky's dirs
 * outside 0, 3..768 is RAD_ERR_ARG. */
int rad_add_light(rad_scene_t *s, const rad_light_t *light);

/* Replaces light K (the index rad_add_light returned) by a copy of LIGHT: any of its
 * fields (colour, intensity, position, direction, even its type), checked as
 * rad_add_light. Takes effect on the next rad_restart(), as rad_set_surface (before
 * anything has shot, or after rad_restart: at once); the power scale is chosen then
 * with it. Relighting: rad_set_light, rad_restart, then rad_rows_shoot (no patch's
 * cube rendered again; the lights' shots are, being their direct light) or rad_shoot.
 * A light whose channels are all 0 (a sky: its horizon's too) shoots nothing and is
 * not rendered, though it counts as a shot: a light group (rad_mix) is solved with
 * every light not in it set dark (and every surface not in it not emitting,
 * rad_set_surface). Returns RAD_OK, RAD_ERR_ARG (K not one of S's lights, or as
 * rad_add_light), RAD_ERR_RANGE (as rad_add_light) or RAD_ERR_STATE (a solve has shot
 * but not all of its lights yet: they would shoot at the scale chosen without the
 * change; rad_restart first). */
int rad_set_light(rad_scene_t *s, uint32_t k, const rad_light_t *light);

#ifdef __cplusplus
}
#endif
#endif
