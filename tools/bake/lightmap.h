/* SPDX-License-Identifier: MIT */
/* lightmap — the light arriving on a mesh's surfaces, baked into an atlas of N x N
 * texels (uses malloc, libm).
 *
 * Charts: polygons joined across shared edges (the same two vertex positions, exactly)
 * or parts of edges (a corner at the same position and an edge of each leaving it the
 * same way, within 10^-3 rad: a T-junction, where regions tessellated apart meet) when
 * they lie in one plane (normals within 10^-3 rad, the neighbour's centroid within
 * 10^-6 of the scene's extent of the plane). Coplanar polygons that do not overlap in
 * space do not overlap on their plane, so such a chart's layout never folds.
 * Smooth charts: then coplanar charts join across gentle folds, so that a column's
 * facets, an arch's or a terrain's triangles do not each take a chart (and its gutter).
 * Seeds are taken largest area first; a seed's chart grows breadth first across edges
 * shared whole where the two polygons' normals lie within the crease (lm_opts.crease,
 * LM_CREASE = 25 degrees by default), taking a neighbouring coplanar chart when every
 * polygon of it lies within the crease of the seed's normal and its projection on the
 * seed's plane overlaps none of the chart's so far (tools/bake/tset.h; a spiral ramp
 * folds over itself and so splits). The seed's plane is the chart's: the chart is a
 * height field over it, each polygon projected with a texel covering at most
 * 1 / cos 25 = 1.10 times its nominal area, and a texel's sample lies on its own
 * polygon and is gathered about that polygon's normal. 25 degrees, not more: a crease
 * of a hard edge (a box's 90, a chamfer's 45) keeps its charts apart, so each side's
 * light stays its own up to the edge; a smooth surface's facets (a column of 16 or
 * more, 22.5 degrees apart) join. A chart is projected on its plane, its u
 * axis along its longest boundary edge, at one texel size T (world units a texel) for
 * the whole atlas: a texel shows the same area everywhere (within the crease's 1.10).
 *
 * Packing: each chart's rectangle holds its texels, a ring of one texel around them
 * (so that a bilinear lookup anywhere on the chart reads texels of this chart only) and
 * a gutter of PADDING texels around the ring, dilated from the chart alone: a mip level
 * m box-filters blocks of 2^m texels, so a block holding a chart's texel reaches at most
 * 2^m - 1 texels past it, inside the gutter when 2^m <= PADDING + 1 (levels 1 and 2 at
 * the default 4: a 2x2 and a 4x4 downsample read the chart alone). Rectangles are
 * sorted by height (then width, then chart) and laid in shelves left to right, top to
 * bottom, side by side; texels of no rectangle stay 0. Without a texel size,
 * T is the smallest (to 2^-20 of itself) at which the shelves fit: no smaller than
 * sqrt(area) / N, the size at which the texels would hold the area and nothing more.
 *
 * Texels: every texel that a polygon's projection touches is covered (the square and
 * the triangle overlap: separating axes), and so is the ring of texels around them;
 * each has a sample point (where it is gathered, once, unless the bake interpolates
 * it: below): the point of its chart nearest the texel's centre, moved 1/8 texel (at
 * least 2^-12 of the scene's extent) in from the chart's boundary edges, lifted off the
 * plane by 2^-12 of the extent. Then four short rays along the plane (3/4 texel) look
 * for a back face: a sample that meets one first is inside geometry (a box on the
 * floor, a thick wall through it) and moves out past it.
 * Gathering the ring (rather than dilating into it) puts values of the surface's own
 * edge under a bilinear lookup there, from either side of a seam. Texels of a
 * rectangle left over (the gutter, a concave chart's rest) get the mean of their filled
 * neighbours of the same chart, ring by ring.
 * A texel holds E, the radiosity arriving (sc_gather's units): a surface of
 * reflectance rho there shows rho E plus its own emission.
 * Sharp lights per texel: a bake that gathers the soft light alone (rad_cli's:
 * sc_gather's SC_SOFT, the elements' light and skies') adds the suns', points' and
 * spots' direct light at every covered texel's own sample afterwards (lm_direct_rows:
 * sc_direct, each light's visibility a ray through the grid of polygons, lm_visible).
 * The adaptive passes below then decide on the soft light, which a sun's shadow edge
 * does not split, and no texel's sun is interpolated across a shadow's edge.
 *
 * Adaptive gathering (a tolerance above 0): not every texel is gathered. A texel is
 * free when its sample is its centre (not moved in from a boundary nor out of
 * geometry) and the four rays meet no face within their 3/4 texel. Each chart's
 * rectangle is cut into blocks of LM_STEP texels from its corner; a block's corners are
 * gathered first (pass 1). A block whose (b + 1)^2 texels are all free and on one
 * plane (coplanar polygons: a floor of tiles) and whose corners' channel sums lie
 * within TOL of the largest is filled by bilinear interpolation of its corners; any
 * other block gathers its edges' midpoints and centre and splits in four, down to
 * blocks of one texel (every texel gathered).
 * So texels near boundaries, geometry and the ring are gathered; where the bake
 * interpolates, the block's gathered corners (4 or 2 texels apart) agree within TOL,
 * and a feature narrower than a block that no corner sees (a thin shadow) is missed,
 * as in any irradiance cache. A pass's
 * decisions depend only on the values gathered before it: any split of each pass's
 * gathers over threads gives the same bits. A tolerance of 0 gathers every texel.
 *
 * Memory: 30 bytes a texel (owner, sample, polygon, colour, state) and a few words and
 * a plane (32 bytes) a polygon.
 */
