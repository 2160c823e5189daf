/* SPDX-License-Identifier: MIT */
/* rad ports — RV32 entry on QEMU's virt machine (-bios none: the reset stub jumps
 * here in M-mode). Sets the global and stack pointers and the trap vector, then
 * continues in C (port_boot in rv32.c). */
    .section .text.start, "ax"
    .globl _start
_start:
    .option push
    .option norelax
    la gp, __global_pointer$
    .option pop
    la sp, __stack_top
    la t0, port_trap_entry
    csrw mtvec, t0
    call port_boot
1:  j 1b

/* Any trap (exception or interrupt: none is enabled) is fatal. */
    .align 4
    .globl port_trap_entry
port_trap_entry:
    la sp, __stack_top
    csrr a0, mcause
    csrr a1, mepc
    call port_trap
2:  j 2b
