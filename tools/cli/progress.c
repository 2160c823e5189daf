/* SPDX-License-Identifier: MIT */
/* rad_cli: progress and ETA of long stages (see progress.h). */
#include "cli.h"

#include "progress.h"

#include <stdlib.h>
#include <unistd.h>

#include "host/clock.h"

#define TTY_EVERY 0.1  /* s between a terminal's redraws */
#define LOG_EVERY 10.0 /* s at most between a log's lines */
#define BAR       30

void progress_begin(progress_t *p, const char *what, int quiet)
{
    const char *env = getenv("RAD_PROGRESS_DELAY");
    char *end = NULL;
    double d = env ? strtod(env, &end) : PROGRESS_DELAY;
    p->what = what;
    p->start = host_now();
    p->last = p->start - LOG_EVERY;
    p->delay = env && end != env && *end == '\0' && d >= 0 ? d : PROGRESS_DELAY;
    p->on = !quiet;
    p->tty = isatty(2);
    p->shown = 0;
    p->tenth = -1;
}

void progress_update(progress_t *p, double frac, const char *detail)
{
    double t = host_now(), run = t - p->start;
    int tenth;
    char eta[64] = "";
    if (!p->on || run < p->delay) return;
    frac = frac > 0 ? (frac < 1 ? frac : 1) : 0;
    tenth = (int)(10 * frac);
    if (p->tty ? t - p->last < TTY_EVERY : tenth == p->tenth && t - p->last < LOG_EVERY) return;
    if (frac > 0) snprintf(eta, sizeof eta, ", ETA %.1f s", run * (1 - frac) / frac);
    if (!detail) detail = "";
    if (p->tty) {
        int bar = (int)(BAR * frac);
        fprintf(stderr, "\r%s [%.*s%*s] %3.0f%%  %s%s%.1f s%s ", p->what, bar,
                "##############################", BAR - bar, "", 100 * frac, detail,
                *detail ? "  " : "", run, eta);
    } else {
        fprintf(stderr, PROG ": %s %.0f%%  %s%s%.1f s%s\n", p->what, 100 * frac, detail,
                *detail ? "  " : "", run, eta);
    }
    p->last = t;
    p->tenth = tenth;
    p->shown = 1;
}

double progress_end(progress_t *p)
{
    if (p->shown && p->tty) fprintf(stderr, "\r%110s\r", "");
    p->shown = 0;
    return host_now() - p->start;
}

int progress_fraction(void *ctx, double frac)
{
    progress_update(ctx, frac, NULL);
    return 0;
}
