/* SPDX-License-Identifier: MIT */
/* hdr — Radiance RGBE images. See hdr.h. */
#include "formats/hdr.h"

#include "formats/file_io.h"
#include "formats/image.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define HDR_MINRUN   4 /* shorter runs of a byte are cheaper as literals */
#define HDR_RLE_MIN  8 /* Radiance encodes rows of 8..32767 pixels; others flat */
#define HDR_RLE_MAX  32767
#define HDR_EXP_BIAS 128 /* exponent byte = e + 128, e in -127..127 */

static int size_ok(int w, int h)
{
    return w >= 1 && h >= 1 && w <= IMG_MAX_DIM && h <= IMG_MAX_DIM;
}

/* ---- encoding ---- */

/* One pixel: 0, or -1 when a value is negative, NaN or needs an exponent above 127.
 * The largest channel v = m 2^e (frexp: m in [0.5, 1)) gets round(m 256) in
 * 128..256; 256 does not fit a byte, so the exponent then grows by one and the
 * largest mantissa is 128 (see hdr.h for the bound this keeps). */
static int rgbe_encode(const float *c, unsigned char out[4])
{
    double v = c[0] > c[1] ? c[0] : c[1], s;
    int e, k;
    if (c[2] > v) v = c[2];
    if (!(c[0] >= 0.0f && c[1] >= 0.0f && c[2] >= 0.0f) || !(v < HUGE_VAL)) return -1;
    (void)frexp(v, &e);
    if (v == 0.0 || e < 1 - HDR_EXP_BIAS) {
        memset(out, 0, 4);
        return 0;
    }
    if (floor(ldexp(v, 8 - e) + 0.5) >= 256.0) e++;
    if (e > 255 - HDR_EXP_BIAS) return -1;
    s = ldexp(1.0, 8 - e);
    for (k = 0; k < 3; k++) out[k] = (unsigned char)floor(c[k] * s + 0.5);
    out[3] = (unsigned char)(e + HDR_EXP_BIAS);
    return 0;
}

/* Length of the run of equal bytes at B[I] (at most 127, within N). */
static int run_at(const unsigned char *b, int i, int n)
{
    int r = 1;
    while (i + r < n && r < 127 && b[i + r] == b[i]) r++;
    return r;
}

/* One channel of a row as Radiance's RLE: runs (128 + n, byte) of HDR_MINRUN..127
 * bytes, literals (n, n bytes) of 1..128 bytes ending where a run begins. */
static int rle_channel(FILE *fp, const unsigned char *b, int n)
{
    int i = 0;
    while (i < n) {
        int r = run_at(b, i, n), lit = 0;
        if (r >= HDR_MINRUN) {
            if (fputc(128 + r, fp) == EOF || fputc(b[i], fp) == EOF) return -1;
            i += r;
            continue;
        }
        while (i + lit < n && lit < 128 && run_at(b, i + lit, n) < HDR_MINRUN) lit++;
        if (fputc(lit, fp) == EOF || fwrite(b + i, 1, (size_t)lit, fp) != (size_t)lit) return -1;
        i += lit;
    }
    return 0;
}

/* Row Y's pixels encoded into ROW (4 bytes a pixel); -1 with the first bad pixel. */
static int encode_row(const float *rgb, int w, int y, unsigned char *row, int *bad_x)
{
    int x;
    for (x = 0; x < w; x++) {
        if (rgbe_encode(rgb + ((size_t)y * w + x) * 3, row + 4 * x) != 0) {
            *bad_x = x;
            return -1;
        }
    }
    return 0;
}

static int write_row(FILE *fp, const unsigned char *row, unsigned char *chan, int w)
{
    int k, x;
    if (w < HDR_RLE_MIN || w > HDR_RLE_MAX)
        return fwrite(row, 4, (size_t)w, fp) == (size_t)w ? 0 : -1;
    if (fputc(2, fp) == EOF || fputc(2, fp) == EOF || fputc(w >> 8, fp) == EOF ||
        fputc(w & 255, fp) == EOF)
        return -1;
    for (k = 0; k < 4; k++) {
        for (x = 0; x < w; x++) chan[x] = row[4 * x + k];
        if (rle_channel(fp, chan, w) != 0) return -1;
    }
    return 0;
}

