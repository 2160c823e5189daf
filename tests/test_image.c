/* SPDX-License-Identifier: MIT */
/* Tests for tools/formats/image.c (PNG/PPM I/O, tone mapping) and tools/bench/plot.c (line plots). */
#include <dirent.h>
#include <float.h>
#include <limits.h>
#include <math.h>
#include <png.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmocka.h>

#include "check.h"
#include "formats/image.h"
#include "bench/plot.h"

/* ---- helpers: one fresh temporary directory per test ---- */

typedef struct {
    char dir[64];
    char path[256];
} tmpdir;

static int setup_dir(void **state)
{
    tmpdir *t = calloc(1, sizeof *t);
    if (!t) return -1;
    strcpy(t->dir, "/tmp/rad_test_image_XXXXXX");
    if (!mkdtemp(t->dir)) {
        free(t);
        return -1;
    }
    *state = t;
    return 0;
}

/* Removes the directory's entries (one level of subdirectories too) and the directory. */
static void remove_tree(const char *dir)
{
    DIR *d = opendir(dir);
    struct dirent *e;
    char p[512];
    if (!d) return;
    while ((e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0) continue;
        snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
        chmod(p, 0700);
        if (unlink(p) != 0) remove_tree(p);
    }
    closedir(d);
    rmdir(dir);
}

static int teardown_dir(void **state)
{
    tmpdir *t = *state;
    remove_tree(t->dir);
    free(t);
    return 0;
}

/* t->path = dir/name (the returned pointer is overwritten by the next call). */
static const char *in_dir(tmpdir *t, const char *name)
{
    snprintf(t->path, sizeof t->path, "%s/%s", t->dir, name);
    return t->path;
}

static int count_entries(const char *dir)
{
    DIR *d = opendir(dir);
    struct dirent *e;
    int n = 0;
    assert_non_null(d);
    while ((e = readdir(d)) != NULL)
        n += strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0;
    closedir(d);
    return n;
}

static int has_tmp_file(const char *dir)
{
    DIR *d = opendir(dir);
    struct dirent *e;
    int found = 0;
    assert_non_null(d);
    while ((e = readdir(d)) != NULL) found |= strstr(e->d_name, ".tmp") != NULL;
    closedir(d);
    return found;
}

static long file_size(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 ? (long)st.st_size : -1;
}

static unsigned char *slurp(const char *path, long *n)
{
    FILE *fp = fopen(path, "rb");
    unsigned char *buf;
    assert_non_null(fp);
    *n = file_size(path);
    CHECK_INT_GT(*n, 0, "size of %s", path);
    buf = malloc((size_t)*n);
    assert_non_null(buf);
    assert_int_equal(fread(buf, 1, (size_t)*n, fp), (size_t)*n);
    fclose(fp);
    return buf;
}

static void spit(const char *path, const void *data, size_t n)
{
    FILE *fp = fopen(path, "wb");
    assert_non_null(fp);
    assert_int_equal(fwrite(data, 1, n, fp), n);
    assert_int_equal(fclose(fp), 0);
}

enum { W = 7, H = 5 };

/* 7x5 test image: red top-left, green top-right, blue bottom-left, white bottom-right,
 * every other pixel distinct, so any flip, transpose or shift shows. */
static void make_image(unsigned char *rgb)
{
    int x, y;
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++) {
            unsigned char *p = rgb + (y * W + x) * 3;
            p[0] = (unsigned char)(10 + 30 * x), p[1] = (unsigned char)(20 + 40 * y),
            p[2] = (unsigned char)(x * y + 7);
        }
    memcpy(rgb, "\xff\x00\x00", 3);
    memcpy(rgb + (W - 1) * 3, "\x00\xff\x00", 3);
    memcpy(rgb + (H - 1) * W * 3, "\x00\x00\xff", 3);
    memcpy(rgb + (H * W - 1) * 3, "\xff\xff\xff", 3);
}

static void assert_px(const img_t *im, int x, int y, int r, int g, int b)
{
    const unsigned char *p = im->rgb + ((size_t)y * (size_t)im->w + (size_t)x) * 3;
    assert_int_equal(p[0], r);
    assert_int_equal(p[1], g);
    assert_int_equal(p[2], b);
}

static void roundtrip(tmpdir *t, const char *name)
{
    unsigned char rgb[W * H * 3];
    char err[256] = "";
    img_t im;
    make_image(rgb);
    assert_int_equal(img_write(in_dir(t, name), rgb, W, H, err, sizeof err), 0);
    assert_int_equal(img_read(in_dir(t, name), &im, err, sizeof err), 0);
    assert_int_equal(im.w, W);
    assert_int_equal(im.h, H);
    assert_memory_equal(im.rgb, rgb, sizeof rgb);
    assert_px(&im, 0, 0, 255, 0, 0); /* row 0 is the top, column 0 the left */
    assert_px(&im, W - 1, 0, 0, 255, 0);
    assert_px(&im, 0, H - 1, 0, 0, 255);
    assert_px(&im, W - 1, H - 1, 255, 255, 255);
    assert_px(&im, 3, 2, 100, 100, 13);
    img_free(&im);
    assert_null(im.rgb);
    img_free(&im); /* idempotent */
    assert_int_equal(count_entries(t->dir), 1);
}

/* ---- image writing and reading ---- */

static void test_png_roundtrip(void **state)
{
    tmpdir *t = *state;
    long n;
    unsigned char *f;
    roundtrip(t, "a.png");
    f = slurp(in_dir(t, "a.png"), &n);
    CHECK_INT_GT(n, 8, "bytes of a.png");
    assert_memory_equal(f, "\x89PNG\r\n\x1a\n", 8);
    free(f);
}

