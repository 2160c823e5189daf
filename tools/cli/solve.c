/* SPDX-License-Identifier: MIT */
/* rad_cli's solves: shooting, or visibility once (the rows) and then shooting or
 * Gauss-Seidel from the rows, each light group alone; their progress (progress.h).
 */
#include "cli.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "host/clock.h"
#include "host/polys.h"
#include "host/parallel.h"
#include "progress.h"

#define GS_MAX_SWEEPS 1000

/* The core compares the unshot fraction with --tol rounded to its own format: in the
 * fixed build Q16.16, to the nearest 2^-16, so a fraction up to half a step above F may
 * be the core's F; in the float build to the nearest float, half an ulp (2^-24 of F). */
#if defined(RAD_FLOAT) && RAD_FLOAT
#define TOL_SLACK(f) ((f) / 16777216.0)
#else
#define TOL_SLACK(f) (0.5 / 65536.0)
#endif

/* The solve's progress: the unshot fraction on a log scale, from 1 (nothing shot) down
 * to the tolerance. */
typedef struct {
    progress_t p;
    double tol;
} solve_progress;

static int progress(void *ctx, int shots, double unshot)
{
    solve_progress *sp = ctx;
    char detail[96];
    snprintf(detail, sizeof detail, "shots %d  unshot %.5f", shots, unshot);
    progress_update(&sp->p, unshot > 0 && sp->tol > 0 ? log(unshot) / log(sp->tol) : 1.0, detail);
    return 0;
}

static int rows_progress(void *ctx, int rows, int total)
{
    solve_progress *sp = ctx;
    char detail[64];
    snprintf(detail, sizeof detail, "rows %d/%d", rows, total);
    progress_update(&sp->p, total ? (double)rows / total : 1.0, detail);
    return 0;
}

static void progress_start(solve_progress *pg, const opts_t *o, const char *what)
{
    progress_begin(&pg->p, what, o->quiet);
    pg->tol = o->tol;
}

/* A progressive solve of SHOTS shots that stopped at --max-shots above --tol. */
static void check_converged(run_t *r, int shots)
{
    sc_stats st;
    sc_get_stats(r->s, &st);
    if (shots >= r->o->max_shots && st.unshot > r->o->tol + TOL_SLACK(r->o->tol)) r->unconverged++;
}

/* Shooting with hemi-cubes: in batches whose cubes render on the threads, or, one shot
 * at a time, threads split each shot's cube by rows: the same bits for any threads. */
static void solve_shoot(run_t *r, solve_progress *pg)
{
    const opts_t *o = r->o;
    int shots = -1;
    /* a lightmap painted from the elements keeps their light apart from the lights'
     * direct light (bake.c; without memory for it, the texels are gathered) */
    if (o->lightmap && o->lightmap_soft == LIGHTMAP_SOFT_ELEMENTS)
        r->soft_kept = sc_solve_lights(r->s, SC_SKIES) == 0;
    if (o->batch >= 2)
        shots = sc_solve_batch(r->s, o->threads, o->batch, o->max_shots, o->tol, progress, pg);
    else if (o->threads >= 2)
        shots = sc_solve_parallel(r->s, o->threads, o->max_shots, o->tol, progress, pg);
    if (shots < 0) shots = sc_solve(r->s, o->max_shots, o->tol, progress, pg);
    r->work = shots;
    check_converged(r, shots);
}

/* Solves from the rows with the chosen solver; returns shots or sweeps, or -1. */
static int solve_rows(run_t *r, solve_progress *pg)
{
    const opts_t *o = r->o;
    char err[512];
    int n;
    if (!o->gauss_seidel) {
        n = sc_rows_solve(r->s, o->max_shots, o->tol, progress, pg);
        check_converged(r, n);
        return n;
    }
    n = sc_rows_gauss_seidel(r->s, GS_MAX_SWEEPS, o->tol, err, sizeof err);
    if (n < 0) fprintf(stderr, PROG ": %s: %s\n", o->scene, err);
    if (n >= GS_MAX_SWEEPS) r->unconverged++;
    return n;
}

