/* SPDX-License-Identifier: MIT */
/* rad ports — text out and exit status through semihosting, shared by the targets. */
#include "port.h"
#include "semihost.h"

void port_puts(const char *s)
{
    semihost_call(SEMIHOST_SYS_WRITE0, (uintptr_t)s);
}

void port_exit(int status)
{
    /* SYS_EXIT_EXTENDED: QEMU exits with STATUS (plain SYS_EXIT on a 32-bit target
     * can only say success or failure). */
    volatile uintptr_t block[2];
    block[0] = SEMIHOST_APPLICATION_EXIT;
    block[1] = (uintptr_t)(uint32_t)status;
    for (;;) semihost_call(SEMIHOST_SYS_EXIT_EXTENDED, (uintptr_t)block);
}

void semihost_fatal(const char *what, uint32_t code)
{
    static const char hex[] = "0123456789abcdef";
    char buf[12];
    int i;
    buf[0] = '0';
    buf[1] = 'x';
    for (i = 0; i < 8; i++) buf[2 + i] = hex[(code >> (28 - 4 * i)) & 15u];
    buf[10] = '\n';
    buf[11] = '\0';
    port_puts("fatal: ");
    port_puts(what);
    port_puts(" ");
    port_puts(buf);
    port_exit(3);
}