static void test_ppm_roundtrip(void **state)
{
    tmpdir *t = *state;
    static const char hdr[] = "P6\n7 5\n255\n";
    long n;
    unsigned char *f;
    roundtrip(t, "a.ppm");
    f = slurp(in_dir(t, "a.ppm"), &n);
    assert_int_equal(n, (long)(sizeof hdr - 1 + W * H * 3));
    assert_memory_equal(f, hdr, sizeof hdr - 1);
    assert_memory_equal(f + sizeof hdr - 1, "\xff\x00\x00", 3); /* first pixel stored: top-left */
    free(f);
}

static void test_extension_case(void **state)
{
    tmpdir *t = *state;
    long n;
    unsigned char *f;
    roundtrip(t, "UP.PNG");
    f = slurp(in_dir(t, "UP.PNG"), &n);
    assert_int_equal(f[1], 'P');
    free(f);
    unlink(in_dir(t, "UP.PNG"));
    roundtrip(t, "Mixed.pPm");
    f = slurp(in_dir(t, "Mixed.pPm"), &n);
    assert_memory_equal(f, "P6", 2);
    free(f);
}

static void test_unknown_extension(void **state)
{
    static const char *const bad[] = {"a.jpg",     "noext", "a.png.bak", "a.",
                                      "sub.png/x", ".pngx", "a.pn"};
    tmpdir *t = *state;
    unsigned char rgb[W * H * 3] = {0};
    char err[256], want[300];
    size_t i;
    assert_int_equal(mkdir(in_dir(t, "sub.png"), 0700), 0);
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        const char *p = in_dir(t, bad[i]);
        snprintf(want, sizeof want, "%s: unknown image extension (use .png or .ppm)", p);
        err[0] = '\0';
        assert_int_equal(img_write(p, rgb, W, H, err, sizeof err), -1);
        assert_string_equal(err, want);
    }
    assert_int_equal(count_entries(t->dir), 1); /* only sub.png/, nothing written */
    assert_int_equal(count_entries(in_dir(t, "sub.png")), 0);
}

static void test_invalid_sizes(void **state)
{
    static const int sizes[][2] = {{0, 5},        {5, 0},     {0, 0},
                                   {-1, 5},       {5, -3},    {INT_MIN, 1},
                                   {32769, 1},    {1, 32769}, {INT_MAX, INT_MAX},
                                   {65536, 65536}};
    tmpdir *t = *state;
    unsigned char rgb[16] = {0};
    char err[256];
    size_t i;
    for (i = 0; i < sizeof sizes / sizeof sizes[0]; i++) {
        err[0] = '\0';
        assert_int_equal(
            img_write(in_dir(t, "s.png"), rgb, sizes[i][0], sizes[i][1], err, sizeof err), -1);
        CHECK_CONTAINS(err, "invalid image size", "the error message");
        assert_int_equal(img_write(in_dir(t, "s.ppm"), rgb, sizes[i][0], sizes[i][1], NULL, 0), -1);
    }
    assert_int_equal(img_write(in_dir(t, "s.png"), NULL, 1, 1, err, sizeof err), -1);
    assert_int_equal(count_entries(t->dir), 0);
    /* Largest allowed dimension in one direction works. */
    {
        unsigned char *wide = calloc(IMG_MAX_DIM, 3);
        img_t im;
        assert_non_null(wide);
        wide[(IMG_MAX_DIM - 1) * 3 + 2] = 9;
        assert_int_equal(img_write(in_dir(t, "wide.png"), wide, IMG_MAX_DIM, 1, err, sizeof err),
                         0);
        assert_int_equal(img_read(in_dir(t, "wide.png"), &im, err, sizeof err), 0);
        assert_int_equal(im.w, IMG_MAX_DIM);
        assert_memory_equal(im.rgb, wide, IMG_MAX_DIM * 3);
        img_free(&im);
        free(wide);
    }
}

static void test_unwritable_path(void **state)
{
    tmpdir *t = *state;
    unsigned char rgb[W * H * 3];
    char err[256] = "", p[300];
    make_image(rgb);
    snprintf(p, sizeof p, "%s/missing/x.png", t->dir);
    assert_int_equal(img_write(p, rgb, W, H, err, sizeof err), -1);
    CHECK_THAT(strncmp(err, p, strlen(p)) == 0, "the error \"%s\" starts with the path %s", err, p);
    CHECK_THAT(strchr(err, '\n') == NULL, "the error \"%s\" is one line", err);
    CHECK_CONTAINS(err, "No such file", "the error message");
    assert_int_equal(count_entries(t->dir), 0);

    /* A directory in the way fails only at the rename: the temporary must be gone. */
    assert_int_equal(mkdir(in_dir(t, "d.ppm"), 0700), 0);
    err[0] = '\0';
    assert_int_equal(img_write(in_dir(t, "d.ppm"), rgb, W, H, err, sizeof err), -1);
    CHECK_INT_NE(err[0], '\0', "the error message's first character");
    assert_int_equal(count_entries(t->dir), 1);
    CHECK_THAT(!has_tmp_file(t->dir), "no temporary file left in %s", t->dir);
    assert_int_equal(count_entries(in_dir(t, "d.ppm")), 0);

    if (geteuid() != 0) { /* root ignores directory permissions */
        assert_int_equal(mkdir(in_dir(t, "ro"), 0500), 0);
        snprintf(p, sizeof p, "%s/ro/x.png", t->dir);
        assert_int_equal(img_write(p, rgb, W, H, err, sizeof err), -1);
        assert_int_equal(count_entries(in_dir(t, "ro")), 0);
    }
}

