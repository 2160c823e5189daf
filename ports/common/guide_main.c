/* SPDX-License-Identifier: MIT */
/* rad ports — the guide check's main (ports/common/guide_check.sh): runs the firmware
 * guide's example (ports/README.md, firmware_rad.c) on a port's startup code and prints
 * its results as `key value` lines; exits 0 when the solve shot at least once. */
#include "port.h"

int rad_firmware_solve(uint32_t max_shots);
int main(void);

static void put(const char *key, uint64_t v, int neg)
{
    char buf[24], *p = buf + sizeof buf - 1;
    *p = '\0';
    do {
        *--p = (char)('0' + (int)(v % 10u));
        v /= 10u;
    } while (v);
    if (neg) *--p = '-';
    port_puts(key);
    port_puts(" ");
    port_puts(p);
    port_puts("\n");
}

int main(void)
{
    uint64_t t0 = 0, t1 = 0;
    uint32_t n;
    int rc;
    port_instructions(&t0);
    rc = rad_firmware_solve(400);
    port_instructions(&t1);
    put("result", rc < 0 ? (uint64_t) - (int64_t)rc : (uint64_t)rc, rc < 0);
    put("instructions", t1 - t0, 0);
    if (port_stack_used(&n) == 1) put("stack", n, 0);
    if (port_static_bytes(&n) == 1) put("static", n, 0);
    port_exit(rc > 0 ? 0 : 1);
}
