/* SPDX-License-Identifier: MIT */
/* bench_bake — rad_bench's gathers and bakes: culled against plain gathers in grids of
 * rooms (--cull), lightmap baking on one thread and two, the lightmap's gather
 * resolution against res 256 (--gather-res) and a level of Sponza's class (--level).
 * See bench.h.
 */
/* getloadavg is a BSD and Linux call, beyond POSIX. */
#define _DEFAULT_SOURCE
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include <pthread.h>

#include "bake/lightmap.h"
#include "bench/bench.h"
#include "bench/level.h"
#include "host/clock.h"
#include "host/defaults.h"
#include "rad/rad.h"

/* ---- culled gathers (rad_cull_build, rad_gather_cull) ------------------------------ */

/* Face F of the box [LO, HI] (bench_add_box's numbering and facing) alone. */
static void box_face(sc_poly *p, int *n, const double lo[3], const double hi[3], int inward, int f,
                     const double rho[3])
{
    sc_poly six[6];
    int m = 0;
    bench_add_box(six, &m, lo, hi, inward, -1, rho);
    p[*n] = six[f];
    p[*n].tag = *n;
    (*n)++;
}

/* A grid of SIDE x SIDE rooms 4.8 x 3 x 4.8 on a 5-unit pitch, walls facing in, each
 * with a ceiling lamp and four cabinets, and doorways 1 wide and 2 high between
 * neighbours along x, near one end of the wall or the other by the room's column, so
 * that no two line up: 27 to 31 polygons a room. Returns them (count in N), or NULL. */
static sc_poly *gen_rooms(int side, int *n)
{
    static const double white[3] = {0.7, 0.7, 0.68}, wood[3] = {0.5, 0.35, 0.2},
                        lamp[3] = {12, 12, 11};
    sc_poly *p = calloc((size_t)side * side * 40, sizeof *p);
    int i, j, k, w, f;
    if (!p) return NULL;
    *n = 0;
    for (i = 0; i < side; i++)
        for (j = 0; j < side; j++) {
            double x0 = 5.0 * i + 0.1, z0 = 5.0 * j + 0.1, x1 = x0 + 4.8, z1 = z0 + 4.8;
            double lo[3] = {x0, 0, z0}, hi[3] = {x1, 3, z1};
            for (f = 2; f < 6; f++)
                box_face(p, n, lo, hi, 1, f, white); /* floor, ceiling, walls along x */
            for (w = 0; w < 2;
                 w++) { /* the walls at x0 and x1, each with its doorway inside the grid */
                int door = w ? i < side - 1 : i > 0;
                double dz =
                    (i + w) % 2 ? 0.6 : 3.2; /* the doorway of the wall between i and i + 1 */
                double seg[3][4] = {
                    {z0, z0 + dz, 0, 3}, {z0 + dz + 1, z1, 0, 3}, {z0 + dz, z0 + dz + 1, 2, 3}};
                if (!door) seg[0][1] = z1;
                for (k = 0; k < (door ? 3 : 1); k++) {
                    double a[3] = {x0, seg[k][2], seg[k][0]}, b[3] = {x1, seg[k][3], seg[k][1]};
                    box_face(p, n, a, b, 1, w, white);
                }
            }
            for (k = 0; k < 4; k++) { /* cabinets in the corners, open below */
                double a[3] = {x0 + (k % 2 ? 3.6 : 0.3), 0, z0 + (k / 2 ? 3.8 : 0.3)}, b[3];
                b[0] = a[0] + 0.9;
                b[1] = 0.6 + 0.3 * k;
                b[2] = a[2] + 0.7;
                bench_add_box(p, n, a, b, 0, 2, wood);
            }
            {
                double v[4][3] = {{x0 + 2, 2.99, z0 + 2},
                                  {x0 + 2.8, 2.99, z0 + 2},
                                  {x0 + 2.8, 2.99, z0 + 2.8},
                                  {x0 + 2, 2.99, z0 + 2.8}};
                bench_add_quad(p, n, (const double(*)[3])v, white, lamp);
            }
        }
    return p;
}

/* Microseconds per gather of G (res 32, as rad_cli's lightmaps) at points on the floors
 * and walls of random rooms of the grid of SIDE: as many as fit in about SECS seconds
 * (at least 8, at most MAX); their number into N. */
static double gather_us(sc_gatherer *g, int side, double secs, int max, int *n)
{
    unsigned long seed = 12345;
    double t0 = host_now(), t = 0;
    int k;
    for (k = 0; k < max && (k < 8 || t < secs); k++) {
        double p[3], nrm[3] = {0, 1, 0}, rgb[3];
        int room, i, j;
        seed = seed * 6364136223846793005ul + 1442695040888963407ul;
        room = (int)((seed >> 33) % (unsigned long)(side * side));
        i = room / side;
        j = room % side;
        p[0] = 5.0 * i + 0.6 + ((seed >> 20) % 1000) * 0.0038;
        p[1] = 0.01;
        p[2] = 5.0 * j + 0.6 + ((seed >> 8) % 1000) * 0.0038;
        if (k % 3 == 2) { /* on the wall along x at z0, facing in */
            p[1] = 0.5 + ((seed >> 40) % 100) * 0.02;
            p[2] = 5.0 * j + 0.11;
            nrm[1] = 0;
            nrm[2] = 1;
        }
        if (sc_gather(g, p, nrm, 0, rgb) < 0) {
            fprintf(stderr, "rad_bench: a gather in the rooms failed\n");
            exit(1);
        }
        t = host_now() - t0;
    }
    *n = k;
    return 1e6 * t / k;
}

