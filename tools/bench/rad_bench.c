/* SPDX-License-Identifier: MIT */
/* rad_bench — speed, memory and accuracy of the fixed core beside its float twin, on
 * the bundled Cornell box at three densities, the original Cornell box (when
 * ../shared/scenes is there) and a generated scene of 20,000+ elements, and rad_cli
 * against a peer (RenderPark's rpkCpp, built outside the repository) as whole
 * processes. Prints a Markdown report, writes it into docs/bench.md between the bench
 * markers (never into README.md), and draws the convergence plots with the project's
 * PNG writer.
 *
 * Times are wall-clock medians of several runs in this one process, two variants
 * solved shot by shot in turn; compare the ratios measured here, not absolute times
 * across machines.
 */
/* wait4 (each child's own peak memory) is a BSD and Linux call, beyond POSIX. */
#define _DEFAULT_SOURCE
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <fcntl.h>
#include <time.h>
#include <unistd.h>

#include <pthread.h>

#include "bake/lightmap.h"
#include "formats/image.h"
#include "formats/obj.h"
#include "formats/texture.h"
#include "host/clock.h"
#include "host/defaults.h"
#include "host/polys.h"
#include "host/parallel.h"
#include "bench/level.h"
#include "bench/plot.h"
#include "rad/rad.h"
#include "reference/reference.h"
#include "host/scene.h"

#define MAXPTS 200000

typedef struct {
    const char *name;
    sc_poly *polys;
    int n;
    double max_element;   /* 0: rad_cli's default */
    double max_patch;     /* 0: the glue's default (1/8 of the extent) */
    int res;
    int runs;
    int big;              /* one of the two largest: not in the overshooting and parallel tables */
    const obj_scene *obj; /* the OBJ scene of POLYS, or NULL (generated) */
} bscene;

/* One solve's record. */
typedef struct {
    int elements, patches, shots[3];   /* shots to unshot 0.1, 0.01, 0.001 */
    int all_shots;
    double t[3], total, mesh;           /* seconds to each, whole solve, meshing */
    double pix_per_s;
    size_t bytes;
    int npts;
    double *xs, *xt, *y;                /* convergence: shots, seconds, unshot */
} brun;

/* A run's progress: its own time so far (SPENT before the current call, which began at
 * T0) and shots (BASE before it). */
typedef struct {
    brun *r;
    double spent, t0;
    int base;
} prog_t;

static int on_shot(void *ctx, int shots, double unshot)
{
    prog_t *p = ctx;
    brun *r = p->r;
    double t = p->spent + host_now() - p->t0;
    int k;
    static const double lim[3] = {0.1, 0.01, 0.001};
    shots += p->base;
    /* The fixed build reports Q16.16 fractions: 0.001 is 66 / 65536 there. */
    for (k = 0; k < 3; k++)
        if (r->shots[k] == 0 && unshot <= lim[k] + 1.0 / 65536) { r->shots[k] = shots; r->t[k] = t; }
    if (r->npts < MAXPTS) {
        r->xs[r->npts] = shots; r->xt[r->npts] = t; r->y[r->npts] = unshot;
        r->npts++;
    }
    return 0;
}

/* The two builds behind one interface. */
typedef struct {
    void *(*create)(const sc_poly *, int, const sc_opts *, char *, size_t);
    int (*solve)(void *, int, double, sc_progress_fn, void *);
    void (*stats)(void *, sc_stats *);
    void (*destroy)(void *);
} build_t;

static void *fx_create(const sc_poly *p, int n, const sc_opts *o, char *e, size_t l) { return sc_create(p, n, o, NULL, NULL, e, l); }
static int fx_solve(void *s, int m, double t, sc_progress_fn f, void *c) { return sc_solve(s, m, t, f, c); }
static void fx_stats(void *s, sc_stats *st) { sc_get_stats(s, st); }
static void fx_destroy(void *s) { sc_destroy(s); }
static void *fl_create(const sc_poly *p, int n, const sc_opts *o, char *e, size_t l) { return scf_create(p, n, o, NULL, NULL, e, l); }
static int fl_solve(void *s, int m, double t, sc_progress_fn f, void *c) { return scf_solve(s, m, t, f, c); }
static void fl_stats(void *s, sc_stats *st) { scf_get_stats(s, st); }
static void fl_destroy(void *s) { scf_destroy(s); }
static const build_t builds[2] = {{fx_create, fx_solve, fx_stats, fx_destroy}, {fl_create, fl_solve, fl_stats, fl_destroy}};

static void run_alloc(brun *r)
{
    memset(r, 0, sizeof *r);
    r->xs = malloc(MAXPTS * sizeof *r->xs);
    r->xt = malloc(MAXPTS * sizeof *r->xt);
    r->y = malloc(MAXPTS * sizeof *r->y);
    if (!r->xs || !r->xt || !r->y) { fprintf(stderr, "rad_bench: out of memory\n"); exit(1); }
}

static void run_free(brun *r) { free(r->xs); free(r->xt); free(r->y); }

static int cmp_d(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_d);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* The scene's mesh and resolution as solver options. */
static sc_opts scene_opts(const bscene *sc)
{
    sc_opts o = {0};
    o.max_element = sc->max_element;
    o.max_patch = sc->max_patch;
    o.res = sc->res;
    return o;
}

/* A fixed-build solver of POLYS (the scene's, or a variant of them) with O; exits on
 * failure. */
static sc_solver *fixed_solver(const bscene *sc, const sc_poly *polys, const sc_opts *o)
{
    char err[256];
    sc_solver *s = sc_create(polys, sc->n, o, NULL, NULL, err, sizeof err);
    if (!s) { fprintf(stderr, "rad_bench: %s: %s\n", sc->name, err); exit(1); }
    return s;
}

/* The solver's counts into R, whose total time is set. */
static void run_stats(brun *r, const sc_stats *st)
{
    r->elements = st->elements;
    r->patches = st->patches;
    r->all_shots = st->shots;
    r->pix_per_s = (double)st->raster_pixels / r->total;
    r->bytes = st->pool_bytes + st->work_bytes;
}

/* Two variants (a build and options each) solved side by side RUNS times, shot by shot
 * (one shot of the first, one of the second, ...): each shot's time is its variant's
 * own, and both see the same machine, whose speed on a shared host drifts within
 * seconds by more than the two builds differ (whole runs in turn could put either
 * ahead). Each keeps its median run (by total time) in OUT, with its times to each
 * fraction the medians over the runs; the others are freed. */
static void interleaved(const bscene *sc, const build_t *const *b, const sc_opts *o, int runs, brun *out)
{
    brun r[2][5];
    double tot[2][5], ti[3][5];
    int i, j, k;
    for (i = 0; i < runs; i++) {
        void *s[2];
        prog_t pg[2];
        int live = 3;
        for (k = 0; k < 2; k++) {
            char err[256];
            double t0 = host_now();
            run_alloc(&r[k][i]);
            s[k] = b[k]->create(sc->polys, sc->n, &o[k], err, sizeof err);
            if (!s[k]) { fprintf(stderr, "rad_bench: %s: %s\n", sc->name, err); exit(1); }
            r[k][i].mesh = host_now() - t0;
            pg[k].r = &r[k][i];
            pg[k].spent = 0;
            pg[k].base = 0;
        }
        while (live)
            for (k = 0; k < 2; k++) {
                int shot;
                if (!(live & (1 << k))) continue;
                pg[k].t0 = host_now();
                shot = b[k]->solve(s[k], 1, 0.001, on_shot, &pg[k]);
                pg[k].spent += host_now() - pg[k].t0;
                pg[k].base += shot;
                if (!shot || pg[k].base >= 1000000) live &= ~(1 << k);
            }
        for (k = 0; k < 2; k++) {
            sc_stats st;
            brun *x = &r[k][i];
            b[k]->stats(s[k], &st);
            x->total = pg[k].spent;
            run_stats(x, &st);
            b[k]->destroy(s[k]);
            tot[k][i] = x->total;
        }
    }
    for (k = 0; k < 2; k++) {
        double m = median(tot[k], runs);
        int best = 0;
        for (j = 0; j < 3; j++)
            for (i = 0; i < runs; i++) ti[j][i] = r[k][i].t[j];
        for (i = 0; i < runs; i++) if (r[k][i].total == m) best = i;
        for (i = 0; i < runs; i++) if (i != best) run_free(&r[k][i]);
        out[k] = r[k][best];
        for (j = 0; j < 3; j++) out[k].t[j] = median(ti[j], runs);
    }
}

/* One fixed-build solve of SC to 0.001, once (for the largest scene), into R. */
static void solo(const bscene *sc, brun *r)
{
    sc_opts o = scene_opts(sc);
    prog_t pg;
    sc_stats st;
    double t0 = host_now();
    sc_solver *s = fixed_solver(sc, sc->polys, &o);
    run_alloc(r);
    r->mesh = host_now() - t0;
    pg.r = r;
    pg.spent = 0;
    pg.base = 0;
    pg.t0 = host_now();
    sc_solve(s, 1000000, 0.001, on_shot, &pg);
    r->total = host_now() - pg.t0;
    sc_get_stats(s, &st);
    run_stats(r, &st);
    sc_destroy(s);
}

/* Both builds at the scene's settings. */
static void bench_pair(const bscene *sc, brun *out_fx, brun *out_fl)
{
    const build_t *b[2] = {&builds[0], &builds[1]};
    sc_opts o[2];
    brun out[2];
    o[0] = o[1] = scene_opts(sc);
    interleaved(sc, b, o, sc->runs, out);
    *out_fx = out[0];
    *out_fl = out[1];
}

/* Fixed against float per element, solved to 0.001 (see ref_twin_diff). */
static void twin_accuracy(const bscene *sc, double *mx, double *rms)
{
    sc_opts o = scene_opts(sc);
    char err[256];
    sc_solver *a = fixed_solver(sc, sc->polys, &o);
    scf_solver *b = scf_create(sc->polys, sc->n, &o, NULL, NULL, err, sizeof err);
    if (!b) { fprintf(stderr, "rad_bench: %s\n", err); exit(1); }
    sc_solve(a, 1000000, 0.001, NULL, NULL);
    scf_solve(b, 1000000, 0.001, NULL, NULL);
    ref_twin_diff(a, b, mx, rms);
    sc_destroy(a);
    scf_destroy(b);
}

/* ---- patch size: shots against accuracy ------------------------------------------- */

static int poly_emits(const sc_poly *p) { return p->emit[0] + p->emit[1] + p->emit[2] > 0; }

/* Area-weighted mean radiosity (r + g + b, with the ambient term) of every OBJ face
 * (polygon tag < NTAG) into M. */
static void face_means(sc_solver *s, int ntag, double *m)
{
    sc_stats st;
    double *a = calloc((size_t)ntag, sizeof *a);
    int e, t;
    if (!a) exit(1);
    sc_get_stats(s, &st);
    for (t = 0; t < ntag; t++) m[t] = 0;
    for (e = 0; e < st.elements; e++) {
        double x[3], area = sc_element_area(s, e);
        t = sc_element_tag(s, e);
        sc_element_rgb(s, e, 1, x);
        m[t] += area * (x[0] + x[1] + x[2]);
        a[t] += area;
    }
    for (t = 0; t < ntag; t++) m[t] = a[t] > 0 ? m[t] / a[t] : 0;
    free(a);
}

/* B against the reference A (every element its own patch), face by face: the meshes
 * differ, so elements cannot be paired, but each OBJ face's mean radiosity can. Over
 * the faces that do not emit and are above 1% of the brightest of them: the largest
 * and rms relative differences. */
static void face_diff(const bscene *sc, sc_solver *a, sc_solver *b, double *worst, double *rms)
{
    int ntag = 0, i, t, n = 0;
    double *ma, *mb, top = 0, s2 = 0;
    char *emits;
    for (i = 0; i < sc->n; i++) if (sc->polys[i].tag + 1 > ntag) ntag = sc->polys[i].tag + 1;
    ma = malloc((size_t)ntag * sizeof *ma);
    mb = malloc((size_t)ntag * sizeof *mb);
    emits = calloc((size_t)ntag, 1);
    if (!ma || !mb || !emits) exit(1);
    for (i = 0; i < sc->n; i++)
        if (poly_emits(&sc->polys[i])) emits[sc->polys[i].tag] = 1;
    face_means(a, ntag, ma);
    face_means(b, ntag, mb);
    for (t = 0; t < ntag; t++) if (!emits[t] && ma[t] > top) top = ma[t];
    *worst = 0;
    for (t = 0; t < ntag; t++) {
        double d;
        if (emits[t] || ma[t] < 0.01 * top) continue;
        d = fabs(mb[t] / ma[t] - 1);
        if (d > *worst) *worst = d;
        s2 += d * d;
        n++;
    }
    *rms = n ? sqrt(s2 / n) : 0;
    free(ma); free(mb); free(emits);
}

typedef struct {
    double max_patch;
    int patches, elements, shots;
    double secs, worst, rms;
} tradeoff_t;

/* The scene SC solved (fixed build) to 0.01 and then 0.001 with patch edge MAX_PATCH
 * (the element edge: every element shoots for itself); the solver is returned. */
