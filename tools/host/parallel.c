/* SPDX-License-Identifier: MIT */
/* rad host glue: the parallel solve (see parallel.h). Each shot has two stages, run by
 * every thread on its own part: rendering a run of the hemi-cube's rows, then (after
 * the calling thread's rad_shot_aim) receiving for a run of the elements. Workers live
 * for the whole solve and wait for each stage by spinning on a stage counter, not by
 * sleeping: a shot takes well under a millisecond, and waking a sleeping thread on an
 * idle core took as long as the shot itself on our 2-core VMs (two threads started for
 * each shot ran no faster than one). Each stage's parts, one a thread, are claimed by
 * whichever thread is free first: on a busy machine a worker may not run for a whole
 * time slice, and the calling thread then does its part instead of waiting for it
 * (waiting made a solve ten times slower than one thread beside another job). Which
 * thread runs a part never changes its bits. A worker that cannot start leaves its
 * part to the others. The counters are GCC/clang __atomic builtins (acquire/release).
 *
 * The batch solve (sc_solve_batch) has two stages a batch, as a shot: rendering, whose
 * parts are the batch's whole hemi-cubes (rad_batch_render), then (after the calling
 * thread's rad_batch_aim) receiving, a run of whole patches' elements a thread
 * (rad_batch_receive_part). */
#if defined(RAD_FLOAT) && RAD_FLOAT
#include "host/float_names.h"
#endif
#include "host/parallel.h"

#include <pthread.h>
#include <sched.h>
#include <stdlib.h>

#include "rad/rad.h"

#define MAX_THREADS 64

/* What the workers share: the stage to run (STAGE counts them, odd to render, even
 * to receive; -1 tells the workers to leave), each part's buffer, and for the stage in
 * progress the next part to claim and the parts finished, each tagged with the stage
 * in its high 32 bits (so that a worker late from an earlier stage claims nothing). */
typedef struct {
    rad_scene_t *s;
    uint32_t patch;
    int batch;                       /* 1: a batch solve's stages */
    uint32_t patches[RAD_BATCH_MAX]; /* the batch's shooters (rad_batch_begin), */
    unsigned n;                      /* how many */
    unsigned nparts;
    size_t bytes;
    void *bufs[MAX_THREADS];
    int stage;
    uint64_t claim, finished;
} crew_t;

static int load(const int *p)
{
    return __atomic_load_n(p, __ATOMIC_ACQUIRE);
}
static void store(int *p, int v)
{
    __atomic_store_n(p, v, __ATOMIC_RELEASE);
}

/* Part PART's share of stage STAGE. */
static void run_stage(crew_t *c, int stage, unsigned part)
{
    if (c->batch && stage % 2)
        rad_batch_render(c->s, c->patches[part], part, c->bufs[part], c->bytes);
    else if (c->batch)
        rad_batch_receive_part(c->s, c->bufs, c->n, part, c->nparts);
    else if (stage % 2)
        rad_shot_part(c->s, c->patch, part, c->nparts, c->bufs[part], c->bytes);
    else
        rad_shot_receive_part(c->s, c->patch, c->bufs, c->nparts, part);
}

/* Parts of stage STAGE, claimed one by one until none is left, or until the stage is
 * over (CLAIM tagged with a later one). */
static void claim_parts(crew_t *c, int stage)
{
    const uint64_t tag = (uint64_t)(uint32_t)stage << 32;
    uint64_t t = __atomic_load_n(&c->claim, __ATOMIC_ACQUIRE);
    for (;;) {
        if ((t & ~0xFFFFFFFFull) != tag || (uint32_t)t >= c->nparts) return;
        if (__atomic_compare_exchange_n(&c->claim, &t, t + 1, 0, __ATOMIC_ACQ_REL,
                                        __ATOMIC_ACQUIRE)) {
            run_stage(c, stage, (unsigned)(uint32_t)t);
            __atomic_fetch_add(&c->finished, 1, __ATOMIC_RELEASE);
            t = __atomic_load_n(&c->claim, __ATOMIC_ACQUIRE);
        }
    }
}

static void *work(void *arg)
{
    crew_t *c = arg;
    int seen = 0;
    for (;;) {
        int stage;
        while ((stage = load(&c->stage)) == seen) sched_yield();
        if (stage < 0) return NULL;
        seen = stage;
        claim_parts(c, stage);
    }
}

/* Stage STAGE on every part, the calling thread claiming parts too, until every part
 * is finished: a part a worker has not claimed when the calling thread is free is the
 * calling thread's. */
