/* SPDX-License-Identifier: MIT */
/* rad port test — one program for the host and every target.
 *
 * Builds a Cornell box in C (no files): five inward-facing walls (red left, green
 * right, white floor, ceiling and back), two white blocks (a short and a tall one,
 * rotated, outward-facing, standing on the floor) and a small emitting quad just under
 * the ceiling, facing down. Solves it by progressive refinement and prints what must be
 * equal on every CPU (the fixed build's counts and a checksum of every element's
 * radiosity) and what each target measures (instructions, RAM).
 *
 * Build switches:
 *   PORT_PROFILE=small|medium|sun (or 1|2|3)  the scene and configuration (default small):
 *       small:  >= 100 elements, hemi-cube res 16: fits the Cortex-M0's 16 KB of RAM.
 *       medium: >= 500 elements, hemi-cube res 32: fits 64 KB of RAM.
 *       sun:    small's box without its ceiling and lamp, lit by a sun (rad_add_light)
 *               slanting in through the open top: the light's orthographic shot
 *               (4 x 4 tiles of 16 pixels) and its shadows, on the Cortex-M0.
 *   PORT_BAND_ROWS=n   render the hemi-cube n rows at a time (work buffer sized for it;
 *                      bit-exact with all faces at once, so checksums do not change)
 *   PORT_WORK_BYTES=n  size the work buffer explicitly (default: what the config needs)
 *   PORT_BENCH=1       also time one shot at hemi-cube resolutions 16, 32 and 64 (the
 *                      work buffer is sized for PORT_BENCH_MAX_RES, default 64; larger
 *                      resolutions report "skipped")
 *   PORT_PROBE=1       (host) pools large enough for any scene, to size them again
 *   RAD_FLOAT=1        the float twin (checksums differ from the fixed build's)
 * All memory is static: the pools are sized for the scene, the work buffer for RES.
 */
#include "rad/rad.h"
#include "port.h"

/* ---- profile ------------------------------------------------------------------- */

#define PORT_PROFILE_small  1
#define PORT_PROFILE_medium 2
#define PORT_PROFILE_sun    3
#define PORT_PROFILE_1      1
#define PORT_PROFILE_2      2
#define PORT_PROFILE_3      3
#ifndef PORT_PROFILE
#define PORT_PROFILE small
#endif
#define PORT_CAT_(a, b) a##b
#define PORT_CAT(a, b)  PORT_CAT_(a, b)
#define PROFILE         PORT_CAT(PORT_PROFILE_, PORT_PROFILE)

/* Q16.16 from a ratio of integers, folded at compile time (no floating point). */
#define Q16(num, den) ((int32_t)(((int64_t)(num)*65536 + (den) / 2) / (den)))

/* The scene is the same in both profiles; the mesh and the hemi-cube differ:
 *   small:  walls 4 x 4 elements (2 x 2 patches), block faces 2 x 2 (tall sides 2 x 4),
 *           light 1: 137 elements, 243 vertices.
 *   medium: walls 10 x 10 elements (2 x 2 patches), block faces 3 x 3 (tall sides 3 x 6),
 *           light 3 x 2: 632 elements, 825 vertices.
 * The pools hold exactly that (emitters get a patch per element): rad_add_polygon
 * fails with RAD_ERR_FULL ("pool full") if the core's meshing changes. */
