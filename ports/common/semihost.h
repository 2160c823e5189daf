/* SPDX-License-Identifier: MIT */
/* rad ports — Arm semihosting (also the RISC-V semihosting ABI): the operations the
 * ports use. Each architecture supplies semihost_call(), its trap sequence. */
#ifndef RAD_PORT_SEMIHOST_H
#define RAD_PORT_SEMIHOST_H

#include <stdint.h>

#define SEMIHOST_SYS_WRITE0        0x04u /* r1: NUL-terminated string */
#define SEMIHOST_SYS_EXIT_EXTENDED 0x20u /* r1: {reason, status} */
#define SEMIHOST_APPLICATION_EXIT  0x20026u

/* Performs semihosting operation OP with argument ARG; returns the host's answer. */
uintptr_t semihost_call(uint32_t op, uintptr_t arg);

/* Prints "fatal: WHAT CODE" and exits with status 3 (used by fault and trap handlers). */
void semihost_fatal(const char *what, uint32_t code) __attribute__((noreturn));

#endif