static void test_overwrite_atomic(void **state)
{
    tmpdir *t = *state;
    unsigned char a[W * H * 3], b[3 * 2 * 3];
    char err[256];
    struct stat st1, st2;
    img_t im;
    const char *p = in_dir(t, "o.png");
    size_t i;
    make_image(a);
    for (i = 0; i < sizeof b; i++) b[i] = (unsigned char)(200 - i);
    assert_int_equal(img_write(p, a, W, H, err, sizeof err), 0);
    assert_int_equal(chmod(p, 0640), 0);
    assert_int_equal(stat(p, &st1), 0);
    assert_int_equal(img_write(p, b, 3, 2, err, sizeof err), 0);
    assert_int_equal(stat(p, &st2), 0);
    assert_int_not_equal(st1.st_ino, st2.st_ino); /* replaced by rename, not rewritten in place */
    assert_int_equal(st2.st_mode & 0777, 0640);   /* the replaced file's mode is kept */
    assert_int_equal(count_entries(t->dir), 1);
    assert_int_equal(img_read(p, &im, err, sizeof err), 0);
    assert_int_equal(im.w, 3);
    assert_int_equal(im.h, 2);
    assert_memory_equal(im.rgb, b, sizeof b);
    img_free(&im);

    /* A failed write leaves the existing file exactly as it was. */
    assert_int_equal(img_write(p, b, 0, 2, err, sizeof err), -1);
    assert_int_equal(stat(p, &st1), 0);
    assert_int_equal(st1.st_ino, st2.st_ino);
    assert_int_equal(st1.st_size, st2.st_size);
    assert_int_equal(count_entries(t->dir), 1);
}

static void test_new_file_mode(void **state)
{
    tmpdir *t = *state;
    unsigned char px[3] = {1, 2, 3};
    struct stat st;
    mode_t old = umask(022);
    assert_int_equal(img_write(in_dir(t, "m.ppm"), px, 1, 1, NULL, 0), 0);
    umask(old);
    assert_int_equal(stat(in_dir(t, "m.ppm"), &st), 0);
    assert_int_equal(st.st_mode & 0777, 0644); /* not mkstemp's 0600 */
}

/* Every proper prefix of a valid file must be rejected cleanly. */
static void truncations(tmpdir *t, const char *name)
{
    unsigned char rgb[W * H * 3];
    char err[256];
    unsigned char *full;
    long n, k;
    img_t im;
    make_image(rgb);
    assert_int_equal(img_write(in_dir(t, name), rgb, W, H, err, sizeof err), 0);
    full = slurp(in_dir(t, name), &n);
    for (k = 0; k < n; k++) {
        spit(in_dir(t, "cut"), full, (size_t)k);
        im.w = 99, im.rgb = full;
        err[0] = '\0';
        assert_int_equal(img_read(in_dir(t, "cut"), &im, err, sizeof err), -1);
        assert_null(im.rgb);
        assert_int_equal(im.w, 0);
        CHECK_THAT(strncmp(err, t->path, strlen(t->path)) == 0,
                   "%s cut at %ld bytes: the error \"%s\" starts with the path", name, k, err);
        CHECK_INT_GT(strlen(err), strlen(t->path) + 2,
                     "%s cut at %ld bytes: length of the error \"%s\"", name, k, err);
    }
    spit(in_dir(t, "cut"), full, (size_t)n); /* and the whole file still reads */
    assert_int_equal(img_read(in_dir(t, "cut"), &im, err, sizeof err), 0);
    img_free(&im);
    free(full);
}

static void test_truncated_png(void **state)
{
    truncations(*state, "t.png");
}
static void test_truncated_ppm(void **state)
{
    truncations(*state, "t.ppm");
}

static void test_ppm_header(void **state)
{
    tmpdir *t = *state;
    static const char ok[] =
        "P6\n# made by hand\n2 # width\n  1\n#max\n255\n\x01\x02\x03\xfa\xfb\xfc";
    char err[256];
    img_t im;
    spit(in_dir(t, "c.ppm"), ok, sizeof ok - 1);
    assert_int_equal(img_read(t->path, &im, err, sizeof err), 0);
    assert_int_equal(im.w, 2);
    assert_int_equal(im.h, 1);
    assert_px(&im, 0, 0, 1, 2, 3);
    assert_px(&im, 1, 0, 0xfa, 0xfb, 0xfc);
    img_free(&im);

    spit(in_dir(t, "d.ppm"), "P6\n1 1\n65535\n\0\0\0\0\0\0", 19);
    assert_int_equal(img_read(t->path, &im, err, sizeof err), -1);
    CHECK_CONTAINS(err, "maxval", "the error message");
    spit(in_dir(t, "e.ppm"), "P3\n1 1\n255\n0 0 0\n", 17);
    assert_int_equal(img_read(t->path, &im, err, sizeof err), -1);
    CHECK_CONTAINS(err, "not a PNG or binary PPM", "the error message");
    spit(in_dir(t, "f.ppm"), "P6\n0 1\n255\n", 11);
    assert_int_equal(img_read(t->path, &im, err, sizeof err), -1);
    spit(in_dir(t, "g.ppm"), "P6\n99999999999 1\n255\n", 21);
    assert_int_equal(img_read(t->path, &im, err, sizeof err), -1);
    spit(in_dir(t, "h.ppm"), "P6\n-1 1\n255\n", 12);
    assert_int_equal(img_read(t->path, &im, err, sizeof err), -1);
    assert_int_equal(img_read(in_dir(t, "absent.png"), &im, err, sizeof err), -1);
    CHECK_CONTAINS(err, "No such file", "the error message");
    assert_null(im.rgb);
}