static void stage_all(crew_t *c, int stage)
{
    const uint64_t tag = (uint64_t)(uint32_t)stage << 32;
    __atomic_store_n(&c->finished, tag, __ATOMIC_RELAXED);
    __atomic_store_n(&c->claim, tag, __ATOMIC_RELEASE);
    store(&c->stage, stage);
    claim_parts(c, stage);
    while (__atomic_load_n(&c->finished, __ATOMIC_ACQUIRE) != tag + c->nparts) sched_yield();
}

/* The crew of THREADS threads over the scene of H with NBUFS part buffers, BATCH
 * set: the workers started (STARTED), or 0 when a buffer cannot be had. */
static int crew_start(crew_t *c, sc_solver *h, int batch, int threads, int nbufs, pthread_t *tid,
                      int *started)
{
    int k, ok = 1;
    c->s = sc_core(h);
    c->patch = 0;
    c->batch = batch;
    c->nparts = (unsigned)nbufs;
    c->bytes = batch ? RAD_BATCH_BYTES(c->s->cfg.res, c->s->pools.max_elements)
                     : RAD_PART_BYTES(c->s->cfg.res);
    c->stage = 0;
    c->claim = c->finished = 0;
    for (k = 0; k < nbufs; k++) {
        c->bufs[k] = malloc(c->bytes);
        ok = ok && c->bufs[k];
    }
    for (k = 1; k < threads && ok; k++) started[k] = pthread_create(&tid[k], NULL, work, c) == 0;
    return ok;
}

/* Ends the crew crew_start began (OK: its return) and frees its buffers. */
static void crew_end(crew_t *c, int ok, int threads, int nbufs, pthread_t *tid, const int *started)
{
    int k;
    if (ok) {
        store(&c->stage, -1);
        for (k = 1; k < threads; k++)
            if (started[k]) pthread_join(tid[k], NULL);
    }
    for (k = 0; k < nbufs; k++) free(c->bufs[k]);
}

/* THREADS into 1..MAX_THREADS. */
static int clamp_threads(int threads)
{
    return threads < 1 ? 1 : threads > MAX_THREADS ? MAX_THREADS : threads;
}

int sc_solve_parallel(sc_solver *h, int threads, int max_shots, double tol, sc_progress_fn progress,
                      void *ctx)
{
    rad_scene_t *s = sc_core(h);
    crew_t c;
    pthread_t tid[MAX_THREADS];
    int started[MAX_THREADS];
    rad_real_t t = RAD_REAL(tol);
    int shots = 0, ok;

    threads = clamp_threads(threads);
    if (s->band_rows != 0) return -1;
    sc_solve_started(h, tol);
    ok = crew_start(&c, h, 0, threads, threads, tid, started);
    while (ok && shots < max_shots && rad_shot_begin(s, t, &c.patch) == 1) {
        stage_all(&c, 2 * shots + 1);
        rad_shot_aim(s, c.patch, c.bufs, c.nparts);
        stage_all(&c, 2 * shots + 2);
        rad_shot_end(s, c.patch, c.bufs, c.nparts);
        shots++;
        if (progress && progress(ctx, shots, RAD_TO_DOUBLE(rad_unshot_fraction(s)))) break;
    }
    crew_end(&c, ok, threads, threads, tid, started);
    return ok ? shots : -1;
}

int sc_solve_batch(sc_solver *h, int threads, int batch, int max_shots, double tol,
                   sc_progress_fn progress, void *ctx)
{
    rad_scene_t *s = sc_core(h);
    crew_t c;
    pthread_t tid[MAX_THREADS];
    int started[MAX_THREADS];
    rad_real_t t = RAD_REAL(tol);
    int shots = 0, stage = 0, n = 0, ok;

    threads = clamp_threads(threads);
    if (batch < 1 || batch > RAD_BATCH_MAX || s->band_rows != 0) return -1;
    sc_solve_started(h, tol);
    ok = crew_start(&c, h, 1, threads, batch, tid, started);
    while (ok && shots < max_shots) {
        /* the last batch is cut to end at MAX_SHOTS */
        unsigned k = (unsigned)(max_shots - shots < batch ? max_shots - shots : batch);
        if ((n = rad_batch_begin(s, t, k, c.patches)) <= 0) break;
        sc_solve_cull(h); /* the geometry is frozen now */
        c.n = c.nparts = (unsigned)n;
        stage_all(&c, ++stage);
        if ((n = rad_batch_aim(s, c.bufs, c.n)) < 0) break;
        c.nparts = c.n < (unsigned)threads ? c.n : (unsigned)threads;
        stage_all(&c, ++stage);
        if ((n = rad_batch_end(s, c.bufs, c.n)) < 0) break;
        shots += n;
        if (progress && progress(ctx, shots, RAD_TO_DOUBLE(rad_unshot_fraction(s)))) break;
    }
    crew_end(&c, ok, threads, batch, tid, started);
    return ok && n >= 0 ? shots : -1;
}
