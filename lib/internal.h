/* rad — declarations shared by lib/ files (the rad__ names), never installed. */
#ifndef RAD_INTERNAL_H
#define RAD_INTERNAL_H

#include "scalar.h"

#if RAD_FLOAT
#define rad__outcodes        radf__outcodes
#define rad__receive         radf__receive
#define rad__shoot           radf__shoot
#define rad__cube_part       radf__cube_part
#define rad__cube_merge      radf__cube_merge
#define rad__surface_corners radf__surface_corners
#define rad__lattice_init    radf__lattice_init
#define rad__lattice_face    radf__lattice_face
#define rad__lattice_span    radf__lattice_span
#endif

/* A vertex in view space before projection: a across, b up, d depth; c a colour. */
typedef struct {
    rad_real_t a, b, d;
    rad_real_t c[3];
} rad__cvert_t;

/* A view frustum of unit slopes: |a| <= d, and d >= b >= -d (or >= 0 when half is
 * set: the hemi-cube's side faces), d >= RAD__NEAR; mapped onto a WIDTH x HEIGHT
 * raster. (The camera scales its axes so that its field of view has unit slopes.) */
typedef struct {
    int half;
    int width, height;
} rad__frustum_t;

/* A family of lattice lines (lattice.c): line k's plane through the cube's centre has
 * normal C0 + k C1 + k^2 C2 (the cube's axes x, y, z), k = 0..N, with K elements to a
 * patch across the lines. */
typedef struct {
    int64_t c[3][3];
    int64_t o[3][3]; /* on the current face, coefficient j's E at pixel (x, y):
                        o[j][0] + x o[j][1] + y o[j][2] */
    uint32_t n, k;
    uint32_t unit, coarse; /* quads: a fine and a coarse step's change of the element id */
    int32_t hint[2];       /* the last span's first and last cells on this face, or -1 */
} rad__family_t;

/* A surface's lattice: 2 families (quad columns, rows) or 3 (triangle i, j, i + j);
 * element ids from FIRST, PU patches across a quad (a triangle's patch levels); seen
 * on a face of resolution RES whose axes a, b, d are the cube's AXIS (0 x, 1 y, 2 z)
 * times SIGN. */
typedef struct {
    rad__family_t fam[3];
    unsigned nfam;
    int32_t res;
    uint32_t first, pu;
    unsigned char axis[3];
    signed char sign[3];
} rad__lattice_t;

/* The lattice of surface SF from its N corners (rad__surface_corners' order) relative
 * to the centre of a cube of resolution RES, on the cube's axes. */
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
 * (STEPS: WIDTH entries of zero for rad__lattice_span). */
typedef struct {
    uint32_t *z;
    rad_index_t *ids;
    rad_rgb_t *rgb;
    rad__lattice_t *lat;
    uint32_t *steps;
    int width, row0, row1;
} rad__target_t;

/* Outcodes of polygon IN against frustum F: returns the OR of the vertices' outside
 * bits (bit p: outside plane p), or RAD__CULLED when all are outside one plane. */
#define RAD__CULLED 0x100u
unsigned rad__outcodes(const rad__frustum_t *f, const rad__cvert_t *in, unsigned n);

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
/* Form factors from patch P's centre to every element, into s->acc. */
void rad__hemicube(rad_scene_t *s, uint32_t p);

/* Element E receives power F * U (three channels) from a shooter; its patch's unshot
 * power grows by what it reflects (solve.c). */
void rad__receive(rad_scene_t *s, const rad_energy_t *u, uint32_t e, rad_ff_t f);
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

/* One shot's cube in parts (hemicube.c): part PART of NPARTS renders its run of the
 * cube's rows into BUF (RAD_PART_BYTES);
 * merging fills s->acc as rad__hemicube would, bit for bit. Needs all five faces in
 * one pass (band_rows 0). */
int rad__cube_part(const rad_scene_t *s, uint32_t p, unsigned part, unsigned nparts, void *buf);
void rad__cube_merge(rad_scene_t *s, void *const *bufs, unsigned nparts);

/* The 3 or 4 corners of surface SF's vertex lattice (mesh.c): every vertex of the
 * surface is a rounded convex combination of them. Returns how many, indices in K. */
unsigned rad__surface_corners(const rad_scene_t *s, const rad_surface_t *sf, uint32_t *k);

/* Channel K (0 r, 1 g, 2 b) of C. */
static inline rad_real_t rad__channel(const rad_rgb_t *c, unsigned k)
{
    return k == 0 ? c->r : k == 1 ? c->g : c->b;
}

/* Number of vertices of element E (3 or 4). */
static inline unsigned rad__nverts(const rad_element_t *e)
{
    return e->v[3] == RAD_INDEX_NONE ? 3u : 4u;
}

#endif