/* Writes every row; 0, -1 on a write error, -2 on a bad pixel (*BX, *BY). */
static int write_pixels(FILE *fp, const float *rgb, int w, int h, int *bx, int *by)
{
    unsigned char *row = malloc((size_t)w * 5);
    int y, rc = row ? 0 : -1;
    if (row && fprintf(fp, "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n", h, w) < 0)
        rc = -1;
    for (y = 0; rc == 0 && y < h; y++) {
        if (encode_row(rgb, w, y, row, bx) != 0) {
            *by = y;
            rc = -2;
        } else if (write_row(fp, row, row + 4 * (size_t)w, w) != 0) {
            rc = -1;
        }
    }
    free(row);
    return rc;
}

int hdr_write(const char *path, const float *rgb, int w, int h, char *err, size_t errlen)
{
    fio_out *o;
    int rc, e, bx = 0, by = 0;
    if (!path || !rgb) {
        fio_err(err, errlen, path, "no %s given", path ? "pixels" : "path");
        return -1;
    }
    if (!size_ok(w, h)) {
        fio_err(err, errlen, path, "invalid image size %dx%d (each must be 1..%d)", w, h,
                IMG_MAX_DIM);
        return -1;
    }
    if (!(o = fio_out_open(path, err, errlen))) return -1;
    errno = 0;
    rc = write_pixels(fio_out_stream(o), rgb, w, h, &bx, &by);
    if (rc == 0) return fio_out_commit(o, err, errlen);
    e = errno;
    fio_out_abort(o);
    if (rc == -2)
        fio_err(err, errlen, path, "pixel %d,%d is negative, not a number or above 1.7e38", bx, by);
    else
        fio_err(err, errlen, path, "write error: %s", e ? strerror(e) : "out of memory");
    return -1;
}

/* ---- decoding ---- */

typedef struct {
    const unsigned char *p, *end;
} cursor;

/* The next header line (without its newline) into LINE; -1 at the end of the data. */
static int next_line(cursor *c, char *line, size_t n)
{
    size_t k = 0;
    while (c->p < c->end && *c->p != '\n') {
        if (k + 1 < n) line[k++] = (char)*c->p;
        c->p++;
    }
    if (c->p >= c->end) return -1;
    c->p++;
    line[k] = '\0';
    return 0;
}

static int read_header(cursor *c, int *w, int *h, const char **why)
{
    char line[256], tail;
    if (next_line(c, line, sizeof line) != 0 ||
        (strcmp(line, "#?RADIANCE") && strcmp(line, "#?RGBE"))) {
        *why = "not a Radiance HDR file (no #?RADIANCE line)";
        return -1;
    }
    for (;;) {
        if (next_line(c, line, sizeof line) != 0) {
            *why = "truncated header";
            return -1;
        }
        if (line[0] == '\0') break;
        if (!strncmp(line, "FORMAT=", 7) && strcmp(line + 7, "32-bit_rle_rgbe")) {
            *why = "unsupported FORMAT (only 32-bit_rle_rgbe)";
            return -1;
        }
    }
    if (next_line(c, line, sizeof line) != 0 || sscanf(line, "-Y %d +X %d%c", h, w, &tail) != 2) {
        *why = "unsupported resolution line (only -Y H +X W)";
        return -1;
    }
    if (!size_ok(*w, *h)) {
        *why = "image size out of range";
        return -1;
    }
    return 0;
}

/* One channel of an RLE row into OUT (stride 4); -1 on a malformed count. */
static int rle_read_channel(cursor *c, unsigned char *out, int w)
{
    int x = 0;
    while (x < w) {
        int n, k;
        if (c->p >= c->end) return -1;
        n = *c->p++;
        if (n > 128) {
            n -= 128;
            if (n > w - x || c->p >= c->end) return -1;
            for (k = 0; k < n; k++) out[4 * (x + k)] = *c->p;
            c->p++;
        } else {
            if (n == 0 || n > w - x || c->end - c->p < n) return -1;
            for (k = 0; k < n; k++) out[4 * (x + k)] = *c->p++;
        }
        x += n;
    }
    return 0;
}