#if PROFILE == 1
#define PROFILE_NAME "small"
#define MAX_ELEMENT  Q16(16, 1)
#define MAX_PATCH    Q16(32, 1)
#define RES          16
#define MAX_SHOTS    400
#define TOL          Q16(1, 50) /* stop at 2% of the emitted power unshot */
#define N_SURFACES   16
#define N_PATCHES    35
#define N_ELEMENTS   137
#define N_VERTICES   243
#elif PROFILE == 2
#define PROFILE_NAME "medium"
#define MAX_ELEMENT  Q16(13, 2) /* 6.5 units: 10 x 10 elements per wall */
#define MAX_PATCH    Q16(32, 1)
#define RES          32
#define MAX_SHOTS    600
#define TOL          Q16(1, 50)
#define N_SURFACES   16
#define N_PATCHES    40
#define N_ELEMENTS   632
#define N_VERTICES   825
#elif PROFILE == 3
#define PROFILE_NAME "sun"
#define MAX_ELEMENT  Q16(16, 1)
#define MAX_PATCH    Q16(32, 1)
#define RES          16
#define MAX_SHOTS    400
#define TOL          Q16(1, 50)
#define N_SURFACES   14
#define N_PATCHES    30
#define N_ELEMENTS   120
#define N_VERTICES   214
#else
#error "PORT_PROFILE must be small, medium, sun, 1, 2 or 3"
#endif
#define SUN (PROFILE == 3)

/* Host only, when the core's meshing changes: -DPORT_PROBE=1 gives the pools room for
 * any scene, and the elements/patches/vertices lines then give the sizes to set above. */
#if defined(PORT_PROBE) && PORT_PROBE
#undef N_PATCHES
#undef N_ELEMENTS
#undef N_VERTICES
#define N_PATCHES  8000
#define N_ELEMENTS 8000
#define N_VERTICES 8000
#endif

#define N_ACC (N_ELEMENTS > N_VERTICES ? N_ELEMENTS : N_VERTICES)

/* The work buffer: for RES (the benchmark: for the largest resolution it times), all
 * five faces at once, or PORT_BAND_ROWS rows of a face at a time. */
#ifndef PORT_BAND_ROWS
#define PORT_BAND_ROWS 0
#endif
#ifndef PORT_BENCH
#define PORT_BENCH 0
#endif
#ifndef PORT_BENCH_MAX_RES
#define PORT_BENCH_MAX_RES 64
#endif
#if PORT_BENCH
#define WORK_RES PORT_BENCH_MAX_RES
#else
#define WORK_RES RES
#endif
#if PORT_BAND_ROWS
#define WORK_PIXELS ((uint32_t)WORK_RES * (uint32_t)PORT_BAND_ROWS)
#else
#define WORK_PIXELS RAD_PIXELS_ALL(WORK_RES)
#endif
#ifndef PORT_WORK_BYTES
#define PORT_WORK_BYTES RAD_WORK_BYTES(WORK_RES, WORK_PIXELS, N_ACC)
#endif

static rad_surface_t surfaces[N_SURFACES];
static rad_patch_t patches[N_PATCHES];
static rad_element_t elements[N_ELEMENTS];
static rad_vec3_t vertices[N_VERTICES];
static uint64_t work[(PORT_WORK_BYTES + 7u) / 8u];
static rad_scene_t scene;
#if SUN
static rad_light_t lights[1];
#endif

/* ---- output: a tiny formatter (no printf on the targets) ------------------------ */

static void put_u64(uint64_t v)
{
    char buf[24];
    char *p = buf + sizeof buf - 1;
    *p = '\0';
    do {
        *--p = (char)('0' + (int)(v % 10u));
        v /= 10u;
    } while (v);
    port_puts(p);
}

static void put_i64(int64_t v)
{
    if (v < 0) {
        port_puts("-");
        put_u64((uint64_t)0 - (uint64_t)v);
    } else {
        put_u64((uint64_t)v);
    }
}

static void put_hex64(uint64_t v)
{
    static const char digits[] = "0123456789abcdef";
    char buf[19];
    int i;
    buf[0] = '0';
    buf[1] = 'x';
    for (i = 0; i < 16; i++) buf[2 + i] = digits[(v >> (60 - 4 * i)) & 15u];
    buf[18] = '\0';
    port_puts(buf);
}

static void line_u(const char *key, uint64_t v)
{
    port_puts(key);
    port_puts(" ");
    put_u64(v);
    port_puts("\n");
}

static void fail(const char *what, int rc)
{
    port_puts("error ");
    port_puts(what);
    port_puts(" ");
    put_i64(rc);
    port_puts(" ");
    port_puts(rad_strerror(rc));
    port_puts("\n");
    port_exit(1);
}

