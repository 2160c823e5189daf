/* SPDX-License-Identifier: MIT */
/* bench_threads — rad_bench's tables of solves on threads: the split shot (each shot's
 * hemi-cube in parts, sc_solve_parallel) and batch shooting (sc_solve_batch), with what
 * two free cores could give, timed on one thread's processor clock. See bench.h.
 */
/* getloadavg is a BSD and Linux call, beyond POSIX. */
#define _DEFAULT_SOURCE
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "bench/bench.h"
#include "host/clock.h"
#include "host/defaults.h"
#include "host/parallel.h"
#include "rad/rad.h"

/* ---- the parallel solve ------------------------------------------------------- */

/* This thread's processor time, seconds. */
double bench_thread_cpu(void)
{
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

/* The scene solved to 0.001 through the core's split shot in NP parts (1 or 2) on this
 * one thread, each part of each stage in turn, each call timed on the thread's
 * processor clock: into SERIAL the calls between the stages, into WORK every part's
 * time, into CRIT the longer part of each stage. */
static void split_times(const bscene *sc, const sc_opts *o, unsigned np, double *serial,
                        double *work, double *crit)
{
    sc_solver *h = bench_fixed_solver(sc, sc->polys, o);
    rad_scene_t *s = sc_core(h);
    size_t bytes = RAD_PART_BYTES(s->cfg.res);
    void *bufs[2] = {malloc(bytes), malloc(bytes)};
    double t, q[2];
    uint32_t p;
    unsigned k, stage;
    if (!bufs[0] || !bufs[1]) exit(1);
    *serial = *work = *crit = 0;
    for (;;) {
        t = bench_thread_cpu();
        if (rad_shot_begin(s, RAD_REAL(0.001), &p) != 1) break;
        *serial += bench_thread_cpu() - t;
        for (stage = 0; stage < 2; stage++) {
            if (stage) {
                t = bench_thread_cpu();
                rad_shot_aim(s, p, bufs, np);
                *serial += bench_thread_cpu() - t;
            }
            q[1] = 0;
            for (k = 0; k < np; k++) {
                t = bench_thread_cpu();
                if (stage)
                    rad_shot_receive_part(s, p, bufs, np, k);
                else
                    rad_shot_part(s, p, k, np, bufs[k], bytes);
                q[k] = bench_thread_cpu() - t;
                *work += q[k];
            }
            *crit += q[0] > q[1] ? q[0] : q[1];
        }
        t = bench_thread_cpu();
        rad_shot_end(s, p, bufs, np);
        *serial += bench_thread_cpu() - t;
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
    sc_solver *h = bench_fixed_solver(sc, sc->polys, o);
    serial = bench_thread_cpu();
    sc_solve(h, 1000000, 0.001, NULL, NULL);
    serial = bench_thread_cpu() - serial;
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
    if (threads)
        sc_solve_parallel(h, threads, 1000000, 0.001, NULL, NULL);
    else
        sc_solve(h, 1000000, 0.001, NULL, NULL);
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
            h[k] = bench_fixed_solver(sc, sc->polys, o);
            t[k][rep] = timed_solve(h[k], k);
        }
        if (sc_checksum(h[1]) != sc_checksum(h[0]) || sc_checksum(h[2]) != sc_checksum(h[0])) {
            fprintf(stderr, "rad_bench: parallel result differs!\n");
            exit(1);
        }
        for (k = 0; k < 3; k++) sc_destroy(h[k]);
    }
    for (k = 0; k < 3; k++) m[k] = bench_median(t[k], 3);
}