static sc_solver *solve_patches(const bscene *sc, double max_patch, tradeoff_t *t)
{
    sc_opts o = scene_opts(sc);
    sc_solver *s;
    sc_stats st;
    double t0;
    o.max_patch = max_patch;
    s = fixed_solver(sc, sc->polys, &o);
    t0 = host_now();
    t->shots = sc_solve(s, 1000000, 0.01, NULL, NULL);
    t->secs = host_now() - t0;
    sc_solve(s, 1000000, 0.001, NULL, NULL);
    sc_get_stats(s, &st);
    t->max_patch = max_patch;
    t->patches = st.patches;
    t->elements = st.elements;
    return s;
}

/* ---- stored form factors: relighting against a fresh solve ------------------------- */

/* Every emitting material of the scene's OBJ gets emission EMIT. */
static void set_emitters(const bscene *sc, sc_solver *s, const double *emit)
{
    char err[256];
    int m;
    for (m = 0; m < sc->obj->nmaterials; m++) {
        const double *ke = sc->obj->materials[m].ke;
        polys_material_match mm;
        if (!(ke[0] + ke[1] + ke[2] > 0)) continue;
        mm.sc = sc->obj;
        mm.material = m;
        if (sc_set_surfaces(s, polys_match_material, &mm, NULL, emit, err, sizeof err) < 0) {
            fprintf(stderr, "rad_bench: %s\n", err);
            exit(1);
        }
    }
}

typedef struct {
    int patches, elements, rows, sweeps, relight_shots, fresh_shots;
    unsigned long entries;
    size_t bytes, matrix_bytes;
    double t_rows, t_relight, t_fresh, t_gs, t_rows_shoot;
} relight_t;

static void relight_bench(const bscene *sc, relight_t *r)
{
    static const double blue[3] = {4, 8, 18};
    sc_opts o = scene_opts(sc);
    char err[256];
    sc_solver *s = fixed_solver(sc, sc->polys, &o), *f;
    sc_rows_stats rs;
    sc_stats st;
    sc_poly *q;
    double t0;
    int i;
    t0 = host_now();
    if (sc_rows_compute(s, NULL, NULL, err, sizeof err) < 0) { fprintf(stderr, "rad_bench: %s\n", err); exit(1); }
    r->t_rows = host_now() - t0;
    sc_get_rows_stats(s, &rs);
    r->rows = rs.rows; r->entries = rs.entries; r->bytes = rs.bytes;
    t0 = host_now();
    sc_rows_solve(s, 1000000, 0.001, NULL, NULL);
    r->t_rows_shoot = host_now() - t0;
    t0 = host_now();
    r->sweeps = sc_rows_gauss_seidel(s, 1000, 0.001, err, sizeof err);
    r->t_gs = host_now() - t0;
    sc_get_rows_stats(s, &rs);
    r->matrix_bytes = rs.matrix_bytes;
    /* A new light colour: emissions changed, visibility kept. */
    t0 = host_now();
    set_emitters(sc, s, blue);
    r->relight_shots = sc_rows_solve(s, 1000000, 0.001, NULL, NULL);
    r->t_relight = host_now() - t0;
    sc_get_stats(s, &st);
    r->patches = st.patches; r->elements = st.elements;
    /* The same new light from scratch: meshing and a hemi-cube per shot. */
    q = malloc((size_t)sc->n * sizeof *q);
    if (!q) exit(1);
    memcpy(q, sc->polys, (size_t)sc->n * sizeof *q);
    for (i = 0; i < sc->n; i++)
        if (poly_emits(&q[i])) memcpy(q[i].emit, blue, sizeof blue);
    t0 = host_now();
    f = fixed_solver(sc, q, &o);
    r->fresh_shots = sc_solve(f, 1000000, 0.001, NULL, NULL);
    r->t_fresh = host_now() - t0;
    sc_destroy(f);
    sc_destroy(s);
    free(q);
}

/* ---- scenes -------------------------------------------------------------------- */

/* The polygons of the OBJ file PATH, its scene kept in KEEP (or freed: NULL). */
static sc_poly *load_obj(const char *path, int *n, obj_scene *keep)
{
    obj_scene sc;
    char err[512];
    sc_poly *p;
    if (obj_load(path, &sc, NULL, NULL, err, sizeof err) < 0) return NULL;
    p = polys_from_obj(&sc, n, NULL, NULL);
    if (keep) *keep = sc;
    else obj_free(&sc);
    return p;
}

static void add_quad(sc_poly *p, int *n, const double v[4][3], const double rho[3], const double em[3])
{
    sc_poly *q = &p[(*n)++];
    memset(q, 0, sizeof *q);
    memcpy(q->v, v, sizeof q->v);
    q->n = 4;
    memcpy(q->rho, rho, sizeof q->rho);
    memcpy(q->emit, em, sizeof q->emit);
    q->tag = *n - 1;
}

/* Faces of the box [lo, hi], inward for a room or outward for furniture, skipping
 * face SKIP (2 * axis + high side; -1 for none). Corners go (lo,lo), (hi,lo), (hi,hi),
 * (lo,hi) in the next two axes, which faces +axis; reversed where that is wrong. */
static void add_box(sc_poly *p, int *n, const double lo[3], const double hi[3], int inward, int skip,
                    const double rho[3])
{
    static const double zero[3] = {0, 0, 0};
    int f;
    for (f = 0; f < 6; f++) {
        int ax = f / 2, hiside = f % 2, u = (ax + 1) % 3, w = (ax + 2) % 3, k;
        double v[4][3];
        static const int cu[4] = {0, 1, 1, 0}, cw[4] = {0, 0, 1, 1};
        if (f == skip) continue;
        for (k = 0; k < 4; k++) {
            /* Counter-clockwise seen from outside on the high side. */
            int kk = (hiside != inward) ? k : 3 - k;
            v[k][ax] = hiside ? hi[ax] : lo[ax];
            v[k][u] = cu[kk] ? hi[u] : lo[u];
            v[k][w] = cw[kk] ? hi[w] : lo[w];
        }
        add_quad(p, n, (const double(*)[3])v, rho, zero);
    }
}

/* A hall 16 x 3 x 12 with a grid of tables and cabinets and six ceiling lights. */
static sc_poly *gen_hall(int *n)
{
    static const double white[3] = {0.75, 0.74, 0.72}, wood[3] = {0.55, 0.38, 0.22},
                        blue[3] = {0.2, 0.3, 0.6}, lamp[3] = {20, 19, 16};
    sc_poly *p = calloc(400, sizeof *p);
    double lo[3] = {-8, 0, -6}, hi[3] = {8, 3, 6};
    int i, j;
    if (!p) return NULL;
    *n = 0;
    add_box(p, n, lo, hi, 1, -1, white);
    for (i = 0; i < 4; i++)
        for (j = 0; j < 3; j++) {
            double a[3] = {-6.5 + 3.6 * i, 0, -4.5 + 3.5 * j}, b[3];
            b[0] = a[0] + (j == 1 ? 0.8 : 1.6); b[1] = j == 1 ? 1.9 : 0.75; b[2] = a[2] + (j == 1 ? 0.6 : 1.0);
            add_box(p, n, a, b, 0, 2, j == 1 ? blue : wood); /* no bottom */
        }
    for (i = 0; i < 3; i++)
        for (j = 0; j < 2; j++) {
            double v[4][3] = {{-5.5 + 5 * i, 2.99, -3.5 + 6 * j}, {-4.5 + 5 * i, 2.99, -3.5 + 6 * j},
                              {-4.5 + 5 * i, 2.99, -2.5 + 6 * j}, {-5.5 + 5 * i, 2.99, -2.5 + 6 * j}};
            add_quad(p, n, (const double(*)[3])v, white, lamp);
        }
    return p;
}

/* ---- report -------------------------------------------------------------------- */

/* Plain shooting (k = 0) against overshooting (k = 1), fixed build: shots and time to
 * each fraction (median of 3, shot by shot), and the distance of the solution at 0.01
 * from one converged to 1e-5. */
typedef struct {
    brun run[2];
    double worst[2], rms[2];
} shootcmp_t;

static void overshoot_bench(const bscene *sc, shootcmp_t *c)
{
    const build_t *b[2] = {&builds[0], &builds[0]};
    sc_opts o[2];
    sc_solver *ref;
    int k;
    o[0] = o[1] = scene_opts(sc);
    o[0].no_overshoot = 1;
    interleaved(sc, b, o, 3, c->run);
    ref = fixed_solver(sc, sc->polys, &o[1]);
    sc_solve(ref, 1000000, 1e-5, NULL, NULL);
    for (k = 0; k < 2; k++) {
        sc_solver *s = fixed_solver(sc, sc->polys, &o[k]);
        sc_solve(s, 1000000, 0.01, NULL, NULL);
        ref_solution_diff(s, ref, &c->worst[k], &c->rms[k]);
        sc_destroy(s);
    }
    sc_destroy(ref);
}

static void fmt_shots(char *b, size_t n, const brun *r)
{
    snprintf(b, n, "%d / %d / %d", r->shots[0], r->shots[1], r->shots[2]);
}

/* ---- the report, section by section ------------------------------------------------ */

typedef struct {
    char md[65536];
    size_t len;
} report_t;

static void out(report_t *rp, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    rp->len += (size_t)vsnprintf(rp->md + rp->len, sizeof rp->md - rp->len, fmt, ap);
    va_end(ap);
}

/* The scenes: the bundled box at three densities, the shared CornellBox-Original if it
 * is there, the generated hall. Returns how many, or 0 (not run from the root). */
static int load_scenes(const char *shared, bscene *scenes)
{
    /* The bundled box is 0.56 m across: element edges for 535, 1,796 and 8,360
     * elements (meshing is by whole divisions of each face: the nearest to the
     * benchmark's targets of 500, 2,000 and 8,000). */
    static const double me[3] = {0.065, 0.035, 0.0165};
    static const char *nm[3] = {"Cornell box (bundled), coarse", "Cornell box (bundled), medium",
                                "Cornell box (bundled), fine"};
    static obj_scene box;
    int ns = 0, k, ncb, n;
    sc_poly *cb = load_obj("examples/cornell_box.obj", &ncb, &box), *p;
    if (!cb) { fprintf(stderr, "rad_bench: run from the repository root (examples/cornell_box.obj)\n"); return 0; }
    for (k = 0; k < 3; k++) {
        scenes[ns].name = nm[k]; scenes[ns].polys = cb; scenes[ns].n = ncb; scenes[ns].obj = &box;
        scenes[ns].max_element = me[k]; scenes[ns].res = 128; scenes[ns].runs = 3;
        scenes[ns].big = k == 2;
        ns++;
    }
    p = load_obj(shared, &n, NULL);
    if (p) {
        /* Element edge 0.08 (of about 2 across): over the 4,000 elements of the peers. */
        scenes[ns].name = "CornellBox-Original (shared)"; scenes[ns].polys = p; scenes[ns].n = n;
        scenes[ns].max_element = 0.08; scenes[ns].res = 128; scenes[ns].runs = 5;
        ns++;
    } else {
        fprintf(stderr, "rad_bench: %s not found: the peer comparison is skipped\n", shared);
    }
    p = gen_hall(&n);
    if (!p) return 0;
    scenes[ns].name = "generated hall (12 pieces of furniture, 6 lights)"; scenes[ns].polys = p;
    scenes[ns].n = n; scenes[ns].max_element = 0.175; scenes[ns].res = 128; scenes[ns].runs = 3;
    scenes[ns].big = 1;
    return ns + 1;
}

static void report_speed(report_t *rp, const bscene *scenes, int ns, const brun *fx, const brun *fl)
{
    int i, k;
    out(rp, "Solve to an unshot fraction of 0.001 at hemi-cube resolution 128, one core; times are medians of "
        "3 runs (5 for CornellBox-Original) in one process, the two builds solved side by side, one shot of each "
        "in turn, so that both see the same machine. fixed/float is the ratio of the two builds' times: below 1 "
        "the fixed build is faster.\n\n");
    out(rp, "| scene | elements | patches | build | shots to 0.1 / 0.01 / 0.001 | s to 0.01 | s to 0.001 | ms per shot "
        "| Mpixel/s | memory KB |\n| --- | ---: | ---: | --- | --- | ---: | ---: | ---: | ---: | ---: |\n");
    for (i = 0; i < ns; i++) {
        for (k = 0; k < 2; k++) {
            const brun *r = k ? &fl[i] : &fx[i];
            char sh[64];
            fmt_shots(sh, sizeof sh, r);
            out(rp, "| %s | %d | %d | %s | %s | %.3f | %.3f | %.3f | %.1f | %zu |\n", k ? "" : scenes[i].name,
                r->elements, r->patches, k ? "float" : "fixed", sh, r->t[1], r->total,
                1000 * r->total / (r->all_shots ? r->all_shots : 1), r->pix_per_s / 1e6, r->bytes / 1024);
        }
        out(rp, "| | | | fixed/float | | %.2f | %.2f | | | |\n", fx[i].t[1] / fl[i].t[1], fx[i].total / fl[i].total);
    }
}

static void report_twin(report_t *rp, const bscene *scenes, int ns, const double *amax, const double *arms)
{
    int i;
    out(rp, "\nFixed against the float twin, per element (with the ambient term), over elements above 1%% of the "
        "brightest:\n\n| scene | max relative difference | rms |\n| --- | ---: | ---: |\n");
    for (i = 0; i < ns; i++) out(rp, "| %s | %.3f%% | %.3f%% |\n", scenes[i].name, 100 * amax[i], 100 * arms[i]);
}

