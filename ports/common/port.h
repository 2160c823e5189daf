/* SPDX-License-Identifier: MIT */
/* rad ports — what a platform gives the port test: text out, exit, and (where the
 * target has one) an instruction counter and a stack high-water mark.
 *
 * ports/host/ implements it with stdio; the targets with semihosting (ports/common/
 * semihost.c over an architecture's trap, ports/common/cortex_m.c, ports/rv32/rv32.c).
 */
#ifndef RAD_PORT_H
#define RAD_PORT_H

#include <stdint.h>

/* Writes the NUL-terminated string S. */
void port_puts(const char *s);

/* Ends the program with STATUS (0: success); never returns. */
void port_exit(int status) __attribute__((noreturn));

/* Instructions retired since boot into *N; returns 1, or 0 when the target has no
 * counter (the host). Deterministic under QEMU -icount shift=0. */
int port_instructions(uint64_t *n);

/* The deepest the stack has been since boot, in bytes, into *N; returns 1, 0 when
 * the platform cannot tell (the host), or -1 when no painted word is left: the stack
 * has used its whole region and has probably overflowed into .bss. */
int port_stack_used(uint32_t *n);

/* Bytes of .data + .bss (every static object) into *N; returns 1, or 0 (the host). */
int port_static_bytes(uint32_t *n);

/* The target's name, for the report. */
const char *port_target(void);

#endif