/* The parallel solve: the same shots, each shot's hemi-cube split over threads. */
void bench_report_parallel(report_t *rp, const bscene *scenes, int ns, const brun *fx)
{
    int i;
    bench_out(rp, "\nParallel solve (pthreads in tools/, each shot's hemi-cube rows split over "
                  "threads, then its "
                  "receiving by runs of whole patches' elements, each sum in the serial order: "
                  "bit-exact with the serial solve, "
                  "checked by tests/test_parallel.c), fixed build, to 0.001, median of 3, with the "
                  "machine's load average (1 "
                  "minute) when each row was measured: the workers spin, so other processes on the "
                  "cores slow them more than one "
                  "thread. Serial is the solve without parts (sc_solve: what one thread runs); one "
                  "part is the split "
                  "shot's path on one thread (its item buffer's half-row bounds and merge cost "
                  "work of their own); the "
                  "speed-up is serial over two threads. The bound is what two free cores could "
                  "give whatever the load: "
                  "the serial solve over the critical path of the solve in two parts (the calls "
                  "between the stages plus "
                  "each stage's longer part), all timed on one thread's processor clock; split is "
                  "the two parts' work over "
                  "the one part's (the surfaces set up on both parts' faces, each part's elements "
                  "merged from both parts' "
                  "pixels). Each scene at res 128 and at rad_cli's defaults (res 192, coarse "
                  "shots):\n\n| scene | settings "
                  "| elements | serial s | one part s | 2 threads s | speed-up | load average | "
                  "split | bound |\n"
                  "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for (i = 0; i < ns; i++) {
        int k;
        if (scenes[i].big) continue; /* too long to repeat */
        for (k = 0; k < 2; k++) {
            sc_opts o = k ? bench_row_opts(bench_scene_opts(&scenes[i]), &bench_peer_rows[1])
                          : bench_scene_opts(&scenes[i]);
            double m[3], load = -1, split, bound;
            parallel_times(&scenes[i], &o, m);
            if (getloadavg(&load, 1) != 1) load = -1;
            bound = parallel_bound(&scenes[i], &o, &split);
            bench_out(rp, "| %s | %s | %d | %.3f | %.3f | %.3f | %.2f | %.2f | %.2f | %.2f |\n",
                      k ? "" : scenes[i].name, k ? "rad_cli's (192, coarse)" : "res 128",
                      fx[i].elements, m[0], m[1], m[2], m[0] / m[2], load, split, bound);
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
static void batch_split(const bscene *sc, const sc_opts *o, int k, double *serial, double *work,
                        double *crit)
{
    sc_solver *h = bench_fixed_solver(sc, sc->polys, o);
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
        t = bench_thread_cpu();
        n = rad_batch_begin(s, RAD_REAL(0.001), (unsigned)k, p);
        *serial += bench_thread_cpu() - t;
        if (n <= 0) break;
        q[0] = q[1] = 0;
        for (i = 0; i < n; i++) {
            double c;
            t = bench_thread_cpu();
            rad_batch_render(s, p[i], (unsigned)i, bufs[i], bytes);
            c = bench_thread_cpu() - t;
            *work += c;
            q[q[1] < q[0]] += c;
        }
        *crit += q[0] > q[1] ? q[0] : q[1];
        t = bench_thread_cpu();
        rad_batch_aim(s, bufs, (unsigned)n);
        *serial += bench_thread_cpu() - t;
        q[0] = q[1] = 0;
        for (i = 0; i < (n < 2 ? n : 2); i++) {
            t = bench_thread_cpu();
            rad_batch_receive_part(s, bufs, (unsigned)n, (unsigned)i, n < 2 ? 1u : 2u);
            q[i] = bench_thread_cpu() - t;
            *work += q[i];
        }
        *crit += q[0] > q[1] ? q[0] : q[1];
        t = bench_thread_cpu();
        rad_batch_end(s, bufs, (unsigned)n);
        *serial += bench_thread_cpu() - t;
    }
    for (i = 0; i < k; i++) free(bufs[i]);
    sc_destroy(h);
}

/* One solve of SC at O to 0.001 in batches of K on THREADS threads (K 0: sc_solve, the
 * serial solve): wall seconds; the solver into *OUT (the caller destroys it). */
static double batch_solve(const bscene *sc, const sc_opts *o, int k, int threads, sc_solver **out)
{
    sc_solver *h = bench_fixed_solver(sc, sc->polys, o);
    double t0 = host_now();
    if (k)
        sc_solve_batch(h, threads, k, 1000000, 0.001, NULL, NULL);
    else
        sc_solve(h, 1000000, 0.001, NULL, NULL);
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
void bench_report_batch_k(report_t *rp, const bscene *sc)
{
    static const double floor[2] = {0.1, 0.01};
    sc_opts o = bench_row_opts(bench_scene_opts(sc), &bench_peer_rows[1]), r;
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
    ref = bench_solved(sc, &r, 1e-4);
    bench_out(rp,
              "\nBatch shooting (rad_batch_begin; rad_cli --batch K): each batch shoots the K "
              "patches whose shots "
              "move the most, their hemi-cubes rendered at once (on any threads: the same bits) "
              "and shot in order. "
              "CornellBox-Original at rad_cli's defaults (res %d, coarse shots, its mesh), fixed "
              "build, to 0.001, one "
              "run each: shots and seconds on one and on two threads (sc_solve_batch; K = 1 is the "
              "serial solve's "
              "bits), and the error of r + g + b per element against a solve of the same mesh at "
              "res 512 to 1e-4 "
              "(rms and largest over the elements above 10%% of the brightest non-emitting one). "
              "Load average (1 minute) "
              "at the start: %.2f on %ld cores.\n\n| K | shots | shots / K=1 | s, 1 thread | s, 2 "
              "threads | 2 threads / 1 "
              "| time / K=1 (2 threads) | rms | max |\n| ---: | ---: | ---: | ---: | ---: | ---: | "
              "---: | ---: | ---: |\n",
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
        bench_element_accuracy(sc, ref, h, floor, rms, mx);
        bench_out(rp, "| %d | %d | %.2f | %.3f | %.3f | %.2f | %.2f | %.2f%% | %.2f%% |\n",
                  batch_ks[i], shots, shots / (double)want[1], t1[i], t2[i], t1[i] / t2[i],
                  t2[i] / t2[0], 100 * rms[0], 100 * mx[0]);
        sc_destroy(h);
        sc_destroy(h2);
    }
    bench_out(rp, "\nLoad average at the end: %.2f.\n", load_now());
    sc_destroy(ref);
}

/* Rounds of the batch speed table, each one solve on one thread then one on two; the
 * medians of the times and of the rounds' ratios are reported: one run's time swings
 * by 1.5x on these machines even when idle (measured: the same solve 3.5 s and 5.2 s),
 * and a slow spell slows both runs of a round alike. */
#define BATCH_RUNS 5

/* The batch solve's speed on one and two threads: each scene at its settings (res 128)
 * and at rad_cli's (res 192, coarse shots), serial against batches of K = 1, 4, 8 and
 * 16 (the 110k hall: rad_cli's settings, K = 1, DEF_BATCH and 8). */
void bench_report_batch_speed(report_t *rp, const bscene *scenes, int ns)
{
    int i, j, m, r;
    bench_out(rp,
              "\nBatch solve on threads (sc_solve_batch, pthreads in tools/), fixed build, to "
              "0.001, medians of %d rounds (a run on one thread, then one on two; 2 threads / 1 "
              "is the median of the rounds' ratios), "
              "with the load average (1 minute) when the row was measured (the workers spin: "
              "other processes on the "
              "cores slow them more than one thread). Serial is sc_solve; K = 1 on one thread "
              "is the same solve through "
              "the batch calls. The bound is what two free cores could give whatever the load: "
              "the batch solve's "
              "processor time on one thread over its critical path on two (rad_batch_begin and "
              "_end on one, the "
              "cubes of each batch shared between two), timed on one thread's processor "
              "clock.\n\n| scene | settings | "
              "elements | K | serial s | 1 thread s | 2 threads s | 2 threads / 1 | serial / 2 "
              "threads | load average "
              "| bound |\n| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: "
              "| ---: |\n",
              BATCH_RUNS);
    for (i = 0; i < ns; i++) {
        int fine = strcmp(scenes[i].name, "generated hall, fine") == 0;
        if (strncmp(scenes[i].name, "CornellBox-Original", 19) &&
            strncmp(scenes[i].name, "generated hall", 14))
            continue;
        /* the 110k hall at rad_cli's settings alone, serial against K = 1, DEF_BATCH and
         * 8: at res 128 its runs alone would take longer than the rest of the bench */
        for (m = fine; m < 2; m++) {
            sc_opts o = m ? bench_row_opts(bench_scene_opts(&scenes[i]), &bench_peer_rows[1])
                          : bench_scene_opts(&scenes[i]);
            sc_solver *h;
            sc_stats st;
            double serial, v[BATCH_RUNS];
            for (r = 0; r < BATCH_RUNS; r++) {
                v[r] = batch_solve(&scenes[i], &o, 0, 1, &h);
                sc_get_stats(h, &st);
                sc_destroy(h);
            }
            serial = bench_median(v, BATCH_RUNS);
            for (j = 0; j < BATCH_KS; j++) {
                int k = batch_ks[j];
                double t1, t2, u[BATCH_RUNS], q[BATCH_RUNS], s, w, c, load = load_now();
                if (k != 1 && k != 4 && k != 8 && k != 16) continue;
                if (fine && k != 1 && k != DEF_BATCH && k != 8) continue;
                fprintf(stderr, "rad_bench: batch speed: %s, K %d ...\n", scenes[i].name, k);
                for (r = 0; r < BATCH_RUNS; r++) { /* in turn: a slow spell slows both */
                    v[r] = batch_solve(&scenes[i], &o, k, 1, &h);
                    sc_destroy(h);
                    u[r] = batch_solve(&scenes[i], &o, k, 2, &h);
                    sc_destroy(h);
                    q[r] = v[r] / u[r];
                }
                t1 = bench_median(v, BATCH_RUNS);
                t2 = bench_median(u, BATCH_RUNS);
                batch_split(&scenes[i], &o, k, &s, &w, &c);
                bench_out(
                    rp, "| %s | %s | %d | %d | %.3f | %.3f | %.3f | %.2f | %.2f | %.2f | %.2f |\n",
                    m != fine || j ? "" : scenes[i].name,
                    j   ? ""
                    : m ? "rad_cli's (192, coarse)"
                        : "res 128",
                    st.elements, k, serial, t1, t2, bench_median(q, BATCH_RUNS), serial / t2, load,
                    (s + w) / (s + c));
            }
        }
    }
}
