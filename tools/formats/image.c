/* SPDX-License-Identifier: MIT */
/* image — PNG/PPM reading and writing, tone mapping. See image.h. */
#include "formats/image.h"

#include "formats/file_io.h"

#include <errno.h>
#include <math.h>
#include <png.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { FMT_NONE, FMT_PNG, FMT_PPM };

static int lower(int c)
{
    return (c >= 'A' && c <= 'Z') ? c - 'A' + 'a' : c;
}

/* Format named by NAME ("png" or "ppm"), case-insensitive. */
static int format_named(const char *name)
{
    char ext[4];
    int i;
    if (strlen(name) != 3) return FMT_NONE;
    for (i = 0; i < 3; i++) ext[i] = (char)lower((unsigned char)name[i]);
    ext[3] = '\0';
    return strcmp(ext, "png") == 0 ? FMT_PNG : strcmp(ext, "ppm") == 0 ? FMT_PPM : FMT_NONE;
}

/* Format from the extension of the last path component, case-insensitive. */
static int format_of(const char *path)
{
    const char *slash = strrchr(path, '/'), *dot = strrchr(path, '.');
    return !dot || (slash && dot < slash) ? FMT_NONE : format_named(dot + 1);
}

static int size_ok(int w, int h)
{
    return w >= 1 && h >= 1 && w <= IMG_MAX_DIM && h <= IMG_MAX_DIM &&
           (size_t)w * (size_t)h <= SIZE_MAX / 3;
}

/* ---- libpng glue: errors land in a message buffer and longjmp back to the caller ---- */

typedef struct {
    char msg[160];
} png_msg;

static void png_on_error(png_structp png, png_const_charp m)
{
    png_msg *pm = (png_msg *)png_get_error_ptr(png);
    if (pm) snprintf(pm->msg, sizeof pm->msg, "%s", m ? m : "libpng error");
    png_longjmp(png, 1);
}

/* Warnings (e.g. unknown chunks) do not change the result; keep stderr quiet. */
static void png_on_warning(png_structp png, png_const_charp m)
{
    (void)png;
    (void)m;
}

/* libpng's own writer says only "Write Error": this one says what failed. */
static void png_write_cb(png_structp png, png_bytep data, png_size_t n)
{
    char m[160];
    if (fwrite(data, 1, n, (FILE *)png_get_io_ptr(png)) != n) {
        snprintf(m, sizeof m, "write error: %s", strerror(errno));
        png_error(png, m);
    }
}

/* fio_out_commit flushes (and checks) once, at the end. */
static void png_flush_cb(png_structp png)
{
    (void)png;
}

/* Only png and info exist across setjmp and neither changes after it, so no volatile
 * is needed; the row loop counter is not read after a longjmp. */