/* ---- the scene ------------------------------------------------------------------ */

/* Coordinates in 1/16 units (exact in Q16.16): the room spans +-32 units. */
#define W 512
enum { WHITE, RED, GREEN, LIGHT };

typedef struct {
    int16_t v[4][3];
    uint8_t mat;
} quad_t;

/* Vertices counter-clockwise seen from the lit side (the normal points into the room). */
static const quad_t walls[] = {
    {{{-W, -W, -W}, {-W, -W, W}, {W, -W, W}, {W, -W, -W}}, WHITE}, /* floor, +y */
    {{{-W, W, -W}, {W, W, -W}, {W, W, W}, {-W, W, W}}, WHITE},     /* ceiling, -y */
    {{{-W, -W, -W}, {W, -W, -W}, {W, W, -W}, {-W, W, -W}}, WHITE}, /* back, +z */
    {{{-W, -W, -W}, {-W, W, -W}, {-W, W, W}, {-W, -W, W}}, RED},   /* left, +x */
    {{{W, -W, -W}, {W, -W, W}, {W, W, W}, {W, W, -W}}, GREEN},     /* right, -x */
    /* the light: 16 x 12 units, one unit under the ceiling, facing down */
    {{{-128, 496, -96}, {128, 496, -96}, {128, 496, 96}, {-128, 496, 96}}, LIGHT},
};

/* A block: footprint corners (x, z) ordered so that the top faces +y, 19 units on a
 * side, rotated by -17 and +17 degrees (rounded to 1/16 unit), and its height span.
 * No shooter's centre (the floor's patches are 16 units on a side) lies under a block. */
typedef struct {
    int16_t x[4], z[4];
    int16_t y0, y1;
} block_t;

static const block_t blocks[] = {
    {{18, 107, 398, 309}, {-69, 222, 133, -158}, -W, -W + 19 * 16},     /* short */
    {{-309, -398, -107, -18}, {-254, 37, 126, -165}, -W, -W + 38 * 16}, /* tall */
};

static const rad_rgb_t materials[4] = {
    {Q16(73, 100), Q16(73, 100), Q16(73, 100)},
    {Q16(63, 100), Q16(65, 1000), Q16(5, 100)},
    {Q16(14, 100), Q16(45, 100), Q16(9, 100)},
    {Q16(78, 100), Q16(78, 100), Q16(78, 100)},
};
static const rad_rgb_t light_emission = {Q16(16, 1), Q16(12, 1), Q16(6, 1)};
#if PROFILE == 3
static const rad_rgb_t sun_irradiance = {Q16(3, 1), Q16(5, 2), Q16(2, 1)};
#endif

static rad_vec3_t point(int32_t x, int32_t y, int32_t z)
{
    rad_vec3_t p;
    p.x = rad_real_from_q16(x * 4096);
    p.y = rad_real_from_q16(y * 4096);
    p.z = rad_real_from_q16(z * 4096);
    return p;
}

static rad_rgb_t colour(const rad_rgb_t *q)
{
    rad_rgb_t c;
    c.r = rad_real_from_q16(q->r);
    c.g = rad_real_from_q16(q->g);
    c.b = rad_real_from_q16(q->b);
    return c;
}

static int add_quad(rad_scene_t *s, const rad_vec3_t *v, unsigned mat)
{
    rad_rgb_t rho = colour(&materials[mat]), e = colour(&light_emission);
    return rad_add_polygon(s, v, 4, &rho, mat == LIGHT ? &e : 0);
}

