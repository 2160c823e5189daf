/* SPDX-License-Identifier: MIT */
/* rad host tools: the monotonic clock (see clock.h). */
#include "host/clock.h"

#include <time.h>

double host_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}