static int png_write_fp(FILE *fp, const unsigned char *rgb, int w, int h, png_msg *pm)
{
    png_structp png =
        png_create_write_struct(PNG_LIBPNG_VER_STRING, pm, png_on_error, png_on_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    int y;
    if (!info) {
        png_destroy_write_struct(&png, NULL);
        snprintf(pm->msg, sizeof pm->msg, "out of memory");
        return -1;
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return -1;
    }
    png_set_write_fn(png, fp, png_write_cb, png_flush_cb);
    png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, 8, PNG_COLOR_TYPE_RGB,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (y = 0; y < h; y++) png_write_row(png, rgb + (size_t)y * (size_t)w * 3);
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    return 0;
}

static int ppm_write_fp(FILE *fp, const unsigned char *rgb, int w, int h, png_msg *pm)
{
    size_t n = (size_t)w * (size_t)h * 3;
    if (fprintf(fp, "P6\n%d %d\n255\n", w, h) < 0 || fwrite(rgb, 1, n, fp) != n) {
        snprintf(pm->msg, sizeof pm->msg, "write error: %s", strerror(errno));
        return -1;
    }
    return 0;
}

int img_write(const char *path, const unsigned char *rgb, int w, int h, char *err, size_t errlen)
{
    return img_write_as(path, NULL, rgb, w, h, err, errlen);
}

int img_write_as(const char *path, const char *format, const unsigned char *rgb, int w, int h,
                 char *err, size_t errlen)
{
    png_msg pm = {""};
    fio_out *o;
    FILE *fp;
    int fmt;
    if (!path || !rgb) {
        fio_err(err, errlen, path, "no %s given", path ? "pixels" : "path");
        return -1;
    }
    if (format && (fmt = format_named(format)) == FMT_NONE) {
        fio_err(err, errlen, path, "unknown image format '%.20s' (use png or ppm)", format);
        return -1;
    }
    if (!format && (fmt = format_of(path)) == FMT_NONE) {
        fio_err(err, errlen, path, "unknown image extension (use .png or .ppm)");
        return -1;
    }
    if (!size_ok(w, h)) {
        fio_err(err, errlen, path, "invalid image size %dx%d (each must be 1..%d)", w, h,
                IMG_MAX_DIM);
        return -1;
    }
    if (!(o = fio_out_open(path, err, errlen))) return -1;
    fp = fio_out_stream(o);
    if ((fmt == FMT_PNG ? png_write_fp(fp, rgb, w, h, &pm) : ppm_write_fp(fp, rgb, w, h, &pm)) !=
        0) {
        fio_out_abort(o);
        fio_err(err, errlen, path, "%s", pm.msg);
        return -1;
    }
    return fio_out_commit(o, err, errlen);
}

/* PNG bytes in memory (for embedding), through the file writer over a memory stream. */
int img_encode_png(const unsigned char *rgb, int w, int h, unsigned char **out, size_t *n,
                   char *err, size_t errlen)
{
    png_msg pm = {"out of memory"};
    char *data = NULL;
    size_t len = 0;
    FILE *fp;
    int rc = -1;
    *out = NULL;
    *n = 0;
    if (!size_ok(w, h)) {
        snprintf(err, errlen, "invalid image size %dx%d (each must be 1..%d)", w, h, IMG_MAX_DIM);
        return -1;
    }
    fp = open_memstream(&data, &len);
    if (fp && png_write_fp(fp, rgb, w, h, &pm) == 0) rc = 0;
    if (fp && fclose(fp) != 0) rc = -1;
    if (rc == 0) {
        *out = (unsigned char *)data;
        *n = len;
        return 0;
    }
    free(data);
    snprintf(err, errlen, "PNG encoding: %s", pm.msg);
    return -1;
}

/* ---- reading ---- */

/* Everything that must be released after a longjmp lives here, in the caller's frame,
 * so png_read_fp's setjmp never leaves it indeterminate. */
typedef struct {
    png_structp png;
    png_infop info;
    png_bytep *rows;
    unsigned char *pix;
    png_uint_32 w, h;
    png_msg pm;
} png_reader;

/* Asks libpng for 8-bit RGB whatever the stored colour type and depth is. */
static void png_want_rgb8(png_structp png, png_infop info)
{
    int ct = png_get_color_type(png, info);
    if (ct == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
    if ((ct & PNG_COLOR_MASK_COLOR) == 0) {
        if (png_get_bit_depth(png, info) < 8) png_set_expand_gray_1_2_4_to_8(png);
        png_set_gray_to_rgb(png);
    }
    if (png_get_bit_depth(png, info) == 16) png_set_strip_16(png);
    /* palette_to_rgb also turns tRNS into alpha, so strip whenever either is present. */
    if ((ct & PNG_COLOR_MASK_ALPHA) || png_get_valid(png, info, PNG_INFO_tRNS))
        png_set_strip_alpha(png);
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
}

static int png_read_fp(FILE *fp, png_reader *r)
{
    png_uint_32 y;
    r->png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &r->pm, png_on_error, png_on_warning);
    r->info = r->png ? png_create_info_struct(r->png) : NULL;
    if (!r->info) {
        snprintf(r->pm.msg, sizeof r->pm.msg, "out of memory");
        return -1;
    }
    if (setjmp(png_jmpbuf(r->png))) return -1;
    png_init_io(r->png, fp);
    png_set_sig_bytes(r->png, 8);
    png_set_user_limits(r->png, IMG_MAX_DIM, IMG_MAX_DIM); /* reject before allocating */
    png_read_info(r->png, r->info);
    png_want_rgb8(r->png, r->info);
    r->w = png_get_image_width(r->png, r->info);
    r->h = png_get_image_height(r->png, r->info);
    if (png_get_channels(r->png, r->info) != 3 || png_get_bit_depth(r->png, r->info) != 8 ||
        png_get_rowbytes(r->png, r->info) != (size_t)r->w * 3)
        png_error(r->png, "cannot convert to 8-bit RGB");
    r->pix = malloc((size_t)r->w * r->h * 3);
    r->rows = malloc(r->h * sizeof *r->rows);
    if (!r->pix || !r->rows) png_error(r->png, "out of memory");
    for (y = 0; y < r->h; y++) r->rows[y] = r->pix + (size_t)y * r->w * 3;
    png_read_image(r->png, r->rows);
    png_read_end(r->png, NULL); /* checks the trailing chunks: a cut-off file is an error */
    return 0;
}

static int img_read_png(FILE *fp, img_t *out, png_msg *pm)
{
    png_reader r;
    int rc;
    memset(&r, 0, sizeof r);
    rc = png_read_fp(fp, &r);
    png_destroy_read_struct(&r.png, r.info ? &r.info : NULL, NULL);
    free(r.rows);
    if (rc != 0) {
        free(r.pix);
        *pm = r.pm;
        return -1;
    }
    out->w = (int)r.w;
    out->h = (int)r.h;
    out->rgb = r.pix;
    return 0;
}

/* Next PPM header number: skips whitespace and '#' comments; consumes the one
 * character after the digits, which must be whitespace. -1 on error. */
static long ppm_number(FILE *fp)
{
    long v = 0;
    int c = getc(fp), digits = 0;
    for (;;) {
        while (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f')
            c = getc(fp);
        if (c != '#') break;
        while (c != '\n' && c != EOF) c = getc(fp);
    }
    for (; c >= '0' && c <= '9'; c = getc(fp), digits++)
        if ((v = v * 10 + (c - '0')) > 1000000) return -1;
    if (!digits || !(c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'))
        return -1;
    return v;
}

static int img_read_ppm(FILE *fp, img_t *out, png_msg *pm)
{
    long w = ppm_number(fp), h = w < 0 ? -1 : ppm_number(fp), maxv = h < 0 ? -1 : ppm_number(fp);
    size_t n, got;
    if (maxv < 0) {
        snprintf(pm->msg, sizeof pm->msg, "bad or truncated PPM header");
        return -1;
    }
    if (maxv != 255) {
        snprintf(pm->msg, sizeof pm->msg, "PPM maxval %ld not supported (only 255)", maxv);
        return -1;
    }
    if (!size_ok((int)w, (int)h)) {
        snprintf(pm->msg, sizeof pm->msg, "unsupported PPM size %ldx%ld", w, h);
        return -1;
    }
    n = (size_t)w * (size_t)h * 3;
    if (!(out->rgb = malloc(n))) {
        snprintf(pm->msg, sizeof pm->msg, "out of memory");
        return -1;
    }
    if ((got = fread(out->rgb, 1, n, fp)) != n) {
        snprintf(pm->msg, sizeof pm->msg, "truncated PPM pixel data (%zu of %zu bytes)", got, n);
        free(out->rgb);
        out->rgb = NULL;
        return -1;
    }
    out->w = (int)w;
    out->h = (int)h;
    return 0;
}

/* Picks the reader by the magic bytes: "P6" for PPM, the 8-byte signature for PNG. */
static int img_read_fp(FILE *fp, img_t *out, png_msg *pm)
{
    unsigned char sig[8];
    if (fread(sig, 1, 2, fp) == 2 && sig[0] == 'P' && sig[1] == '6')
        return img_read_ppm(fp, out, pm);
    if (fread(sig + 2, 1, 6, fp) == 6 && png_sig_cmp(sig, 0, 8) == 0)
        return img_read_png(fp, out, pm);
    snprintf(pm->msg, sizeof pm->msg, "not a PNG or binary PPM (P6) file");
    return -1;
}

int img_read(const char *path, img_t *out, char *err, size_t errlen)
{
    png_msg pm = {""};
    FILE *fp;
    char *data;
    size_t n;
    int rc;
    if (!out) {
        fio_err(err, errlen, path, "no output image given");
        return -1;
    }
    out->w = out->h = 0;
    out->rgb = NULL;
    if (fio_read_all(path, FIO_LIMIT_IMAGE, &data, &n, err, errlen) != 0) return -1;
    /* fmemopen needs at least one byte; an empty file is no image either way. */
    if (!(fp = n ? fmemopen(data, n, "rb") : NULL))
        snprintf(pm.msg, sizeof pm.msg, "%s",
                 n ? strerror(errno) : "not a PNG or binary PPM (P6) file");
    rc = fp ? img_read_fp(fp, out, &pm) : -1;
    if (fp) fclose(fp);
    free(data);
    if (rc != 0) fio_err(err, errlen, path, "%s", pm.msg);
    return rc;
}

void img_free(img_t *img)
{
    if (!img) return;
    free(img->rgb);
    img->rgb = NULL;
    img->w = img->h = 0;
}

/* ---- tone mapping ---- */

double srgb_encode(double linear)
{
    if (!(linear > 0.0)) /* also NaN */
        return 0.0;
    if (linear >= 1.0) return 1.0;
    return linear <= 0.0031308 ? 12.92 * linear : 1.055 * pow(linear, 1.0 / 2.4) - 0.055;
}

void tonemap(const float *lin, size_t npix, double exposure, unsigned char *out)
{
    size_t i;
    for (i = 0; i < npix * 3; i++) {
        double v = srgb_encode((double)lin[i] * exposure) * 255.0 + 0.5;
        out[i] = (unsigned char)(v >= 255.0 ? 255 : (int)v);
    }
}

static int cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

double tonemap_auto_exposure(const float *lin, size_t npix)
{
    float *m = malloc((npix ? npix : 1) * sizeof *m);
    size_t i, n = 0, rank;
    double e;
    if (!m) return 1.0;
    for (i = 0; i < npix; i++) {
        const float *p = lin + i * 3;
        float v = p[0] > p[1] ? p[0] : p[1];
        v = v > p[2] ? v : p[2];
        if (v > 0.0f && isfinite(v)) m[n++] = v;
    }
    if (n == 0) {
        free(m);
        return 1.0;
    }
    qsort(m, n, sizeof *m, cmp_float);
    /* Nearest rank ceil(0.97 n) = n - floor(0.03 n), in integers so it is exact. */
    rank = n - ((n / 100) * 3 + (n % 100) * 3 / 100);
    e = 1.0 / (double)m[rank - 1];
    free(m);
    return isfinite(e) ? e : 1.0;
}
