/* SPDX-License-Identifier: MIT */
/* image — 8-bit RGB image files (PNG via libpng, binary PPM P6) and tone mapping of
 * linear radiosity to display values, for the host tools (uses malloc, stdio, libm).
 *
 * Errors are one line, "PATH: what is wrong", copied into a caller buffer (which may be
 * NULL or of length 0 when the caller does not want the text).
 */
#ifndef RAD_TOOLS_IMAGE_H
#define RAD_TOOLS_IMAGE_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Largest accepted width or height, for writing and for reading. */
#define IMG_MAX_DIM 32768

typedef struct {
    int w, h;
    unsigned char *rgb;
} img_t; /* 8-bit RGB, row 0 at the top, w*h*3 bytes */

/* Writes rgb (w*h*3) to PATH as PNG (libpng) or binary PPM P6, chosen by extension
 * (.png/.ppm, case-insensitive; anything else is an error).
 * Written through file_io (fio_out_open): a regular file is replaced atomically (a
 * temporary file beside it, renamed over it; on any failure PATH is left untouched and
 * no temporary file stays), keeping its permissions (else 0666 & ~umask); a symbolic
 * link is kept and its target replaced; a device or FIFO is written in place.
 * Sizes must be 1..IMG_MAX_DIM each. Returns 0, or -1 with a message in err. */
int img_write(const char *path, const unsigned char *rgb, int w, int h, char *err, size_t errlen);

/* As img_write, in FORMAT ("png" or "ppm", any case) whatever PATH is called: for an
 * output with no extension, such as /dev/stdout. FORMAT NULL: by the extension. */
int img_write_as(const char *path, const char *format, const unsigned char *rgb, int w, int h,
                 char *err, size_t errlen);

/* RGB (w*h*3) encoded as PNG bytes in memory: *OUT (malloc'd, the caller frees) and *N.
 * Returns 0, or -1 with a message in err (*OUT NULL). */
int img_encode_png(const unsigned char *rgb, int w, int h, unsigned char **out, size_t *n,
                   char *err, size_t errlen);

/* Reads a PNG (any colour type/bit depth: 16-bit is stripped to 8, palette and grey are
 * expanded, alpha and tRNS are dropped) or a binary P6 PPM (maxval 255, header comments
 * allowed). The format is chosen by the file's magic bytes, not its name. The file is
 * read whole through fio_read_all, at most FIO_LIMIT_IMAGE bytes. On success
 * *out owns a malloc'd buffer (release with img_free); on failure *out is {0, 0, NULL}.
 * Returns 0 or -1 with a message in err. */
int img_read(const char *path, img_t *out, char *err, size_t errlen);

/* Frees img->rgb and zeroes *img. NULL-safe and idempotent. */
void img_free(img_t *img);

/* Tone mapping of linear radiosity to display: out = round(255 * srgb_encode(clamp(lin *
 * exposure, 0, 1))). lin is npix*3 floats (RGB); out is npix*3 bytes. NaN maps to 0. */
void tonemap(const float *lin, size_t npix, double exposure, unsigned char *out);

/* Automatic exposure: 1 / (97th percentile, nearest-rank, of max(r,g,b) over the pixels
 * whose max is finite and > 0), so lights may clip while most of the scene is well
 * exposed. Returns 1.0 when no pixel is lit (or memory runs out). */
double tonemap_auto_exposure(const float *lin, size_t npix);

/* sRGB transfer function (IEC 61966-2-1) for one value; input is clamped to [0,1]. */
double srgb_encode(double linear);

#ifdef __cplusplus
}
#endif

#endif