/* Culled against plain gathers on grids of rooms from 1 to 44 x 44 (27 to 59,840
 * polygons), fixed build, one core: the hierarchy's build time and each gather's. */
void bench_report_cull(report_t *rp)
{
    static const int sides[] = {1, 2, 4, 8, 16, 32, 44};
    const int ns = (int)(sizeof sides / sizeof *sides);
    double us[2][8], first[2] = {0, 0};
    int k, surf0 = 0, surf = 0;
    bench_out(rp, "\nCulled gathers (rad_cull_build, rad_gather_cull): a grid of rooms with "
                  "doorways (27 to 31 "
                  "polygons a room), one shot, then gathers at res 32 on floors and walls of "
                  "random rooms, drawing every surface "
                  "against drawing through the hierarchy (the same values, bit for bit), fixed "
                  "build, one core:\n\n"
                  "| rooms | surfaces | elements | gatherer and hierarchy ms | us per gather, all "
                  "drawn | us per gather, culled "
                  "| culled speed-up |\n| ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for (k = 0; k < ns; k++) {
        int n, m[2], c;
        char err[256];
        sc_opts o = {0};
        sc_stats st;
        sc_poly *p = gen_rooms(sides[k], &n);
        sc_solver *s;
        sc_gatherer *g;
        double t0, build;
        if (!p) exit(1);
        o.max_element = 2.5;
        o.max_patch = 5;
        o.res = 32;
        fprintf(stderr, "rad_bench: culled gathers, %d rooms ...\n", sides[k] * sides[k]);
        if (!(s = sc_create(p, n, &o, NULL, NULL, err, sizeof err)) ||
            sc_solve(s, 1, 0, NULL, NULL) < 0) {
            fprintf(stderr, "rad_bench: rooms: %s\n", err);
            exit(1);
        }
        sc_get_stats(s, &st);
        t0 = host_now(); /* a new gatherer, its hierarchy built as it is first used */
        if (!(g = sc_gatherer_new(s, 32, 0)) || sc_gatherer_cull(g, 1) < 0) exit(1);
        build = 1000 * (host_now() - t0);
        sc_gatherer_cull(g, 0);
        us[0][k] = gather_us(g, sides[k], 0.3, 2000, &m[0]);
        sc_gatherer_cull(g, 1);
        us[1][k] = gather_us(g, sides[k], 0.3, 2000, &m[1]);
        for (c = 0; c < 2; c++)
            if (k == 0) first[c] = us[c][k];
        if (k == 0) surf0 = st.surfaces;
        surf = st.surfaces;
        bench_out(rp, "| %d | %d | %d | %.1f | %.0f | %.0f | %.2f |\n", sides[k] * sides[k],
                  st.surfaces, st.elements, build, us[0][k], us[1][k], us[0][k] / us[1][k]);
        sc_gatherer_free(g);
        sc_destroy(s);
        free(p);
    }
    bench_out(rp,
              "\nFrom %d to %d surfaces (%.0f times as many) a gather drawing every surface grew "
              "%.1f times, a "
              "culled one %.1f times.\n",
              surf0, surf, (double)surf / surf0, us[0][ns - 1] / first[0],
              us[1][ns - 1] / first[1]);
    bench_report_cull_shots(rp);
}

/* A hash of S's solution: every element's radiosity and patch's unshot power as the
 * core holds them (the same bits or not). */
static unsigned long long solution_hash(sc_solver *s)
{
    const rad_scene_t *c = sc_core(s);
    unsigned long long h = 14695981039346656037ull;
    uint32_t k;
    size_t i;
    for (k = 0; k < c->n_elements; k++)
        for (i = 0; i < sizeof(rad_rgb_t); i++)
            h = (h ^ ((const unsigned char *)&c->pools.elements[k].radiosity)[i]) *
                1099511628211ull;
    for (k = 0; k < c->n_patches; k++)
        for (i = 0; i < sizeof c->pools.patches[k].unshot; i++)
            h = (h ^ ((const unsigned char *)c->pools.patches[k].unshot)[i]) * 1099511628211ull;
    return h;
}

#define CULL_SHOTS 2000 /* timed, after the lights' shots (or one patch's) */

/* One scene's shots drawing every surface (ON 0) or through the hierarchy: the
 * processor seconds of CULL_SHOTS shots at rad_cli's hemi-cube defaults, one thread,
 * after the lights' shots; the solution's hash into *HASH. */
static double shots_secs(const sc_poly *p, int n, const sc_light *lights, int nl, int on,
                         unsigned long long *hash, sc_stats *st)
{
    sc_opts o = {0};
    char err[256];
    sc_solver *s;
    double t0, t;
    o.max_element = lights ? 0.0 : 2.5;
    o.max_patch = lights ? 0.0 : 5;
    o.res = DEF_RES;
    o.coarse = DEF_COARSE;
    o.coarse_res = DEF_COARSE_FLOOR(DEF_RES);
    o.lights = lights;
    o.nlights = nl;
    if (!(s = sc_create(p, n, &o, NULL, NULL, err, sizeof err)) ||
        sc_solve(s, nl ? nl : 1, 0, NULL, NULL) < 0) {
        fprintf(stderr, "rad_bench: culled shots: %s\n", err);
        exit(1);
    }
    sc_shoot_cull(s, on);
    t0 = bench_thread_cpu();
    sc_solve(s, CULL_SHOTS, 0, NULL, NULL);
    t = bench_thread_cpu() - t0;
    *hash = solution_hash(s);
    sc_get_stats(s, st);
    sc_destroy(s);
    return t;
}

