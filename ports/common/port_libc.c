/* SPDX-License-Identifier: MIT */
/* rad ports — memcpy and memset for the targets. GCC requires every freestanding
 * environment to provide them (with memmove and memcmp): at -Os on the Cortex-M0 and
 * RV32 it calls memcpy even for 12- and 24-byte struct copies, including in the core's
 * inner loops, so these copy whole words when they can.
 * Built with -fno-tree-loop-distribute-patterns: the loops must not become calls to
 * the very functions they implement. */
#include <stddef.h>
#include <stdint.h>

typedef uint32_t __attribute__((may_alias)) port_word_t;

void *memcpy(void *restrict dst, const void *restrict src, size_t n);
void *memset(void *dst, int c, size_t n);

void *memcpy(void *restrict dst, const void *restrict src, size_t n)
{
    unsigned char *d = dst;
    const unsigned char *s = src;
    if ((((uintptr_t)d | (uintptr_t)s) & 3u) == 0) {
        port_word_t *dw = (port_word_t *)(void *)d;
        const port_word_t *sw = (const port_word_t *)(const void *)s;
        for (; n >= 4; n -= 4) *dw++ = *sw++;
        d = (unsigned char *)dw;
        s = (const unsigned char *)sw;
    }
    while (n--) *d++ = *s++;
    return dst;
}

void *memset(void *dst, int c, size_t n)
{
    unsigned char *d = dst;
    if (((uintptr_t)d & 3u) == 0) {
        port_word_t *dw = (port_word_t *)(void *)d;
        port_word_t w = (unsigned char)c * 0x01010101u;
        for (; n >= 4; n -= 4) *dw++ = w;
        d = (unsigned char *)dw;
    }
    while (n--) *d++ = (unsigned char)c;
    return dst;
}
