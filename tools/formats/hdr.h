/* SPDX-License-Identifier: MIT */
/* hdr — Radiance RGBE (.hdr) images of linear float RGB: the lightmap's high dynamic
 * range output (uses malloc, stdio, libm).
 *
 * A pixel is three 8-bit mantissas sharing one exponent byte (Ward, "Real pixels",
 * Graphics Gems II, 1991): for the largest channel v = m 2^e, m in [0.5, 1), each
 * channel c is stored as round(c 2^(8-e)) and read back as byte 2^(e-8). Rounding to
 * the nearest step of 2^(e-8) errs by at most half a step, 2^(e-9), and the largest
 * channel reads back as at least 128 steps, 2^(e-1) (when round(m 256) = 256, e grows
 * by one and it reads back as 2^e, 128 new steps): every channel is within 2^-8 of the
 * pixel's largest channel as read back (a channel far below the largest keeps only
 * that absolute precision). Values below 2^-128 are written as black; negative values,
 * NaN, and values needing an exponent above 127 (about 1.7e38) are refused.
 *
 * Files: the header "#?RADIANCE", "FORMAT=32-bit_rle_rgbe", a blank line, "-Y H +X W"
 * (rows top to bottom), then rows run-length encoded as Radiance writes them (widths
 * 8..32767; other widths flat). The reader takes this file's form (also "#?RGBE", other
 * header lines ignored, flat or RLE rows); other orientations and the old RLE are
 * refused, and so, before anything is allocated, are pixel data shorter than the
 * header's size can take (each row at least its flat or RLE minimum) and an image whose
 * floats exceed the memory budget (fio_memory_budget). Errors are one line, "PATH: what is wrong", in a caller buffer (NULL or
 * length 0: none); outputs are written through file_io (atomic, never a partial file).
 */
#ifndef RAD_TOOLS_HDR_H
#define RAD_TOOLS_HDR_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    int w, h;
    float *rgb; /* w*h*3 linear RGB, row 0 at the top, malloc'd */
} hdr_image;

/* Writes RGB (w*h*3 floats, row 0 at the top) to PATH, each size 1..IMG_MAX_DIM.
 * Returns 0, or -1 with err (a value negative, NaN or too large, named by pixel). */
int hdr_write(const char *path, const float *rgb, int w, int h, char *err, size_t errlen);

/* Reads PATH (at most FIO_LIMIT_IMAGE bytes) into *OUT (free with hdr_free). Returns 0,
 * or -1 with err, and then *OUT is {0, 0, NULL}. */
int hdr_read(const char *path, hdr_image *out, char *err, size_t errlen);

/* Frees out->rgb and zeroes *OUT; NULL-safe. */
void hdr_free(hdr_image *out);

#ifdef __cplusplus
}
#endif

#endif