/* Shots drawing every surface against shots through the hierarchy (rad_shoot_cull,
 * which draws all for a while after a cube that tested more nodes than a third of the
 * surfaces), on grids of rooms and the generated level, one core. */
void bench_report_cull_shots(report_t *rp)
{
    static const int sides[] = {4, 16, 44};
    int k;
    bench_out(rp,
              "\nCulled shots (rad_shoot_cull): %d shots from the same start (after the "
              "lights' shots, or one patch's), drawing every surface against through the "
              "hierarchy, rad_cli's hemi-cube defaults (res %d, coarse shots), fixed build, "
              "one core, processor seconds; the same solution when the hashes of every "
              "element's radiosity and patch's unshot power agree:\n\n"
              "| scene | surfaces | elements | ms per shot, all drawn | ms per shot, "
              "culled | culled speed-up | same bits |\n"
              "| --- | ---: | ---: | ---: | ---: | ---: | --- |\n",
              CULL_SHOTS, DEF_RES);
    for (k = 0; k <= (int)(sizeof sides / sizeof *sides); k++) {
        sc_light lights[LEVEL_LIGHTS];
        unsigned long long h[2];
        sc_stats st;
        double t[2];
        char name[64];
        int n, c, level = k == (int)(sizeof sides / sizeof *sides);
        sc_poly *p = level ? level_atrium(&n, lights) : gen_rooms(sides[k], &n);
        if (!p) exit(1);
        if (level)
            snprintf(name, sizeof name, "generated level (rad_bench --level)");
        else
            snprintf(name, sizeof name, "%d rooms", sides[k] * sides[k]);
        fprintf(stderr, "rad_bench: culled shots, %s ...\n", name);
        for (c = 0; c < 2; c++)
            t[c] = shots_secs(p, n, level ? lights : NULL, level ? LEVEL_LIGHTS : 0, c, &h[c], &st);
        bench_out(rp, "| %s | %d | %d | %.3f | %.3f | %.2f | %s |\n", name, st.surfaces,
                  st.elements, 1e3 * t[0] / CULL_SHOTS, 1e3 * t[1] / CULL_SHOTS, t[0] / t[1],
                  h[0] == h[1] ? "yes" : "NO");
        free(p);
    }
}

/* ---- lightmap baking ---------------------------------------------------------- */

/* A lightmap bake's worker: the marked texels of rows Y % STEP == FIRST through a
 * gatherer of its own; its gathers counted and its thread's processor time. */
typedef struct {
    lm_atlas *a;
    sc_gatherer *g;
    int first, step;
    long gathers;
    double cpu;
} lm_work;

static int lm_count(void *ctx, const double p[3], const double n[3], double rgb[3])
{
    lm_work *w = ctx;
    w->gathers++;
    return sc_gather(w->g, p, n, SC_AMBIENT | SC_SOFT, rgb);
}

static void *lm_worker(void *arg)
{
    lm_work *w = arg;
    double t = bench_thread_cpu();
    if (lm_gather_rows(w->a, w->first, w->step, lm_count, w) != 0) exit(1);
    w->cpu += bench_thread_cpu() - t;
    return NULL;
}

/* The marked texels of the rows Y % STEP in FIRST[0..NT-1] of A gathered at RES on NT
 * threads at once (one per set), pass by pass (lm_plan) when PLAN; their gathers into
 * *N, the wall time returned, the processor time of the first thread a gather (its
 * gathers alone) into *CPU0. */
static double lm_rows(sc_solver *s, lm_atlas *a, int res, int step, const int *first, int nt,
                      int plan, long *n, double *cpu0)
{
    lm_work w[2];
    pthread_t th;
    double t0;
    int k;
    for (k = 0; k < nt; k++) {
        w[k].a = a;
        w[k].first = first[k];
        w[k].step = step;
        w[k].gathers = 0;
        w[k].cpu = 0.0;
        if (!(w[k].g = sc_gatherer_new(s, res, 0))) exit(1);
    }
    t0 = host_now();
    while (!plan || lm_plan(a) > 0) {
        if (nt > 1 && pthread_create(&th, NULL, lm_worker, &w[1]) != 0) exit(1);
        lm_worker(&w[0]);
        if (nt > 1) pthread_join(th, NULL);
        if (!plan) break;
    }
    t0 = host_now() - t0;
    *n = 0;
    for (k = 0; k < nt; k++) {
        if (nt > 1)
            fprintf(stderr, "rad_bench: thread %d: %ld gathers, %.2f processor s\n", k,
                    w[k].gathers, w[k].cpu);
        *n += w[k].gathers;
        sc_gatherer_free(w[k].g);
    }
    *cpu0 = w[0].cpu / (w[0].gathers ? w[0].gathers : 1);
    return t0;
}

/* A laid out for SC at tolerance TOL, its first pass planned; its covered texels. */
static long lm_layout(const bscene *sc, double tol, lm_atlas *a)
{
    lm_opts lo = {512, 0, 0, tol, 0};
    char err[512];
    long covered = 0;
    int x, y;
    if (lm_build(a, sc->polys, sc->n, &lo, err, sizeof err) != 0) {
        fprintf(stderr, "rad_bench: %s\n", err);
        exit(1);
    }
    for (y = 0; y < a->size; y++)
        for (x = 0; x < a->size; x++) {
            double p[3];
            covered += lm_texel_point(a, x, y, p);
        }
    return covered;
}

/* CornellBox-Original (SC, NULL when absent) baked into 512 x 512 texels: the whole
 * adaptive bake (the default tolerance and gather resolution) on one thread and on two,
 * then per gather resolution the time of a gather over a subset of rows (every STEP-th
 * of the every-texel bake: it would take minutes at 64), on one thread and on two (the
 * same rows split in two sets). */