static void report_hemicube(report_t *rp)
{
    static const int res[4] = {32, 64, 128, 256};
    int k;
    out(rp, "\nHemi-cube form factors against Lambert's contour formula (7 unoccluded receivers: parallel, offset, "
        "perpendicular, tilted, large, grazing, triangle), fixed build:\n\n| resolution | mean error | max "
        "error |\n| ---: | ---: | ---: |\n");
    for (k = 0; k < 4; k++) {
        double sum = 0, mx = 0;
        int r;
        for (r = 0; r < REF_RECEIVERS; r++) {
            double want, got = ref_hemicube_ff(r, res[k], 0, &want), e = fabs(got / want - 1);
            sum += e;
            if (e > mx) mx = e;
        }
        out(rp, "| %d | %.3f%% | %.3f%% |\n", res[k], 100 * sum / REF_RECEIVERS, 100 * mx);
    }
}

/* ---- the peer: whole processes, alternating ------------------------------------- */

#define PEER_RUNS 9

/* Runs ARGV (stdout and stderr to /dev/null) and waits for it: its wall time in SECS,
 * and from wait4's rusage its processor time (user + system) in CPU and its own peak
 * resident memory in KB. Returns 0 when it ran and exited with status 0. */
static int run_child(char *const argv[], double *secs, double *cpu, long *kb)
{
    struct rusage ru;
    double t0 = host_now();
    int st;
    pid_t pid = fork();
    if (pid < 0) return -1;
    if (pid == 0) {
        int fd = open("/dev/null", O_WRONLY);
        if (fd >= 0) { dup2(fd, 1); dup2(fd, 2); close(fd); }
        execv(argv[0], argv);
        _exit(127);
    }
    if (wait4(pid, &st, 0, &ru) != pid) return -1;
    *secs = host_now() - t0;
    *cpu = ru.ru_utime.tv_sec + ru.ru_stime.tv_sec + 1e-6 * (ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
    *kb = ru.ru_maxrss;
    return WIFEXITED(st) && WEXITSTATUS(st) == 0 ? 0 : -1;
}

static int is_file(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

/* PATH's folder (up to its last '/', or "." ) into OUT. */
static void dir_of(const char *path, char *out, size_t n)
{
    const char *sl = strrchr(path, '/');
    if (!sl) snprintf(out, n, ".");
    else snprintf(out, n, "%.*s", (int)(sl - path), path);
}

/* The programs of the peer table: rad_cli to 0.01 and 0.001 at its defaults, rpkCpp,
 * then every shot at 128 (rad_cli's default before coarse shots), and at the bench's
 * element edge 0.08 the defaults, every shot at 128 and coarse shots from res 256. */
#define PEER_CMDS 7
#define PEER_RPK  2

/* rad_cli's defaults (host/defaults.h): the emitters' shots at res 192, the others at 96, 48
 * and 24 as the unshot fraction falls below 1, 1/8 and 1/64 (chosen on
 * CornellBox-Original: more accurate than every shot at 128, about half its time; see
 * the peer table's accuracy column). */
#define DEF_FLOOR DEF_COARSE_FLOOR(DEF_RES)

/* Each rad_cli row of the peer table as the solver's settings: its tolerance, element
 * edge (0: rad_cli's default), res, coarse fraction and floor, and its flags. */
typedef struct {
    double tol, edge;
    int res;
    double coarse;
    int coarse_res;
    const char *flags;
} peer_row_t;

static const peer_row_t peer_rows[PEER_CMDS] = {
    {0.01, 0, DEF_RES, DEF_COARSE, DEF_FLOOR, "--tol 0.01"},
    {0.001, 0, DEF_RES, DEF_COARSE, DEF_FLOOR, "--tol 0.001"},
    {0, 0, 0, 0, 0, NULL}, /* rpkCpp */
    {0.001, 0, 128, 0, 0, "--tol 0.001 --res 128 --coarse 0"},
    {0.001, 0.08, DEF_RES, DEF_COARSE, DEF_FLOOR, "--tol 0.001 --max-element 0.08"},
    {0.001, 0.08, 128, 0, 0, "--tol 0.001 --max-element 0.08 --res 128 --coarse 0"},
    {0.001, 0.08, 256, 2, DEF_COARSE_FLOOR(256), "--tol 0.001 --max-element 0.08 --res 256 --coarse 2"}};

typedef struct {
    char why[3072];                        /* empty when measured; else why not */
    double t[PEER_CMDS], ratio[PEER_CMDS]; /* medians: each program; rad/rpkCpp per round */
    double cpu[PEER_CMDS], cpu_ratio[PEER_CMDS]; /* the same in processor time */
    long kb[PEER_CMDS];                    /* peaks over the runs */
    /* per element against a res-512 solve to 1e-4 of the same mesh (peer_accuracy):
     * rms and max relative error over elements above 10% and above 1% of the brightest */
    double rms[PEER_CMDS][2], max[PEER_CMDS][2];
    int elements[PEER_CMDS];
    size_t bytes[PEER_CMDS];               /* pools and work buffer */
} peer_t;

/* The peer's scene beside it: converted from the OBJ SCENE with the shared converter
 * (SCENE's folder/../peers/obj2mgf.py) when it is missing. */
static int peer_scene(const char *scene, const char *mgf, peer_t *pr)
{
    char dir[512], conv[1024];
    double t, cpu;
    long kb;
    char *argv[] = {"/usr/bin/env", "python3", conv, "-o", (char *)mgf, "--channel", "rgb", (char *)scene, NULL};
    if (is_file(mgf)) return 0;
    dir_of(scene, dir, sizeof dir);
    snprintf(conv, sizeof conv, "%s/../peers/obj2mgf.py", dir);
    fprintf(stderr, "rad_bench: converting %s to %s ...\n", scene, mgf);
    if (!is_file(conv) || run_child(argv, &t, &cpu, &kb) < 0 || !is_file(mgf)) {
        snprintf(pr->why, sizeof pr->why, "the scene could not be converted to %s (with %s)", mgf, conv);
        return -1;
    }
    return 0;
}

/* rad_cli (beside this program) to 0.01 and 0.001 against rpkCpp's Galerkin solve,
 * whole processes in turn, PEER_RUNS rounds. The peer is in $RAD_PEER_RPK, or
 * ../peer-rpk: its build/rpk and cbo.mgf. */
static void peer_bench(const char *self, const char *scene, peer_t *pr)
{
    const char *root = getenv("RAD_PEER_RPK");
    char rpk[1024], mgf[1024], cli[1024], dir[512], png[1024];
    char *cmd[PEER_CMDS][24], words[PEER_CMDS][128];
    char *rpk_cmd[] = {rpk, "-force-onesided", "-radiance-method", "Galerkin", "-raytracing-method", "none",
                       "-iterations", "30", mgf, NULL};
    double t[PEER_CMDS][PEER_RUNS], c[PEER_CMDS][PEER_RUNS], r[PEER_CMDS][PEER_RUNS], rc[PEER_CMDS][PEER_RUNS];
    int i, k;
    memset(pr, 0, sizeof *pr);
    if (!root || !*root) root = "../peer-rpk";
    snprintf(rpk, sizeof rpk, "%s/build/rpk", root);
    snprintf(mgf, sizeof mgf, "%s/cbo.mgf", root);
    dir_of(self, dir, sizeof dir);
    snprintf(cli, sizeof cli, "%s/rad_cli", dir);
    snprintf(png, sizeof png, "%s/bench_peer.ppm", dir);
    if (!is_file(rpk) || access(rpk, X_OK) != 0) {
        snprintf(pr->why, sizeof pr->why, "rpkCpp is not built (no %s; set RAD_PEER_RPK to its folder)", rpk);
        return;
    }
    if (!is_file(cli)) { snprintf(pr->why, sizeof pr->why, "no %s", cli); return; }
    if (!is_file(scene)) { snprintf(pr->why, sizeof pr->why, "no %s", scene); return; }
    if (peer_scene(scene, mgf, pr) < 0) return;
    for (k = 0; k < PEER_CMDS; k++) {
        char *w, *save = NULL;
        int j = 2;
        if (k == PEER_RPK) {
            memcpy(cmd[k], rpk_cmd, sizeof rpk_cmd);
            continue;
        }
        cmd[k][0] = cli;
        cmd[k][1] = (char *)scene;
        snprintf(words[k], sizeof words[k], "%s --width 64 --height 64 -o", peer_rows[k].flags);
        for (w = strtok_r(words[k], " ", &save); w; w = strtok_r(NULL, " ", &save)) cmd[k][j++] = w;
        cmd[k][j++] = png;
        cmd[k][j] = NULL;
    }
    fprintf(stderr, "rad_bench: rad_cli against rpkCpp, %d rounds ...\n", PEER_RUNS);
    for (i = 0; i < PEER_RUNS; i++)
        for (k = 0; k < PEER_CMDS; k++) {
            long kb;
            if (run_child(cmd[k], &t[k][i], &c[k][i], &kb) < 0) {
                snprintf(pr->why, sizeof pr->why, "%s failed on %s", cmd[k][0], k != PEER_RPK ? scene : mgf);
                return;
            }
            if (kb > pr->kb[k]) pr->kb[k] = kb;
        }
    remove(png);
    for (i = 0; i < PEER_RUNS; i++)
        for (k = 0; k < PEER_CMDS; k++) {
            r[k][i] = t[k][i] / t[PEER_RPK][i];
            rc[k][i] = c[k][i] / c[PEER_RPK][i];
        }
    for (k = 0; k < PEER_CMDS; k++) {
        pr->t[k] = median(t[k], PEER_RUNS);
        pr->cpu[k] = median(c[k], PEER_RUNS);
        pr->ratio[k] = median(r[k], PEER_RUNS);
        pr->cpu_ratio[k] = median(rc[k], PEER_RUNS);
    }
}

/* Per element, A against the reference REF of the same mesh: the relative error of
 * r + g + b (with the ambient term) over the elements of SC's non-emitting faces above
 * FLOOR[k] of the brightest of them, rms in RMS[k] and largest in MAX[k]. */
static void element_accuracy(const bscene *sc, sc_solver *ref, sc_solver *a, const double floor[2], double *rms,
                             double *mx)
{
    sc_stats st;
    double *b, top = 0, s2[2] = {0, 0};
    int e, k, i, n[2] = {0, 0}, ntag = 0;
    char *emits;
    for (i = 0; i < sc->n; i++) if (sc->polys[i].tag + 1 > ntag) ntag = sc->polys[i].tag + 1;
    sc_get_stats(ref, &st);
    b = malloc((size_t)st.elements * sizeof *b);
    emits = calloc((size_t)ntag + 1, 1);
    if (!b || !emits) exit(1);
    for (i = 0; i < sc->n; i++) if (poly_emits(&sc->polys[i])) emits[sc->polys[i].tag] = 1;
    for (e = 0; e < st.elements; e++) {
        double x[3];
        sc_element_rgb(ref, e, 1, x);
        b[e] = x[0] + x[1] + x[2];
        if (!emits[sc_element_tag(ref, e)] && b[e] > top) top = b[e];
    }
    for (k = 0; k < 2; k++) mx[k] = 0;
    for (e = 0; e < st.elements; e++) {
        double x[3], d;
        if (emits[sc_element_tag(ref, e)]) continue;
        sc_element_rgb(a, e, 1, x);
        d = fabs((x[0] + x[1] + x[2]) / b[e] - 1);
        for (k = 0; k < 2; k++) {
            if (b[e] <= floor[k] * top) continue;
            s2[k] += d * d;
            n[k]++;
            if (d > mx[k]) mx[k] = d;
        }
    }
    for (k = 0; k < 2; k++) rms[k] = n[k] ? sqrt(s2[k] / n[k]) : 0;
    free(b);
    free(emits);
}

/* SC's solve at O to TOL (fixed build). */
static sc_solver *solved(const bscene *sc, const sc_opts *o, double tol)
{
    sc_solver *s = fixed_solver(sc, sc->polys, o);
    sc_solve(s, 1000000, tol, NULL, NULL);
    return s;
}

/* O with peer row ROW's res and coarse shots (rad_cli's defaults, or a row's flags). */
static sc_opts row_opts(sc_opts o, const peer_row_t *row)
{
    o.res = row->res;
    o.coarse = row->coarse;
    o.coarse_res = row->coarse_res;
    return o;
}

/* Each rad_cli row of the peer table solved in this process (the same core, mesh and
 * settings, so the same bits) against a solve of its mesh at res 512 to 1e-4: the
 * accuracy column. */
static void peer_accuracy(const char *scene, peer_t *pr)
{
    static const double floor[2] = {0.1, 0.01};
    static const double edge[2] = {0, 0.08}; /* rad_cli's default, the bench's */
    bscene sc;
    int m, k;
    memset(&sc, 0, sizeof sc);
    sc.polys = load_obj(scene, &sc.n, NULL);
    sc.name = scene;
    if (!sc.polys) return;
    for (m = 0; m < 2; m++) {
        sc_opts o = {0};
        sc_solver *ref;
        o.max_element = edge[m];
        o.res = 512;
        fprintf(stderr, "rad_bench: the res-512 reference (element edge %s) ...\n", m ? "0.08" : "default");
        ref = solved(&sc, &o, 1e-4);
        for (k = 0; k < PEER_CMDS; k++) {
            sc_opts v = row_opts(o, &peer_rows[k]);
            sc_solver *a;
            sc_stats st;
            if (k == PEER_RPK || peer_rows[k].edge != edge[m]) continue;
            a = solved(&sc, &v, peer_rows[k].tol);
            element_accuracy(&sc, ref, a, floor, pr->rms[k], pr->max[k]);
            sc_get_stats(a, &st);
            pr->elements[k] = st.elements;
            pr->bytes[k] = st.pool_bytes + st.work_bytes;
            sc_destroy(a);
        }
        sc_destroy(ref);
    }
    free(sc.polys);
}

static void report_peers(report_t *rp, const peer_t *p, const brun *fx)
{
    out(rp, "\nAgainst a peer on CornellBox-Original: RenderPark's hierarchical Galerkin radiosity (rpkCpp, "
        "`rpk -force-onesided -radiance-method Galerkin -raytracing-method none -iterations 30`, one core, about "
        "4,000 elements) beside `rad_cli --tol 0.01` (and 0.001) `--width 64 --height 64` (fixed build, default "
        "mesh), whole processes in turn, %d rounds: medians of wall and processor (user + system) "
        "time, the median of each round's ratio, and each program's peak resident memory over the rounds (wait4). ",
        PEER_RUNS);
    if (p->why[0]) {
        out(rp, "Not measured: %s.\n", p->why);
    } else {
        int k;
        out(rp, "The accuracy column: each rad row solved again in this process (the same bits), per element "
            "against a solve of its mesh at res 512 to an unshot fraction of 1e-4, relative error of r + g + b "
            "(with the ambient term) over the non-emitting elements above 10%% (and 1%%) of the brightest: rms / "
            "max. rad_cli's defaults: the emitters' shots at res 192, the others at 96, 48, 24 as the unshot "
            "fraction falls below 1, 1/8, 1/64 (`--res 192 --coarse 1 --coarse-res 24`); `--res 128 --coarse 0`: "
            "every shot at 128, the defaults before; `--res 256 --coarse 2`: 256, then 128, 64, 32 below 2, 1/4, "
            "1/32.\n\n"
            "| program | elements | wall s | rad/rpkCpp | processor s | rad/rpkCpp | peak memory MB | pools + "
            "work MB | accuracy >10%%: rms / max | >1%%: rms / max |\n"
            "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
        for (k = 0; k < PEER_CMDS; k++) {
            char a[32] = "", b[32] = "", n[32] = "", mb[32] = "", acc[2][48] = {"", ""}, nm[160] = "rpkCpp Galerkin";
            int j;
            if (k != PEER_RPK) {
                snprintf(nm, sizeof nm, "rad_cli %s", peer_rows[k].flags);
                snprintf(a, sizeof a, "%.2f", p->ratio[k]);
                snprintf(b, sizeof b, "%.2f", p->cpu_ratio[k]);
            }
            if (k != PEER_RPK && p->elements[k]) {
                snprintf(n, sizeof n, "%d", p->elements[k]);
                snprintf(mb, sizeof mb, "%.2f", p->bytes[k] / 1048576.0);
                for (j = 0; j < 2; j++)
                    snprintf(acc[j], sizeof acc[j], "%.2f%% / %.2f%%", 100 * p->rms[k][j], 100 * p->max[k][j]);
            }
            out(rp, "| %s | %s | %.3f | %s | %.3f | %s | %.1f | %s | %s | %s |\n", nm, n, p->t[k], a, p->cpu[k],
                b, p->kb[k] / 1024.0, mb, acc[0], acc[1]);
        }
    }
    out(rp, "\nIn this process (res 128, element edge 0.08, %d elements): %.3f s to an unshot fraction of 0.01 and "
        "%.3f s to 0.001, in %.2f MB of pools and work buffer.\n",
        fx->elements, fx->t[1], fx->total, fx->bytes / 1048576.0);
}

/* Patch size on the original Cornell box: fewer, larger shooters against accuracy. */
static void report_patches(report_t *rp, const bscene *sc)
{
    static const double mp[5] = {0.08, 0.16, 0.25, 0, 0.5}; /* 0: the default, 1/8 of the extent */
    tradeoff_t t[5];
    sc_solver *ref;
    int k;
    fprintf(stderr, "rad_bench: patch sizes ...\n");
    ref = solve_patches(sc, mp[0], &t[0]);
    t[0].worst = t[0].rms = 0;
    for (k = 1; k < 5; k++) {
        sc_solver *b = solve_patches(sc, mp[k], &t[k]);
        face_diff(sc, ref, b, &t[k].worst, &t[k].rms);
        sc_destroy(b);
    }
    sc_destroy(ref);
    out(rp, "\nPatch size on CornellBox-Original (element edge 0.08, res 128, fixed build): shooters larger than "
        "the elements they group (Cohen et al. 1986) cut the shots, at a price in accuracy: a patch shoots "
        "from its centre, so surfaces close to a large patch (the blocks on the floor) get the light of one "
        "point. Solved to 0.001 and compared with every element shooting for itself (first row); the meshes "
        "differ, so the comparison is of each non-emitting OBJ face's mean radiosity:\n\n| patch edge | "
        "patches | elements | shots to 0.01 | s to 0.01 | max face difference | rms face difference |\n"
        "| ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for (k = 0; k < 5; k++) {
        char w[32] = "reference", r[32] = "reference", e[32] = "default (1/8 of the extent)";
        if (k) {
            snprintf(w, sizeof w, "%.2f%%", 100 * t[k].worst);
            snprintf(r, sizeof r, "%.2f%%", 100 * t[k].rms);
        }
        if (t[k].max_patch > 0) snprintf(e, sizeof e, "%.2f", t[k].max_patch);
        out(rp, "| %s | %d | %d | %d | %.3f | %s | %s |\n", e, t[k].patches, t[k].elements, t[k].shots,
            t[k].secs, w, r);
    }
}

/* Overshooting against plain progressive refinement. */
static void report_overshoot(report_t *rp, const bscene *scenes, int ns)
{
    int i, k;
    out(rp, "\nOvershooting (the default; Feda & Purgathofer 1992) against plain progressive refinement (Cohen et al. "
        "1988, `--no-overshoot`), fixed build, res 128, median of 3 runs, the two shot by shot; the last two columns are the "
        "solution at 0.01 (with the ambient term) against one converged to 1e-5, per element above 1%% of the "
        "brightest:\n\n| scene | elements | shooting | shots to 0.1 / 0.01 / 0.001 | s to 0.01 | s to 0.001 | "
        "max difference at 0.01 | rms |\n| --- | ---: | --- | --- | ---: | ---: | ---: | ---: |\n");
    for (i = 0; i < ns; i++) {
        shootcmp_t c;
        if (scenes[i].big) continue; /* too long to repeat */
        fprintf(stderr, "rad_bench: overshooting on %s ...\n", scenes[i].name);
        overshoot_bench(&scenes[i], &c);
        for (k = 0; k < 2; k++) {
            char sh[64];
            fmt_shots(sh, sizeof sh, &c.run[k]);
            out(rp, "| %s | %d | %s | %s | %.3f | %.3f | %.2f%% | %.2f%% |\n", k ? "" : scenes[i].name,
                c.run[k].elements, k ? "overshooting" : "plain", sh, c.run[k].t[1], c.run[k].total,
                100 * c.worst[k], 100 * c.rms[k]);
            run_free(&c.run[k]);
        }
    }
}

/* Stored form factors (the 1985 paper's relighting) on the bundled box. */
static void report_relight(report_t *rp, const bscene *sc)
{
    relight_t rl;
    fprintf(stderr, "rad_bench: stored form factors ...\n");
    relight_bench(sc, &rl);
    out(rp, "\nStored form factors on %s (%d elements, %d patches, res 128, fixed build): every patch's row "
        "rendered once in %.3f s, %lu entries in %zu bytes (%.1f KB per patch). From the rows, no hemi-cube: "
        "progressive shooting to 0.001 %.3f s; the 1985 full-matrix Gauss-Seidel solve %d sweeps to 0.001 in "
        "%.3f s (matrix %zu KB). A new light colour, re-solved from the rows in %.3f s (%d shots) against "
        "%.3f s (%d shots) for a fresh mesh and hemi-cube solve: %.0f times faster.\n",
        sc->name, rl.elements, rl.patches, rl.t_rows, rl.entries, rl.bytes, rl.bytes / 1024.0 / rl.rows,
        rl.t_rows_shoot, rl.sweeps, rl.t_gs, rl.matrix_bytes / 1024, rl.t_relight, rl.relight_shots, rl.t_fresh,
        rl.fresh_shots, rl.t_fresh / rl.t_relight);
}

/* The generated hall meshed to over 100,000 elements, solved once (fixed build). */
static void report_large(report_t *rp)
{
    bscene sc;
    brun r;
    char sh[64];
    memset(&sc, 0, sizeof sc);
    sc.name = "generated hall, fine";
    sc.polys = gen_hall(&sc.n);
    if (!sc.polys) exit(1);
    /* Element edge 0.078: 110,646 elements (the hall's 0.175 gives 23,384). */
    sc.max_element = 0.078;
    sc.res = 128;
    fprintf(stderr, "rad_bench: %s ...\n", sc.name);
    solo(&sc, &r);
    if (r.elements < 100000)
        fprintf(stderr, "rad_bench: warning: the fine hall has %d elements, fewer than 100,000\n", r.elements);
    fmt_shots(sh, sizeof sh, &r);
    out(rp, "\nA large scene: the generated hall meshed finer, solved once (fixed build, res 128, one core); "
        "memory is the core's pools and work buffer, all it uses:\n\n| scene | elements | patches | meshing s | "
        "shots to 0.1 / 0.01 / 0.001 | s to 0.01 | s to 0.001 | ms per shot | memory MB |\n"
        "| --- | ---: | ---: | ---: | --- | ---: | ---: | ---: | ---: |\n");
    out(rp, "| %s | %d | %d | %.3f | %s | %.2f | %.2f | %.3f | %.2f |\n", sc.name, r.elements, r.patches, r.mesh, sh,
        r.t[1], r.total, 1000 * r.total / (r.all_shots ? r.all_shots : 1), r.bytes / 1048576.0);
    run_free(&r);
    free(sc.polys);
}

/* ---- culled gathers (rad_cull_build, rad_gather_cull) ------------------------------ */

/* Face F of the box [LO, HI] (add_box's numbering and facing) alone. */
static void box_face(sc_poly *p, int *n, const double lo[3], const double hi[3], int inward, int f,
                     const double rho[3])
{
    sc_poly six[6];
    int m = 0;
    add_box(six, &m, lo, hi, inward, -1, rho);
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
    static const double white[3] = {0.7, 0.7, 0.68}, wood[3] = {0.5, 0.35, 0.2}, lamp[3] = {12, 12, 11};
    sc_poly *p = calloc((size_t)side * side * 40, sizeof *p);
    int i, j, k, w, f;
    if (!p) return NULL;
    *n = 0;
    for (i = 0; i < side; i++)
        for (j = 0; j < side; j++) {
            double x0 = 5.0 * i + 0.1, z0 = 5.0 * j + 0.1, x1 = x0 + 4.8, z1 = z0 + 4.8;
            double lo[3] = {x0, 0, z0}, hi[3] = {x1, 3, z1};
            for (f = 2; f < 6; f++) box_face(p, n, lo, hi, 1, f, white); /* floor, ceiling, walls along x */
            for (w = 0; w < 2; w++) { /* the walls at x0 and x1, each with its doorway inside the grid */
                int door = w ? i < side - 1 : i > 0;
                double dz = (i + w) % 2 ? 0.6 : 3.2; /* the doorway of the wall between i and i + 1 */
                double seg[3][4] = {{z0, z0 + dz, 0, 3}, {z0 + dz + 1, z1, 0, 3}, {z0 + dz, z0 + dz + 1, 2, 3}};
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
                add_box(p, n, a, b, 0, 2, wood);
            }
            {
                double v[4][3] = {{x0 + 2, 2.99, z0 + 2}, {x0 + 2.8, 2.99, z0 + 2}, {x0 + 2.8, 2.99, z0 + 2.8},
                                  {x0 + 2, 2.99, z0 + 2.8}};
                add_quad(p, n, (const double(*)[3])v, white, lamp);
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
static void report_cull(report_t *rp)
{
    static const int sides[] = {1, 2, 4, 8, 16, 32, 44};
    const int ns = (int)(sizeof sides / sizeof *sides);
    double us[2][8], first[2] = {0, 0};
    int k, surf0 = 0, surf = 0;
    out(rp, "\nCulled gathers (rad_cull_build, rad_gather_cull): a grid of rooms with doorways (27 to 31 polygons a "
        "room), one shot, then gathers at res 32 on floors and walls of random rooms, drawing every surface against "
        "drawing through the hierarchy (the same values, bit for bit), fixed build, one core:\n\n"
        "| rooms | surfaces | elements | gatherer and hierarchy ms | us per gather, all drawn | us per gather, culled | "
        "culled speed-up |\n| ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
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
        if (!(s = sc_create(p, n, &o, NULL, NULL, err, sizeof err)) || sc_solve(s, 1, 0, NULL, NULL) < 0) {
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
        out(rp, "| %d | %d | %d | %.1f | %.0f | %.0f | %.2f |\n", sides[k] * sides[k], st.surfaces, st.elements, build,
            us[0][k], us[1][k], us[0][k] / us[1][k]);
        sc_gatherer_free(g);
        sc_destroy(s);
        free(p);
    }
    out(rp, "\nFrom %d to %d surfaces (%.0f times as many) a gather drawing every surface grew %.1f times, a culled "
        "one %.1f times.\n", surf0, surf, (double)surf / surf0, us[0][ns - 1] / first[0], us[1][ns - 1] / first[1]);
}

/* Coarse shots on the generated hall: every shot at res 128 (the scene's settings, the
 * bits of the build before coarse shots) against peer rows 1 (rad_cli's defaults) and
 * 6 (res 256, coarse 2), each pair solved side by side in this process (shot by shot,
 * fixed build), and each against a res-512 solve to 1e-4. */
static void report_hall_coarse(report_t *rp, const bscene *sc)
{
    static const double floor[2] = {0.1, 0.01};
    static const int rows[2] = {1, 6};
    const build_t *b[2] = {&builds[0], &builds[0]};
    sc_opts o[3], r512 = scene_opts(sc);
    brun run[2][2];
    double rms[3][2], mx[3][2];
    sc_solver *ref;
    int k;
    fprintf(stderr, "rad_bench: coarse shots on the hall ...\n");
    o[0] = scene_opts(sc);
    for (k = 0; k < 2; k++) {
        sc_opts pair[2];
        o[k + 1] = row_opts(o[0], &peer_rows[rows[k]]);
        pair[0] = o[0];
        pair[1] = o[k + 1];
        interleaved(sc, b, pair, sc->runs, run[k]);
    }
    r512.res = 512;
    ref = solved(sc, &r512, 1e-4);
    for (k = 0; k < 3; k++) {
        sc_solver *a = solved(sc, &o[k], 0.001);
        element_accuracy(sc, ref, a, floor, rms[k], mx[k]);
        sc_destroy(a);
    }
    sc_destroy(ref);
    out(rp, "\nCoarse shots on the generated hall (%d elements, %d patches), fixed build, one core: every shot at "
        "res 128 (`--res 128 --coarse 0`) against rad_cli's defaults and against `--res 256 --coarse 2`, each "
        "pair solved side by side to 0.001 in this process, one shot of each in turn, median of %d (time / res "
        "128 is that pair's ratio); accuracy per element against a res-512 solve to 1e-4 of the same mesh, as in "
        "the peer table:\n\n"
        "| settings | shots | s to 0.001 | time / res 128 | pools + work MB | accuracy >10%%: rms / max | "
        ">1%%: rms / max |\n| --- | ---: | ---: | ---: | ---: | ---: | ---: |\n",
        run[0][0].elements, run[0][0].patches, sc->runs);
    for (k = 0; k < 3; k++) {
        const brun *r = k ? &run[k - 1][1] : &run[0][0];
        out(rp, "| %s | %d | %.3f | %.2f | %.2f | %.2f%% / %.2f%% | %.2f%% / %.2f%% |\n",
            k == 0   ? "`--res 128 --coarse 0`"
            : k == 1 ? "rad_cli's defaults (res 192, coarse 1)"
                     : "`--res 256 --coarse 2`",
            r->all_shots, r->total, k ? r->total / run[k - 1][0].total : 1.0, r->bytes / 1048576.0, 100 * rms[k][0],
            100 * mx[k][0], 100 * rms[k][1], 100 * mx[k][1]);
    }
    for (k = 0; k < 4; k++) run_free(&run[k / 2][k % 2]);
}

/* This thread's processor time, seconds. */
static double thread_cpu(void)
{
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

/* The scene solved to 0.001 through the core's split shot in NP parts (1 or 2) on this
 * one thread, each part of each stage in turn, each call timed on the thread's
 * processor clock: into SERIAL the calls between the stages, into WORK every part's
 * time, into CRIT the longer part of each stage. */
static void split_times(const bscene *sc, const sc_opts *o, unsigned np, double *serial, double *work,
                        double *crit)
{
    sc_solver *h = fixed_solver(sc, sc->polys, o);
    rad_scene_t *s = sc_core(h);
    size_t bytes = RAD_PART_BYTES(s->cfg.res);
    void *bufs[2] = {malloc(bytes), malloc(bytes)};
    double t, q[2];
    uint32_t p;
    unsigned k, stage;
    if (!bufs[0] || !bufs[1]) exit(1);
    *serial = *work = *crit = 0;
    for (;;) {
        t = thread_cpu();
        if (rad_shot_begin(s, RAD_REAL(0.001), &p) != 1) break;
        *serial += thread_cpu() - t;
        for (stage = 0; stage < 2; stage++) {
            if (stage) {
                t = thread_cpu();
                rad_shot_aim(s, p, bufs, np);
                *serial += thread_cpu() - t;
            }
            q[1] = 0;
            for (k = 0; k < np; k++) {
                t = thread_cpu();
                if (stage) rad_shot_receive_part(s, p, bufs, np, k);
                else rad_shot_part(s, p, k, np, bufs[k], bytes);
                q[k] = thread_cpu() - t;
                *work += q[k];
            }
            *crit += q[0] > q[1] ? q[0] : q[1];
        }
        t = thread_cpu();
        rad_shot_end(s, p, bufs, np);
        *serial += thread_cpu() - t;
    }
    free(bufs[0]);
    free(bufs[1]);
    sc_destroy(h);
}

/* What two free cores could do, whatever the load: the serial solve's time (sc_solve,
 * what one thread runs) over the two-part solve's critical path (the calls between the
 * stages plus the longer part of each stage). Cutting a shot in two costs work of its own
 * (surfaces set up on both parts' faces, each part's elements merged from both
 * parts' pixels), so this is below the two parts' own time over that path. SPLIT gets
 * the two parts' work over the one part's. */
static double parallel_bound(const bscene *sc, const sc_opts *o, double *split)
{
    double s1, w1, c1, s2, w2, c2, serial;
    sc_solver *h = fixed_solver(sc, sc->polys, o);
    serial = thread_cpu();
    sc_solve(h, 1000000, 0.001, NULL, NULL);
    serial = thread_cpu() - serial;
    sc_destroy(h);
    split_times(sc, o, 1, &s1, &w1, &c1);
    split_times(sc, o, 2, &s2, &w2, &c2);
    *split = w2 / w1;
    return serial / (s2 + c2);
}

/* H solved to 0.001 on THREADS threads through the split shot, or (0) by sc_solve, the
 * serial solve: wall seconds. */
static double timed_solve(sc_solver *h, int threads)
{
    double t0 = host_now();
    if (threads) sc_solve_parallel(h, threads, 1000000, 0.001, NULL, NULL);
    else sc_solve(h, 1000000, 0.001, NULL, NULL);
    return host_now() - t0;
}

/* Medians of 3 into M[0] the serial solve, M[1] the split shot in one part (on one
 * thread), M[2] in two parts on two threads; all three give the same bits. */
static void parallel_times(const bscene *sc, const sc_opts *o, double m[3])
{
    double t[3][3];
    int rep, k;
    for (rep = 0; rep < 3; rep++) {
        sc_solver *h[3];
        for (k = 0; k < 3; k++) {
            h[k] = fixed_solver(sc, sc->polys, o);
            t[k][rep] = timed_solve(h[k], k);
        }
        if (sc_checksum(h[1]) != sc_checksum(h[0]) || sc_checksum(h[2]) != sc_checksum(h[0])) {
            fprintf(stderr, "rad_bench: parallel result differs!\n");
            exit(1);
        }
        for (k = 0; k < 3; k++) sc_destroy(h[k]);
    }
    for (k = 0; k < 3; k++) m[k] = median(t[k], 3);
}

/* The parallel solve: the same shots, each shot's hemi-cube split over threads. */
static void report_parallel(report_t *rp, const bscene *scenes, int ns, const brun *fx)
{
    int i;
    out(rp, "\nParallel solve (pthreads in tools/, each shot's hemi-cube rows split over threads, then its receiving by "
        "runs of whole patches' elements, each sum in the serial order: bit-exact with the serial solve, checked by "
        "tests/test_parallel.c), fixed build, to 0.001, median of 3, with the machine's load average (1 minute) "
        "when each row was measured: the workers spin, so other processes on the cores slow them more than one "
        "thread. Serial is the solve without parts (sc_solve: what one thread runs); one part is the split "
        "shot's path on one thread (its item buffer's half-row bounds and merge cost work of their own); the "
        "speed-up is serial over two threads. The bound is what two free cores could give whatever the load: "
        "the serial solve over the critical path of the solve in two parts (the calls between the stages plus "
        "each stage's longer part), all timed on one thread's processor clock; split is the two parts' work over "
        "the one part's (the surfaces set up on both parts' faces, each part's elements merged from both parts' "
        "pixels). Each scene at res 128 and at rad_cli's defaults (res 192, coarse shots):\n\n| scene | settings "
        "| elements | serial s | one part s | 2 threads s | speed-up | load average | split | bound |\n"
        "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for (i = 0; i < ns; i++) {
        int k;
        if (scenes[i].big) continue; /* too long to repeat */
        for (k = 0; k < 2; k++) {
            sc_opts o = k ? row_opts(scene_opts(&scenes[i]), &peer_rows[1]) : scene_opts(&scenes[i]);
            double m[3], load = -1, split, bound;
            parallel_times(&scenes[i], &o, m);
            if (getloadavg(&load, 1) != 1) load = -1;
            bound = parallel_bound(&scenes[i], &o, &split);
            out(rp, "| %s | %s | %d | %.3f | %.3f | %.3f | %.2f | %.2f | %.2f | %.2f |\n", k ? "" : scenes[i].name,
                k ? "rad_cli's (192, coarse)" : "res 128", fx[i].elements, m[0], m[1], m[2], m[0] / m[2], load,
                split, bound);
        }
    }
}

/* ---- batch shooting ------------------------------------------------------------ */

/* Shots a batch in the batch tables: K = 1 (the serial solve's bits) and the rest. */
static const int batch_ks[] = {1, 2, 4, 8, 16, 32};
#define BATCH_KS ((int)(sizeof batch_ks / sizeof batch_ks[0]))

/* The scene solved to 0.001 in batches of K on this one thread, each call timed on the
 * thread's processor clock: into SERIAL rad_batch_begin, _aim and _end (what the
 * calling thread does alone), into WORK every cube's render and both parts of the
 * receipts, into CRIT the renders as two threads share them (each cube, in order, to
 * the one with less so far) and the longer part of the receipts: what two free cores
 * could do is (SERIAL + WORK) / (SERIAL + CRIT). */
static void batch_split(const bscene *sc, const sc_opts *o, int k, double *serial, double *work, double *crit)
{
    sc_solver *h = fixed_solver(sc, sc->polys, o);
    rad_scene_t *s = sc_core(h);
    size_t bytes = RAD_BATCH_BYTES(s->cfg.res, s->n_elements);
    void *bufs[RAD_BATCH_MAX];
    uint32_t p[RAD_BATCH_MAX];
    double t, q[2];
    int i, n;
    for (i = 0; i < k; i++)
        if (!(bufs[i] = malloc(bytes))) exit(1);
    *serial = *work = *crit = 0;
    for (;;) {
        t = thread_cpu();
        n = rad_batch_begin(s, RAD_REAL(0.001), (unsigned)k, p);
        *serial += thread_cpu() - t;
        if (n <= 0) break;
        q[0] = q[1] = 0;
        for (i = 0; i < n; i++) {
            double c;
            t = thread_cpu();
            rad_batch_render(s, p[i], (unsigned)i, bufs[i], bytes);
            c = thread_cpu() - t;
            *work += c;
            q[q[1] < q[0]] += c;
        }
        *crit += q[0] > q[1] ? q[0] : q[1];
        t = thread_cpu();
        rad_batch_aim(s, bufs, (unsigned)n);
        *serial += thread_cpu() - t;
        q[0] = q[1] = 0;
        for (i = 0; i < (n < 2 ? n : 2); i++) {
            t = thread_cpu();
            rad_batch_receive_part(s, bufs, (unsigned)n, (unsigned)i, n < 2 ? 1u : 2u);
            q[i] = thread_cpu() - t;
            *work += q[i];
        }
        *crit += q[0] > q[1] ? q[0] : q[1];
        t = thread_cpu();
        rad_batch_end(s, bufs, (unsigned)n);
        *serial += thread_cpu() - t;
    }
    for (i = 0; i < k; i++) free(bufs[i]);
    sc_destroy(h);
}

/* One solve of SC at O to 0.001 in batches of K on THREADS threads (K 0: sc_solve, the
 * serial solve): wall seconds; the solver into *OUT (the caller destroys it). */
static double batch_solve(const bscene *sc, const sc_opts *o, int k, int threads, sc_solver **out)
{
    sc_solver *h = fixed_solver(sc, sc->polys, o);
    double t0 = host_now();
    if (k) sc_solve_batch(h, threads, k, 1000000, 0.001, NULL, NULL);
    else sc_solve(h, 1000000, 0.001, NULL, NULL);
    t0 = host_now() - t0;
    *out = h;
    return t0;
}

/* The 1-minute load average, or -1. */
static double load_now(void)
{
    double load = -1;
    return getloadavg(&load, 1) == 1 ? load : -1;
}

/* Batch shooting against K = 1 on CornellBox-Original at rad_cli's defaults: shots and
 * time to 0.001 on one and two threads, accuracy against res 512. */
static void report_batch_k(report_t *rp, const bscene *sc)
{
    static const double floor[2] = {0.1, 0.01};
    sc_opts o = row_opts(scene_opts(sc), &peer_rows[1]), r;
    sc_solver *ref, *h;
    sc_stats st;
    uint64_t want[2] = {0, 0};
    double t1[BATCH_KS], t2[BATCH_KS];
    int i;
    o.max_element = 0; /* rad_cli's default mesh */
    r = o;
    r.res = 512;
    r.coarse = 0;
    fprintf(stderr, "rad_bench: batch shooting: the res-512 reference ...\n");
    ref = solved(sc, &r, 1e-4);
    out(rp, "\nBatch shooting (rad_batch_begin; rad_cli --batch K): each batch shoots the K patches whose shots "
        "move the most, their hemi-cubes rendered at once (on any threads: the same bits) and shot in order. "
        "CornellBox-Original at rad_cli's defaults (res %d, coarse shots, its mesh), fixed build, to 0.001, one "
        "run each: shots and seconds on one and on two threads (sc_solve_batch; K = 1 is the serial solve's "
        "bits), and the error of r + g + b per element against a solve of the same mesh at res 512 to 1e-4 "
        "(rms and largest over the elements above 10%% of the brightest non-emitting one). Load average (1 minute) "
        "at the start: %.2f on %ld cores.\n\n| K | shots | shots / K=1 | s, 1 thread | s, 2 threads | 2 threads / 1 "
        "| time / K=1 (2 threads) | rms | max |\n| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n",
        DEF_RES, load_now(), sysconf(_SC_NPROCESSORS_ONLN));
    for (i = 0; i < BATCH_KS; i++) {
        sc_solver *h2;
        double rms[2], mx[2];
        int shots;
        t1[i] = batch_solve(sc, &o, batch_ks[i], 1, &h);
        t2[i] = batch_solve(sc, &o, batch_ks[i], 2, &h2);
        if (sc_checksum(h2) != sc_checksum(h)) {
            fprintf(stderr, "rad_bench: batch K=%d differs on two threads!\n", batch_ks[i]);
            exit(1);
        }
        if (i == 0) {
            sc_solver *ser;
            batch_solve(sc, &o, 0, 1, &ser);
            want[0] = sc_checksum(ser);
            sc_destroy(ser);
            if (sc_checksum(h) != want[0]) {
                fprintf(stderr, "rad_bench: batch K=1 differs from the serial solve!\n");
                exit(1);
            }
        }
        sc_get_stats(h, &st);
        shots = st.shots;
        if (i == 0) want[1] = (uint64_t)shots;
        element_accuracy(sc, ref, h, floor, rms, mx);
        out(rp, "| %d | %d | %.2f | %.3f | %.3f | %.2f | %.2f | %.2f%% | %.2f%% |\n", batch_ks[i], shots,
            shots / (double)want[1], t1[i], t2[i], t1[i] / t2[i], t2[i] / t2[0], 100 * rms[0], 100 * mx[0]);
        sc_destroy(h);
        sc_destroy(h2);
    }
    out(rp, "\nLoad average at the end: %.2f.\n", load_now());
    sc_destroy(ref);
}

/* The batch solve's speed on one and two threads: each scene at its settings (res 128)
 * and at rad_cli's (res 192, coarse shots), serial against batches of DEF_BATCH_BENCH. */
static void report_batch_speed(report_t *rp, const bscene *scenes, int ns)
{
    int i, j, m;
    out(rp, "\nBatch solve on threads (sc_solve_batch, pthreads in tools/), fixed build, to 0.001, one run each, "
        "with the load average (1 minute) when the row was measured (the workers spin: other processes on the "
        "cores slow them more than one thread). Serial is sc_solve; K = 1 on one thread is the same solve through "
        "the batch calls. The bound is what two free cores could give whatever the load: the batch solve's "
        "processor time on one thread over its critical path on two (rad_batch_begin and _end on one, the "
        "cubes of each batch shared between two), timed on one thread's processor clock.\n\n| scene | settings | "
        "elements | K | serial s | 1 thread s | 2 threads s | 2 threads / 1 | serial / 2 threads | load average "
        "| bound |\n| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for (i = 0; i < ns; i++) {
        if (strncmp(scenes[i].name, "CornellBox-Original", 19) && strncmp(scenes[i].name, "generated hall", 14))
            continue;
        for (m = 0; m < 2; m++) {
            sc_opts o = m ? row_opts(scene_opts(&scenes[i]), &peer_rows[1]) : scene_opts(&scenes[i]);
            sc_solver *h;
            sc_stats st;
            double serial = batch_solve(&scenes[i], &o, 0, 1, &h);
            sc_get_stats(h, &st);
            sc_destroy(h);
            for (j = 0; j < BATCH_KS; j++) {
                int k = batch_ks[j];
                double t1, t2, s, w, c, load = load_now();
                if (k != 1 && k != 4 && k != 8 && k != 16) continue;
                fprintf(stderr, "rad_bench: batch speed: %s, K %d ...\n", scenes[i].name, k);
                t1 = batch_solve(&scenes[i], &o, k, 1, &h);
                sc_destroy(h);
                t2 = batch_solve(&scenes[i], &o, k, 2, &h);
                sc_destroy(h);
                batch_split(&scenes[i], &o, k, &s, &w, &c);
                out(rp, "| %s | %s | %d | %d | %.3f | %.3f | %.3f | %.2f | %.2f | %.2f | %.2f |\n",
                    m || j ? "" : scenes[i].name, j ? "" : m ? "rad_cli's (192, coarse)" : "res 128",
                    st.elements, k, serial, t1, t2, t1 / t2, serial / t2, load, (s + w) / (s + c));
            }
        }
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
    return sc_gather(w->g, p, n, 1, rgb);
}

static void *lm_worker(void *arg)
{
    lm_work *w = arg;
    double t = thread_cpu();
    if (lm_gather_rows(w->a, w->first, w->step, lm_count, w) != 0) exit(1);
    w->cpu += thread_cpu() - t;
    return NULL;
}

/* The marked texels of the rows Y % STEP in FIRST[0..NT-1] of A gathered at RES on NT
 * threads at once (one per set), pass by pass (lm_plan) when PLAN; their gathers into
 * *N, the wall time returned, the processor time of the first thread a gather (its
 * gathers alone) into *CPU0. */
static double lm_rows(sc_solver *s, lm_atlas *a, int res, int step, const int *first, int nt, int plan, long *n,
                      double *cpu0)
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
    if (lm_build(a, sc->polys, sc->n, &lo, err, sizeof err) != 0) { fprintf(stderr, "rad_bench: %s\n", err); exit(1); }
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
static void report_lightmap(report_t *rp, const bscene *sc, const char *shared)
{
    static const int res[3] = {16, 32, 64}, steps[3] = {4, 8, 32};
    lm_atlas a;
    sc_opts o;
    sc_solver *s;
    long covered, n1, n2;
    double load = -1, cpu, cpu2, t1, t2;
    int i, one[1] = {0}, two[2] = {0, 1};
    out(rp, "\nLightmap baking (tools/bake/lightmap.c, `--lightmap`): CornellBox-Original at 512 x 512 texels, "
        "solved as above (fixed build, to 0.001), a gather `sc_gather` with the ambient term. The whole bake at "
        "the defaults (gather resolution %d, `--lightmap-tol` %g: the adaptive passes), once on one thread and "
        "once on two (each pass's rows in two sets), wall time of the gathers' passes (the planning between them "
        "included, not the solve nor the layout):\n\n", DEF_GATHER_RES, LM_TOL);
    if (!sc) {
        out(rp, "skipped: %s not found.\n", shared);
        return;
    }
    o = scene_opts(sc);
    s = fixed_solver(sc, sc->polys, &o);
    sc_solve(s, 1000000, 0.001, NULL, NULL);
    fprintf(stderr, "rad_bench: lightmap, the whole adaptive bake ...\n");
    covered = lm_layout(sc, LM_TOL, &a);
    t1 = lm_rows(s, &a, DEF_GATHER_RES, 1, one, 1, 1, &n1, &cpu);
    lm_free(&a);
    lm_layout(sc, LM_TOL, &a);
    t2 = lm_rows(s, &a, DEF_GATHER_RES, 2, two, 2, 1, &n2, &cpu2);
    if (getloadavg(&load, 1) != 1) load = -1;
    out(rp, "| charts | texels covered | gathers | of the covered | us per gather | s, 1 thread | s, 2 threads | "
        "speed-up | load average |\n| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n"
        "| %d | %ld | %ld | %.1f%% | %.1f | %.2f | %.2f | %.2f | %.2f |\n\n", a.ncharts, covered, n1,
        100.0 * n1 / covered, 1e6 * cpu, t1, t2, t1 / t2, load);
    lm_free(&a);
    out(rp, "Each gather resolution over every n-th row of the every-texel bake (`--lightmap-tol 0`: a sample of "
        "the texels), once on one thread and once on two (the same rows in two sets); us per gather is the "
        "processor time of one thread over its gathers, the every-texel bake's estimate that times the covered "
        "texels:\n\n| gather res | rows | gathers | us per gather | texels/s, 1 thread | texels/s, 2 threads | "
        "speed-up | every-texel bake s, 1 thread (estimate) | load average |\n"
        "| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for (i = 0; i < 3; i++) {
        int sets[2] = {0, steps[i]};
        fprintf(stderr, "rad_bench: lightmap at gather resolution %d ...\n", res[i]);
        lm_layout(sc, 0.0, &a);
        lm_plan(&a);
        t1 = lm_rows(s, &a, res[i], steps[i], one, 1, 0, &n1, &cpu);
        lm_free(&a);
        lm_layout(sc, 0.0, &a);
        lm_plan(&a);
        t2 = lm_rows(s, &a, res[i], 2 * steps[i], sets, 2, 0, &n2, &cpu2);
        lm_free(&a);
        if (getloadavg(&load, 1) != 1) load = -1;
        out(rp, "| %d | 1 in %d | %ld | %.1f | %.0f | %.0f | %.2f | %.1f | %.2f |\n", res[i], steps[i], n1, 1e6 * cpu,
            n1 / t1, n2 / t2, (n2 / t2) / (n1 / t1), cpu * covered, load);
    }
    sc_destroy(s);
}

/* docs/bench.md's part between the bench markers, regenerated: the page's own text
 * around them stays, and the file is replaced whole (a temporary beside it, renamed)
 * or, on any error, left as it was with a line on stderr saying why. */
static void write_docs(const report_t *rp)
{
    static const char path[] = "docs/bench.md", tmp[] = "docs/bench.md.tmp";
    static const char begin[] = "<!-- bench:begin -->\n", end[] = "<!-- bench:end -->";
    static char buf[1 << 20];
    FILE *r = fopen(path, "r"), *w;
    size_t n = r ? fread(buf, 1, sizeof buf - 1, r) : 0;
    char *a, *b;
    int ok;
    if (!r || ferror(r) || n == sizeof buf - 1) {
        fprintf(stderr, "rad_bench: %s: %s; the report is on standard output only\n", path,
                !r ? strerror(errno) : n == sizeof buf - 1 ? "larger than 1 MiB" : "read error");
        if (r) fclose(r);
        return;
    }
    fclose(r);
    buf[n] = '\0';
    a = strstr(buf, begin);
    b = a ? strstr(a, end) : NULL;
    if (!b) {
        fprintf(stderr,
                "rad_bench: %s: no '%.20s' line followed by '%s'; the report is on standard "
                "output only\n",
                path, begin, end);
        return;
    }
    w = fopen(tmp, "w");
    if (!w) {
        fprintf(stderr, "rad_bench: %s: %s\n", tmp, strerror(errno));
        return;
    }
    a += strlen(begin);
    ok = fwrite(buf, 1, (size_t)(a - buf), w) == (size_t)(a - buf) && fputs(rp->md, w) >= 0 &&
         fputs(b, w) >= 0;
    if (fclose(w) != 0 || !ok || rename(tmp, path) != 0) {
        fprintf(stderr, "rad_bench: writing %s failed: %s\n", path, strerror(errno));
        remove(tmp);
    }
}

/* The convergence plots, against shots and against seconds. */
static void draw_plots(const bscene *scenes, int ns, const brun *fx)
{
    static const unsigned char col[6][3] = {{200, 30, 30}, {30, 120, 200}, {30, 160, 60}, {150, 60, 170},
                                             {220, 140, 0}, {90, 90, 90}};
    plot_series ser[8];
    plot_opts po;
    char err[256];
    int i;
    for (i = 0; i < ns; i++) {
        ser[i].label = scenes[i].name;
        ser[i].x = fx[i].xs; ser[i].y = fx[i].y; ser[i].n = fx[i].npts;
        memcpy(ser[i].rgb, col[i % 6], 3);
    }
    memset(&po, 0, sizeof po);
    po.title = "Progressive refinement, fixed build, res 128";
    po.xlabel = "shots"; po.ylabel = "unshot fraction"; po.log_y = 1; po.width = 800; po.height = 500;
    if (plot_write("docs/convergence_shots.png", ser, ns, &po, err, sizeof err) < 0) fprintf(stderr, "%s\n", err);
    for (i = 0; i < ns; i++) ser[i].x = fx[i].xt;
    po.xlabel = "seconds";
    if (plot_write("docs/convergence_time.png", ser, ns, &po, err, sizeof err) < 0) fprintf(stderr, "%s\n", err);
}

/* ---- textures: loading and sampling them, whole processes ---------------------------- */

#define TEX_RUNS 9
#define TEX_SIDE 512 /* texels a side of each generated map */
#define TEX_MAPS 7   /* six walls and the block */

typedef struct {
    char why[256];          /* empty when measured; else why not */
    int elements, shots[3]; /* textures, --no-textures, the textures' means as Kd */
    double t[2][3], cpu[2][3]; /* medians per view size (64, 512 square), variant as above */
    double ratio[2][2], cpu_ratio[2][2]; /* the maps over the other two: median per round */
} texbench_t;

/* A map of TEX_SIDE^2: bricks of 64 x 32 in a hue of its own, mortar lines, noise. */
static int write_map(const char *path, int m)
{
    unsigned char *rgb = malloc((size_t)TEX_SIDE * TEX_SIDE * 3);
    int x, y, k, rc;
    if (!rgb) return -1;
    for (y = 0; y < TEX_SIDE; y++)
        for (x = 0; x < TEX_SIDE; x++) {
            unsigned h = (unsigned)x * 73856093u ^ (unsigned)y * 19349663u ^ (unsigned)m * 83492791u;
            int mortar = y % 32 < 2 || (x + (y / 32 % 2) * 32) % 64 < 2;
            for (k = 0; k < 3; k++)
                rgb[3 * ((size_t)y * TEX_SIDE + x) + k] =
                    (unsigned char)(mortar ? 200 : 60 + 25 * ((m + k) % 5) + (int)((h >> (8 * k)) % 40));
        }
    rc = img_write(path, rgb, TEX_SIDE, TEX_SIDE, NULL, 0);
    free(rgb);
    return rc;
}

/* DIR/room.obj: a room of 2 m with a block and a lamp, each wall and the block with a
 * map of its own (walls' UVs 0..2: the map twice across), mtllib MTL. */
static int write_room(const char *dir, const char *name, const char *mtl)
{
    static const double grey[3] = {0.5, 0.5, 0.5}, lo[3] = {-1, -1, -1}, hi[3] = {1, 1, 1};
    static const double blo[3] = {-0.5, -1, -0.4}, bhi[3] = {0.1, -0.2, 0.3};
    static const double lamp[4][3] = {{-0.3, 0.98, -0.3}, {0.3, 0.98, -0.3}, {0.3, 0.98, 0.3}, {-0.3, 0.98, 0.3}};
    sc_poly p[12];
    char path[600];
    FILE *f;
    int n = 0, i, k;
    add_box(p, &n, lo, hi, 1, -1, grey);
    add_box(p, &n, blo, bhi, 0, 2, grey);
    snprintf(path, sizeof path, "%s/%s", dir, name);
    if (!(f = fopen(path, "w"))) return -1;
    fprintf(f, "mtllib %s\nvt 0 0\nvt 2 0\nvt 2 2\nvt 0 2\nvt 1 0\nvt 1 1\nvt 0 1\n", mtl);
    for (i = 0; i <= n; i++) {
        for (k = 0; k < 4; k++)
            fprintf(f, "v %.17g %.17g %.17g\n", i < n ? p[i].v[k][0] : lamp[k][0], i < n ? p[i].v[k][1] : lamp[k][1],
                    i < n ? p[i].v[k][2] : lamp[k][2]);
        if (i == n) fprintf(f, "usemtl lamp\nf -4 -3 -2 -1\n");
        else if (i < 6) fprintf(f, "usemtl m%d\nf -4/1 -3/2 -2/3 -1/4\n", i);
        else fprintf(f, "usemtl m6\nf -4/1 -3/5 -2/6 -1/7\n");
    }
    return fclose(f);
}

/* DIR/kd.mtl: each material's Kd the reflectance rad gives its textured face (the
 * same bits reach the core), so that solve is the textured one without the maps. */
static int write_kd_mtl(const char *dir, const char *obj)
{
    obj_scene sc;
    tex_image maps[TEX_MAPS + 1];
    sc_poly *p;
    char path[600];
    FILE *f;
    int n, i, m;
    if (obj_load(obj, &sc, NULL, NULL, path, sizeof path) < 0) return -1;
    if (sc.nmaterials > TEX_MAPS + 1 || tex_load_materials(&sc, maps, NULL, NULL, 1) != TEX_MAPS) {
        obj_free(&sc);
        return -1;
    }
    p = polys_from_obj_tex(&sc, maps, &n, NULL, NULL);
    snprintf(path, sizeof path, "%s/kd.mtl", dir);
    f = p ? fopen(path, "w") : NULL;
    for (m = 0; f && m < sc.nmaterials; m++)
        for (i = 0; i < n; i++)
            if (sc.faces[p[i].tag].material == m) {
                fprintf(f, "newmtl %s\nKd %.17g %.17g %.17g\nKe %.17g %.17g %.17g\n", sc.materials[m].name, p[i].rho[0],
                        p[i].rho[1], p[i].rho[2], p[i].emit[0], p[i].emit[1], p[i].emit[2]);
                break;
            }
    for (m = 0; m < sc.nmaterials; m++) tex_free(&maps[m]);
    free(p);
    obj_free(&sc);
    return f && fclose(f) == 0 ? 0 : -1;
}

static int make_tex_scene(const char *dir)
{
    char path[600];
    FILE *f;
    int m;
    snprintf(path, sizeof path, "%s/room.mtl", dir);
    if (!(f = fopen(path, "w"))) return -1;
    for (m = 0; m < TEX_MAPS; m++) fprintf(f, "newmtl m%d\nKd 0 0 0\nmap_Kd map%d.png\n", m, m);
    fprintf(f, "newmtl lamp\nKd 0 0 0\nKe 12 12 12\n");
    if (fclose(f) != 0) return -1;
    for (m = 0; m < TEX_MAPS; m++) {
        snprintf(path, sizeof path, "%s/map%d.png", dir, m);
        if (write_map(path, m) < 0) return -1;
    }
    snprintf(path, sizeof path, "%s/room.obj", dir);
    if (write_room(dir, "room.obj", "room.mtl") < 0 || write_room(dir, "room_kd.obj", "kd.mtl") < 0) return -1;
    return write_kd_mtl(dir, path);
}

/* The three variants' shots and elements, solved here at rad_cli's settings. */
static void tex_shots(const char *dir, texbench_t *tb)
{
    static const char *const obj[3] = {"room.obj", "room.obj", "room_kd.obj"};
    int v;
    for (v = 0; v < 3; v++) {
        obj_scene sc;
        tex_image maps[TEX_MAPS + 1];
        sc_opts o = row_opts((sc_opts){.max_element = 0.08, .max_patch = 0.32}, &peer_rows[1]); /* rad_cli's */
        char path[600], err[256];
        sc_poly *p;
        sc_solver *s;
        sc_stats st;
        int n, m;
        snprintf(path, sizeof path, "%s/%s", dir, obj[v]);
        if (obj_load(path, &sc, NULL, NULL, err, sizeof err) < 0) continue;
        if (v == 0) tex_load_materials(&sc, maps, NULL, NULL, 1);
        p = v == 0 ? polys_from_obj_tex(&sc, maps, &n, NULL, NULL) : polys_from_obj(&sc, &n, NULL, NULL);
        if (v == 1)
            for (m = 0; p && m < n; m++) /* --no-textures: Kd 0 shows 0.5 grey (obj_map_fallback) */
                if (p[m].emit[0] == 0) p[m].rho[0] = p[m].rho[1] = p[m].rho[2] = 0.5;
        s = p ? sc_create(p, n, &o, NULL, NULL, err, sizeof err) : NULL;
        if (s) {
            tb->shots[v] = sc_solve(s, 1000000, 0.001, NULL, NULL);
            sc_get_stats(s, &st);
            tb->elements = st.elements;
            sc_destroy(s);
        }
        if (v == 0)
            for (m = 0; m < sc.nmaterials; m++) tex_free(&maps[m]);
        free(p);
        obj_free(&sc);
    }
}

/* rad_cli with the maps, with --no-textures, and on the maps' means as Kd, whole
 * processes in turn, TEX_RUNS rounds, views of 64 and 512 square. */
static void tex_bench(const char *self, texbench_t *tb)
{
    static const char *const files[] = {"room.obj", "room_kd.obj", "room.mtl", "kd.mtl", "view.png"};
    char dir[64] = "/tmp/rad_bench_tex.XXXXXX", cli[1024], here[512], room[600], kd[600], png[600];
    char w[2][8] = {"64", "512"};
    double t[2][3][TEX_RUNS], c[2][3][TEX_RUNS], r[2][2][TEX_RUNS], rc[2][2][TEX_RUNS];
    int i, k, v, m;
    long kb;
    memset(tb, 0, sizeof *tb);
    dir_of(self, here, sizeof here);
    snprintf(cli, sizeof cli, "%s/rad_cli", here);
    if (!is_file(cli)) { snprintf(tb->why, sizeof tb->why, "no %.200s", cli); return; }
    if (!mkdtemp(dir) || make_tex_scene(dir) < 0) { snprintf(tb->why, sizeof tb->why, "the scene could not be written"); return; }
    snprintf(room, sizeof room, "%s/room.obj", dir);
    snprintf(kd, sizeof kd, "%s/room_kd.obj", dir);
    snprintf(png, sizeof png, "%s/view.png", dir);
    fprintf(stderr, "rad_bench: textures, %d rounds ...\n", TEX_RUNS);
    tex_shots(dir, tb);
    for (i = 0; i < TEX_RUNS && !tb->why[0]; i++)
        for (k = 0; k < 2; k++)
            for (v = 0; v < 3; v++) {
                char *cmd[16] = {cli, v == 2 ? kd : room, "--max-element", "0.08", "--width", w[k], "--height", w[k],
                                 "-o", png, v == 1 ? "--no-textures" : NULL, NULL};
                if (run_child(cmd, &t[k][v][i], &c[k][v][i], &kb) < 0) snprintf(tb->why, sizeof tb->why, "rad_cli failed");
            }
    for (m = 0; m < TEX_MAPS; m++) {
        snprintf(png, sizeof png, "%s/map%d.png", dir, m);
        remove(png);
    }
    for (m = 0; m < 5; m++) {
        snprintf(png, sizeof png, "%s/%s", dir, files[m]);
        remove(png);
    }
    rmdir(dir);
    if (tb->why[0]) return;
    for (k = 0; k < 2; k++) {
        for (i = 0; i < TEX_RUNS; i++)
            for (v = 0; v < 2; v++) {
                r[k][v][i] = t[k][0][i] / t[k][v + 1][i];
                rc[k][v][i] = c[k][0][i] / c[k][v + 1][i];
            }
        for (v = 0; v < 3; v++) {
            tb->t[k][v] = median(t[k][v], TEX_RUNS);
            tb->cpu[k][v] = median(c[k][v], TEX_RUNS);
        }
        for (v = 0; v < 2; v++) {
            tb->ratio[k][v] = median(r[k][v], TEX_RUNS);
            tb->cpu_ratio[k][v] = median(rc[k][v], TEX_RUNS);
        }
    }
}

static void report_textures(report_t *rp, const char *self)
{
    static const char *const nm[3] = {"with the maps", "`--no-textures` (Kd 0: 0.5 grey)",
                                      "the maps' means as Kd (the faces' means)"};
    texbench_t tb;
    int k, v;
    tex_bench(self, &tb);
    out(rp, "\nTextures: a generated room of 2 m (six walls and a block, each with a %d x %d PNG map_Kd of its own, "
        "the walls' twice across; a lamp), `rad_cli --max-element 0.08` (fixed build, its defaults: res 192, coarse "
        "shots), whole processes in turn, %d rounds: medians of wall and processor (user + system) time and of each round's ratio (the "
        "run with the maps over this one). The maps change the light, so "
        "`--no-textures` solves another scene; the third run gives every face the reflectance the maps give it as "
        "Kd: the solve without loading or sampling a map, but for the maps' run giving each element the mean of "
        "its own footprint (the light moves within a face; the shots differ by a few). ", TEX_SIDE, TEX_SIDE, TEX_RUNS);
    if (tb.why[0]) {
        out(rp, "Not measured: %s.\n", tb.why);
        return;
    }
    out(rp, "%d elements.\n\n| run | shots to 0.001 | view | wall s | ratio | processor s | ratio |\n"
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: |\n", tb.elements);
    for (v = 0; v < 3; v++)
        for (k = 0; k < 2; k++) {
            char a[2][32] = {"", ""};
            if (v > 0) {
                snprintf(a[0], sizeof a[0], "%.2f", tb.ratio[k][v - 1]);
                snprintf(a[1], sizeof a[1], "%.2f", tb.cpu_ratio[k][v - 1]);
            }
            out(rp, "| %s | %d | %s | %.3f | %s | %.3f | %s |\n", k ? "" : nm[v], tb.shots[v], k ? "512" : "64",
                tb.t[k][v], a[0], tb.cpu[k][v], a[1]);
        }
}

/* Index of the scene named NAME, or -1. */
/* ---- rad_bench --gather-res: the lightmap's gather resolution against res 256 ------ */

#define GR_SIZE 128 /* the atlas's texels a side */
#define GR_EVERY 3  /* the texels compared: those with (x + y) % GR_EVERY == 0 */

/* A room 6 x 3 x 4 with a cornice (0.2 x 0.2, 0.2 below the ceiling) and a shelf
 * (at 1.2, 0.15 deep) along its walls, a 1 x 1 lamp in the ceiling's middle. */
static sc_poly *gen_cornice_room(int *n)
{
    static const double white[3] = {0.75, 0.74, 0.72}, lamp[3] = {12, 11, 9};
    sc_poly *p = calloc(64, sizeof *p);
    double lo[3] = {-3, 0, -2}, hi[3] = {3, 3, 2}, v[4][3] = {{-0.5, 2.99, -0.5}, {0.5, 2.99, -0.5},
                                                              {0.5, 2.99, 0.5}, {-0.5, 2.99, 0.5}};
    int k;
    if (!p) return NULL;
    *n = 0;
    add_box(p, n, lo, hi, 1, -1, white);
    for (k = 0; k < 4; k++) { /* along the walls x = -3, x = 3, z = -2, z = 2 */
        double a[3], b[3], c[3], d[3];
        int ax = k < 2 ? 0 : 2, hs = k % 2, o = 2 - ax;
        a[ax] = hs ? hi[ax] - 0.2 : lo[ax];
        b[ax] = hs ? hi[ax] : lo[ax] + 0.2;
        a[o] = lo[o];
        b[o] = hi[o];
        a[1] = 2.6;
        b[1] = 2.8;
        add_box(p, n, a, b, 0, -1, white);
        c[ax] = hs ? hi[ax] - 0.15 : lo[ax];
        d[ax] = hs ? hi[ax] : lo[ax] + 0.15;
        c[o] = lo[o] + 0.5;
        d[o] = hi[o] - 0.5;
        c[1] = 1.2;
        d[1] = 1.26;
        add_box(p, n, c, d, 0, -1, white);
    }
    add_quad(p, n, (const double(*)[3])v, white, lamp);
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
    t = thread_cpu();
    for (y = 0; y < a->size; y++)
        for (x = 0; x < a->size; x++) {
            size_t at = (size_t)y * a->size + (size_t)x;
            if ((x + y) % GR_EVERY || !lm_texel_point(a, x, y, p)) continue;
            if (sc_gather(g, p, &a->planes[4 * (size_t)a->poly[at]], 1, &e[3 * m++]) != 0) exit(1);
        }
    t = (thread_cpu() - t) / (m ? m : 1);
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
    if (!(s = sc_create(polys, n, &o, NULL, NULL, err, sizeof err)) || lm_build(&a, polys, n, &lo, err, sizeof err)) {
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
            double d = fabs(e[3 * i] + e[3 * i + 1] + e[3 * i + 2] - ref[3 * i] - ref[3 * i + 1] - ref[3 * i + 2]);
            ss += d * d;
            mx = fmax(mx, d);
        }
        if (getloadavg(&load, 1) != 1) load = -1;
        out(rp, "| %s | %d | %ld | %.2f%% | %.1f%% | %.1f | %.1f | %.2f |\n", name, res[r], m, 100 * sqrt(ss / m) / mean,
            100 * mx / mean, 1e6 * t, 1e6 * tref, load);
    }
    free(ref);
    free(e);
    lm_free(&a);
    sc_destroy(s);
}

/* rad_bench --gather-res [SHARED]: the table to stdout. */
static int gather_res_bench(int argc, char **argv)
{
    static report_t rp;
    const char *shared = argc > 2 ? argv[2] : "../shared/scenes/CornellBox-Original.obj";
    sc_poly *p;
    int n;
    out(&rp, "Lightmap texels gathered at resolution 16 to 64 against 256 (`rad_bench --gather-res`): a %d x %d atlas, "
        "every covered texel's sample with (x + y) %% %d == 0, the solve to 0.001 at res 128. rms and max of the "
        "difference in a texel's channel sum, over the mean channel sum of the texels compared; processor "
        "microseconds a gather (at 256 in its own column).\n\n"
        "| scene | gather res | texels | rms | max | us per gather | us at 256 | load average |\n"
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n", GR_SIZE, GR_SIZE, GR_EVERY);
    if (!(p = gen_cornice_room(&n))) return 1;
    gr_scene(&rp, "room with cornices and shelves", p, n);
    free(p);
    if ((p = load_obj(shared, &n, NULL)) != NULL) {
        gr_scene(&rp, "CornellBox-Original", p, n);
        free(p);
    } else {
        out(&rp, "\n%s: not found, skipped.\n", shared);
    }
    fputs(rp.md, stdout);
    return 0;
}

/* ---- rad_bench --level: a level of Sponza's class ---------------------------------- */

#define LEVEL_SIZE 1024 /* the lightmap's texels a side */

/* A run's progress on stderr every 10 s: the solve's shots and unshot fraction. */
typedef struct {
    double t0, last;
} level_prog;

static int level_shot(void *ctx, int shots, double unshot)
{
    level_prog *p = ctx;
    double t = host_now();
    if (t - p->last >= 10.0) {
        fprintf(stderr, "rad_bench: level: %d shots, unshot %.4f, %.0f s\n", shots, unshot, t - p->t0);
        p->last = t;
    }
    return 0;
}

/* The bake's gathers on this thread, stopping once STOP seconds of them have passed
 * (0: never): their count and progress every 10 s. */
typedef struct {
    sc_gatherer *g;
    long gathers;
    double t0, last, stop;
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
    return sc_gather(b->g, p, n, 1, rgb);
}

/* One level (POLYS, N of them, lit by LIGHTS) measured and reported as a table row:
 * the solve to 0.01 at rad_cli's hemi-cube defaults, the core's memory and the
 * process's peak, the 1024 x 1024 atlas's charts and layout time, and its bake (the
 * adaptive default, gather resolution DEF_GATHER_RES, one thread), cut short after STOP
 * seconds when STOP > 0. Times are this thread's processor seconds (the machine may
 * be shared) and wall seconds. */
static void level_row(report_t *rp, const char *name, const sc_poly *polys, int n, const sc_light *lights, int nl,
                      double stop)
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
    double c0, w0, solve_cpu, solve_wall, lay_cpu, bake_cpu, bake_wall, load = -1;
    long covered;
    int done, x, y;
    o.res = DEF_RES;
    o.coarse = DEF_COARSE;
    o.coarse_res = DEF_COARSE_FLOOR(DEF_RES);
    o.lights = lights;
    o.nlights = nl;
    fprintf(stderr, "rad_bench: level: %s, %d polygons: solving to 0.01 ...\n", name, n);
    c0 = thread_cpu();
    w0 = pg.t0 = pg.last = host_now();
    if (!(s = sc_create(polys, n, &o, NULL, NULL, err, sizeof err))) {
        fprintf(stderr, "rad_bench: %s: %s\n", name, err);
        exit(1);
    }
    sc_solve(s, 10000000, 0.01, level_shot, &pg);
    solve_cpu = thread_cpu() - c0;
    solve_wall = host_now() - w0;
    sc_get_stats(s, &st);
    fprintf(stderr, "rad_bench: level: solved in %.1f s; the lightmap's layout ...\n", solve_wall);
    c0 = thread_cpu();
    if (lm_build(&a, polys, n, &lo, err, sizeof err) != 0) {
        fprintf(stderr, "rad_bench: %s: %s\n", name, err);
        exit(1);
    }
    lay_cpu = thread_cpu() - c0;
    for (covered = 0, y = 0; y < a.size; y++)
        for (x = 0; x < a.size; x++) {
            double p[3];
            covered += lm_texel_point(&a, x, y, p);
        }
    memset(&b, 0, sizeof b);
    if (!(b.g = sc_gatherer_new(s, DEF_GATHER_RES, 0))) exit(1);
    c0 = thread_cpu();
    b.t0 = b.last = host_now();
    b.stop = stop;
    done = lm_bake(&a, level_gather, &b) == 0;
    bake_cpu = thread_cpu() - c0;
    bake_wall = host_now() - b.t0;
    getrusage(RUSAGE_SELF, &ru);
    if (getloadavg(&load, 1) != 1) load = -1;
    out(rp, "| %s | %d | %d | %d | %d | %.2f (%.2f) | %.1f | %.1f | %d | %.2f | %ld | %ld | %s%.1f (%.1f) | %.0f | %.1f "
        "| %.2f |\n", name, n, st.elements, st.patches, st.shots, solve_cpu, solve_wall, (st.pool_bytes + st.work_bytes) / 1048576.0,
        ru.ru_maxrss / 1024.0, a.ncharts, lay_cpu, covered, b.gathers, done ? "" : "stopped: ", bake_cpu, bake_wall,
        1e6 * bake_cpu / (b.gathers ? b.gathers : 1), 1e6 * bake_cpu / (b.gathers ? b.gathers : 1) * covered / 1e6,
        load);
    sc_gatherer_free(b.g);
    lm_free(&a);
    sc_destroy(s);
}

/* rad_bench --level [STOP] [SCENE]: the generated atrium (tools/bench/level.h) and, when
 * SCENE (default ../shared/scenes/sponza.obj) is there, that scene under the same sun
 * and sky; each bake cut short after STOP seconds when STOP > 0. The table to stdout. */
static int level_bench(int argc, char **argv)
{
    static report_t rp;
    sc_light lights[LEVEL_LIGHTS];
    obj_scene keep;
    const char *scene = "../shared/scenes/sponza.obj";
    double stop = 0.0;
    sc_poly *p;
    int n, i;
    for (i = 2; i < argc; i++) {
        char *end;
        double v = strtod(argv[i], &end);
        if (*end == '\0' && end != argv[i] && v >= 0) stop = v;
        else scene = argv[i];
    }
    if (!(p = level_atrium(&n, lights))) return 1;
    out(&rp, "A level of Sponza's class (`rad_bench --level`): the generated two-storey atrium "
        "(tools/bench/level.h) under a sun and a %d-direction sky, solved to an unshot fraction of 0.01 at rad_cli's "
        "hemi-cube defaults (res %d, coarse shots), then baked into a %d x %d lightmap at the defaults (adaptive, "
        "tolerance %g, gather resolution %d) on one thread. Times are processor seconds of the one thread (wall "
        "seconds in brackets: the machine may be shared); memory is the core's pools and work buffer, and the "
        "process's peak resident size; the every-texel estimate is the covered texels times the time per gather "
        "(an upper bound of the adaptive bake).\n\n"
        "| scene | polygons | elements | patches | shots | solve s | core MB | peak MB | charts | layout s | "
        "texels covered | gathers | bake s | us per gather | every-texel s (estimate) | load average |\n"
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n",
        lights[1].dirs, DEF_RES, LEVEL_SIZE, LEVEL_SIZE, LM_TOL, DEF_GATHER_RES);
    level_row(&rp, "generated atrium", p, n, lights, LEVEL_LIGHTS, stop);
    free(p);
    if ((p = load_obj(scene, &n, &keep)) != NULL) {
        level_row(&rp, scene, p, n, lights, LEVEL_LIGHTS, stop);
        free(p);
        obj_free(&keep);
    } else {
        out(&rp, "\n%s: not found, skipped.\n", scene);
    }
    fputs(rp.md, stdout);
    return 0;
}

static int scene_named(const bscene *scenes, int ns, const char *name)
{
    int i;
    for (i = 0; i < ns; i++)
        if (strcmp(scenes[i].name, name) == 0) return i;
    return -1;
}

int main(int argc, char **argv)
{
    static bscene scenes[8];
    static brun fx[8], fl[8];
    static report_t rp;
    static peer_t peer;
    double amax[8], arms[8];
    int ns, i, orig;

    const char *shared = argc > 1 ? argv[1] : "../shared/scenes/CornellBox-Original.obj";

    if (argc > 1 && strcmp(argv[1], "--cull") == 0) { /* this report alone, printed */
        report_cull(&rp);
        fputs(rp.md, stdout);
        return 0;
    }
    if (argc > 1 && strcmp(argv[1], "--level") == 0) return level_bench(argc, argv);
    if (argc > 1 && strcmp(argv[1], "--gather-res") == 0) return gather_res_bench(argc, argv);

    /* First, while this process is small: a child's peak memory starts at its parent's
     * at fork (Linux keeps the high-water mark across exec). */
    peer_bench(argv[0], shared, &peer);
    if (!peer.why[0]) peer_accuracy(shared, &peer);
    ns = load_scenes(shared, scenes);
    if (!ns) return 1;
    for (i = 0; i < ns; i++) {
        fprintf(stderr, "rad_bench: %s ...\n", scenes[i].name);
        bench_pair(&scenes[i], &fx[i], &fl[i]);
        twin_accuracy(&scenes[i], &amax[i], &arms[i]);
    }
    if (fx[ns - 1].elements < 20000)
        fprintf(stderr, "rad_bench: warning: the generated scene has %d elements, fewer than the 20,000 asked for\n",
                fx[ns - 1].elements);
    orig = scene_named(scenes, ns, "CornellBox-Original (shared)");
    report_speed(&rp, scenes, ns, fx, fl);
    report_twin(&rp, scenes, ns, amax, arms);
    report_hemicube(&rp);
    if (orig >= 0) report_peers(&rp, &peer, &fx[orig]);
    if (orig >= 0) report_patches(&rp, &scenes[orig]);
    report_overshoot(&rp, scenes, ns);
    report_relight(&rp, &scenes[1]);
    report_parallel(&rp, scenes, ns, fx);
    if (orig >= 0) report_batch_k(&rp, &scenes[orig]);
    report_batch_speed(&rp, scenes, ns);
    report_large(&rp);
    report_textures(&rp, argv[0]);
    report_lightmap(&rp, orig >= 0 ? &scenes[orig] : NULL, shared);
    report_hall_coarse(&rp, &scenes[ns - 1]);
    report_cull(&rp);
    fputs(rp.md, stdout);
    write_docs(&rp);
    draw_plots(scenes, ns, fx);
    return 0;
}
