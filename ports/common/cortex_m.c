/* SPDX-License-Identifier: MIT */
/* rad ports — Cortex-M boot and platform (ARMv6-M and ARMv7-M: the M0 and M3 ports).
 *
 * Vector table, reset (copy .data, zero .bss, paint the stack), SysTick as the
 * instruction counter, faults routed to a failing exit, semihosting through bkpt 0xab.
 * The board's linker script (ports/<target>/link.ld) places memory; the build passes
 * PORT_TARGET_NAME and PORT_CPU_HZ (the SysTick clock with CLKSOURCE = processor).
 *
 * Counting instructions: under QEMU's -icount shift=0 every instruction advances the
 * virtual clock by 1 ns, and SysTick runs on that clock, so one tick is 10^9 /
 * PORT_CPU_HZ instructions (40 on mps2-an385 at 25 MHz, 62.5 on the micro:bit at 16 MHz).
 * The 24-bit counter wraps every 2^24 ticks; its interrupt counts the wraps.
 */
#include "port.h"
#include "probes.h"
#include "semihost.h"

#ifndef PORT_TARGET_NAME
#error "define PORT_TARGET_NAME"
#endif
#ifndef PORT_CPU_HZ
#error "define PORT_CPU_HZ"
#endif

int main(void);

/* Linker script symbols. */
extern uint32_t __data_load[], __data_start[], __data_end[], __bss_start[], __bss_end[];
extern uint32_t __stack_top[];

#define REG(a)         (*(volatile uint32_t *)(a))
#define SYST_CSR       REG(0xE000E010u)
#define SYST_RVR       REG(0xE000E014u)
#define SYST_CVR       REG(0xE000E018u)
#define SCB_ICSR       REG(0xE000ED04u)
#define ICSR_PENDSTSET (1u << 26)
#ifndef PORT_SYST_PERIOD
#define PORT_SYST_PERIOD (1u << 24) /* ticks per wrap (tests use short periods) */
#endif
#define SYST_PERIOD ((uint32_t)PORT_SYST_PERIOD)

#define HALF_NS_PER_TICK (2000000000u / (uint32_t)PORT_CPU_HZ)
#if 2000000000u % PORT_CPU_HZ != 0
#error "PORT_CPU_HZ must divide 2 GHz (one tick = a whole number of half nanoseconds)"
#endif

static volatile uint32_t systick_wraps;

/* ---- semihosting ---------------------------------------------------------------- */

uintptr_t semihost_call(uint32_t op, uintptr_t arg)
{
    register uintptr_t r0 __asm__("r0") = op;
    register uintptr_t r1 __asm__("r1") = arg;
    __asm__ volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
    return r0;
}

/* ---- exceptions ----------------------------------------------------------------- */

static void fault_handler(void)
{
    uint32_t ipsr;
    __asm__ volatile("mrs %0, ipsr" : "=r"(ipsr));
    semihost_fatal("exception", ipsr & 0x1FFu);
}

static void systick_handler(void)
{
    systick_wraps++;
}

void port_reset(void) __attribute__((noreturn));

typedef void (*vector_t)(void);

/* The initial stack pointer, then 15 system vectors and 32 interrupts; everything but
 * reset and SysTick is fatal. */
typedef struct {
    uint32_t *initial_sp;
    vector_t handler[47];
} vector_table_t;

__attribute__((section(".vectors"), used)) static const vector_table_t vectors = {
    __stack_top,
    {
        port_reset,
        fault_handler,
        fault_handler,
        fault_handler,
        fault_handler,
        fault_handler, /* NMI..Usage */
        0,
        0,
        0,
        0,
        fault_handler,
        fault_handler,
        0,
        fault_handler, /* SVC..PendSV */
        systick_handler,
        fault_handler,
        fault_handler,
        fault_handler,
        fault_handler,
        fault_handler,
        fault_handler,
        fault_handler,
        fault_handler,
        fault_handler,
        fault_handler,
        fault_handler,
        fault_handler,
        fault_handler,
        fault_handler,
        fault_handler,
        fault_handler,
        fault_handler,
        fault_handler,
        fault_handler,
        fault_handler,
        fault_handler,
        fault_handler,
        fault_handler,
        fault_handler,
        fault_handler,
        fault_handler,
        fault_handler,
        fault_handler,
        fault_handler,
        fault_handler,
        fault_handler,
        fault_handler,
    },
};

void port_reset(void)
{
    uint32_t *p, *src, *sp;

    for (src = __data_load, p = __data_start; p < __data_end;) *p++ = *src++;
    for (p = __bss_start; p < __bss_end;) *p++ = 0;
    /* Paint the free stack below this frame; port_stack_used() finds the high-water mark. */
    __asm__ volatile("mov %0, sp" : "=r"(sp));
    port_paint_stack(sp);

    SYST_RVR = SYST_PERIOD - 1u;
    SYST_CVR = 0;
    SYST_CSR = 7u; /* processor clock, interrupt, enable */
    while (SYST_CVR == 0) {
        /* the counter loads the reload value on its first tick */
    }

    main();
    port_exit(0);
}

/* ---- platform ------------------------------------------------------------------- */

int port_instructions(uint64_t *n)
{
    uint32_t w, v, pend;
    uint64_t ticks;
    do {
        w = systick_wraps;
        v = SYST_CVR;
        pend = SCB_ICSR & ICSR_PENDSTSET;
    } while (w != systick_wraps);
    /* Wrapped but not yet counted (interrupt pending): V is already the reloaded value. */
    if (pend && v >= SYST_PERIOD / 2u) w++;
    ticks = (uint64_t)w * SYST_PERIOD + (SYST_PERIOD - 1u - v);
    /* Half-instructions per tick times ticks, halved: no division, whose length would
     * depend on the value and blur the measurement it is part of. */
    *n = ticks * HALF_NS_PER_TICK >> 1;
    return 1;
}

#define PORT_STR_(x) #x
#define PORT_STR(x)  PORT_STR_(x)
const char *port_target(void)
{
    return PORT_STR(PORT_TARGET_NAME);
}