void bench_report_lightmap(report_t *rp, const bscene *sc, const char *shared)
{
    static const int res[3] = {16, 32, 64}, steps[3] = {4, 8, 32};
    lm_atlas a;
    sc_opts o;
    sc_solver *s;
    long covered, n1, n2;
    double load = -1, cpu, cpu2, t1, t2;
    int i, one[1] = {0}, two[2] = {0, 1};
    bench_out(rp,
              "\nLightmap baking (tools/bake/lightmap.c, `--lightmap`): CornellBox-Original at 512 "
              "x 512 texels, "
              "solved as above (fixed build, to 0.001), a gather `sc_gather` with the ambient "
              "term. The whole bake at "
              "the defaults (gather resolution %d, `--lightmap-tol` %g: the adaptive passes), once "
              "on one thread and "
              "once on two (each pass's rows in two sets), wall time of the gathers' passes (the "
              "planning between them "
              "included, not the solve nor the layout):\n\n",
              DEF_GATHER_RES, LM_TOL);
    if (!sc) {
        bench_out(rp, "skipped: %s not found.\n", shared);
        return;
    }
    o = bench_scene_opts(sc);
    s = bench_fixed_solver(sc, sc->polys, &o);
    sc_solve(s, 1000000, 0.001, NULL, NULL);
    fprintf(stderr, "rad_bench: lightmap, the whole adaptive bake ...\n");
    covered = lm_layout(sc, LM_TOL, &a);
    t1 = lm_rows(s, &a, DEF_GATHER_RES, 1, one, 1, 1, &n1, &cpu);
    lm_free(&a);
    lm_layout(sc, LM_TOL, &a);
    t2 = lm_rows(s, &a, DEF_GATHER_RES, 2, two, 2, 1, &n2, &cpu2);
    if (getloadavg(&load, 1) != 1) load = -1;
    bench_out(rp,
              "| charts | texels covered | gathers | of the covered | us per gather | s, 1 thread "
              "| s, 2 threads | "
              "speed-up | load average |\n| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: "
              "| ---: |\n"
              "| %d | %ld | %ld | %.1f%% | %.1f | %.2f | %.2f | %.2f | %.2f |\n\n",
              a.ncharts, covered, n1, 100.0 * n1 / covered, 1e6 * cpu, t1, t2, t1 / t2, load);
    lm_free(&a);
    bench_out(rp, "Each gather resolution over the rows 0 and 1 mod 2 n of the every-texel bake "
                  "(`--lightmap-tol 0`: a sample of "
                  "the texels), once on one thread and once on two (a set each); us "
                  "per gather is the "
                  "processor time of one thread over its gathers, the every-texel bake's estimate "
                  "that times the covered "
                  "texels:\n\n| gather res | rows | gathers | us per gather | texels/s, 1 thread | "
                  "texels/s, 2 threads | "
                  "speed-up | every-texel bake s, 1 thread (estimate) | load average |\n"
                  "| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for (i = 0; i < 3; i++) {
        /* rows 0 and 1 mod 2 steps: one set after the other, then a set to each thread
         * (neighbouring rows cost alike: the threads' shares balance) */
        int sets[2] = {0, 1};
        long m;
        double c1;
        fprintf(stderr, "rad_bench: lightmap at gather resolution %d ...\n", res[i]);
        lm_layout(sc, 0.0, &a);
        lm_plan(&a);
        t1 = lm_rows(s, &a, res[i], 2 * steps[i], sets, 1, 0, &n1, &cpu);
        t1 += lm_rows(s, &a, res[i], 2 * steps[i], sets + 1, 1, 0, &m, &c1);
        cpu = (cpu * n1 + c1 * m) / (n1 + m);
        n1 += m;
        lm_free(&a);
        lm_layout(sc, 0.0, &a);
        lm_plan(&a);
        t2 = lm_rows(s, &a, res[i], 2 * steps[i], sets, 2, 0, &n2, &cpu2);
        lm_free(&a);
        if (getloadavg(&load, 1) != 1) load = -1;
        bench_out(rp, "| %d | 1 in %d | %ld | %.1f | %.0f | %.0f | %.2f | %.1f | %.2f |\n", res[i],
                  steps[i], n1, 1e6 * cpu, n1 / t1, n2 / t2, (n2 / t2) / (n1 / t1), cpu * covered,
                  load);
    }
    sc_destroy(s);
}

/* ---- rad_bench --gather-res: the lightmap's gather resolution against res 256 ------ */

#define GR_SIZE  128 /* the atlas's texels a side */
#define GR_EVERY 3   /* the texels compared: those with (x + y) % GR_EVERY == 0 */

/* A room 6 x 3 x 4 with a cornice (0.2 x 0.2, 0.2 below the ceiling) and a shelf
 * (at 1.2, 0.15 deep) along its walls, a 1 x 1 lamp in the ceiling's middle. */
