/* Tests for what game tools bake: tools/formats/hdr.c (Radiance RGBE images),
 * tools/bake/lightmap.c (charts, atlas, texels, dilation) and tools/bake/probes.c. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <cmocka.h>

#include "check.h"
#include "tmpdir.h"
#include "formats/hdr.h"

/* stb_image's own HDR reader, an independent decoder of what hdr_write writes (static:
 * its unused functions are reported at the end of the file, so that warning stays off). */
#if defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wmissing-prototypes"
#pragma GCC diagnostic ignored "-Wundef"
#pragma GCC diagnostic ignored "-Wpedantic"
#endif
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_HDR
#include <stb/stb_image.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

TMPDIR_GROUP("bake")

/* ---- hdr ---------------------------------------------------------------------------- */

/* A known image: channels m 2^e over e in -40..40 (a pixel's channels apart by up to
 * 2^12, so the small ones test the shared exponent), zeros, runs of one value (the
 * RLE's runs), and largest channels just below a power of two (m 256 rounding to 256). */
static float *hdr_known(int w, int h)
{
    float *p = malloc((size_t)w * h * 3 * sizeof *p);
    uint32_t x = 12345u;
    int i, k;
    for (i = 0; p && i < w * h; i++) {
        for (k = 0; k < 3; k++) {
            x = x * 1664525u + 1013904223u;
            p[3 * i + k] = (float)ldexp(0.5 + (x >> 8) / 33554432.0, (int)((x >> 4) % 81) - 40 - 6 * k);
        }
        if (i % 7 == 0) p[3 * i + 1] = 0.0f;
        if (i % 11 == 0) p[3 * i] = p[3 * i + 1] = p[3 * i + 2] = 0.0f;
        if (i % 13 == 0) p[3 * i] = (float)ldexp(1.0 - 1.0 / 1024.0, i % 9);
        if (i / w == 1) p[3 * i] = p[3 * i + 1] = p[3 * i + 2] = 0.25f; /* a run */
    }
    return p;
}

/* Every channel of every pixel within 2^-8 of the pixel's largest channel as read
 * back (hdr.h derives it: half a step of 2^(e-8), the largest at least 128 steps). */
static double hdr_check_close(const float *want, const float *got, int w, int h)
{
    double worst = 0.0;
    int i, k;
    for (i = 0; i < w * h; i++) {
        double m = fmax(got[3 * i], fmax(got[3 * i + 1], got[3 * i + 2]));
        for (k = 0; k < 3; k++) {
            double d = fabs((double)got[3 * i + k] - want[3 * i + k]);
            CHECK_LE(d, ldexp(m, -8), "pixel %d channel %d: |read - written| against 2^-8 of the largest channel", i, k);
            if (m > 0.0 && d / m > worst) worst = d / m;
        }
    }
    return worst;
}

static void hdr_round_trip(int w, int h)
{
    const char *path = tmp_path("rt.hdr");
    char err[256] = "";
    float *img = hdr_known(w, h), *stb;
    hdr_image back;
    int sw = 0, sh = 0, sn = 0;
    assert_non_null(img);
    CHECK_INT_EQ(hdr_write(path, img, w, h, err, sizeof err), 0, "hdr_write %dx%d (%s)", w, h, err);
    CHECK_INT_EQ(hdr_read(path, &back, err, sizeof err), 0, "hdr_read %dx%d (%s)", w, h, err);
    CHECK_INT_EQ(back.w, w, "width read back");
    CHECK_INT_EQ(back.h, h, "height read back");
    printf("hdr %dx%d: worst error %.6f of the pixel's largest channel (bound 2^-8 = %.6f)\n", w, h,
           hdr_check_close(img, back.rgb, w, h), ldexp(1.0, -8));
    /* stb_image decodes the same file to the same floats: the format is Radiance's. */
    stb = stbi_loadf(path, &sw, &sh, &sn, 3);
    assert_non_null(stb);
    CHECK_INT_EQ(sw * 100000 + sh, w * 100000 + h, "stb_image's size (w * 100000 + h)");
    assert_memory_equal(stb, back.rgb, (size_t)w * h * 3 * sizeof *stb);
    stbi_image_free(stb);
    hdr_free(&back);
    free(img);
}