/* Writes a PNG of any colour type straight through libpng, to test the reader's
 * conversions. rows is h rows of packed samples, rowbytes each. */
static void raw_png(const char *path, int w, int h, int depth, int ctype, int interlace,
                    const unsigned char *rows, size_t rowbytes, const png_color *pal, int npal,
                    const unsigned char *trns, int ntrns, const png_color_16 *tc)
{
    FILE *fp = fopen(path, "wb");
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png_create_info_struct(png);
    png_bytep rp[8];
    int y;
    assert_non_null(fp);
    assert_non_null(info);
    CHECK_INT_LE(h, 8, "rows of the test PNG");
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        fclose(fp);
        fail_msg("libpng could not write %s", path);
    }
    png_init_io(png, fp);
    png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, depth, ctype, interlace,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    if (pal) png_set_PLTE(png, info, pal, npal);
    if (trns || tc) png_set_tRNS(png, info, trns, ntrns, tc);
    for (y = 0; y < h; y++) rp[y] = (png_bytep)(rows + (size_t)y * rowbytes);
    png_write_info(png, info);
    png_write_image(png, rp);
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    assert_int_equal(fclose(fp), 0);
}

static void read_expect(const char *path, int w, int h, const unsigned char *want)
{
    char err[256] = "";
    img_t im;
    int rc = img_read(path, &im, err, sizeof err);
    if (rc != 0) fail_msg("%s", err);
    assert_int_equal(im.w, w);
    assert_int_equal(im.h, h);
    assert_memory_equal(im.rgb, want, (size_t)w * (size_t)h * 3);
    img_free(&im);
}

static void test_png_colour_types(void **state)
{
    tmpdir *t = *state;
    static const unsigned char grey8[] = {0, 128, 255, 7, 8, 9};
    static const unsigned char grey8_rgb[] = {0, 0, 0, 128, 128, 128, 255, 255, 255,
                                              7, 7, 7, 8,   8,   8,   9,   9,   9};
    static const unsigned char grey16[] = {0xab, 0x12, 0x01, 0xff};
    static const unsigned char grey16_rgb[] = {0xab, 0xab, 0xab, 0x01, 0x01, 0x01};
    static const unsigned char ga[] = {10, 0, 20, 255};
    static const unsigned char ga_rgb[] = {10, 10, 10, 20, 20, 20};
    static const unsigned char rgba[] = {1, 2, 3, 0, 4, 5, 6, 128};
    static const unsigned char rgba_rgb[] = {1, 2, 3, 4, 5, 6};
    static const unsigned char rgb16[] = {0x10, 0xff, 0x20, 0x00, 0x30, 0x80};
    static const unsigned char rgb16_rgb[] = {0x10, 0x20, 0x30};
    static const unsigned char grey1[] = {0xa0}; /* 1 0 1 */
    static const unsigned char grey1_rgb[] = {255, 255, 255, 0, 0, 0, 255, 255, 255};
    static const png_color pal[3] = {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}};
    static const unsigned char trns[3] = {255, 0, 128};
    static const unsigned char idx4[] = {0x12, 0x00, 0x21, 0x00}; /* rows: 1 2 0 / 2 1 0 */
    static const unsigned char idx4_rgb[] = {0, 255, 0,   0, 0,   255, 255, 0, 0,
                                             0, 0,   255, 0, 255, 0,   255, 0, 0};
    static const unsigned char grey2[] = {0x6c}; /* 1 2 3 */
    static const unsigned char grey2_rgb[] = {85, 85, 85, 170, 170, 170, 255, 255, 255};
    static const unsigned char rgbt[] = {2, 2, 2, 9, 8, 7};
    static const png_color_16 key = {0, 2, 2, 2, 2};
    unsigned char inter[8 * 8 * 3], *p;
    int i;

    raw_png(in_dir(t, "g8.png"), 3, 2, 8, PNG_COLOR_TYPE_GRAY, 0, grey8, 3, NULL, 0, NULL, 0, NULL);
    read_expect(t->path, 3, 2, grey8_rgb);
    raw_png(in_dir(t, "g16.png"), 2, 1, 16, PNG_COLOR_TYPE_GRAY, 0, grey16, 4, NULL, 0, NULL, 0,
            NULL);
    read_expect(t->path, 2, 1, grey16_rgb);
    raw_png(in_dir(t, "ga.png"), 2, 1, 8, PNG_COLOR_TYPE_GRAY_ALPHA, 0, ga, 4, NULL, 0, NULL, 0,
            NULL);
    read_expect(t->path, 2, 1, ga_rgb);
    raw_png(in_dir(t, "rgba.png"), 2, 1, 8, PNG_COLOR_TYPE_RGB_ALPHA, 0, rgba, 8, NULL, 0, NULL, 0,
            NULL);
    read_expect(t->path, 2, 1, rgba_rgb);
    raw_png(in_dir(t, "rgb16.png"), 1, 1, 16, PNG_COLOR_TYPE_RGB, 0, rgb16, 6, NULL, 0, NULL, 0,
            NULL);
    read_expect(t->path, 1, 1, rgb16_rgb);
    raw_png(in_dir(t, "g1.png"), 3, 1, 1, PNG_COLOR_TYPE_GRAY, 0, grey1, 1, NULL, 0, NULL, 0, NULL);
    read_expect(t->path, 3, 1, grey1_rgb);
    raw_png(in_dir(t, "p4.png"), 3, 2, 4, PNG_COLOR_TYPE_PALETTE, 0, idx4, 2, pal, 3, trns, 3,
            NULL);
    read_expect(t->path, 3, 2, idx4_rgb);
    /* Grey and RGB with a tRNS colour key: the key is dropped, not composited. */
    raw_png(in_dir(t, "g2t.png"), 3, 1, 2, PNG_COLOR_TYPE_GRAY, 0, grey2, 1, NULL, 0, NULL, 0,
            &key);
    read_expect(t->path, 3, 1, grey2_rgb);
    raw_png(in_dir(t, "rgbt.png"), 2, 1, 8, PNG_COLOR_TYPE_RGB, 0, rgbt, 6, NULL, 0, NULL, 0, &key);
    read_expect(t->path, 2, 1, rgbt);
    for (i = 0, p = inter; i < 64 * 3; i++) p[i] = (unsigned char)(i * 7 + 3);
    raw_png(in_dir(t, "il.png"), 8, 8, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_ADAM7, inter, 24, NULL,
            0, NULL, 0, NULL);
    read_expect(t->path, 8, 8, inter);
}