/* Visibility once: every patch's row, loaded or rendered (then saved). */
static int rows_step(run_t *r, solve_progress *pg)
{
    const opts_t *o = r->o;
    char err[1024];
    int rc = o->gauss_seidel && sc_gauss_seidel_check(r->s, err, sizeof err) < 0
                 ? -1 /* before any row */
             : o->load_ff ? sc_rows_load(r->s, o->load_ff, err, sizeof err)
                          : sc_rows_compute(r->s, rows_progress, pg, err, sizeof err);
    progress_end(&pg->p);
    if (rc < 0) {
        fprintf(stderr, PROG ": %s%s%s\n", o->load_ff ? "" : o->scene, o->load_ff ? "" : ": ", err);
        return -1;
    }
    if (o->save_ff && sc_rows_save(r->s, o->save_ff, err, sizeof err) < 0) {
        fprintf(stderr, PROG ": %s\n", err);
        return -1;
    }
    return 0;
}

int cli_mix_groups(run_t *r, sc_solution *const *sol, const double (*k)[3], int n)
{
    char err[256];
    if (sc_mix(r->s, sol, k, n, err, sizeof err) < 0) {
        fprintf(stderr, PROG ": %s\n", err);
        return -1;
    }
    return 0;
}

/* Group G's emitters and lights lit, every other emitter and light dark. */
static int light_group(run_t *r, int g)
{
    static const double dark[3] = {0, 0, 0};
    const obj_scene *sc = &r->sc;
    char err[512];
    int m;
    for (m = 0; m < r->nlights; m++) {
        const sc_light *l = &r->lights[m];
        int lit = r->light_group_of[m] == g;
        if (sc_set_light(r->s, m, lit ? l->rgb : dark, lit ? l->horizon : dark, err, sizeof err) <
            0) {
            fprintf(stderr, PROG ": %s: %s\n", r->o->scene, err);
            return -1;
        }
    }
    for (m = 0; m < sc->nmaterials; m++) {
        polys_material_match mm;
        if (r->group_of[m] < 0) continue;
        mm.sc = sc;
        mm.material = m;
        if (sc_set_surfaces(r->s, polys_match_material, &mm, NULL,
                            r->group_of[m] == g ? sc->materials[m].ke : dark, err,
                            sizeof err) < 0) {
            fprintf(stderr, PROG ": %s: %s: %s\n", r->o->scene, sc->materials[m].name, err);
            return -1;
        }
    }
    return 0;
}

/* Each group alone (the other emitters dark), kept aside, then the run's mix. */
static int solve_groups(run_t *r, solve_progress *pg)
{
    const opts_t *o = r->o;
    int g, n = o->ngroups ? o->ngroups : 1;
    r->sol = calloc((size_t)n, sizeof *r->sol);
    r->ks = calloc((size_t)n, sizeof *r->ks);
    if (!r->sol || !r->ks) {
        fprintf(stderr, PROG ": out of memory\n");
        return -1;
    }
    for (g = 0; g < o->ngroups; g++) {
        int k;
        if (light_group(r, g) < 0 || (k = solve_rows(r, pg)) < 0) return -1;
        r->work += k;
        r->sol[g] = sc_keep(r->s, r->ambient);
        if (!r->sol[g]) {
            fprintf(stderr, PROG ": out of memory\n");
            return -1;
        }
        memcpy(r->ks[g], o->groups[g].k, sizeof r->ks[g]);
    }
    return cli_mix_groups(r, r->sol, (const double(*)[3])r->ks, o->ngroups);
}

int cli_solve_step(run_t *r)
{
    solve_progress pg;
    int rc = 0;
    double t0 = host_now();
    progress_start(&pg, r->o, r->rows_mode ? "form factors" : "solving");
    if (!r->rows_mode) {
        solve_shoot(r, &pg);
    } else {
        if (rows_step(r, &pg) < 0) return -1;
        sc_get_stats(r->s, &r->st);
        r->raster_before_solve = r->st.raster_calls;
        r->t_rows = host_now() - t0;
        progress_start(&pg, r->o, "solving");
        if (!r->groups_mode)
            rc = (r->work = solve_rows(r, &pg)) < 0 ? -1 : 0;
        else
            rc = solve_groups(r, &pg);
    }
    progress_end(&pg.p);
    r->t_solve = host_now();
    sc_get_stats(r->s, &r->st);
    return rc;
}
