/* SPDX-License-Identifier: MIT */
/* rad ports — stack painting, the stack high-water mark and the static size (see
 * probes.h and port.h), shared by the Cortex-M and RV32 platforms. */
#include "port.h"
#include "probes.h"

/* Linker script symbols. */
extern uint32_t __data_start[], __bss_end[];
extern uint32_t __stack_limit[], __stack_top[];

#define STACK_PAINT 0x5AC3A55Cu

void port_paint_stack(const uint32_t *sp)
{
    uint32_t *p;
    for (p = __stack_limit; p < sp - 16;) *p++ = STACK_PAINT;
}

int port_stack_used(uint32_t *n)
{
    const uint32_t *p = __stack_limit;
    while (p < __stack_top && *p == STACK_PAINT) p++;
    *n = (uint32_t)((uintptr_t)__stack_top - (uintptr_t)p);
    return p == __stack_limit ? -1 : 1;
}

int port_static_bytes(uint32_t *n)
{
    *n = (uint32_t)((uintptr_t)__bss_end - (uintptr_t)__data_start);
    return 1;
}