static sc_poly *gen_cornice_room(int *n)
{
    static const double white[3] = {0.75, 0.74, 0.72}, lamp[3] = {12, 11, 9};
    sc_poly *p = calloc(64, sizeof *p);
    double lo[3] = {-3, 0, -2}, hi[3] = {3, 3, 2},
           v[4][3] = {{-0.5, 2.99, -0.5}, {0.5, 2.99, -0.5}, {0.5, 2.99, 0.5}, {-0.5, 2.99, 0.5}};
    int k;
    if (!p) return NULL;
    *n = 0;
    bench_add_box(p, n, lo, hi, 1, -1, white);
    for (k = 0; k < 4; k++) { /* along the walls x = -3, x = 3, z = -2, z = 2 */
        double a[3], b[3], c[3], d[3];
        int ax = k < 2 ? 0 : 2, hs = k % 2, o = 2 - ax;
        a[ax] = hs ? hi[ax] - 0.2 : lo[ax];
        b[ax] = hs ? hi[ax] : lo[ax] + 0.2;
        a[o] = lo[o];
        b[o] = hi[o];
        a[1] = 2.6;
        b[1] = 2.8;
        bench_add_box(p, n, a, b, 0, -1, white);
        c[ax] = hs ? hi[ax] - 0.15 : lo[ax];
        d[ax] = hs ? hi[ax] : lo[ax] + 0.15;
        c[o] = lo[o] + 0.5;
        d[o] = hi[o] - 0.5;
        c[1] = 1.2;
        d[1] = 1.26;
        bench_add_box(p, n, c, d, 0, -1, white);
    }
    bench_add_quad(p, n, (const double(*)[3])v, white, lamp);
    return p;
}

/* The light at the compared covered texels of A gathered at RES into E (3 a texel, in
 * order); the processor seconds a gather. */
static double gr_gather(sc_solver *s, const lm_atlas *a, int res, double *e)
{
    sc_gatherer *g = sc_gatherer_new(s, res, 0);
    double t, p[3];
    long m = 0;
    int x, y;
    if (!g) exit(1);
    t = bench_thread_cpu();
    for (y = 0; y < a->size; y++)
        for (x = 0; x < a->size; x++) {
            size_t at = (size_t)y * a->size + (size_t)x;
            if ((x + y) % GR_EVERY || !lm_texel_point(a, x, y, p)) continue;
            if (sc_gather(g, p, &a->planes[4 * (size_t)a->poly[at]], 1, &e[3 * m++]) != 0) exit(1);
        }
    t = (bench_thread_cpu() - t) / (m ? m : 1);
    sc_gatherer_free(g);
    return t;
}

/* One scene's row per resolution: rms and max of the texels' channel-sum differences
 * from res 256, over the mean channel sum (so a dark texel counts for what it shows),
 * and the processor time a gather. */
static void gr_scene(report_t *rp, const char *name, const sc_poly *polys, int n)
{
    static const int res[4] = {16, 32, 48, 64};
    sc_opts o = {0};
    lm_opts lo = {GR_SIZE, 0.0, 0, 0.0, 0.0};
    lm_atlas a;
    char err[512];
    sc_solver *s;
    double *ref, *e, mean = 0.0, tref;
    long m = 0, i;
    int x, y, r;
    o.res = 128;
    if (!(s = sc_create(polys, n, &o, NULL, NULL, err, sizeof err)) ||
        lm_build(&a, polys, n, &lo, err, sizeof err)) {
        fprintf(stderr, "rad_bench: %s: %s\n", name, err);
        exit(1);
    }
    sc_solve(s, 1000000, 0.001, NULL, NULL);
    for (y = 0; y < a.size; y++)
        for (x = 0; x < a.size; x++) {
            double p[3];
            m += (x + y) % GR_EVERY == 0 && lm_texel_point(&a, x, y, p);
        }
    ref = malloc(3 * (size_t)m * sizeof *ref);
    e = malloc(3 * (size_t)m * sizeof *e);
    if (!ref || !e) exit(1);
    fprintf(stderr, "rad_bench: gather resolution: %s, %ld texels at res 256 ...\n", name, m);
    tref = gr_gather(s, &a, 256, ref);
    for (i = 0; i < 3 * m; i++) mean += ref[i] / m;
    for (r = 0; r < 4; r++) {
        double t = gr_gather(s, &a, res[r], e), ss = 0.0, mx = 0.0, load = -1;
        for (i = 0; i < m; i++) {
            double d = fabs(e[3 * i] + e[3 * i + 1] + e[3 * i + 2] - ref[3 * i] - ref[3 * i + 1] -
                            ref[3 * i + 2]);
            ss += d * d;
            mx = fmax(mx, d);
        }
        if (getloadavg(&load, 1) != 1) load = -1;
        bench_out(rp, "| %s | %d | %ld | %.2f%% | %.1f%% | %.1f | %.1f | %.2f |\n", name, res[r], m,
                  100 * sqrt(ss / m) / mean, 100 * mx / mean, 1e6 * t, 1e6 * tref, load);
    }
    free(ref);
    free(e);
    lm_free(&a);
    sc_destroy(s);
}

/* rad_bench --gather-res [SHARED]: the table to stdout. */
int bench_gather_res(int argc, char **argv)
{
    static report_t rp;
    const char *shared = argc > 2 ? argv[2] : "../shared/scenes/CornellBox-Original.obj";
    sc_poly *p;
    int n;
    bench_out(
        &rp,
        "Lightmap texels gathered at resolution 16 to 64 against 256 (`rad_bench --gather-res`): a "
        "%d x %d "
        "atlas, every covered texel's sample with (x + y) %% %d == 0, the solve to 0.001 at res "
        "128. rms and max of "
        "the difference in a texel's channel sum, over the mean channel sum of the texels "
        "compared; processor "
        "microseconds a gather (at 256 in its own column).\n\n"
        "| scene | gather res | texels | rms | max | us per gather | us at 256 | load average |\n"
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n",
        GR_SIZE, GR_SIZE, GR_EVERY);
    if (!(p = gen_cornice_room(&n))) return 1;
    gr_scene(&rp, "room with cornices and shelves", p, n);
    free(p);
    if ((p = bench_load_obj(shared, &n, NULL)) != NULL) {
        gr_scene(&rp, "CornellBox-Original", p, n);
        free(p);
    } else {
        bench_out(&rp, "\n%s: not found, skipped.\n", shared);
    }
    fputs(rp.md, stdout);
    return 0;
}