/* One row into ROW (4 bytes a pixel): RLE when it starts 2, 2, then the width. */
static int read_row(cursor *c, unsigned char *row, int w, const char **why)
{
    int k, x;
    *why = "truncated or corrupt pixel data";
    if (w >= HDR_RLE_MIN && w <= HDR_RLE_MAX && c->end - c->p >= 4 && c->p[0] == 2 &&
        c->p[1] == 2 && !(c->p[2] & 0x80)) {
        if (((c->p[2] << 8) | c->p[3]) != w) return -1;
        c->p += 4;
        for (k = 0; k < 4; k++)
            if (rle_read_channel(c, row + k, w) != 0) return -1;
        return 0;
    }
    if (c->end - c->p < 4 * (long)w) return -1;
    for (x = 0; x < w; x++) {
        if (c->p[4 * x] == 1 && c->p[4 * x + 1] == 1 && c->p[4 * x + 2] == 1) {
            *why = "old-style run-length encoding (not supported)";
            return -1;
        }
    }
    memcpy(row, c->p, 4 * (size_t)w);
    c->p += 4 * (size_t)w;
    return 0;
}

static void rgbe_decode(const unsigned char *b, float *c)
{
    double s = b[3] ? ldexp(1.0, b[3] - HDR_EXP_BIAS - 8) : 0.0;
    c[0] = (float)(b[0] * s);
    c[1] = (float)(b[1] * s);
    c[2] = (float)(b[2] * s);
}

/* The fewest bytes a row of W pixels takes: flat 4 W; RLE (widths 8..32767) its 4-byte
 * start and per channel runs of at most 127 pixels, 2 bytes each. */
static double row_bytes_min(int w)
{
    double flat = 4.0 * w, rle = 4.0 + 4.0 * 2.0 * ((w + 126) / 127);
    return w >= HDR_RLE_MIN && w <= HDR_RLE_MAX && rle < flat ? rle : flat;
}

static int read_pixels(cursor *c, hdr_image *im, const char **why)
{
    unsigned char *row;
    int x, y;
    /* Refused before any allocation: a size the data cannot hold (a header alone may
     * claim 32768 x 32768), or floats beyond the memory budget (file_io.h). */
    if ((double)(c->end - c->p) < row_bytes_min(im->w) * im->h) {
        *why = "truncated or corrupt pixel data: shorter than the header's size needs";
        return -1;
    }
    if ((double)im->w * im->h * 3 * sizeof *im->rgb > fio_memory_budget()) {
        *why = "image too large for the memory budget (RAD_MEMORY_BUDGET, else half the physical "
               "memory)";
        return -1;
    }
    row = malloc(4 * (size_t)im->w);
    im->rgb = row ? malloc((size_t)im->w * im->h * 3 * sizeof *im->rgb) : NULL;
    if (!im->rgb) {
        free(row);
        *why = "out of memory";
        return -1;
    }
    for (y = 0; y < im->h; y++) {
        if (read_row(c, row, im->w, why) != 0) {
            free(row);
            return -1;
        }
        for (x = 0; x < im->w; x++) rgbe_decode(row + 4 * x, im->rgb + ((size_t)y * im->w + x) * 3);
    }
    free(row);
    return 0;
}

int hdr_read(const char *path, hdr_image *out, char *err, size_t errlen)
{
    char *data;
    size_t n;
    cursor c;
    const char *why = NULL;
    hdr_image im = {0, 0, NULL};
    if (out) *out = im;
    if (!path || !out) {
        fio_err(err, errlen, path, "no %s given", path ? "image" : "path");
        return -1;
    }
    if (fio_read_all(path, FIO_LIMIT_IMAGE, &data, &n, err, errlen) != 0) return -1;
    c.p = (const unsigned char *)data;
    c.end = c.p + n;
    if (read_header(&c, &im.w, &im.h, &why) == 0 && read_pixels(&c, &im, &why) == 0) {
        free(data);
        *out = im;
        return 0;
    }
    free(data);
    free(im.rgb);
    fio_err(err, errlen, path, "%s", why);
    return -1;
}

void hdr_free(hdr_image *out)
{
    if (!out) return;
    free(out->rgb);
    out->rgb = NULL;
    out->w = out->h = 0;
}