#ifndef RAD_TOOLS_LIGHTMAP_H
#define RAD_TOOLS_LIGHTMAP_H

#include <stddef.h>

#include "formats/obj.h"
#include "host/scene.h"

#define LM_MAX_SIZE    8192
#define LM_PADDING     4    /* the default gutter from 512 texels a side: mip levels 1, 2 */
#define LM_MAX_PADDING 64   /* mip levels up to 6 */
#define LM_STEP        4    /* texels between the first pass's gathers, within a chart */
#define LM_TOL         0.05 /* the default tolerance of the adaptive bake (tests/test_bake.c) */
#define LM_CREASE      25   /* degrees: the default crease of smooth charts (see above) */
#define LM_MAX_CREASE  60   /* a texel then covers up to 1 / cos 60 = 2 times its area */

/* The light arriving at world point P on a surface of unit normal N, into RGB.
 * Returns 0, or nonzero to stop the bake. */
typedef int (*lm_gather_fn)(void *ctx, const double p[3], const double n[3], double rgb[3]);

typedef struct {
    int size;      /* N: the atlas is N x N texels, 1..LM_MAX_SIZE */
    double texel;  /* world units a texel; 0: the smallest that fits */
    int padding;   /* texels of gutter around each chart, 1..LM_MAX_PADDING; -1: none; 0: size / 128
                    * within 1..LM_PADDING (a small atlas's charts are a few texels wide:
                    * a 64 x 64 one of the Cornell box's 16 charts covers 2652 texels at
                    * 1, 729 at 4) */
    double tol;    /* adaptive gathering's tolerance, 0..1 (LM_TOL); 0: every texel */
    double crease; /* degrees, up to LM_MAX_CREASE: charts joined across folds (see above);
                    * 0: LM_CREASE; negative: coplanar charts only */
} lm_opts;

typedef struct {
    double o[3], u[3], v[3], n[3]; /* world point = o + s T u + t T v at texel (s, t) of
                                    * the rectangle; n = u x v, the lit side */
    int x, y, w, h;                /* the rectangle in the atlas, ring included */
    int first, count;              /* its polygons: chart_polys[first .. first + count) */
} lm_chart;