/* ---- rad_bench --level: a level of Sponza's class ---------------------------------- */

#define LEVEL_SIZE   1024 /* the lightmap's texels a side */
/* The texels-per-second sample: the rows 0 and 1 mod LEVEL_ROWS of a LEVEL_BIG atlas
 * gathered at every texel, on one thread and on two (a thread each: neighbouring rows
 * cost alike, where a gather costs 10.8 ms on some rows of the level and 18.2 ms on
 * others), about 12,000 gathers. */
#define LEVEL_BIG    2048
#define LEVEL_ROWS   256
#define LEVEL_ROUNDS 3 /* of the sample, one thread then two: a run swings by 1.5x */

/* A run's progress on stderr every 10 s: the solve's shots and unshot fraction. */
typedef struct {
    double t0, last;
} level_prog;

static int level_shot(void *ctx, int shots, double unshot)
{
    level_prog *p = ctx;
    double t = host_now();
    if (t - p->last >= 10.0) {
        fprintf(stderr, "rad_bench: level: %d shots, unshot %.4f, %.0f s\n", shots, unshot,
                t - p->t0);
        p->last = t;
    }
    return 0;
}

/* The bake's gathers on this thread, stopping once STOP seconds of them have passed
 * (0: never): their count and progress every 10 s. */
typedef struct {
    sc_solver *s;
    sc_gatherer *g;
    lm_atlas *a;
    long gathers;
    double t0, last, stop;
    int skies; /* SC_SKIES: the skies per texel too (sc_direct) */
} level_bake;

static int level_gather(void *ctx, const double p[3], const double n[3], double rgb[3])
{
    level_bake *b = ctx;
    double t;
    if ((++b->gathers & 63) == 0 && (t = host_now()) - b->last >= 10.0) {
        fprintf(stderr, "rad_bench: level: lightmap, %ld gathers, %.0f s\n", b->gathers, t - b->t0);
        b->last = t;
        if (b->stop > 0 && t - b->t0 >= b->stop) return 1;
    }
    return sc_gather(b->g, p, n, SC_AMBIENT | SC_SOFT | b->skies, rgb);
}

/* The sharp lights at a texel, as rad_cli adds them (tools/cli/bake.c). */
static int level_direct(void *ctx, const double p[3], const double n[3], double rgb[3])
{
    level_bake *b = ctx;
    return sc_direct(b->s, p, n, b->skies, lm_visible, b->a, rgb);
}

/* The rows checked against every texel's gather: one in LEVEL_CHECK, 16 rows of the
 * 1024 x 1024 atlas. */
#define LEVEL_CHECK 64

/* The baked texels of A's rows 0 mod LEVEL_CHECK against each gathered (with its
 * lights' direct light per texel, as B's bake adds it) as the bake would at every
 * texel: the rms, 90th percentile and largest difference of a texel's channel sum over
 * the mean channel sum of the checked texels, into ERR[0], ERR[1], ERR[2]; B's
 * gatherer. */
static void level_check(level_bake *b, lm_atlas *a, double err[3])
{
    double sum = 0.0, sq = 0.0,
           *d = malloc((size_t)a->size * (a->size / LEVEL_CHECK + 1) * sizeof *d);
    long n = 0;
    int x, y, k;
    if (!d) exit(1);
    for (y = 0; y < a->size; y += LEVEL_CHECK)
        for (x = 0; x < a->size; x++) {
            size_t i = (size_t)y * a->size + (size_t)x;
            const double *nrm;
            double p[3], g[3], l[3], want = 0.0, got = 0.0;
            if (!lm_texel_point(a, x, y, p)) continue;
            nrm = &a->planes[4 * (size_t)a->poly[i]];
            if (sc_gather(b->g, p, nrm, SC_AMBIENT | SC_SOFT | b->skies, g) < 0 ||
                level_direct(b, p, nrm, l) < 0)
                exit(1);
            for (k = 0; k < 3; k++) {
                want += g[k] + l[k];
                got += a->rgb[3 * i + k];
            }
            sum += want;
            sq += (got - want) * (got - want);
            d[n++] = fabs(got - want);
        }
    sum = n && sum > 0.0 ? sum / n : 1.0;
    bench_sort(d, n);
    err[0] = n ? sqrt(sq / n) / sum : 0.0;
    err[1] = n ? d[n * 9 / 10] / sum : 0.0;
    err[2] = n ? d[n - 1] / sum : 0.0;
    free(d);
}

/* The bake's error as a table cell: rms / 90th percentile / max. */
static void err_cell(char *s, size_t n, const double err[3])
{
    if (err[0] >= 0.0)
        snprintf(s, n, "%.2f%% / %.2f%% / %.1f%%", 100 * err[0], 100 * err[1], 100 * err[2]);
    else
        snprintf(s, n, "-");
}

/* POLYS (N) laid out into A at O, or the bench ends naming scene NAME. */
static void level_layout(lm_atlas *a, const sc_poly *polys, int n, const lm_opts *o,
                         const char *name)
{
    char err[512];
    if (lm_build(a, polys, n, o, err, sizeof err) != 0) {
        fprintf(stderr, "rad_bench: %s: %s\n", name, err);
        exit(1);
    }
}