/* Prepares the scene at hemi-cube resolution RES; returns 0 or a RAD_ERR_*. */
static int build_scene(rad_scene_t *s, uint16_t res, uint16_t band_rows)
{
    rad_pools_t pools;
    /* Designated: every field not named (coarse shots among them) is 0, its default. */
    rad_config_t cfg = {.res = 0};
    unsigned i, k;
    int rc;

    pools.surfaces = surfaces;
    pools.max_surfaces = N_SURFACES;
    pools.patches = patches;
    pools.max_patches = N_PATCHES;
    pools.elements = elements;
    pools.max_elements = N_ELEMENTS;
    pools.vertices = vertices;
    pools.max_vertices = N_VERTICES;
    pools.work = work;
    pools.work_bytes = sizeof work;
    cfg.max_element = rad_real_from_q16(MAX_ELEMENT);
    cfg.max_patch = rad_real_from_q16(MAX_PATCH);
    cfg.res = res;
    cfg.band_rows = band_rows;
    cfg.flags = 0;
    rc = rad_init(s, &pools, &cfg);
    if (rc < 0) return rc;

    for (i = 0; i < sizeof walls / sizeof walls[0]; i++) {
        rad_vec3_t v[4];
        if (SUN && (i == 1 || walls[i].mat == LIGHT)) continue; /* open to the sun */
        for (k = 0; k < 4; k++) v[k] = point(walls[i].v[k][0], walls[i].v[k][1], walls[i].v[k][2]);
        rc = add_quad(s, v, walls[i].mat);
        if (rc < 0) return rc;
    }
    for (i = 0; i < sizeof blocks / sizeof blocks[0]; i++) {
        const block_t *b = &blocks[i];
        rad_vec3_t v[4];
        for (k = 0; k < 4; k++) v[k] = point(b->x[k], b->y1, b->z[k]);
        rc = add_quad(s, v, WHITE); /* top */
        if (rc < 0) return rc;
        for (k = 0; k < 4; k++) {
            unsigned n = (k + 1u) & 3u;
            v[0] = point(b->x[k], b->y0, b->z[k]);
            v[1] = point(b->x[n], b->y0, b->z[n]);
            v[2] = point(b->x[n], b->y1, b->z[n]);
            v[3] = point(b->x[k], b->y1, b->z[k]);
            rc = add_quad(s, v, WHITE);
            if (rc < 0) return rc;
        }
    }
#if SUN
    {
        rad_light_t sun = {0};
        sun.type = RAD_LIGHT_SUN;
        sun.direction = point(-5, -16, -7); /* down, and into the box from its front */
        sun.intensity = colour(&sun_irradiance);
        rc = rad_use_lights(s, lights, 1);
        if (rc == 0) rc = rad_add_light(s, &sun);
        if (rc < 0) return rc;
    }
#endif
    return 0;
}

/* ---- results -------------------------------------------------------------------- */

static uint32_t bits32(rad_real_t r)
{
#if RAD_FLOAT
    union {
        float f;
        uint32_t u;
    } c;
    c.f = r;
    return c.u;
#else
    return (uint32_t)r;
#endif
}

/* FNV-1a 64 over every element's radiosity r, g, b as little-endian int32 bytes. */
static uint64_t checksum(rad_scene_t *s)
{
    uint64_t h = 0xcbf29ce484222325u;
    uint32_t e;
    for (e = 0; e < s->n_elements; e++) {
        rad_rgb_t b;
        uint32_t w[3];
        unsigned c, k;
        rad_element_radiosity(s, e, 0, &b);
        w[0] = bits32(b.r);
        w[1] = bits32(b.g);
        w[2] = bits32(b.b);
        for (c = 0; c < 3; c++)
            for (k = 0; k < 4; k++) {
                h ^= (w[c] >> (8 * k)) & 0xFFu;
                h *= 0x100000001b3u;
            }
    }
    return h;
}

/* The unshot fraction in Q16.16 in both builds. */
static int64_t unshot_q16(rad_scene_t *s)
{
#if RAD_FLOAT
    float f = rad_unshot_fraction(s) * 65536.0f + 0.5f;
    return f > 0.0f ? (int64_t)f : 0;
#else
    return rad_unshot_fraction(s);
#endif
}

static int now(uint64_t *n)
{
    return port_instructions(n);
}

#if PORT_BENCH
#ifndef PORT_BENCH_FF
#define PORT_BENCH_FF 1
#endif
#if PORT_BENCH_FF
static rad_ff_t ff_row[N_ELEMENTS];