typedef struct {
    int size, padding;
    double texel, extent;
    int npolys, ncharts;
    lm_chart *charts;
    int *poly_chart;      /* per polygon: its chart, -1 for a degenerate polygon */
    int *chart_polys;     /* polygons by chart */
    int *owner;           /* size^2: the chart whose rectangle holds the texel, -1: none */
    float *sample;        /* size^2 * 2: a covered texel's sample (s, t) in its rectangle,
                       * NaN when not covered */
    float *rgb;           /* size^2 * 3: the baked light, row 0 at the top */
    int *poly;            /* size^2: the polygon of a covered texel's sample */
    unsigned char *state; /* size^2: LM_FREE, and how the texel got its light */
    unsigned char *block; /* size^2: the size of the block waiting with its corner here, 0: none */
    double *planes;       /* npolys * 4: each polygon's unit normal (a texel's gather's) and
                       * offset d (n . x = d) */
    double tol;
    int pass, waiting; /* passes planned so far; the size of the blocks waiting */
    const sc_poly *polys;
    void *grid; /* the polygons by cell, for the sample's rays */
    /* lm_build_file only (NULL, 0: rad's charts) */
    double *file_uv;  /* 8 per polygon: its corners' places in texels (x right, y down) */
    lm_chart *frames; /* 2 per polygon, its fan triangles (corners 0 1 2, 0 2 3): world =
                       * o + x T u + y T v at atlas texel position (x, y); count 1 when
                       * the triangle has UV area, else 0 */
    int file_charts;  /* the file's charts: polygons joined across shared UV edges */
    int painted;      /* lm_paint filled the texels: lm_plan's one pass gathers the rest */
} lm_atlas;

/* Charts, packing and texel samples for POLYS (kept by pointer until lm_free). Returns
 * 0, or -1 with one line in err: a size of 0 or above LM_MAX_SIZE, a tolerance outside
 * 0..1, an atlas that cannot fit (at the given texel size, or at any with too many
 * charts), out of memory. */
int lm_build(lm_atlas *a, const sc_poly *polys, int n, const lm_opts *o, char *err, size_t errlen);

/* The file's own lightmap UVs (a second UV set: glTF's TEXCOORD_1) instead of rad's
 * charts: lm_build laid out by UV (8 per polygon: corner K of polygon I at u =
 * UV[8 I + 2 K], v = UV[8 I + 2 K + 1], glTF's convention, origin at the image's top
 * left; NaN for a polygon without), each texel a triangle's UV covers sampled on that
 * triangle by the affine map from its UV corners to its world corners. The file's charts
 * are its polygons joined across edges whose world and UV endpoints are both the same;
 * a chart's boundary edges keep the samples 1/8 texel in, as rad's do, and texels
 * within PADDING (lm_build's rule) rings of a chart's texels that no other chart holds
 * make its gutter, dilated from it alone (the first chart in order to reach a texel
 * takes it). The adaptive bake cuts the whole atlas into blocks. What is wrong with the
 * UVs is counted into *REP: corners outside [0, 1] (texels past the atlas's edge are
 * lost), texels whose centre lies inside triangles of two polygons (overlapping charts:
 * the nearest sample wins), triangles of no UV area (below 10^-12 of their sides'
 * squares: no texels) and polygons with no UVs (no texels). Returns 0, or -1 with one
 * line in err (lm_build's, or no polygon with UVs). */
typedef struct {
    long outside, overlap, zero_area, missing;
} lm_file_report;
int lm_build_file(lm_atlas *a, const sc_poly *polys, int n, const double *uv, const lm_opts *o,
                  lm_file_report *rep, char *err, size_t errlen);
/* lm_build_file's UV array for POLYS (tags = face indices of SC, polys_from_obj) from SC's
 * second UV set (obj_scene.uv2): each polygon corner takes the UV of its face's first
 * corner at the same position. NULL when out of memory or SC has none. */
double *lm_poly_file_uvs(const obj_scene *sc, const sc_poly *polys, int n);

/* Texel states: LM_FREE a flag (see above), and at most one of the others. */
enum { LM_FREE = 1, LM_WANT = 2, LM_GATHERED = 4, LM_LERPED = 8 };

/* Gathers the covered texels through FN (every one, or adaptively: see above), adds
 * DIRECT's light at every covered texel (unless NULL: lm_direct_rows), then dilates.
 * Returns 0, or -1 when FN or DIRECT stopped it (the atlas then holds what was
 * gathered, undilated) or there was no memory for the dilation. */
int lm_bake(lm_atlas *a, lm_gather_fn fn, lm_gather_fn direct, void *ctx);
/* lm_bake in parts: while lm_plan gives a count of texels above 0 (it decides, from
 * the texels gathered so far, which blocks are interpolated and which split, and marks
 * the texels the next pass gathers), gather them: lm_gather_rows gathers the marked
 * texels of the rows Y with Y % STEP == FIRST (threads may gather such sets at once,
 * each through a context of its own: a texel's value does not depend on which thread
 * gathers it); once lm_plan gives 0, lm_direct_rows (by rows, as lm_gather_rows), then
 * the dilation. lm_gather_rows and lm_dilate return 0, or -1 (FN stopped it; no memory
 * for the dilation). */
