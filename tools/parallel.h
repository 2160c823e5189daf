/* rad host glue: progressive refinement with each shot's hemi-cube rendered by several
 * threads (pthreads here; the core has none), each a run of its rows. The result is
 * bit for bit that of the serial solve. Compiled twice, like scene_twin.c: sc_* and scf_*. */
#ifndef RAD_TOOLS_PARALLEL_H
#define RAD_TOOLS_PARALLEL_H

#include "scene.h"

#define PAR_DECLARE(P)                                                                   \
    /* As P##_solve with THREADS threads (1: serial through the same split). Returns   \
     * the shots done, or -1 when the core cannot split (its work buffer bands the      \
     * hemi-cube) or threads cannot start. */                                           \
    int P##_solve_parallel(P##_solver *s, int threads, int max_shots, double tol, sc_progress_fn progress, void *ctx);

PAR_DECLARE(sc)
PAR_DECLARE(scf)

#endif