/* Widths 8..32767 are run-length encoded, others flat: both, and one of a single pixel. */
static void test_hdr_round_trip(void **state)
{
    (void)state;
    hdr_round_trip(37, 23);
    hdr_round_trip(300, 4);
    hdr_round_trip(5, 9);
    hdr_round_trip(1, 1);
}

static void test_hdr_rle_smaller(void **state)
{
    const char *path = tmp_path("flat.hdr");
    char err[256] = "";
    float *img = calloc(512 * 64 * 3, sizeof *img);
    struct stat st;
    (void)state;
    assert_non_null(img);
    img[3 * 700] = 3.0f;
    CHECK_INT_EQ(hdr_write(path, img, 512, 64, err, sizeof err), 0, "hdr_write (%s)", err);
    CHECK_INT_EQ(stat(path, &st), 0, "stat of the written file");
    /* A black row is 4 channels of 4 runs of 127/128 bytes: 2 bytes each, 4 bytes of
     * row header: 36 bytes a row against 2048 flat. */
    CHECK_INT_LE(st.st_size, 64 * 48 + 200, "bytes of a 512 x 64 black image with one lit pixel");
    free(img);
}

static void test_hdr_bad_input(void **state)
{
    const char *path = tmp_path("bad.hdr"), *junk = tmp_path("junk.hdr");
    char err[256] = "";
    float img[3 * 12] = {0};
    hdr_image back;
    FILE *fp;
    (void)state;
    CHECK_INT_EQ(hdr_write(path, img, 4, 3, err, sizeof err), 0, "a black image (%s)", err);
    img[3 * 6 + 1] = -1.0f;
    CHECK_INT_EQ(hdr_write(path, img, 4, 3, err, sizeof err), -1, "a negative value refused");
    CHECK_CONTAINS(err, "pixel 2,1", "the message names the pixel");
    img[3 * 6 + 1] = NAN;
    CHECK_INT_EQ(hdr_write(path, img, 4, 3, err, sizeof err), -1, "NaN refused");
    img[3 * 6 + 1] = INFINITY;
    CHECK_INT_EQ(hdr_write(path, img, 4, 3, err, sizeof err), -1, "infinity refused");
    CHECK_INT_EQ(hdr_write(path, img, 0, 3, err, sizeof err), -1, "a width of 0 refused");
    CHECK_CONTAINS(err, "invalid image size", "the size named");
    /* The first, good file is still there, whole. */
    CHECK_INT_EQ(hdr_read(path, &back, err, sizeof err), 0, "the earlier file read (%s)", err);
    CHECK_INT_EQ(back.w * 10 + back.h, 43, "its size (w * 10 + h)");
    hdr_free(&back);
    fp = fopen(junk, "wb");
    assert_non_null(fp);
    fputs("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 40\n\2\2\0\50\1", fp);
    fclose(fp);
    CHECK_INT_EQ(hdr_read(junk, &back, err, sizeof err), -1, "a truncated file refused");
    CHECK_CONTAINS(err, "truncated or corrupt", "the message");
    assert_null(back.rgb);
    fp = fopen(junk, "wb");
    assert_non_null(fp);
    fputs("P6\n1 1\n255\nabc", fp);
    fclose(fp);
    CHECK_INT_EQ(hdr_read(junk, &back, err, sizeof err), -1, "a PPM is not an HDR file");
    CHECK_CONTAINS(err, "not a Radiance HDR", "the message");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hdr_round_trip),
        cmocka_unit_test(test_hdr_rle_smaller),
        cmocka_unit_test(test_hdr_bad_input),
    };
    return cmocka_run_group_tests_name("bake", tests, group_setup, group_teardown);
}