long lm_plan(lm_atlas *a);
/* The covered texels neither gathered nor interpolated yet: the most that the passes
 * left may gather. */
long lm_undecided(const lm_atlas *a);
int lm_gather_rows(lm_atlas *a, int first, int step, lm_gather_fn fn, void *ctx);
int lm_dilate(lm_atlas *a);
/* The soft light painted from a solve's elements (N of EL: sc_soft_elements) instead of gathered: each
 * element corner takes the area-weighted mean of the known elements with a corner at
 * that place (within 2^-20 of the extent) on that chart, linear over each element's
 * triangles (corners 0 1 2, 0 2 3) as a Gouraud shading draws it; a covered texel takes
 * the value at the nearest point of its own polygon's elements, when that lies within
 * LM_PAINT_REACH texels of its sample and on a known element. The other covered texels
 * (on elements not known, or polygons the solve did not mesh) are what lm_plan then
 * gives, in one pass, to gather. The bake's sharp lights stay per texel
 * (lm_direct_rows). Memory while it runs: 4 bytes a texel, 72 an element corner. Returns
 * the texels left to gather, or -1 out of memory. */
#define LM_PAINT_REACH 2.0
long lm_paint(lm_atlas *a, const sc_soft_element *el, long n);

/* Adds FN's light (the sharp lights' direct light: sc_direct) at every covered texel's
 * sample of the rows Y with Y % STEP == FIRST, after the gathers (FN's value at the
 * texel's own point, never interpolated). 0, or -1 when FN stopped it. */
int lm_direct_rows(lm_atlas *a, int first, int step, lm_gather_fn fn, void *ctx);
/* Whether the ray from P along unit DIR reaches LEN (HUGE_VAL: unbounded) without
 * meeting a polygon of ATLAS (an lm_atlas), from either side: sc_visible_fn's. */
int lm_visible(void *atlas, const double p[3], const double dir[3], double len);

/* Covered texel (X, Y)'s sample point into P; 1 if covered, 0 if not. */
int lm_texel_point(const lm_atlas *a, int x, int y, double p[3]);

/* The atlas position (in texels, x right, y down; divide by size for UV) of world
 * point P on polygon POLY, projected on its chart's plane. -1 for a degenerate polygon. */
int lm_uv(const lm_atlas *a, int poly, const double p[3], double xy[2]);

/* A bilinear lookup at atlas position XY (texel centres at half-integers), as a GPU
 * filters with clamping at the atlas's border. */
void lm_lookup(const lm_atlas *a, const double xy[2], double rgb[3]);

/* Writes the atlas: .hdr (linear, tools/formats/hdr.h) or .png/.ppm (sRGB at EXPOSURE;
 * 0: automatic over the covered texels). 0, or -1 with err; never a partial file. */
int lm_write(const lm_atlas *a, const char *path, double exposure, char *err, size_t errlen);

/* Each face corner of SC (whose faces the atlas's polygons came from: tags = face
 * indices, polys_from_obj) as a glTF UV on the atlas ([0, 1], origin at the top left),
 * into UV[2 * corner]: on the polygon of its face that has the corner's vertex (the
 * face's first polygon if none has; (0, 0) for a face without one); an atlas of
 * lm_build_file: the corner's own second UV (obj_scene.uv2; (0, 0) where none). 0, or
 * -1 out of memory. */
int lm_corner_uvs(const lm_atlas *a, const obj_scene *sc, double *uv);

/* The atlas as 8-bit sRGB PNG bytes for embedding (*PNG, malloc'd, *N bytes), scaled so
 * that its largest channel is white: a texel's light is *SCALE times its sRGB-decoded
 * value, within half a code's step (no texel clips). 0, or -1 with err. */
int lm_png(const lm_atlas *a, unsigned char **png, size_t *n, double *scale, char *err,
           size_t errlen);

void lm_free(lm_atlas *a);

#endif
