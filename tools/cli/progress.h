/* SPDX-License-Identifier: MIT */
/* rad_cli's one progress mechanism: a long stage's progress and ETA on stderr.
 *
 * A stage (the solve, the rows, a view's gathers, the vertices' gathers, a lightmap
 * pass, the probes) says how far it is, a fraction 0..1 and a detail; nothing is shown
 * until it has run PROGRESS_DELAY seconds (1; the environment's RAD_PROGRESS_DELAY, a
 * number of seconds >= 0, replaces it: the tests set 0), nor ever with --quiet. On a
 * terminal one line is redrawn at most every 0.1 s and cleared at the end; elsewhere
 * (a log) a line is written each time the stage passes a tenth of its way, or 10 s
 * after the last. The ETA is the time so far times (1 - f) / f: the stage's own rate.
 */
#ifndef RAD_CLI_PROGRESS_H
#define RAD_CLI_PROGRESS_H

#define PROGRESS_DELAY 1.0

typedef struct {
    const char *what;
    double start, last, delay;
    int on, tty, shown, tenth;
} progress_t;

/* A stage named WHAT starts now (QUIET: it never shows). */
void progress_begin(progress_t *p, const char *what, int quiet);
/* The stage is FRAC of its way (clamped to 0..1), DETAIL (may be NULL) what that is. */
void progress_update(progress_t *p, double frac, const char *detail);
/* The stage ends: a terminal's line cleared. Returns its seconds. */
double progress_end(progress_t *p);
/* progress_update for callbacks: CTX a progress_t, no detail; 0 (go on). */
int progress_fraction(void *ctx, double frac);

#endif