/* ---- tone mapping ---- */

static double srgb_ref(double v)
{
    return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}

static void test_srgb_encode(void **state)
{
    static const double pts[] = {0.0, 0.0031308, 0.5, 1.0, 0.001, 0.0031309, 0.18, 0.999};
    size_t i;
    (void)state;
    CHECK_EQ(srgb_encode(0.0), 0.0, "srgb_encode(0)");
    CHECK_EQ(srgb_encode(1.0), 1.0, "srgb_encode(1)");
    CHECK_LT(fabs(srgb_encode(0.0031308) - 0.040449936), 1e-12, "srgb_encode(0.0031308): error");
    CHECK_LT(fabs(srgb_encode(0.5) - 0.7353569830524495), 1e-12, "srgb_encode(0.5): error");
    for (i = 0; i < sizeof pts / sizeof pts[0]; i++)
        CHECK_LT(fabs(srgb_encode(pts[i]) - srgb_ref(pts[i])), 1e-12,
                 "srgb_encode(%g): error against the standard curve", pts[i]);
    /* Both branches meet at the threshold (continuity of the standard curve). */
    CHECK_LT(fabs(srgb_encode(0.0031308) - (1.055 * pow(0.0031308, 1 / 2.4) - 0.055)), 1e-6,
             "srgb_encode(0.0031308): error against the power branch");
    CHECK_EQ(srgb_encode(-0.5), 0.0, "srgb_encode(-0.5)");
    CHECK_EQ(srgb_encode(7.0), 1.0, "srgb_encode(7)");
    CHECK_EQ(srgb_encode(NAN), 0.0, "srgb_encode(NaN)");
}

static void test_tonemap(void **state)
{
    const float lin[] = {0.0f,    1.0f, -1.0f,    2.0f,  0.5f, 0.001f,
                         0.0015f, NAN,  INFINITY, 0.25f, 0.6f, -INFINITY};
    unsigned char out[12];
    size_t i;
    (void)state;
    memset(out, 0x55, sizeof out);
    tonemap(lin, 4, 1.0, out);
    assert_int_equal(out[0], 0);
    assert_int_equal(out[1], 255);
    assert_int_equal(out[2], 0);   /* negative clamps to 0 */
    assert_int_equal(out[3], 255); /* > 1 clamps to 1 */
    assert_int_equal(out[4], 188); /* 255 * 0.73536 = 187.52 rounds up */
    assert_int_equal(out[5], 3);   /* 255 * 12.92 * 0.001 = 3.29 rounds down */
    assert_int_equal(out[6], 5);   /* 4.94 rounds up */
    assert_int_equal(out[7], 0);   /* NaN */
    assert_int_equal(out[8], 255);
    assert_int_equal(out[9], 137); /* 255 * srgb(0.25) = 136.8 */
    assert_int_equal(out[11], 0);
    for (i = 0; i < 12; i++)
        if (isfinite(lin[i]) && lin[i] >= 0.0f && lin[i] <= 1.0f)
            assert_int_equal(out[i], (int)floor(255.0 * srgb_ref(lin[i]) + 0.5));
    tonemap(lin, 4, 2.0, out);      /* exposure scales before clamping */
    assert_int_equal(out[9], 188);  /* 0.25 * 2 = 0.5 */
    assert_int_equal(out[10], 255); /* 0.6 * 2 clips */
    assert_int_equal(out[4], 255);
    assert_int_equal(out[5], 7); /* 0.002: 255 * 12.92 * 0.002 = 6.59 */
}