/* The lightmap painted from S's elements (lm_paint; the texels on elements not known
 * gathered, every light's direct light per texel) into a fresh layout of POLYS at O,
 * checked as the gathered bake is: a row of PP's table. */
static void level_paint(report_t *pp, const char *name, sc_solver *s, const sc_poly *polys, int n,
                        const lm_opts *o)
{
    level_bake b;
    lm_atlas a;
    sc_soft_element *el;
    char errs[64];
    double c0, cpu, e[3];
    long ne, left;
    memset(&b, 0, sizeof b);
    level_layout(&a, polys, n, o, name);
    if (!(b.g = sc_gatherer_new(s, DEF_GATHER_RES, 0))) exit(1);
    b.s = s;
    b.a = &a;
    b.skies = SC_SKIES;
    b.t0 = b.last = host_now();
    fprintf(stderr, "rad_bench: level: the lightmap painted from the elements ...\n");
    c0 = bench_thread_cpu();
    if (!(el = sc_soft_elements(s, 1, &ne)) || (left = lm_paint(&a, el, ne)) < 0 ||
        lm_bake(&a, level_gather, level_direct, &b) != 0)
        exit(1);
    cpu = bench_thread_cpu() - c0;
    free(el);
    fprintf(stderr, "rad_bench: level: painted in %.1f s; against every texel of 1 row in %d ...\n",
            cpu, LEVEL_CHECK);
    level_check(&b, &a, e);
    err_cell(errs, sizeof errs, e);
    bench_out(pp, "| %s | %ld | %ld | %.1f | %s |\n", name, ne, left, cpu, errs);
    sc_gatherer_free(b.g);
    lm_free(&a);
}

/* One level (POLYS, N of them, lit by LIGHTS) measured and reported as a table row:
 * the solve to 0.01 at rad_cli's hemi-cube defaults, the core's memory and the
 * process's peak, the 1024 x 1024 atlas's charts and layout time, and its bake (the
 * adaptive default, gather resolution DEF_GATHER_RES, one thread), cut short after STOP
 * seconds when STOP > 0. Times are this thread's processor seconds (the machine may
 * be shared) and wall seconds. */
static void level_row(report_t *rp, report_t *pp, const char *name, const sc_poly *polys, int n,
                      const sc_light *lights, int nl, double stop)
{
    sc_opts o = {0};
    sc_stats st;
    lm_opts lo = {LEVEL_SIZE, 0.0, 0, LM_TOL, 0.0};
    level_prog pg;
    level_bake b;
    lm_atlas a;
    char err[512];
    struct rusage ru;
    sc_solver *s;
    double c0, w0, solve_cpu, solve_wall, lay_cpu, bake_cpu, bake_wall, load = -1, tps[2],
                                                                        bake_err[3];
    double rate[2][LEVEL_ROUNDS], ratio[LEVEL_ROUNDS];
    long covered, tn[2];
    int done, x, y, charts, i;
    char errs[64];
    o.res = DEF_RES;
    o.coarse = DEF_COARSE;
    o.coarse_res = DEF_COARSE_FLOOR(DEF_RES);
    o.lights = lights;
    o.nlights = nl;
    fprintf(stderr, "rad_bench: level: %s, %d polygons: solving to 0.01 ...\n", name, n);
    c0 = bench_thread_cpu();
    w0 = pg.t0 = pg.last = host_now();
    if (!(s = sc_create(polys, n, &o, NULL, NULL, err, sizeof err))) {
        fprintf(stderr, "rad_bench: %s: %s\n", name, err);
        exit(1);
    }
    if (sc_solve_lights(s, SC_SKIES) < 0) exit(1); /* for the painted bake */
    sc_solve(s, 10000000, 0.01, level_shot, &pg);
    solve_cpu = bench_thread_cpu() - c0;
    solve_wall = host_now() - w0;
    sc_get_stats(s, &st);
    fprintf(stderr, "rad_bench: level: solved in %.1f s; the lightmap's layout ...\n", solve_wall);
    c0 = bench_thread_cpu();
    level_layout(&a, polys, n, &lo, name);
    lay_cpu = bench_thread_cpu() - c0;
    for (covered = 0, y = 0; y < a.size; y++)
        for (x = 0; x < a.size; x++) {
            double p[3];
            covered += lm_texel_point(&a, x, y, p);
        }
    level_paint(pp, name, s, polys, n, &lo);
    memset(&b, 0, sizeof b);
    if (!(b.g = sc_gatherer_new(s, DEF_GATHER_RES, 0))) exit(1);
    b.s = s;
    b.a = &a;
    c0 = bench_thread_cpu();
    b.t0 = b.last = host_now();
    b.stop = stop;
    done = lm_bake(&a, level_gather, level_direct, &b) == 0;
    bake_cpu = bench_thread_cpu() - c0;
    bake_wall = host_now() - b.t0;
    charts = a.ncharts;
    bake_err[0] = bake_err[1] = bake_err[2] = -1.0;
    if (done) {
        fprintf(stderr, "rad_bench: level: the bake against every texel of 1 row in %d ...\n",
                LEVEL_CHECK);
        level_check(&b, &a, bake_err);
    }
    lm_free(&a);
    lo.size = LEVEL_BIG;
    lo.tol = 0.0;
    fprintf(stderr, "rad_bench: level: texels per second at %d x %d, 1 and 2 threads ...\n",
            LEVEL_BIG, LEVEL_BIG);
    for (i = 0; i < LEVEL_ROUNDS * 2; i++) { /* rows 0 and 1 mod LEVEL_ROWS: one after the
                                                 other, then at once */
        int sets[2] = {0, 1}, k;
        double cpu, wall = 0.0;
        long got;
        x = i % 2;
        level_layout(&a, polys, n, &lo, name);
        lm_plan(&a);
        tn[x] = 0;
        for (k = 0; k < (x ? 1 : 2); k++) {
            wall += lm_rows(s, &a, DEF_GATHER_RES, LEVEL_ROWS, sets + k, x + 1, 0, &got, &cpu);
            tn[x] += got;
        }
        rate[x][i / 2] = tn[x] / wall;
        if (x) ratio[i / 2] = rate[1][i / 2] / rate[0][i / 2];
        lm_free(&a);
    }
    for (x = 0; x < 2; x++) tps[x] = bench_median(rate[x], LEVEL_ROUNDS);
    err_cell(errs, sizeof errs, bake_err);
    getrusage(RUSAGE_SELF, &ru);
    if (getloadavg(&load, 1) != 1) load = -1;
    bench_out(rp,
              "| %s | %d | %d | %d | %d | %.2f (%.2f) | %.1f | %.1f | %d | %.2f | %ld | %ld | "
              "%s%.1f (%.1f) | %s | %.0f "
              "| %.1f | %ld | %.1f | %.1f | %.2f | %.2f |\n",
              name, n, st.elements, st.patches, st.shots, solve_cpu, solve_wall,
              (st.pool_bytes + st.work_bytes) / 1048576.0, ru.ru_maxrss / 1024.0, charts, lay_cpu,
              covered, b.gathers, done ? "" : "stopped: ", bake_cpu, bake_wall, errs,
              1e6 * bake_cpu / (b.gathers ? b.gathers : 1),
              1e6 * bake_cpu / (b.gathers ? b.gathers : 1) * covered / 1e6, tn[0], tps[0], tps[1],
              bench_median(ratio, LEVEL_ROUNDS), load);
    sc_gatherer_free(b.g);
    sc_destroy(s);
}

