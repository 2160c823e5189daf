/* SPDX-License-Identifier: MIT */
/* rad host tools: the one wall clock of the tools, the benchmark and the tests. */
#ifndef RAD_TOOLS_CLOCK_H
#define RAD_TOOLS_CLOCK_H

/* Seconds on the monotonic clock (CLOCK_MONOTONIC) from an arbitrary origin: only
 * differences mean anything. */
double host_now(void);

#endif