static void test_auto_exposure(void **state)
{
    float lin[200 * 3];
    float *big;
    size_t i;
    (void)state;
    /* 100 lit pixels whose max is 1..100 (in scrambled channels), plus unlit ones. */
    memset(lin, 0, sizeof lin);
    for (i = 0; i < 100; i++) {
        float *p = lin + ((i * 37) % 100) * 3;
        p[i % 3] = (float)(i + 1);
        p[(i + 1) % 3] = 0.5f;
    }
    for (i = 100; i < 200; i++) lin[i * 3] = i % 2 ? -5.0f : 0.0f;
    CHECK_LT(fabs(tonemap_auto_exposure(lin, 200) - 1.0 / 97.0), 1e-12,
             "exposure of 200 pixels: error against 1/97 (the 97th percentile maps to white)");
    CHECK_LT(fabs(tonemap_auto_exposure(lin, 100) - 1.0 / 97.0), 1e-12,
             "exposure of 100 pixels: error against 1/97 (the 97th percentile maps to white)");
    CHECK_EQ(tonemap_auto_exposure(lin + 300, 100), 1.0, "exposure with nothing lit");
    CHECK_EQ(tonemap_auto_exposure(lin, 0), 1.0, "exposure of no pixels");
    lin[0] = 0.0f, lin[1] = 4.0f, lin[2] = 1.0f;
    CHECK_EQ(tonemap_auto_exposure(lin, 1), 0.25, "exposure of one pixel of max 4");
    /* 3% bright lights clip, the rest (0.5) maps to 1.0. */
    big = malloc(1000 * 3 * sizeof *big);
    assert_non_null(big);
    for (i = 0; i < 3000; i++) big[i] = (i / 3) < 970 ? 0.5f : 100.0f;
    CHECK_EQ(tonemap_auto_exposure(big, 1000), 2.0,
             "exposure with 3%% of lights at 100, the rest 0.5");
    big[970 * 3] = NAN; /* non-finite values are not "lit" */
    big[971 * 3] = INFINITY;
    CHECK_EQ(tonemap_auto_exposure(big, 1000), 2.0,
             "exposure with a NaN and an infinity among the lights");
    free(big);
}

/* ---- plots ---- */

enum { PW = 320, PH = 240 };
static const unsigned char RED[3] = {255, 0, 0}, BLUE[3] = {0, 0, 255};

static int is_col(const unsigned char *rgb, int x, int y, const unsigned char c[3])
{
    return memcmp(rgb + ((size_t)y * PW + (size_t)x) * 3, c, 3) == 0;
}

static int count_col(const unsigned char *rgb, const unsigned char c[3])
{
    int i, n = 0;
    for (i = 0; i < PW * PH; i++) n += memcmp(rgb + i * 3, c, 3) == 0;
    return n;
}

/* The frame: leftmost column and lowest row that are mostly black. */
static void find_frame(const unsigned char *rgb, int *x0, int *y1)
{
    static const unsigned char black[3] = {0, 0, 0};
    int x, y, n;
    *x0 = *y1 = -1;
    for (x = 0; x < PW && *x0 < 0; x++) {
        for (y = 0, n = 0; y < PH; y++) n += is_col(rgb, x, y, black);
        if (n > PH / 2) *x0 = x;
    }
    for (y = PH - 1; y >= 0 && *y1 < 0; y--) {
        for (x = 0, n = 0; x < PW; x++) n += is_col(rgb, x, y, black);
        if (n > PW / 2) *y1 = y;
    }
}

/* Rows in column x that have colour c: first and last, -1 if none. */
static void col_span(const unsigned char *rgb, int x, const unsigned char c[3], int *top, int *bot)
{
    int y;
    *top = *bot = -1;
    for (y = 0; y < PH; y++)
        if (is_col(rgb, x, y, c)) {
            *top = *top < 0 ? y : *top;
            *bot = y;
        }
}

static void test_plot_lines(void **state)
{
    double x[11], up[11], down[11];
    plot_series s[2] = {{NULL, x, up, 11, {255, 0, 0}}, {NULL, x, down, 11, {0, 0, 255}}};
    plot_opts o = {.title = "Title", .xlabel = "iteration", .ylabel = "residual"};
    unsigned char *rgb = malloc(PW * PH * 3);
    int i, x0, y1, top, bot, t2, b2;
    (void)state;
    assert_non_null(rgb);
    for (i = 0; i < 11; i++) x[i] = i, up[i] = i, down[i] = 10 - i;
    memset(rgb, 0x55, PW * PH * 3);
    assert_int_equal(plot_render(rgb, PW, PH, s, 2, &o), 0);
    for (i = 0; i < PW * PH * 3; i++)
        CHECK_INT_NE(rgb[i], 0x55, "canvas byte %d (the whole canvas is painted)", i);
    find_frame(rgb, &x0, &y1);
    /* room for tick labels and the y label */
    CHECK_INT_GT(x0, 10, "the frame's left column");
    CHECK_INT_LT(x0, PW / 3, "the frame's left column");
    CHECK_INT_GT(y1, PH * 2 / 3, "the frame's bottom row");
    CHECK_INT_LT(y1, PH - 10, "the frame's bottom row");
    CHECK_THAT(is_col(rgb, x0 - 2, y1, (const unsigned char *)"\0\0\0"),
               "pixel %d, %d: the black tick mark at 0,0", x0 - 2, y1);
    /* The rising red line is low at the left and high at the right; blue the reverse. */
    col_span(rgb, x0 + 3, RED, &top, &bot);
    col_span(rgb, x0 + 3, BLUE, &t2, &b2);
    CHECK_INT_GT(top, 0, "left: the red line's top row");
    CHECK_INT_GE(bot, y1 - 8, "left: the red line's bottom row (near the frame's bottom)");
    CHECK_INT_LT(bot, y1, "left: the red line's bottom row (above the frame's bottom)");
    CHECK_INT_GT(t2, 0, "left: the blue line's top row");
    CHECK_INT_LT(t2, PH / 4, "left: the blue line's top row");
    col_span(rgb, PW - 30, RED, &top, &bot);
    col_span(rgb, PW - 30, BLUE, &t2, &b2);
    CHECK_INT_GT(top, 0, "right: the red line's top row");
    CHECK_INT_LT(top, PH / 3, "right: the red line's top row");
    CHECK_INT_GT(b2, PH / 2, "right: the blue line's bottom row");
    CHECK_INT_LT(b2, y1, "right: the blue line's bottom row");
    /* Black text above the frame (title) and below it (tick labels, x label). */
    for (i = 0, top = 0; i < PW * 20; i++) top += memcmp(rgb + i * 3, "\0\0\0", 3) == 0;
    CHECK_INT_GT(top, 20, "black pixels of the title above the frame");
    free(rgb);
}

