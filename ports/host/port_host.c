/* SPDX-License-Identifier: MIT */
/* rad port test on the host: stdio out, exit(), no instruction counter. */
#include <stdio.h>
#include <stdlib.h>
#include "port.h"

void port_puts(const char *s)
{
    fputs(s, stdout);
}

void port_exit(int status)
{
    fflush(stdout);
    exit(status);
}

int port_instructions(uint64_t *n)
{
    *n = 0;
    return 0;
}
int port_stack_used(uint32_t *n)
{
    *n = 0;
    return 0;
}
int port_static_bytes(uint32_t *n)
{
    *n = 0;
    return 0;
}
const char *port_target(void)
{
    return "host";
}
