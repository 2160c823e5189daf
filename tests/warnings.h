/* SPDX-License-Identifier: MIT */
/* The loaders' warnings as a test sees them: collect() is an obj_warn_fn that keeps the
 * first four messages of a warnings_t and counts them all. */
#ifndef RAD_TESTS_WARNINGS_H
#define RAD_TESTS_WARNINGS_H

#include <stdio.h>

typedef struct {
    int n;
    char msg[4][512];
} warnings;

static inline void collect(void *ctx, const char *msg)
{
    warnings *w = ctx;
    if (w->n < 4) snprintf(w->msg[w->n], sizeof w->msg[0], "%s", msg);
    w->n++;
}

#endif