static void test_plot_legend_and_flat(void **state)
{
    double x[2] = {0, 100}, y[2] = {3, 3};
    plot_series s = {"flat", x, y, 2, {255, 0, 0}};
    unsigned char *rgb = malloc(PW * PH * 3);
    int x0, y1, top, bot, t2, b2, row, xx, run, best = 0;
    (void)state;
    assert_non_null(rgb);
    assert_int_equal(plot_render(rgb, PW, PH, &s, 1, NULL), 0);
    find_frame(rgb, &x0, &y1);
    /* All-equal y: one horizontal line in the middle of the plot, 2 px thick. */
    col_span(rgb, x0 + 5, RED, &top, &bot);
    CHECK_INT_GT(top, 0, "the flat line's top row");
    CHECK_INT_EQ(bot - top, 1, "the flat line's thickness less one");
    CHECK_INT_GT(top, PH / 4, "the flat line's top row (in the middle)");
    CHECK_INT_LT(top, PH * 3 / 4, "the flat line's top row (in the middle)");
    col_span(rgb, (x0 + PW) / 2, RED, &t2, &b2);
    assert_int_equal(t2, top);
    /* The legend sample is a red run of >= 16 px on a row other than the line's. */
    for (row = 0; row < PH; row++) {
        if (row == top || row == bot) continue;
        for (xx = 0, run = 0; xx < PW; xx++) {
            run = is_col(rgb, xx, row, RED) ? run + 1 : 0;
            best = run > best ? run : best;
        }
    }
    CHECK_INT_GE(best, 16, "the longest red run off the line (the legend sample)");
    free(rgb);
}

static void test_plot_degenerate(void **state)
{
    double y[6] = {1, 0, -5, 10, 100, NAN}, neg[3] = {0, -1, -2}, one = 42;
    plot_series s[3] = {{"a", NULL, y, 6, {255, 0, 0}},
                        {NULL, NULL, neg, 3, {0, 0, 255}},
                        {"", NULL, &one, 0, {0, 0, 255}}};
    plot_opts o = {.log_y = 1};
    unsigned char *rgb = malloc(PW * PH * 3), tiny[10 * 10 * 3 + 64];
    int x0, y1, i, tw, th;
    (void)state;
    assert_non_null(rgb);
    /* Log axis: nonpositive and NaN points are skipped; the all-nonpositive series and
     * the empty one (both without legend entries) draw nothing. */
    assert_int_equal(plot_render(rgb, PW, PH, s, 3, &o), 0);
    CHECK_INT_GT(count_col(rgb, RED), 40, "red pixels of the log plot");
    assert_int_equal(count_col(rgb, BLUE), 0);
    s[0].n = 0;
    s[0].label = s[1].label = s[2].label = NULL;
    assert_int_equal(plot_render(rgb, PW, PH, s, 3, &o), 0);
    assert_int_equal(count_col(rgb, RED), 0);
    assert_int_equal(count_col(rgb, BLUE), 0);
    find_frame(rgb, &x0, &y1);
    CHECK_INT_GT(x0, 0, "the frame's left column");
    CHECK_INT_GT(y1, 0, "the frame's bottom row");
    assert_int_equal(plot_render(rgb, PW, PH, NULL, 0, NULL), 0); /* no series at all */
    s[2].n = 1;                                                   /* one point: a dot */
    o.log_y = 0;
    assert_int_equal(plot_render(rgb, PW, PH, &s[2], 1, &o), 0);
    CHECK_INT_GE(count_col(rgb, BLUE), 4, "blue pixels of the one-point dot");
    /* Canvases too small for the layout: still nothing written outside them. */
    for (tw = 1; tw <= 10; tw += 3)
        for (th = 1; th <= 10; th += 3) {
            memset(tiny, 0x55, sizeof tiny);
            assert_int_equal(plot_render(tiny, tw, th, s, 3, &o), 0);
            for (i = tw * th * 3; i < (int)sizeof tiny; i++) assert_int_equal(tiny[i], 0x55);
        }
    /* Extreme values must not overflow the axis arithmetic. */
    y[0] = 1e300, y[1] = -1e300, y[2] = 1e-300, y[3] = DBL_MAX, y[4] = -DBL_MAX;
    s[0].n = 6;
    assert_int_equal(plot_render(rgb, PW, PH, s, 1, &o), 0);
    o.log_y = 1;
    assert_int_equal(plot_render(rgb, PW, PH, s, 1, &o), 0);
    /* Bad arguments. */
    assert_int_equal(plot_render(NULL, PW, PH, s, 1, &o), -1);
    assert_int_equal(plot_render(rgb, 0, PH, s, 1, &o), -1);
    assert_int_equal(plot_render(rgb, PW, PH, NULL, 1, &o), -1);
    assert_int_equal(plot_render(rgb, PW, PH, s, -1, &o), -1);
    s[0].n = -1;
    assert_int_equal(plot_render(rgb, PW, PH, s, 1, &o), -1);
    s[0].n = 1, s[0].y = NULL;
    assert_int_equal(plot_render(rgb, PW, PH, s, 1, &o), -1);
    free(rgb);
}

