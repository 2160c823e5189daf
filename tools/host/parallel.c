/* rad host glue: the parallel solve (see parallel.h). Workers live for the whole
 * solve and wait for each shot by spinning on a shot counter, not by sleeping: a shot
 * takes well under a millisecond, and waking a sleeping thread on an idle core took as
 * long as the shot itself on our 2-core VMs (two threads started for each shot ran no
 * faster than one). A worker that cannot start has its part rendered by the calling
 * thread. The counters are GCC/clang __atomic builtins (acquire/release). */
#if defined(RAD_FLOAT) && RAD_FLOAT
#include "host/float_names.h"
#endif
#include "host/parallel.h"

#include <pthread.h>
#include <sched.h>
#include <stdlib.h>

#include "rad/rad.h"


#define MAX_THREADS 64

/* What the workers share: the shot to render (SHOT counts them; -1 tells the workers
 * to leave) and each part's buffer and the last shot it finished. */
typedef struct {
    const rad_scene_t *s;
    uint32_t patch;
    unsigned nparts;
    size_t bytes;
    void *bufs[MAX_THREADS];
    int done[MAX_THREADS];
    int shot;
} crew_t;

typedef struct {
    crew_t *crew;
    unsigned part;
} worker_t;

static int load(const int *p) { return __atomic_load_n(p, __ATOMIC_ACQUIRE); }
static void store(int *p, int v) { __atomic_store_n(p, v, __ATOMIC_RELEASE); }

static void render(crew_t *c, unsigned part)
{
    rad_shot_part(c->s, c->patch, part, c->nparts, c->bufs[part], c->bytes);
}

static void *work(void *arg)
{
    worker_t *w = arg;
    crew_t *c = w->crew;
    int seen = 0;
    for (;;) {
        int shot;
        while ((shot = load(&c->shot)) == seen) sched_yield();
        if (shot < 0) return NULL;
        seen = shot;
        render(c, w->part);
        store(&c->done[w->part], shot);
    }
}

int sc_solve_parallel(sc_solver *h, int threads, int max_shots, double tol, sc_progress_fn progress, void *ctx)
{
    rad_scene_t *s = sc_core(h);
    crew_t c;
    worker_t wk[MAX_THREADS];
    pthread_t tid[MAX_THREADS];
    int started[MAX_THREADS];
    rad_real_t t = RAD_REAL(tol);
    int k, shots = 0, ok = 1;

    if (threads < 1) threads = 1;
    if (threads > MAX_THREADS) threads = MAX_THREADS;
    if (s->band_rows != 0) return -1;
    sc_solve_started(h, tol);
    c.s = s;
    c.patch = 0;
    c.nparts = (unsigned)threads;
    c.bytes = RAD_PART_BYTES(s->cfg.res);
    c.shot = 0;
    for (k = 0; k < threads; k++) {
        c.bufs[k] = malloc(c.bytes);
        c.done[k] = 0;
        ok = ok && c.bufs[k];
    }
    for (k = 1; k < threads && ok; k++) {
        wk[k].crew = &c;
        wk[k].part = (unsigned)k;
        started[k] = pthread_create(&tid[k], NULL, work, &wk[k]) == 0;
    }
    while (ok && shots < max_shots && rad_shot_begin(s, t, &c.patch) == 1) {
        store(&c.shot, shots + 1);
        render(&c, 0);
        for (k = 1; k < threads; k++) {
            if (!started[k]) render(&c, (unsigned)k);
            else while (load(&c.done[k]) != shots + 1) sched_yield();
        }
        rad_shot_end(s, c.patch, c.bufs, (unsigned)threads);
        shots++;
        if (progress && progress(ctx, shots, RAD_TO_DOUBLE(rad_unshot_fraction(s)))) break;
    }
    if (ok) {
        store(&c.shot, -1);
        for (k = 1; k < threads; k++) if (started[k]) pthread_join(tid[k], NULL);
    }
    for (k = 0; k < threads; k++) free(c.bufs[k]);
    return ok ? shots : -1;
}