/* rad_bench --level [STOP] [SCENE]: the generated atrium (tools/bench/level.h) and, when
 * SCENE (default ../shared/scenes/sponza.obj) is there, that scene under the same sun
 * and sky; each bake cut short after STOP seconds when STOP > 0. The two tables to stdout. */
int bench_level(int argc, char **argv)
{
    static report_t rp;
    sc_light lights[LEVEL_LIGHTS];
    obj_scene keep;
    const char *scene = "../shared/scenes/sponza.obj";
    double stop = 0.0;
    sc_poly *p;
    static report_t pp;
    int n, i;
    for (i = 2; i < argc; i++) {
        char *end;
        double v = strtod(argv[i], &end);
        if (*end == '\0' && end != argv[i] && v >= 0)
            stop = v;
        else
            scene = argv[i];
    }
    if (!(p = level_atrium(&n, lights))) return 1;
    bench_out(
        &rp,
        "A level of Sponza's class (`rad_bench --level`): the generated two-storey atrium "
        "(tools/bench/level.h) under a sun and a %d-direction sky, solved to an unshot "
        "fraction of 0.01 at rad_cli's "
        "hemi-cube defaults (res %d, coarse shots), then baked into a %d x %d lightmap at "
        "the defaults (adaptive, "
        "tolerance %g, gather resolution %d) on one thread. Times are processor seconds of "
        "the one thread (wall "
        "seconds in brackets: the machine may be shared); memory is the core's pools and "
        "work buffer, and the "
        "process's peak resident size; the every-texel estimate is the covered texels times "
        "the time per gather "
        "(an upper bound of the adaptive bake). Texels per second: the rows 0 and 1 mod %d "
        "of a %d x %d atlas gathered at every texel, on one thread and on two (a thread "
        "each), wall time, medians of %d rounds (one thread, then two), the speed-up the "
        "median of the rounds' ratios.\n\n"
        "| scene | polygons | elements | patches | shots | solve s | core MB | peak MB | "
        "charts | layout s | "
        "texels covered | gathers | bake s | rms / p90 / max vs every texel | us per gather | "
        "every-texel s (estimate) | "
        "sample texels | texels/s, 1 thread | texels/s, 2 threads | speed-up | load "
        "average |\n"
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: "
        "| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: "
        "| ---: |\n",
        lights[1].dirs, DEF_RES, LEVEL_SIZE, LEVEL_SIZE, LM_TOL, DEF_GATHER_RES, LEVEL_ROWS,
        LEVEL_BIG, LEVEL_BIG, LEVEL_ROUNDS);
    bench_out(&pp,
              "The same solve's %d x %d lightmap painted from its elements (`rad_cli "
              "--lightmap-soft elements`: lm_paint; the texels on elements whose light is not "
              "known gathered, every light's direct light a ray per texel), one thread, "
              "processor seconds, checked as above (rms / 90th percentile / max).\n\n"
              "| scene | elements | texels gathered | bake s | rms / p90 / max vs every texel |\n"
              "| --- | ---: | ---: | ---: | ---: |\n",
              LEVEL_SIZE, LEVEL_SIZE);
    level_row(&rp, &pp, "generated atrium", p, n, lights, LEVEL_LIGHTS, stop);
    free(p);
    if ((p = bench_load_obj(scene, &n, &keep)) != NULL) {
        level_row(&rp, &pp, scene, p, n, lights, LEVEL_LIGHTS, stop);
        free(p);
        obj_free(&keep);
    } else {
        bench_out(&rp, "\n%s: not found, skipped.\n", scene);
    }
    fputs(rp.md, stdout);
    fputs("\n", stdout);
    fputs(pp.md, stdout);
    return 0;
}
