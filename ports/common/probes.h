/* SPDX-License-Identifier: MIT */
/* rad ports — the stack and size probes of the targets that boot from ports/common/
 * (Cortex-M and RV32): one copy, over the linker scripts' symbols __stack_limit,
 * __stack_top, __data_start and __bss_end. port_stack_used and port_static_bytes are
 * port.h's; this adds the painting they rely on. */
#ifndef RAD_PORT_PROBES_H
#define RAD_PORT_PROBES_H

#include <stdint.h>

/* Paints the free stack, from its limit up to 16 words below SP (the caller's stack
 * pointer at boot), so that port_stack_used finds the high-water mark. The 16 words
 * hold this function's own frame: it is a leaf, saving a few registers at most. */
void port_paint_stack(const uint32_t *sp);

#endif