/* The patch rad_shoot() picks first: the most unshot power (the light). */
static uint32_t first_shooter(const rad_scene_t *s)
{
    uint32_t p, best = 0;
    rad_energy_t most = 0;
    for (p = 0; p < s->n_patches; p++) {
        const rad_patch_t *pt = &s->pools.patches[p];
        rad_energy_t u = pt->unshot[0] + pt->unshot[1] + pt->unshot[2];
        if (u > most) {
            most = u;
            best = p;
        }
    }
    return best;
}
#endif

/* Instructions of the first shot (the light) at resolution RES, and of one hemi-cube
 * from the same patch alone (rad_form_factors: clear, render, accumulate; no
 * distribution of power). */
static void bench_shot(uint16_t res)
{
    uint64_t t0, t1;
    int rc = build_scene(&scene, res, PORT_BAND_ROWS);
    port_puts("bench_res ");
    put_u64(res);
    if (rc == RAD_ERR_WORK) {
        port_puts(" skipped work_buffer_too_small\n");
        return;
    }
    if (rc < 0) fail("build", rc);
#if PORT_BENCH_FF
    uint64_t h0, h1;
    now(&h0);
    rc = rad_form_factors(&scene, first_shooter(&scene), ff_row);
    now(&h1);
    if (rc < 0) fail("form factors", rc);
#endif
    now(&t0);
    rc = rad_shoot(&scene, 1, 0);
    now(&t1);
    if (rc != 1) fail("shoot", rc);
    port_puts(" band ");
    put_u64(scene.band_rows);
    port_puts(" shot_instructions ");
    put_u64(t1 - t0);
#if PORT_BENCH_FF
    port_puts(" hemicube_instructions ");
    put_u64(h1 - h0);
#endif
    port_puts("\n");
}
#endif

int main(void)
{
    uint64_t t0 = 0, t1 = 0, t2 = 0;
    uint32_t st, stack;
    int rc, shots, counter;

    port_puts("target ");
    port_puts(port_target());
    port_puts("\nprofile " PROFILE_NAME "\n");
    line_u("float", RAD_FLOAT);
    line_u("res", RES);

#if PORT_BENCH
    bench_shot(16);
    bench_shot(32);
    bench_shot(64);
#endif

    counter = now(&t0);
    rc = build_scene(&scene, RES, PORT_BAND_ROWS);
    if (rc < 0) {
        line_u("elements_so_far", scene.n_elements);
        line_u("patches_so_far", scene.n_patches);
        line_u("vertices_so_far", scene.n_vertices);
        fail("build", rc);
    }
    now(&t1);
    shots = rad_shoot(&scene, MAX_SHOTS, rad_real_from_q16(TOL));
    now(&t2);
    if (shots < 0) fail("shoot", shots);

    line_u("band", scene.band_rows);
    line_u("surfaces", scene.n_surfaces);
    line_u("elements", scene.n_elements);
    line_u("patches", scene.n_patches);
    line_u("vertices", scene.n_vertices);
    line_u("shots", (uint64_t)shots);
    port_puts("unshot ");
    put_i64(unshot_q16(&scene));
    port_puts("\n");
    line_u("saturations", scene.stats.saturations);
    port_puts("checksum ");
    put_hex64(checksum(&scene));
    port_puts("\n");
    if (counter) {
        line_u("setup_instructions", t1 - t0);
        line_u("instructions", t2 - t1);
    }
    line_u("pools", sizeof surfaces + sizeof patches + sizeof elements + sizeof vertices);
    line_u("work", sizeof work);
    if (port_static_bytes(&st)) line_u("static", st);
    rc = port_stack_used(&stack);
    if (rc < 0) {
        port_puts("error stack: the whole stack region was used (overflow?)\n");
        port_exit(1);
    }
    if (rc) {
        line_u("stack", stack);
        if (port_static_bytes(&st)) line_u("ram", (uint64_t)st + stack);
    }
    port_puts("done\n");
    port_exit(0);
}
