/* SPDX-License-Identifier: MIT */
/* libFuzzer harness: image writing, reading and tone mapping (tools/formats/image.c).
 *
 * Input: a small header, then payload bytes.
 *   byte  0      flags: bit 0-1 path kind (0 name in the directory, 1 in a missing
 *                subdirectory, 2 NULL path, 3 NULL pixels), bit 2 a file already sits at
 *                the path, bit 3 no error buffer, bits 4-7 error buffer length - 1 (when
 *                small) or the full 256 bytes (15)
 *   bytes 1-8    width and height, int32 little-endian (any value: negative, 0, huge)
 *   byte  9      name length L (mod 41), then L bytes of name ('/' and NUL become '_')
 *   8 bytes      exposure, a double's bits (NaN, infinities, negatives, denormals)
 *   the rest     pixels for img_write, floats for tonemap, and a file for img_read
 *
 * Checked: img_write succeeds only for valid sizes and names ending in .png/.ppm, leaves
 * exactly the file (which img_read returns bit for bit) on success, and on failure
 * leaves the directory as it was (no temporary, the old file untouched); error messages
 * are NUL-terminated within the buffer and start with the path; tonemap maps every float
 * to a byte, NaN to 0, and is monotone in the input; img_read never crashes on the bytes.
 */
#include <dirent.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "formats/image.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define CHECK(c)                                                                               \
    do {                                                                                       \
        if (!(c)) {                                                                            \
            fprintf(stderr, "fuzz_image: check failed: %s (%s:%d)\n", #c, __FILE__, __LINE__); \
            abort();                                                                           \
        }                                                                                      \
    } while (0)

#define MAX_PIXEL_BYTES (1u << 16)

static char dir[64];

static int count_entries(void)
{
    DIR *d = opendir(dir);
    struct dirent *de;
    int n = 0;
    CHECK(d != NULL);
    while ((de = readdir(d)) != NULL)
        if (strcmp(de->d_name, ".") && strcmp(de->d_name, "..")) n++;
    closedir(d);
    return n;
}

static void empty_dir(void)
{
    DIR *d = opendir(dir);
    struct dirent *de;
    char p[400];
    CHECK(d != NULL);
    while ((de = readdir(d)) != NULL)
        if (strcmp(de->d_name, ".") && strcmp(de->d_name, "..")) {
            snprintf(p, sizeof p, "%s/%s", dir, de->d_name);
            unlink(p);
        }
    closedir(d);
}

static uint32_t rd32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static int ends_with_ci(const char *s, const char *ext)
{
    size_t n = strlen(s), k = strlen(ext), i;
    if (n < k) return 0;
    for (i = 0; i < k; i++) {
        char c = s[n - k + i];
        if (c >= 'A' && c <= 'Z') c = (char)(c - 'A' + 'a');
        if (c != ext[i]) return 0;
    }
    return 1;
}

static void check_err(const char *err, size_t errlen, const char *path)
{
    size_t n;
    if (!err || !errlen) return;
    CHECK(memchr(err, '\0', errlen) != NULL);
    n = strlen(err);
    CHECK(n > 0 || errlen == 1);
    if (path && errlen > strlen(path) + 2) CHECK(strncmp(err, path, strlen(path)) == 0);
}

static void fuzz_write(uint8_t flags, int32_t w, int32_t h, const char *name, const uint8_t *pix,
                       size_t npix)
{
    char path[400], errbuf[256], *err = errbuf;
    size_t errlen =
        (flags & 8) ? 0 : ((flags >> 4) == 15 ? sizeof errbuf : (size_t)(flags >> 4) + 1u);
    unsigned kind = flags & 3u;
    const unsigned char old[4] = {'o', 'l', 'd', '\n'};
    unsigned char *buf = NULL;
    int valid_size = w >= 1 && h >= 1 && w <= IMG_MAX_DIM && h <= IMG_MAX_DIM, rc, before, existed;
    size_t need = valid_size ? (size_t)w * (size_t)h * 3u : 0;

    if (errlen == 0) err = (flags & 0x80) ? NULL : errbuf;
    snprintf(path, sizeof path, kind == 1 ? "%s/missing/%s" : "%s/%s", dir, name);
    if (valid_size && need > MAX_PIXEL_BYTES) return; /* would need a real buffer that big */
    if (valid_size) {
        buf = malloc(need);
        CHECK(buf != NULL);
        if (npix) {
            size_t i;
            for (i = 0; i < need; i++) buf[i] = pix[i % npix];
        } else {
            memset(buf, 0x5a, need);
        }
    } else {
        buf = malloc(1); /* must not be read: the size is refused first */
        CHECK(buf != NULL);
        buf[0] = 0;
    }
    if ((flags & 4) && kind == 0) {
        FILE *f = fopen(path, "wb");
        if (f) {
            fwrite(old, 1, sizeof old, f);
            fclose(f);
        }
    }
    existed = access(path, F_OK) == 0;
    before = count_entries();
    memset(errbuf, 'x', sizeof errbuf);
    rc = img_write(kind == 2 ? NULL : path, kind == 3 ? NULL : buf, w, h, err, errlen);
    CHECK(rc == 0 || rc == -1);
    if (rc == 0) {
        img_t im;
        char e2[256];
        CHECK(kind == 0 && valid_size);
        CHECK(ends_with_ci(path, ".png") || ends_with_ci(path, ".ppm"));
        CHECK(count_entries() == before + !existed);
        CHECK(img_read(path, &im, e2, sizeof e2) == 0);
        CHECK(im.w == w && im.h == h && memcmp(im.rgb, buf, need) == 0);
        img_free(&im);
        CHECK(im.rgb == NULL);
    } else {
        CHECK(count_entries() == before); /* nothing left behind */
        if (existed) {
            unsigned char got[8];
            FILE *f = fopen(path, "rb");
            /* the old file is untouched (unless the path was a directory or similar) */
            if (f) {
                size_t n = fread(got, 1, sizeof got, f);
                fclose(f);
                CHECK(n == sizeof old && memcmp(got, old, sizeof old) == 0);
            }
        }
        if (err) check_err(err, errlen, kind == 2 ? "(null)" : path);
    }
    if (!valid_size || kind >= 2) CHECK(rc == -1);
    free(buf);
    empty_dir();
}

static void fuzz_tonemap(const uint8_t *p, size_t n, double exposure)
{
    size_t npix = n / 12, i;
    float *lin;
    unsigned char *out;
    double e;
    if (npix == 0) return;
    lin = malloc(npix * 12);
    out = malloc(npix * 3);
    CHECK(lin && out);
    memcpy(lin, p, npix * 12);
    tonemap(lin, npix, exposure, out);
    for (i = 0; i < npix * 3; i++) {
        double v = (double)lin[i] * exposure;
        if (v != v || v <= 0) CHECK(out[i] == 0);
        if (v >= 1) CHECK(out[i] == 255);
    }
    /* monotone: sorting inputs (at a finite positive exposure) sorts outputs */
    if (isfinite(exposure) && exposure > 0)
        for (i = 0; i + 1 < npix * 3; i++)
            if (lin[i] == lin[i] && lin[i + 1] == lin[i + 1] && lin[i] <= lin[i + 1])
                CHECK(out[i] <= out[i + 1]);
    e = tonemap_auto_exposure(lin, npix);
    CHECK(isfinite(e) && e > 0);
    (void)srgb_encode(exposure);
    free(lin);
    free(out);
}

static void fuzz_read(const uint8_t *p, size_t n)
{
    char path[128], err[200];
    img_t im;
    FILE *f;
    int rc;
    snprintf(path, sizeof path, "%s/in.bin", dir);
    f = fopen(path, "wb");
    CHECK(f != NULL);
    fwrite(p, 1, n, f);
    CHECK(fclose(f) == 0);
    rc = img_read(path, &im, err, sizeof err);
    CHECK(rc == 0 || rc == -1);
    if (rc == 0) {
        CHECK(im.w >= 1 && im.h >= 1 && im.w <= IMG_MAX_DIM && im.h <= IMG_MAX_DIM && im.rgb);
    } else {
        CHECK(im.w == 0 && im.h == 0 && im.rgb == NULL);
        CHECK(memchr(err, '\0', sizeof err) && strncmp(err, path, strlen(path)) == 0);
    }
    img_free(&im);
    unlink(path);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char name[48];
    size_t pos, L, i;
    int32_t w, h;
    double exposure;
    uint64_t bits;

    if (!dir[0]) {
        snprintf(dir, sizeof dir, "/tmp/rad_fuzz_image.XXXXXX");
        if (!mkdtemp(dir)) abort();
    }
    if (size < 10) return 0;
    w = (int32_t)rd32(data + 1);
    h = (int32_t)rd32(data + 5);
    L = data[9] % 41u;
    pos = 10;
    if (size < pos + L + 8) return 0;
    for (i = 0; i < L; i++) {
        char c = (char)data[pos + i];
        name[i] = (c == '/' || c == '\0') ? '_' : c;
    }
    name[L] = '\0';
    /* "." and ".." would name the directory itself */
    if (!strcmp(name, ".") || !strcmp(name, "..") || L == 0) strcpy(name, L ? "_" : "x.png");
    pos += L;
    bits = (uint64_t)rd32(data + pos) | (uint64_t)rd32(data + pos + 4) << 32;
    memcpy(&exposure, &bits, sizeof exposure);
    pos += 8;
    fuzz_write(data[0], w, h, name, data + pos, size - pos);
    fuzz_tonemap(data + pos, size - pos, exposure);
    fuzz_read(data + pos, size - pos);
    return 0;
}