/* The row of the middle of the red pixels in column X, -1 when none. */
static int red_row(const unsigned char *rgb, int x)
{
    int top, bot;
    col_span(rgb, x, RED, &top, &bot);
    return top < 0 ? -1 : (top + bot) / 2;
}

/* y = x^2 from 10 to 1000 on log-log axes is a straight line: at the middle of its
 * columns the row lies within 2 pixels of its ends' mean. With a linear x axis the
 * same points bend (the middle column is x = 505, whose log y is 85% of the way up,
 * not 50%): the test tells the two apart. */
static void test_plot_log_x(void **state)
{
    double x[5] = {10, 31.6227766, 100, 316.227766, 1000}, y[5];
    plot_series s = {NULL, x, y, 5, {255, 0, 0}};
    plot_opts o = {.log_x = 1, .log_y = 1};
    unsigned char *rgb = malloc(PW * PH * 3);
    int k, xl = -1, xr = -1, xx, mid, ends;
    (void)state;
    assert_non_null(rgb);
    for (k = 0; k < 5; k++) y[k] = x[k] * x[k];
    for (k = 0; k < 2; k++) {
        assert_int_equal(plot_render(rgb, PW, PH, &s, 1, &o), 0);
        for (xx = 0, xl = xr = -1; xx < PW; xx++)
            if (red_row(rgb, xx) >= 0) {
                xl = xl < 0 ? xx : xl;
                xr = xx;
            }
        CHECK_INT_GT(xr - xl, PW / 3, "the red line's width in columns");
        mid = red_row(rgb, (xl + xr) / 2);
        ends = (red_row(rgb, xl + 2) + red_row(rgb, xr - 2)) / 2;
        if (k == 0)
            CHECK_INT_LE(abs(mid - ends), 2,
                         "log-log: the middle row's distance from the ends' mean");
        else
            CHECK_INT_GT(abs(mid - ends), 20,
                         "linear x: the middle row's distance from the ends' mean");
        o.log_x = 0;
    }
    free(rgb);
}

static void test_plot_text(void **state)
{
    unsigned char c[12 * 10 * 3];
    const unsigned char k[3] = {0, 0, 0};
    int x;
    (void)state;
    memset(c, 255, sizeof c);
    assert_int_equal(plot_text(c, 12, 10, 2, 1, "-", 1, k), 6);
    for (x = 0; x < 12; x++) { /* '-' is the full 5-pixel middle row of its cell */
        assert_int_equal(c[((1 + 3) * 12 + x) * 3], x >= 2 && x <= 6 ? 0 : 255);
        assert_int_equal(c[((1 + 2) * 12 + x) * 3], 255);
    }
    memset(c, 255, sizeof c);
    plot_text(c, 12, 10, 0, 0, "|", 1, k); /* '|' is column 2, all 7 rows */
    for (x = 0; x < 10; x++) assert_int_equal(c[(x * 12 + 2) * 3], x < 7 ? 0 : 255);
    plot_text(c, 12, 10, -100, -100, "clipped \x01\xff", 3, k); /* off-canvas, odd bytes */
}

static void test_plot_write(void **state)
{
    tmpdir *t = *state;
    double y[3] = {3, 1, 2};
    plot_series s = {"s", NULL, y, 3, {0, 128, 0}};
    plot_opts o = {.title = "t", .xlabel = "x", .ylabel = "y", .width = 400, .height = 300};
    char err[256] = "";
    img_t im;
    assert_int_equal(plot_write(in_dir(t, "p.png"), &s, 1, &o, err, sizeof err), 0);
    assert_int_equal(img_read(t->path, &im, err, sizeof err), 0);
    assert_int_equal(im.w, 400);
    assert_int_equal(im.h, 300);
    assert_px(&im, 0, 0, 255, 255, 255);
    img_free(&im);
    assert_int_equal(plot_write(in_dir(t, "p.gif"), &s, 1, &o, err, sizeof err), -1);
    CHECK_CONTAINS(err, "unknown image extension", "the error message");
    s.n = -1;
    assert_int_equal(plot_write(in_dir(t, "q.png"), &s, 1, NULL, err, sizeof err), -1);
    assert_int_equal(count_entries(t->dir), 1);
}

#define T(f) cmocka_unit_test_setup_teardown(f, setup_dir, teardown_dir)

int main(void)
{
    const struct CMUnitTest tests[] = {
        T(test_png_roundtrip),
        T(test_ppm_roundtrip),
        T(test_extension_case),
        T(test_unknown_extension),
        T(test_invalid_sizes),
        T(test_unwritable_path),
        T(test_overwrite_atomic),
        T(test_new_file_mode),
        T(test_truncated_png),
        T(test_truncated_ppm),
        T(test_ppm_header),
        T(test_png_colour_types),
        cmocka_unit_test(test_srgb_encode),
        cmocka_unit_test(test_tonemap),
        cmocka_unit_test(test_auto_exposure),
        T(test_plot_lines),
        T(test_plot_legend_and_flat),
        T(test_plot_degenerate),
        T(test_plot_log_x),
        T(test_plot_text),
        T(test_plot_write),
    };
    return cmocka_run_group_tests_name("image", tests, NULL, NULL);
}
