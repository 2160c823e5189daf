/* rad host glue: the parallel solve (see parallel.h). Threads are started for each
 * shot and joined before it is merged: simple and robust (a thread that cannot start
 * has its part rendered by the calling thread), at a cost of tens of microseconds a
 * shot against the shot's hundreds. */
#include "parallel.h"

#include <pthread.h>
#include <stdlib.h>

#include "rad/rad.h"

#if RAD_FLOAT
#define SC(x) scf_##x
#else
#define SC(x) sc_##x
#endif

#define MAX_THREADS 64

typedef struct {
    const rad_scene_t *s;
    uint32_t patch;
    unsigned part, nparts;
    void *buf;
    size_t bytes;
} job_t;

static void *run(void *arg)
{
    job_t *j = arg;
    rad_shot_part(j->s, j->patch, j->part, j->nparts, j->buf, j->bytes);
    return NULL;
}

int SC(solve_parallel)(SC(solver) *h, int threads, int max_shots, double tol, sc_progress_fn progress, void *ctx)
{
    rad_scene_t *s = SC(core)(h);
    void *bufs[MAX_THREADS];
    job_t job[MAX_THREADS];
    pthread_t tid[MAX_THREADS];
    int started[MAX_THREADS];
    rad_real_t t = RAD_REAL(tol);
    size_t bytes;
    uint32_t patch;
    int k, shots = 0, ok = 1;

    if (threads < 1) threads = 1;
    if (threads > MAX_THREADS) threads = MAX_THREADS;
    if (s->band_rows != 0) return -1;
    bytes = RAD_PART_BYTES(s->cfg.res);
    for (k = 0; k < threads; k++) {
        bufs[k] = malloc(bytes);
        ok = ok && bufs[k];
    }
    while (ok && shots < max_shots && rad_shot_begin(s, t, &patch) == 1) {
        for (k = 0; k < threads; k++) {
            job[k].s = s; job[k].patch = patch; job[k].part = (unsigned)k; job[k].nparts = (unsigned)threads;
            job[k].buf = bufs[k]; job[k].bytes = bytes;
            started[k] = k > 0 && pthread_create(&tid[k], NULL, run, &job[k]) == 0;
        }
        for (k = 0; k < threads; k++) if (!started[k]) run(&job[k]);
        for (k = 1; k < threads; k++) if (started[k]) pthread_join(tid[k], NULL);
        rad_shot_end(s, patch, bufs, (unsigned)threads);
        shots++;
        if (progress && progress(ctx, shots, RAD_TO_DOUBLE(rad_unshot_fraction(s)))) break;
    }
    for (k = 0; k < threads; k++) free(bufs[k]);
    return ok ? shots : -1;
}
