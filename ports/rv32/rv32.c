/* SPDX-License-Identifier: MIT */
/* rad ports — RV32 (rv32imac) platform on QEMU's virt machine.
 *
 * Boot (zero .bss, paint the stack), semihosting through the RISC-V trap sequence,
 * traps routed to a failing exit, and minstret as the instruction counter: under
 * QEMU's -icount it is the exact number of instructions retired.
 */
#include "port.h"
#include "probes.h"
#include "semihost.h"

int main(void);
void port_boot(void) __attribute__((noreturn));
void port_trap(uint32_t cause, uint32_t epc) __attribute__((noreturn));

extern uint32_t __bss_start[], __bss_end[];

/* The semihosting trap: ebreak between two marker instructions, uncompressed and
 * inside one 16-byte block so the debugger-side check can read all three. */
uintptr_t semihost_call(uint32_t op, uintptr_t arg)
{
    register uintptr_t a0 __asm__("a0") = op;
    register uintptr_t a1 __asm__("a1") = arg;
    __asm__ volatile(".option push\n"
                     ".option norvc\n"
                     ".balign 16\n"
                     "slli zero, zero, 0x1f\n"
                     "ebreak\n"
                     "srai zero, zero, 7\n"
                     ".option pop\n"
                     : "+r"(a0)
                     : "r"(a1)
                     : "memory");
    return a0;
}

void port_trap(uint32_t cause, uint32_t epc)
{
    (void)epc;
    semihost_fatal("trap, mcause", cause);
}

void port_boot(void)
{
    uint32_t *p, *sp;
    /* .data is loaded in place by QEMU (code and data share RAM): only .bss to clear. */
    for (p = __bss_start; p < __bss_end;) *p++ = 0;
    __asm__ volatile("mv %0, sp" : "=r"(sp));
    port_paint_stack(sp);
    main();
    port_exit(0);
}

int port_instructions(uint64_t *n)
{
    uint32_t hi, lo, hi2;
    do {
        __asm__ volatile("csrr %0, minstreth" : "=r"(hi));
        __asm__ volatile("csrr %0, minstret" : "=r"(lo));
        __asm__ volatile("csrr %0, minstreth" : "=r"(hi2));
    } while (hi != hi2);
    *n = ((uint64_t)hi << 32) | lo;
    return 1;
}

const char *port_target(void)
{
    return "rv32";
}
