/* SPDX-License-Identifier: MIT */
/* rad host glue: progressive refinement with each shot's hemi-cube rendered by several
 * threads (pthreads here; the core has none), each a run of its rows. The result is
 * bit for bit that of the serial solve. Built once per build of the core, like
 * host/scene.c (the float twin's scf_solve_parallel is in host/scene_float.h). */
#ifndef RAD_TOOLS_PARALLEL_H
#define RAD_TOOLS_PARALLEL_H

#include "host/scene.h"

/* As sc_solve with THREADS threads (1: serial through the same split). Returns the
 * shots done, or -1 when the core cannot split (its work buffer bands the hemi-cube)
 * or threads cannot start. */
int sc_solve_parallel(sc_solver *s, int threads, int max_shots, double tol, sc_progress_fn progress,
                      void *ctx);

/* As sc_solve, in batches of BATCH shots (1..RAD_BATCH_MAX; rad_batch_begin) whose
 * hemi-cubes render on THREADS threads, a whole cube each: the same bits for any
 * THREADS, and for BATCH 1 the serial solve's. Returns the shots done, or -1 when the
 * core bands the hemi-cube, BATCH is out of range, buffers cannot be had or the core
 * refuses a batch. */
int sc_solve_batch(sc_solver *s, int threads, int batch, int max_shots, double tol,
                   sc_progress_fn progress, void *ctx);

#define RAD_TWIN_PARALLEL /* the float twin's names of the above (generated): */
#include "host/scene_float.h"

#endif
