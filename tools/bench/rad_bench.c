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
 *
 * The tables are in sections over the files bench.h lists; this file holds main, the
 * scenes and runs the sections share, and the report's small sections.
 */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench/bench.h"
#include "bench/level.h"
#include "bench/plot.h"
#include "host/clock.h"
#include "host/polys.h"
#include "reference/reference.h"

#define MAXPTS 200000

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
        if (r->shots[k] == 0 && unshot <= lim[k] + 1.0 / 65536) {
            r->shots[k] = shots;
            r->t[k] = t;
        }
    if (r->npts < MAXPTS) {
        r->xs[r->npts] = shots;
        r->xt[r->npts] = t;
        r->y[r->npts] = unshot;
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

static void *fx_create(const sc_poly *p, int n, const sc_opts *o, char *e, size_t l)
{
    return sc_create(p, n, o, NULL, NULL, e, l);
}
static int fx_solve(void *s, int m, double t, sc_progress_fn f, void *c)
{
    return sc_solve(s, m, t, f, c);
}
static void fx_stats(void *s, sc_stats *st)
{
    sc_get_stats(s, st);
}
static void fx_destroy(void *s)
{
    sc_destroy(s);
}
static void *fl_create(const sc_poly *p, int n, const sc_opts *o, char *e, size_t l)
{
    return scf_create(p, n, o, NULL, NULL, e, l);
}
static int fl_solve(void *s, int m, double t, sc_progress_fn f, void *c)
{
    return scf_solve(s, m, t, f, c);
}
static void fl_stats(void *s, sc_stats *st)
{
    scf_get_stats(s, st);
}
static void fl_destroy(void *s)
{
    scf_destroy(s);
}
static const build_t builds[2] = {{fx_create, fx_solve, fx_stats, fx_destroy},
                                  {fl_create, fl_solve, fl_stats, fl_destroy}};

static void run_alloc(brun *r)
{
    memset(r, 0, sizeof *r);
    r->xs = malloc(MAXPTS * sizeof *r->xs);
    r->xt = malloc(MAXPTS * sizeof *r->xt);
    r->y = malloc(MAXPTS * sizeof *r->y);
    if (!r->xs || !r->xt || !r->y) {
        fprintf(stderr, "rad_bench: out of memory\n");
        exit(1);
    }
}

static void run_free(brun *r)
{
    free(r->xs);
    free(r->xt);
    free(r->y);
}

static int cmp_d(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

void bench_sort(double *v, long n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_d);
}

double bench_median(double *v, int n)
{
    bench_sort(v, n);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* The scene's mesh and resolution as solver options. */
sc_opts bench_scene_opts(const bscene *sc)
{
    sc_opts o = {0};
    o.max_element = sc->max_element;
    o.max_patch = sc->max_patch;
    o.res = sc->res;
    return o;
}

/* A fixed-build solver of POLYS (the scene's, or a variant of them) with O; exits on
 * failure. */
sc_solver *bench_fixed_solver(const bscene *sc, const sc_poly *polys, const sc_opts *o)
{
    char err[256];
    sc_solver *s = sc_create(polys, sc->n, o, NULL, NULL, err, sizeof err);
    if (!s) {
        fprintf(stderr, "rad_bench: %s: %s\n", sc->name, err);
        exit(1);
    }
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
static void interleaved(const bscene *sc, const build_t *const *b, const sc_opts *o, int runs,
                        brun *out)
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
            if (!s[k]) {
                fprintf(stderr, "rad_bench: %s: %s\n", sc->name, err);
                exit(1);
            }
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
        double m = bench_median(tot[k], runs);
        int best = 0;
        for (j = 0; j < 3; j++)
            for (i = 0; i < runs; i++) ti[j][i] = r[k][i].t[j];
        for (i = 0; i < runs; i++)
            if (r[k][i].total == m) best = i;
        for (i = 0; i < runs; i++)
            if (i != best) run_free(&r[k][i]);
        out[k] = r[k][best];
        for (j = 0; j < 3; j++) out[k].t[j] = bench_median(ti[j], runs);
    }
}

/* One fixed-build solve of SC to 0.001, once (for the largest scene), into R. */
static void solo(const bscene *sc, brun *r)
{
    sc_opts o = bench_scene_opts(sc);
    prog_t pg;
    sc_stats st;
    double t0 = host_now();
    sc_solver *s = bench_fixed_solver(sc, sc->polys, &o);
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
static void run_pair(const bscene *sc, brun *out_fx, brun *out_fl)
{
    const build_t *b[2] = {&builds[0], &builds[1]};
    sc_opts o[2];
    brun out[2];
    o[0] = o[1] = bench_scene_opts(sc);
    interleaved(sc, b, o, sc->runs, out);
    *out_fx = out[0];
    *out_fl = out[1];
}

/* Fixed against float per element, solved to 0.001 (see ref_twin_diff). */
static void twin_accuracy(const bscene *sc, double *mx, double *rms)
{
    sc_opts o = bench_scene_opts(sc);
    char err[256];
    sc_solver *a = bench_fixed_solver(sc, sc->polys, &o);
    scf_solver *b = scf_create(sc->polys, sc->n, &o, NULL, NULL, err, sizeof err);
    if (!b) {
        fprintf(stderr, "rad_bench: %s\n", err);
        exit(1);
    }
    sc_solve(a, 1000000, 0.001, NULL, NULL);
    scf_solve(b, 1000000, 0.001, NULL, NULL);
    ref_twin_diff(a, b, mx, rms);
    sc_destroy(a);
    scf_destroy(b);
}

/* ---- patch size: shots against accuracy ------------------------------------------- */

int bench_poly_emits(const sc_poly *p)
{
    return p->emit[0] + p->emit[1] + p->emit[2] > 0;
}

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
    for (i = 0; i < sc->n; i++)
        if (sc->polys[i].tag + 1 > ntag) ntag = sc->polys[i].tag + 1;
    ma = malloc((size_t)ntag * sizeof *ma);
    mb = malloc((size_t)ntag * sizeof *mb);
    emits = calloc((size_t)ntag, 1);
    if (!ma || !mb || !emits) exit(1);
    for (i = 0; i < sc->n; i++)
        if (bench_poly_emits(&sc->polys[i])) emits[sc->polys[i].tag] = 1;
    face_means(a, ntag, ma);
    face_means(b, ntag, mb);
    for (t = 0; t < ntag; t++)
        if (!emits[t] && ma[t] > top) top = ma[t];
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
    free(ma);
    free(mb);
    free(emits);
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
    sc_opts o = bench_scene_opts(sc);
    sc_solver *s;
    sc_stats st;
    double t0;
    o.max_patch = max_patch;
    s = bench_fixed_solver(sc, sc->polys, &o);
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
    sc_opts o = bench_scene_opts(sc);
    char err[256];
    sc_solver *s = bench_fixed_solver(sc, sc->polys, &o), *f;
    sc_rows_stats rs;
    sc_stats st;
    sc_poly *q;
    double t0;
    int i;
    t0 = host_now();
    if (sc_rows_compute(s, NULL, NULL, err, sizeof err) < 0) {
        fprintf(stderr, "rad_bench: %s\n", err);
        exit(1);
    }
    r->t_rows = host_now() - t0;
    sc_get_rows_stats(s, &rs);
    r->rows = rs.rows;
    r->entries = rs.entries;
    r->bytes = rs.bytes;
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
    r->patches = st.patches;
    r->elements = st.elements;
    /* The same new light from scratch: meshing and a hemi-cube per shot. */
    q = malloc((size_t)sc->n * sizeof *q);
    if (!q) exit(1);
    memcpy(q, sc->polys, (size_t)sc->n * sizeof *q);
    for (i = 0; i < sc->n; i++)
        if (bench_poly_emits(&q[i])) memcpy(q[i].emit, blue, sizeof blue);
    t0 = host_now();
    f = bench_fixed_solver(sc, q, &o);
    r->fresh_shots = sc_solve(f, 1000000, 0.001, NULL, NULL);
    r->t_fresh = host_now() - t0;
    sc_destroy(f);
    sc_destroy(s);
    free(q);
}

/* ---- scenes -------------------------------------------------------------------- */

/* The polygons of the OBJ file PATH, its scene kept in KEEP (or freed: NULL). */
sc_poly *bench_load_obj(const char *path, int *n, obj_scene *keep)
{
    obj_scene sc;
    char err[512];
    sc_poly *p;
    if (obj_load(path, &sc, NULL, NULL, err, sizeof err) < 0) return NULL;
    p = polys_from_obj(&sc, n, NULL, NULL);
    if (keep)
        *keep = sc;
    else
        obj_free(&sc);
    return p;
}

void bench_add_quad(sc_poly *p, int *n, const double v[4][3], const double rho[3],
                    const double em[3])
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
void bench_add_box(sc_poly *p, int *n, const double lo[3], const double hi[3], int inward, int skip,
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
        bench_add_quad(p, n, (const double(*)[3])v, rho, zero);
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
    bench_add_box(p, n, lo, hi, 1, -1, white);
    for (i = 0; i < 4; i++)
        for (j = 0; j < 3; j++) {
            double a[3] = {-6.5 + 3.6 * i, 0, -4.5 + 3.5 * j}, b[3];
            b[0] = a[0] + (j == 1 ? 0.8 : 1.6);
            b[1] = j == 1 ? 1.9 : 0.75;
            b[2] = a[2] + (j == 1 ? 0.6 : 1.0);
            bench_add_box(p, n, a, b, 0, 2, j == 1 ? blue : wood); /* no bottom */
        }
    for (i = 0; i < 3; i++)
        for (j = 0; j < 2; j++) {
            double v[4][3] = {{-5.5 + 5 * i, 2.99, -3.5 + 6 * j},
                              {-4.5 + 5 * i, 2.99, -3.5 + 6 * j},
                              {-4.5 + 5 * i, 2.99, -2.5 + 6 * j},
                              {-5.5 + 5 * i, 2.99, -2.5 + 6 * j}};
            bench_add_quad(p, n, (const double(*)[3])v, white, lamp);
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
    o[0] = o[1] = bench_scene_opts(sc);
    o[0].no_overshoot = 1;
    interleaved(sc, b, o, 3, c->run);
    ref = bench_fixed_solver(sc, sc->polys, &o[1]);
    sc_solve(ref, 1000000, 1e-5, NULL, NULL);
    for (k = 0; k < 2; k++) {
        sc_solver *s = bench_fixed_solver(sc, sc->polys, &o[k]);
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

void bench_out(report_t *rp, const char *fmt, ...)
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
    sc_poly *cb = bench_load_obj("examples/cornell_box.obj", &ncb, &box), *p;
    if (!cb) {
        fprintf(stderr, "rad_bench: run from the repository root (examples/cornell_box.obj)\n");
        return 0;
    }
    for (k = 0; k < 3; k++) {
        scenes[ns].name = nm[k];
        scenes[ns].polys = cb;
        scenes[ns].n = ncb;
        scenes[ns].obj = &box;
        scenes[ns].max_element = me[k];
        scenes[ns].res = 128;
        scenes[ns].runs = 3;
        scenes[ns].big = k == 2;
        ns++;
    }
    p = bench_load_obj(shared, &n, NULL);
    if (p) {
        /* Element edge 0.08 (of about 2 across): over the 4,000 elements of the peers. */
        scenes[ns].name = "CornellBox-Original (shared)";
        scenes[ns].polys = p;
        scenes[ns].n = n;
        scenes[ns].max_element = 0.08;
        scenes[ns].res = 128;
        scenes[ns].runs = 5;
        ns++;
    } else {
        fprintf(stderr, "rad_bench: %s not found: the peer comparison is skipped\n", shared);
    }
    p = gen_hall(&n);
    if (!p) return 0;
    scenes[ns].name = "generated hall (12 pieces of furniture, 6 lights)";
    scenes[ns].polys = p;
    scenes[ns].n = n;
    scenes[ns].max_element = 0.175;
    scenes[ns].res = 128;
    scenes[ns].runs = 3;
    scenes[ns].big = 1;
    return ns + 1;
}

static void report_speed(report_t *rp, const bscene *scenes, int ns, const brun *fx, const brun *fl)
{
    int i, k;
    bench_out(rp, "Solve to an unshot fraction of 0.001 at hemi-cube resolution 128, one core; "
                  "times are medians of "
                  "3 runs (5 for CornellBox-Original) in one process, the two builds solved side "
                  "by side, one shot of each "
                  "in turn, so that both see the same machine. fixed/float is the ratio of the two "
                  "builds' times: below 1 "
                  "the fixed build is faster.\n\n");
    bench_out(rp, "| scene | elements | patches | build | shots to 0.1 / 0.01 / 0.001 | s to 0.01 "
                  "| s to 0.001 | ms "
                  "per shot | Mpixel/s | memory KB |\n| --- | ---: | ---: | --- | --- | ---: | "
                  "---: | ---: | ---: | ---: |\n");
    for (i = 0; i < ns; i++) {
        for (k = 0; k < 2; k++) {
            const brun *r = k ? &fl[i] : &fx[i];
            char sh[64];
            fmt_shots(sh, sizeof sh, r);
            bench_out(rp, "| %s | %d | %d | %s | %s | %.3f | %.3f | %.3f | %.1f | %zu |\n",
                      k ? "" : scenes[i].name, r->elements, r->patches, k ? "float" : "fixed", sh,
                      r->t[1], r->total, 1000 * r->total / (r->all_shots ? r->all_shots : 1),
                      r->pix_per_s / 1e6, r->bytes / 1024);
        }
        bench_out(rp, "| | | | fixed/float | | %.2f | %.2f | | | |\n", fx[i].t[1] / fl[i].t[1],
                  fx[i].total / fl[i].total);
    }
}

static void report_twin(report_t *rp, const bscene *scenes, int ns, const double *amax,
                        const double *arms)
{
    int i;
    bench_out(rp,
              "\nFixed against the float twin, per element (with the ambient term), over elements "
              "above 1%% of the "
              "brightest:\n\n| scene | max relative difference | rms |\n| --- | ---: | ---: |\n");
    for (i = 0; i < ns; i++)
        bench_out(rp, "| %s | %.3f%% | %.3f%% |\n", scenes[i].name, 100 * amax[i], 100 * arms[i]);
}

static void report_hemicube(report_t *rp)
{
    static const int res[4] = {32, 64, 128, 256};
    int k;
    bench_out(rp, "\nHemi-cube form factors against Lambert's contour formula (7 unoccluded "
                  "receivers: parallel, "
                  "offset, perpendicular, tilted, large, grazing, triangle), fixed build:\n\n| "
                  "resolution | mean error | max "
                  "error |\n| ---: | ---: | ---: |\n");
    for (k = 0; k < 4; k++) {
        double sum = 0, mx = 0;
        int r;
        for (r = 0; r < REF_RECEIVERS; r++) {
            double want, got = ref_hemicube_ff(r, res[k], 0, &want), e = fabs(got / want - 1);
            sum += e;
            if (e > mx) mx = e;
        }
        bench_out(rp, "| %d | %.3f%% | %.3f%% |\n", res[k], 100 * sum / REF_RECEIVERS, 100 * mx);
    }
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
    bench_out(rp, "\nPatch size on CornellBox-Original (element edge 0.08, res 128, fixed build): "
                  "shooters larger than "
                  "the elements they group (Cohen et al. 1986) cut the shots, at a price in "
                  "accuracy: a patch shoots "
                  "from its centre, so surfaces close to a large patch (the blocks on the floor) "
                  "get the light of one "
                  "point. Solved to 0.001 and compared with every element shooting for itself "
                  "(first row); the meshes "
                  "differ, so the comparison is of each non-emitting OBJ face's mean "
                  "radiosity:\n\n| patch edge | "
                  "patches | elements | shots to 0.01 | s to 0.01 | max face difference | rms face "
                  "difference |\n"
                  "| ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for (k = 0; k < 5; k++) {
        char w[32] = "reference", r[32] = "reference", e[32] = "default (1/8 of the extent)";
        if (k) {
            snprintf(w, sizeof w, "%.2f%%", 100 * t[k].worst);
            snprintf(r, sizeof r, "%.2f%%", 100 * t[k].rms);
        }
        if (t[k].max_patch > 0) snprintf(e, sizeof e, "%.2f", t[k].max_patch);
        bench_out(rp, "| %s | %d | %d | %d | %.3f | %s | %s |\n", e, t[k].patches, t[k].elements,
                  t[k].shots, t[k].secs, w, r);
    }
}

/* Overshooting against plain progressive refinement. */
static void report_overshoot(report_t *rp, const bscene *scenes, int ns)
{
    int i, k;
    bench_out(
        rp,
        "\nOvershooting (the default; Feda & Purgathofer 1992) against plain progressive "
        "refinement (Cohen "
        "et al. 1988, `--no-overshoot`), fixed build, res 128, median of 3 runs, the two shot by "
        "shot; the last two "
        "columns are the solution at 0.01 (with the ambient term) against one converged to 1e-5, "
        "per element above 1%% "
        "of the brightest:\n\n| scene | elements | shooting | shots to 0.1 / 0.01 / 0.001 | s to "
        "0.01 | s to 0.001 | "
        "max difference at 0.01 | rms |\n| --- | ---: | --- | --- | ---: | ---: | ---: | ---: |\n");
    for (i = 0; i < ns; i++) {
        shootcmp_t c;
        if (scenes[i].big) continue; /* too long to repeat */
        fprintf(stderr, "rad_bench: overshooting on %s ...\n", scenes[i].name);
        overshoot_bench(&scenes[i], &c);
        for (k = 0; k < 2; k++) {
            char sh[64];
            fmt_shots(sh, sizeof sh, &c.run[k]);
            bench_out(rp, "| %s | %d | %s | %s | %.3f | %.3f | %.2f%% | %.2f%% |\n",
                      k ? "" : scenes[i].name, c.run[k].elements, k ? "overshooting" : "plain", sh,
                      c.run[k].t[1], c.run[k].total, 100 * c.worst[k], 100 * c.rms[k]);
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
    bench_out(rp,
              "\nStored form factors on %s (%d elements, %d patches, res 128, fixed build): every "
              "patch's row "
              "rendered once in %.3f s, %lu entries in %zu bytes (%.1f KB per patch). From the "
              "rows, no hemi-cube: "
              "progressive shooting to 0.001 %.3f s; the 1985 full-matrix Gauss-Seidel solve %d "
              "sweeps to 0.001 in "
              "%.3f s (matrix %zu KB). A new light colour, re-solved from the rows in %.3f s (%d "
              "shots) against "
              "%.3f s (%d shots) for a fresh mesh and hemi-cube solve: %.0f times faster.\n",
              sc->name, rl.elements, rl.patches, rl.t_rows, rl.entries, rl.bytes,
              rl.bytes / 1024.0 / rl.rows, rl.t_rows_shoot, rl.sweeps, rl.t_gs,
              rl.matrix_bytes / 1024, rl.t_relight, rl.relight_shots, rl.t_fresh, rl.fresh_shots,
              rl.t_fresh / rl.t_relight);
}

/* The generated hall meshed to over 100,000 elements into *SC (its polygons the
 * caller's to free). */
static void fine_hall(bscene *sc)
{
    memset(sc, 0, sizeof *sc);
    sc->name = "generated hall, fine";
    sc->polys = gen_hall(&sc->n);
    if (!sc->polys) exit(1);
    /* Element edge 0.078: 110,646 elements (the hall's 0.175 gives 23,384). */
    sc->max_element = 0.078;
    sc->res = 128;
    sc->big = 1;
}

/* The fine hall solved once (fixed build). */
static void report_large(report_t *rp, const bscene *fine)
{
    bscene sc = *fine;
    brun r;
    char sh[64];
    fprintf(stderr, "rad_bench: %s ...\n", sc.name);
    solo(&sc, &r);
    if (r.elements < 100000)
        fprintf(stderr, "rad_bench: warning: the fine hall has %d elements, fewer than 100,000\n",
                r.elements);
    fmt_shots(sh, sizeof sh, &r);
    bench_out(rp,
              "\nA large scene: the generated hall meshed finer, solved once (fixed build, res "
              "128, one core); "
              "memory is the core's pools and work buffer, all it uses:\n\n| scene | elements | "
              "patches | meshing s | "
              "shots to 0.1 / 0.01 / 0.001 | s to 0.01 | s to 0.001 | ms per shot | memory MB |\n"
              "| --- | ---: | ---: | ---: | --- | ---: | ---: | ---: | ---: |\n");
    bench_out(rp, "| %s | %d | %d | %.3f | %s | %.2f | %.2f | %.3f | %.2f |\n", sc.name, r.elements,
              r.patches, r.mesh, sh, r.t[1], r.total,
              1000 * r.total / (r.all_shots ? r.all_shots : 1), r.bytes / 1048576.0);
    run_free(&r);
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
    sc_opts o[3], r512 = bench_scene_opts(sc);
    brun run[2][2];
    double rms[3][2], mx[3][2];
    sc_solver *ref;
    int k;
    fprintf(stderr, "rad_bench: coarse shots on the hall ...\n");
    o[0] = bench_scene_opts(sc);
    for (k = 0; k < 2; k++) {
        sc_opts pair[2];
        o[k + 1] = bench_row_opts(o[0], &bench_peer_rows[rows[k]]);
        pair[0] = o[0];
        pair[1] = o[k + 1];
        interleaved(sc, b, pair, sc->runs, run[k]);
    }
    r512.res = 512;
    ref = bench_solved(sc, &r512, 1e-4);
    for (k = 0; k < 3; k++) {
        sc_solver *a = bench_solved(sc, &o[k], 0.001);
        bench_element_accuracy(sc, ref, a, floor, rms[k], mx[k]);
        sc_destroy(a);
    }
    sc_destroy(ref);
    bench_out(rp,
              "\nCoarse shots on the generated hall (%d elements, %d patches), fixed build, one "
              "core: every shot "
              "at res 128 (`--res 128 --coarse 0`) against rad_cli's defaults and against `--res "
              "256 --coarse 2`, each "
              "pair solved side by side to 0.001 in this process, one shot of each in turn, median "
              "of %d (time / res "
              "128 is that pair's ratio); accuracy per element against a res-512 solve to 1e-4 of "
              "the same mesh, as in "
              "the peer table:\n\n"
              "| settings | shots | s to 0.001 | time / res 128 | pools + work MB | accuracy "
              ">10%%: rms / max | "
              ">1%%: rms / max |\n| --- | ---: | ---: | ---: | ---: | ---: | ---: |\n",
              run[0][0].elements, run[0][0].patches, sc->runs);
    for (k = 0; k < 3; k++) {
        const brun *r = k ? &run[k - 1][1] : &run[0][0];
        bench_out(rp, "| %s | %d | %.3f | %.2f | %.2f | %.2f%% / %.2f%% | %.2f%% / %.2f%% |\n",
                  k == 0   ? "`--res 128 --coarse 0`"
                  : k == 1 ? "rad_cli's defaults (res 192, coarse 1)"
                           : "`--res 256 --coarse 2`",
                  r->all_shots, r->total, k ? r->total / run[k - 1][0].total : 1.0,
                  r->bytes / 1048576.0, 100 * rms[k][0], 100 * mx[k][0], 100 * rms[k][1],
                  100 * mx[k][1]);
    }
    for (k = 0; k < 4; k++) run_free(&run[k / 2][k % 2]);
}

/* docs/bench.md's part between the markers of SECTION ("<!-- SECTION:begin -->" and
 * ":end"), regenerated: the page's own text around them stays, and the file is replaced
 * whole (a temporary beside it, renamed) or, on any error, left as it was with a line
 * on stderr saying why. */
static void write_docs(const report_t *rp, const char *section)
{
    static const char path[] = "docs/bench.md", tmp[] = "docs/bench.md.tmp";
    static char buf[1 << 20];
    char begin[64], end[64];
    FILE *r = fopen(path, "r"), *w;
    size_t n = r ? fread(buf, 1, sizeof buf - 1, r) : 0;
    char *a, *b;
    int ok;
    snprintf(begin, sizeof begin, "<!-- %s:begin -->\n", section);
    snprintf(end, sizeof end, "<!-- %s:end -->", section);
    if (!r || ferror(r) || n == sizeof buf - 1) {
        fprintf(stderr, "rad_bench: %s: %s; the report is on standard output only\n", path,
                !r                    ? strerror(errno)
                : n == sizeof buf - 1 ? "larger than 1 MiB"
                                      : "read error");
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
    static const unsigned char col[6][3] = {{200, 30, 30},  {30, 120, 200}, {30, 160, 60},
                                            {150, 60, 170}, {220, 140, 0},  {90, 90, 90}};
    plot_series ser[8];
    plot_opts po;
    char err[256];
    int i;
    for (i = 0; i < ns; i++) {
        ser[i].label = scenes[i].name;
        ser[i].x = fx[i].xs;
        ser[i].y = fx[i].y;
        ser[i].n = fx[i].npts;
        memcpy(ser[i].rgb, col[i % 6], 3);
    }
    memset(&po, 0, sizeof po);
    po.title = "Progressive refinement, fixed build, res 128";
    po.xlabel = "shots";
    po.ylabel = "unshot fraction";
    po.log_y = 1;
    po.width = 800;
    po.height = 500;
    if (plot_write("docs/convergence_shots.png", ser, ns, &po, err, sizeof err) < 0)
        fprintf(stderr, "%s\n", err);
    for (i = 0; i < ns; i++) ser[i].x = fx[i].xt;
    po.xlabel = "seconds";
    if (plot_write("docs/convergence_time.png", ser, ns, &po, err, sizeof err) < 0)
        fprintf(stderr, "%s\n", err);
}

/* Index of the scene named NAME, or -1. */
static int scene_named(const bscene *scenes, int ns, const char *name)
{
    int i;
    for (i = 0; i < ns; i++)
        if (strcmp(scenes[i].name, name) == 0) return i;
    return -1;
}

/* The batch tables: K against K = 1 on CornellBox-Original (when loaded), and the
 * speed on threads over SCENES[0..NS) and the fine hall, put at SCENES[NS]. */
static void report_batch(report_t *rp, bscene *scenes, int ns)
{
    int orig = scene_named(scenes, ns, "CornellBox-Original (shared)");
    fine_hall(&scenes[ns]);
    if (orig >= 0) bench_report_batch_k(rp, &scenes[orig]);
    bench_report_batch_speed(rp, scenes, ns + 1);
}

int main(int argc, char **argv)
{
    static bscene scenes[8];
    static brun fx[8], fl[8];
    static report_t rp;
    static peer_t peer;
    double amax[8], arms[8];
    int ns, i, orig;

    static const char shared_default[] = "../shared/scenes/CornellBox-Original.obj";
    const char *shared = argc > 1 ? argv[1] : shared_default;

    if (argc > 1 && strcmp(argv[1], "--cull") == 0) { /* this report alone, printed */
        bench_report_cull(&rp);
        fputs(rp.md, stdout);
        return 0;
    }
    if (argc > 1 && strcmp(argv[1], "--level") == 0) return bench_level(argc, argv);
    if (argc > 1 && strcmp(argv[1], "--curve") == 0) { /* the cost curve, into docs/bench.md */
        static curve_t cv;
        int rounds = argc > 2 ? atoi(argv[2]) : 3;
        if (rounds < 1 || rounds > CURVE_ROUNDS) {
            fprintf(stderr, "rad_bench: --curve ROUNDS: 1 to %d\n", CURVE_ROUNDS);
            return 2;
        }
        bench_curve(argv[0], argc > 3 ? argv[3] : shared_default, rounds, &cv);
        bench_report_curve(&rp, &cv, "docs/cost_curve.png");
        fputs(rp.md, stdout);
        if (!cv.why[0]) write_docs(&rp, "curve");
        return cv.why[0] ? 1 : 0;
    }
    if (argc > 2 && strcmp(argv[1], "--write-level") == 0) { /* make readme-image's scene */
        char err[512];
        if (level_write(argv[2], err, sizeof err) == 0) return 0;
        fprintf(stderr, "rad_bench: %s\n", err);
        return 1;
    }
    if (argc > 1 && strcmp(argv[1], "--gather-res") == 0) return bench_gather_res(argc, argv);
    if (argc > 1 && strcmp(argv[1], "--batch") == 0) { /* the batch tables alone, printed */
        if (!(ns = load_scenes(argc > 2 ? argv[2] : shared_default, scenes))) return 1;
        report_batch(&rp, scenes, ns);
        fputs(rp.md, stdout);
        return 0;
    }

    /* First, while this process is small: a child's peak memory starts at its parent's
     * at fork (Linux keeps the high-water mark across exec). */
    bench_peer(argv[0], shared, &peer);
    if (!peer.why[0]) bench_peer_accuracy(shared, &peer);
    ns = load_scenes(shared, scenes);
    if (!ns) return 1;
    for (i = 0; i < ns; i++) {
        fprintf(stderr, "rad_bench: %s ...\n", scenes[i].name);
        run_pair(&scenes[i], &fx[i], &fl[i]);
        twin_accuracy(&scenes[i], &amax[i], &arms[i]);
    }
    if (fx[ns - 1].elements < 20000)
        fprintf(stderr,
                "rad_bench: warning: the generated scene has %d elements, fewer than the 20,000 "
                "asked for\n",
                fx[ns - 1].elements);
    orig = scene_named(scenes, ns, "CornellBox-Original (shared)");
    report_speed(&rp, scenes, ns, fx, fl);
    report_twin(&rp, scenes, ns, amax, arms);
    report_hemicube(&rp);
    if (orig >= 0) bench_report_peers(&rp, &peer, &fx[orig]);
    if (orig >= 0) report_patches(&rp, &scenes[orig]);
    report_overshoot(&rp, scenes, ns);
    report_relight(&rp, &scenes[1]);
    bench_report_parallel(&rp, scenes, ns, fx);
    report_batch(&rp, scenes, ns);
    report_large(&rp, &scenes[ns]);
    bench_report_textures(&rp, argv[0]);
    bench_report_lightmap(&rp, orig >= 0 ? &scenes[orig] : NULL, shared);
    report_hall_coarse(&rp, &scenes[ns - 1]);
    bench_report_cull(&rp);
    fputs(rp.md, stdout);
    write_docs(&rp, "bench");
    draw_plots(scenes, ns, fx);
    return 0;
}
