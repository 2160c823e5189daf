/* SPDX-License-Identifier: MIT */
/* Black-box tests of the command-line program: build/rad_cli (fixed-point core) and
 * build/rad_cli_float (the float twin). Each test runs a binary with posix_spawn, with
 * stdout and stderr captured in files of a mkdtemp() directory under /tmp, and checks
 * the exit status, the messages and the decoded output images (img_read) or files.
 *
 * Run from the repository root (make test does). A missing binary skips the tests that
 * need it (make all builds them).
 *
 * Speed: most runs use the coarse solver settings COARSE on the 0.55 m Cornell box
 * (about 30 ms a solve); only the fixed/float comparison uses the default settings.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "check.h"
#include "formats/hdr.h"
#include "formats/image.h"
#include "tmpdir.h"
#include "formats/obj.h"

extern char **environ;

#define FIXED   "build/rad_cli"
#define FLOAT   "build/rad_cli_float"
#define CORNELL "examples/cornell_box.obj"
#define DATA    "tests/data/cli/"

/* Coarse solver settings for the Cornell box: elements of 0.1 m (patches 0.4 m, the
 * default 4x) and a 32x32 hemi-cube. Coarse but every feature the tests look at (the
 * coloured walls, the light, the darkened floor next to the blocks) is still there. */
#define COARSE "--max-element", "0.1", "--res", "32"

#define MAX_ARGS      64
#define RUN_TIMEOUT_S 120.0 /* a run that takes longer is hung: it is killed and fails */

/* ---- temporary directory ------------------------------------------------------ */

TMPDIR_GROUP("cli")

/* ---- files -------------------------------------------------------------------- */

/* Whole file, NUL-terminated (NULL if it cannot be read); *len gets its size. */
static char *slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    char *buf = NULL;
    size_t n = 0, cap = 0, got;
    if (!f) return NULL;
    do {
        if (cap - n < 4096) {
            char *nb = realloc(buf, cap + 65536);
            if (!nb) {
                free(buf);
                fclose(f);
                return NULL;
            }
            buf = nb;
            cap += 65536;
        }
        got = fread(buf + n, 1, cap - n - 1, f);
        n += got;
    } while (got > 0);
    fclose(f);
    buf[n] = '\0';
    if (len) *len = n;
    return buf;
}

static void write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    assert_int_equal(fputs(text, f) >= 0, 1);
    assert_int_equal(fclose(f), 0);
}

static int file_exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

/* Number of files in the temporary directory whose name starts with PREFIX. */
static int count_tmp_files(const char *prefix)
{
    DIR *d = opendir(tmpdir);
    struct dirent *de;
    int n = 0;
    assert_non_null(d);
    while ((de = readdir(d)) != NULL)
        if (strncmp(de->d_name, prefix, strlen(prefix)) == 0) n++;
    closedir(d);
    return n;
}

/* ---- running the programs ----------------------------------------------------- */

typedef struct {
    pid_t pid;
    int status;      /* exit status; 128 + signal if killed by one */
    char *out, *err; /* captured stdout and stderr */
    char outpath[256], errpath[256];
} run_t;

static void need(const char *bin)
{
    if (access(bin, X_OK) != 0) {
        print_message("%s is missing (run make all): skipped\n", bin);
        skip();
    }
}

/* Starts BIN with ARGS (NULL-terminated), stdin from /dev/null, stdout and stderr to
 * files in the temporary directory. */
static void run_start(run_t *r, const char *bin, const char *const *args)
{
    static int seq;
    char *argv[MAX_ARGS + 2];
    posix_spawn_file_actions_t fa;
    int n = 0, rc;
    memset(r, 0, sizeof *r);
    snprintf(r->outpath, sizeof r->outpath, "%s/run%03d.out", tmpdir, seq);
    snprintf(r->errpath, sizeof r->errpath, "%s/run%03d.err", tmpdir, seq);
    seq++;
    argv[n++] = (char *)bin;
    while (args[n - 1]) {
        CHECK_INT_LE(n, MAX_ARGS, "rad_cli arguments");
        argv[n] = (char *)args[n - 1];
        n++;
    }
    argv[n] = NULL;
    assert_int_equal(posix_spawn_file_actions_init(&fa), 0);
    assert_int_equal(posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0), 0);
    assert_int_equal(
        posix_spawn_file_actions_addopen(&fa, 1, r->outpath, O_WRONLY | O_CREAT | O_TRUNC, 0600),
        0);
    assert_int_equal(
        posix_spawn_file_actions_addopen(&fa, 2, r->errpath, O_WRONLY | O_CREAT | O_TRUNC, 0600),
        0);
    rc = posix_spawn(&r->pid, bin, &fa, NULL, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    if (rc != 0) fail_msg("posix_spawn %s: %s", bin, strerror(rc));
}

/* Waits for the run (killing it after RUN_TIMEOUT_S) and reads what it printed. */
static void run_finish(run_t *r)
{
    struct timespec t0, t, nap = {0, 5000000};
    int st = 0;
    pid_t w;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    for (;;) {
        w = waitpid(r->pid, &st, WNOHANG);
        if (w == r->pid) break;
        if (w < 0 && errno != EINTR) fail_msg("waitpid: %s", strerror(errno));
        clock_gettime(CLOCK_MONOTONIC, &t);
        if ((double)(t.tv_sec - t0.tv_sec) + 1e-9 * (double)(t.tv_nsec - t0.tv_nsec) >
            RUN_TIMEOUT_S) {
            kill(r->pid, SIGKILL);
            waitpid(r->pid, &st, 0);
            fail_msg("run timed out after %.0f s", RUN_TIMEOUT_S);
        }
        nanosleep(&nap, NULL);
    }
    r->status = WIFEXITED(st) ? WEXITSTATUS(st) : WIFSIGNALED(st) ? 128 + WTERMSIG(st) : -1;
    r->out = slurp(r->outpath, NULL);
    r->err = slurp(r->errpath, NULL);
    assert_non_null(r->out);
    assert_non_null(r->err);
}

static void run_free(run_t *r)
{
    free(r->out);
    free(r->err);
    r->out = r->err = NULL;
}

static void run_args(run_t *r, const char *bin, const char *const *args)
{
    run_start(r, bin, args);
    run_finish(r);
}

/* RUN(&r, BIN, "arg", ...): runs BIN with the arguments and waits for it. */
#define RUN(r, bin, ...)   run_args((r), (bin), (const char *const[]){__VA_ARGS__, NULL})
#define START(r, bin, ...) run_start((r), (bin), (const char *const[]){__VA_ARGS__, NULL})

/* The run must have exited with STATUS; on mismatch, show what it printed. */
static void expect_status_at(const run_t *r, int status, const char *file, int line)
{
    if (r->status == status) return;
    print_error("exit status %d, expected %d\nstdout: %s\nstderr: %s\n", r->status, status, r->out,
                r->err);
    _fail(file, line);
}
#define expect_status(r, s) expect_status_at((r), (s), __FILE__, __LINE__)

static int count_lines(const char *s)
{
    int n = 0;
    for (; *s; s++) n += *s == '\n';
    return n;
}

static int starts_with(const char *s, const char *prefix)
{
    return strncmp(s, prefix, strlen(prefix)) == 0;
}

/* Some line of TEXT starts with PREFIX. */
static int has_line(const char *text, const char *prefix)
{
    const char *p = text;
    while (p && *p) {
        if (starts_with(p, prefix)) return 1;
        p = strchr(p, '\n');
        if (p) p++;
    }
    return 0;
}

/* ---- images ------------------------------------------------------------------- */

static void load_img(const char *path, img_t *im)
{
    char e[512];
    if (img_read(path, im, e, sizeof e) < 0) fail_msg("img_read: %s", e);
}

static const unsigned char *px(const img_t *im, int x, int y)
{
    return im->rgb + ((size_t)y * (size_t)im->w + (size_t)x) * 3;
}

/* The inverse of the sRGB encoding of tonemap(): 8-bit value to linear. */
static double srgb_decode(int v)
{
    double c = v / 255.0;
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

/* A rectangle in fractions of the image size: [x0, x1) x [y0, y1), y down. */
typedef struct {
    double x0, y0, x1, y1;
} rect_t;

/* Mean of each channel over R, as 8-bit values (LINEAR = 0) or decoded to linear
 * light (LINEAR = 1). */
static void region_mean(const img_t *im, rect_t r, int linear, double m[3])
{
    int x, y, c, x0 = (int)(r.x0 * im->w), x1 = (int)(r.x1 * im->w);
    int y0 = (int)(r.y0 * im->h), y1 = (int)(r.y1 * im->h);
    long n = 0;
    CHECK_INT_GT(x1, x0, "the region's right column against its left");
    CHECK_INT_GT(y1, y0, "the region's bottom row against its top");
    m[0] = m[1] = m[2] = 0;
    for (y = y0; y < y1; y++)
        for (x = x0; x < x1; x++, n++)
            for (c = 0; c < 3; c++) m[c] += linear ? srgb_decode(px(im, x, y)[c]) : px(im, x, y)[c];
    for (c = 0; c < 3; c++) m[c] /= (double)n;
}

static double luma(const double m[3])
{
    return 0.2126 * m[0] + 0.7152 * m[1] + 0.0722 * m[2];
}

/* Centroid (fractions of the size) of the pixels for which PRED holds; returns their
 * count. */
typedef int (*pix_pred)(const unsigned char *p);
static long centroid(const img_t *im, pix_pred pred, double *cx, double *cy)
{
    int x, y;
    long n = 0;
    double sx = 0, sy = 0;
    for (y = 0; y < im->h; y++)
        for (x = 0; x < im->w; x++)
            if (pred(px(im, x, y))) {
                sx += x + 0.5;
                sy += y + 0.5;
                n++;
            }
    *cx = n ? sx / n / im->w : -1;
    *cy = n ? sy / n / im->h : -1;
    return n;
}

static int is_white(const unsigned char *p)
{
    return p[0] >= 250 && p[1] >= 250 && p[2] >= 250;
}
static int is_red(const unsigned char *p)
{
    return p[0] > 60 && p[0] > 2 * p[1] && p[0] > 2 * p[2];
}
static int is_green(const unsigned char *p)
{
    return p[1] > 60 && p[1] > p[0] + 20 && p[1] > 2 * p[2];
}
static int is_blue(const unsigned char *p)
{
    return p[2] > 40 && p[2] > 2 * p[0] && p[2] > 2 * p[1];
}
/* Lit, unsaturated, not the lamp: the white floor of orient.obj. */
static int is_grey(const unsigned char *p)
{
    int lo = p[0] < p[1] ? p[0] : p[1], hi = p[0] > p[1] ? p[0] : p[1];
    lo = p[2] < lo ? p[2] : lo;
    hi = p[2] > hi ? p[2] : hi;
    return lo > 30 && hi < 250 && hi - lo < hi / 4 + 4;
}

static long count_black(const img_t *im)
{
    long n = 0;
    size_t i;
    for (i = 0; i < (size_t)im->w * (size_t)im->h; i++)
        n += im->rgb[3 * i] == 0 && im->rgb[3 * i + 1] == 0 && im->rgb[3 * i + 2] == 0;
    return n;
}

static void expect_same_pixels(const img_t *a, const img_t *b)
{
    assert_int_equal(a->w, b->w);
    assert_int_equal(a->h, b->h);
    assert_memory_equal(a->rgb, b->rgb, (size_t)a->w * (size_t)a->h * 3);
}

static int same_pixels(const img_t *a, const img_t *b)
{
    return a->w == b->w && a->h == b->h &&
           memcmp(a->rgb, b->rgb, (size_t)a->w * (size_t)a->h * 3) == 0;
}

/* The file starts with the PNG signature / the P6 magic. */
static void expect_magic(const char *path, const char *magic, size_t n)
{
    size_t len;
    char *d = slurp(path, &len);
    assert_non_null(d);
    CHECK_INT_GE(len, n, "bytes of %s", path);
    assert_memory_equal(d, magic, n);
    free(d);
}
#define PNG_SIG "\x89PNG\r\n\x1a\n"

/* "patches P  elements E  vertices V" from --stats output. */
static void parse_counts(const char *out, int *patches, int *elements, int *vertices)
{
    const char *p = strstr(out, "patches ");
    assert_non_null(p);
    assert_int_equal(sscanf(p, "patches %d elements %d vertices %d", patches, elements, vertices),
                     3);
    CHECK_INT_GT(*patches, 0, "--stats patches");
    CHECK_INT_GE(*elements, *patches, "--stats elements against patches");
    CHECK_INT_GT(*vertices, 0, "--stats vertices");
}

/* ---- 1. the Cornell box ------------------------------------------------------- */

/* Sample regions of the default view, read off a 128x128 render of the coarse solve
 * (the default camera looks down -z at the open side and frames the 0.556 x 0.549 m
 * front opening with a 5% margin, so the box fills x, y ~ 2.5%..97%):
 *  - red wall (x = -0.556, left): covers x ~ 3%..23% at mid height (the back wall
 *    starts at x ~ 23%), so 8%..20% x 40%..60% is red wall only;
 *  - green wall (right): its mirror image, 80%..92%;
 *  - the light (0.13 x 0.105 m at the ceiling): x ~ 42%..58%, y ~ 15%..17.5% on screen,
 *    so 45%..55% x 15.5%..17% lies inside it;
 *  - the floor is visible below the blocks only in a strip y ~ 91%..97%. The floor just
 *    in front of the short block (x 56%..70%: the block's front face ends at y ~ 93%)
 *    lies in the block's shadow (the light is behind it, at z = -0.23..-0.33, the
 *    block's front edge at z = -0.065..-0.11) and next to its base; the open floor on
 *    the left (x 12%..35%, left of both blocks, in front of the tall block's shadow)
 *    sees the light directly. Rows 94%..96.5% are floor in both. */
static const rect_t RED_WALL = {0.08, 0.40, 0.20, 0.60};
static const rect_t GREEN_WALL = {0.80, 0.40, 0.92, 0.60};
static const rect_t LIGHT = {0.45, 0.155, 0.55, 0.17};
static const rect_t LIGHT_WINDOW = {0.35, 0.10, 0.65, 0.25}; /* around the light, with room */
static const rect_t FLOOR_SHADOW = {0.56, 0.94, 0.70, 0.965};
static const rect_t FLOOR_OPEN = {0.12, 0.94, 0.35, 0.965};

static void test_cornell_box(void **state)
{
    run_t r;
    img_t im;
    double red[3], green[3], redl[3], greenl[3], light[3], shadow[3], open[3];
    int x, y, c, inside = 0, outside = 0;
    const int corner = 2; /* px: the margin is ~2.4% = 3 px at 128, so 2x2 is outside */
    (void)state;
    need(FIXED);
    RUN(&r, FIXED, "--quiet", "--width", "128", "--height", "128", COARSE, "-o",
        tmp_path("cornell.png"), CORNELL);
    expect_status(&r, 0);
    assert_string_equal(r.err, "");
    run_free(&r);
    expect_magic(tmp_path("cornell.png"), PNG_SIG, 8);
    load_img(tmp_path("cornell.png"), &im);
    assert_int_equal(im.w, 128);
    assert_int_equal(im.h, 128);

    /* Red wall: Kd 0.62 0.07 0.05 under a warm light: R/G is ~10 in linear light and
     * ~3.4 in 8-bit sRGB, so R > 1.5 G holds with a wide margin. */
    region_mean(&im, RED_WALL, 0, red);
    region_mean(&im, RED_WALL, 1, redl);
    print_message("red wall   8-bit %.0f %.0f %.0f\n", red[0], red[1], red[2]);
    CHECK_GT(red[0], 1.5 * red[1], "red wall: 8-bit R against 1.5 G");
    CHECK_GT(red[0], 1.5 * red[2], "red wall: 8-bit R against 1.5 B");
    CHECK_GT(redl[0], 3.0 * redl[1], "red wall: linear R against 3 G");
    /* Green wall: Kd 0.15 0.45 0.10, but the light is warm (Ke 18 12.8 4.4), so G/R is
     * only ~2.1 in linear light (0.45 * 12.8 / (0.15 * 18)) and the sRGB encoding
     * squeezes that to ~1.4 in 8-bit values. So "G > 1.5 R" is
     * asserted on linear light (decoded 8-bit values), plus a plain G > 1.2 R on the
     * 8-bit values. */
    region_mean(&im, GREEN_WALL, 0, green);
    region_mean(&im, GREEN_WALL, 1, greenl);
    print_message("green wall 8-bit %.0f %.0f %.0f, linear G/R %.2f\n", green[0], green[1],
                  green[2], greenl[1] / greenl[0]);
    CHECK_GT(greenl[1], 1.5 * greenl[0], "green wall: linear G against 1.5 R");
    CHECK_GT(green[1], 1.2 * green[0], "green wall: 8-bit G against 1.2 R");
    CHECK_GT(green[1], 1.5 * green[2], "green wall: 8-bit G against 1.5 B");

    /* The light clips to white (Ke 18 12.8 4.4 times the automatic exposure ~3 is > 1 in
     * every channel), and nothing else does: the brightest lit surfaces (ceiling near
     * the light, top of the short block) stay below 250 in blue, because reflected light
     * is warm. */
    region_mean(&im, LIGHT, 0, light);
    CHECK_GE(light[0], 250, "the light: 8-bit R (clipped to white)");
    CHECK_GE(light[1], 250, "the light: 8-bit G (clipped to white)");
    CHECK_GE(light[2], 250, "the light: 8-bit B (clipped to white)");
    for (y = 0; y < im.h; y++)
        for (x = 0; x < im.w; x++) {
            double fx = (x + 0.5) / im.w, fy = (y + 0.5) / im.h;
            int in = fx >= LIGHT_WINDOW.x0 && fx < LIGHT_WINDOW.x1 && fy >= LIGHT_WINDOW.y0 &&
                     fy < LIGHT_WINDOW.y1;
            if (is_white(px(&im, x, y))) *(in ? &inside : &outside) += 1;
        }
    print_message("near-white pixels: %d at the light, %d elsewhere\n", inside, outside);
    CHECK_INT_GE(inside, 20, "near-white pixels at the light (it is ~20 x 4 px at this size)");
    assert_int_equal(outside, 0);
    CHECK_GT(luma(light), luma(red), "luma of the light against the red wall");
    CHECK_GT(luma(light), luma(green), "luma of the light against the green wall");

    /* Soft shadow: the floor in front of the short block is well below the open floor
     * (the test prints both); 0.8 leaves room for mesh changes but fails if the block
     * casts no shadow (a ratio near or above 1). */
    region_mean(&im, FLOOR_SHADOW, 0, shadow);
    region_mean(&im, FLOOR_OPEN, 0, open);
    print_message("floor luma: shadow %.0f, open %.0f\n", luma(shadow), luma(open));
    /* the open floor is lit, so the comparison means something */
    CHECK_GT(luma(open), 100, "8-bit luma of the open floor");
    CHECK_LT(luma(shadow), 0.8 * luma(open),
             "8-bit luma of the shadowed floor against 0.8 x the open floor");

    /* Corners lie outside the box (nothing there): exactly black. */
    for (y = 0; y < corner; y++)
        for (x = 0; x < corner; x++)
            for (c = 0; c < 3; c++) {
                assert_int_equal(px(&im, x, y)[c], 0);
                assert_int_equal(px(&im, im.w - 1 - x, y)[c], 0);
                assert_int_equal(px(&im, x, im.h - 1 - y)[c], 0);
                assert_int_equal(px(&im, im.w - 1 - x, im.h - 1 - y)[c], 0);
            }
    img_free(&im);
}

/* ---- 2. orientation ----------------------------------------------------------- */

/* Mean 8-bit luma of the is_grey pixels in R (which must hold some). */
static double grey_luma(const img_t *im, rect_t r)
{
    int x, y;
    long n = 0;
    double s = 0;
    for (y = (int)(r.y0 * im->h); y < (int)(r.y1 * im->h); y++)
        for (x = (int)(r.x0 * im->w); x < (int)(r.x1 * im->w); x++)
            if (is_grey(px(im, x, y))) {
                const unsigned char *p = px(im, x, y);
                s += 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
                n++;
            }
    CHECK_INT_GE(n, 50, "grey pixels in the region");
    return s / (double)n;
}

/* tests/data/cli/orient.obj: lamp at x = -0.9..-0.5, y = 1.2 (seen from below), blue
 * wall at x = 0.9, white floor at y = 0. From the front (eye on +z looking -z, up +y)
 * the lamp must appear top-left, the wall right, the floor at the bottom, and the floor
 * under the lamp (left) brighter than on the right. From the back (eye on -z looking
 * +z) left and right swap, top and bottom do not. */
static void check_orientation(const char *path, int front)
{
    img_t im;
    double lx, ly, bx, by, gx, gy, left, right;
    long nl, nb, ng;
    load_img(path, &im);
    assert_int_equal(im.w, 96);
    assert_int_equal(im.h, 96);
    nl = centroid(&im, is_white, &lx, &ly);
    nb = centroid(&im, is_blue, &bx, &by);
    ng = centroid(&im, is_grey, &gx, &gy);
    print_message("%s view: lamp %ld px at (%.2f, %.2f), wall %ld px at (%.2f, %.2f), floor %ld px "
                  "at (%.2f, %.2f)\n",
                  front ? "front" : "back", nl, lx, ly, nb, bx, by, ng, gx, gy);
    /* Minimum sizes: about a fifth of what each covers at 96 x 96 in both views (the
     * test prints the counts), plenty to locate them. */
    CHECK_INT_GE(nl, 10, "%s view: lamp pixels", front ? "front" : "back");
    CHECK_INT_GE(nb, 100, "%s view: blue wall pixels", front ? "front" : "back");
    CHECK_INT_GE(ng, 300, "%s view: floor pixels", front ? "front" : "back");
    /* Vertical: lamp in the top third, floor in the bottom third, the image not flipped. */
    CHECK_LT(ly, 0.34, "%s view: the lamp's centroid y (a fraction of the height, down)",
             front ? "front" : "back");
    CHECK_GT(gy, 0.66, "%s view: the floor's centroid y (a fraction of the height, down)",
             front ? "front" : "back");
    /* Horizontal: the lamp is at x = -0.7, the wall at x = +0.9 in the scene. */
    if (front) {
        CHECK_LT(lx, 0.40, "front view: the lamp's centroid x (a fraction of the width)");
        CHECK_GT(bx, 0.70, "front view: the wall's centroid x (a fraction of the width)");
    } else {
        CHECK_GT(lx, 0.60, "back view: the lamp's centroid x (a fraction of the width)");
        CHECK_LT(bx, 0.30, "back view: the wall's centroid x (a fraction of the width)");
    }
    /* The floor (its grey pixels only: the blue wall reaches into the lower corner on
     * its side) is brighter on the lamp's side. */
    left = grey_luma(&im, (rect_t){0.0, 0.5, 0.4, 1.0});
    right = grey_luma(&im, (rect_t){0.6, 0.5, 1.0, 1.0});
    print_message("%s view: floor luma left %.0f right %.0f\n", front ? "front" : "back", left,
                  right);
    if (front)
        CHECK_GT(left, right + 20,
                 "front view: floor luma on the lamp's side (left) against the right + 20");
    else
        CHECK_GT(right, left + 20,
                 "back view: floor luma on the lamp's side (right) against the left + 20");
    img_free(&im);
}

static void test_orientation(void **state)
{
    run_t r;
    (void)state;
    need(FIXED);
    /* Exposure 2: the lamp (Ke 10) clips to white, the brightest floor (radiosity
     * ~0.26 a channel) stays near 190, so "white" finds the lamp only. */
    RUN(&r, FIXED, "--quiet", "--width", "96", "--height", "96", "--exposure", "2", "--camera",
        "0,0.6,3,0,0.6,0", "-o", tmp_path("front.png"), "--camera", "0,0.6,-3,0,0.6,0", "-o",
        tmp_path("back.png"), DATA "orient.obj");
    expect_status(&r, 0);
    run_free(&r);
    check_orientation(tmp_path("front.png"), 1);
    check_orientation(tmp_path("back.png"), 0);
}

/* ---- 3. PPM output ------------------------------------------------------------ */

/* A non-square size catches swapped width and height. */
static void test_ppm_matches_png(void **state)
{
    run_t r;
    img_t png, ppm, ppm2;
    size_t len;
    char *d;
    static const char hdr[] = "P6\n80 48\n255\n";
    (void)state;
    need(FIXED);
    /* One run writing both formats of the same view, and a second run writing PPM only:
     * the three must hold the same pixels (the solve is deterministic). */
    RUN(&r, FIXED, "--quiet", "--width", "80", "--height", "48", COARSE, "-o", tmp_path("fmt.png"),
        "-o", tmp_path("fmt.ppm"), CORNELL);
    expect_status(&r, 0);
    run_free(&r);
    RUN(&r, FIXED, "--quiet", "--width", "80", "--height", "48", COARSE, "-o", tmp_path("fmt2.PPM"),
        CORNELL);
    expect_status(&r, 0);
    run_free(&r);

    expect_magic(tmp_path("fmt.png"), PNG_SIG, 8);
    d = slurp(tmp_path("fmt.ppm"), &len);
    assert_non_null(d);
    assert_int_equal(len, sizeof hdr - 1 + 80 * 48 * 3); /* binary P6, nothing after the pixels */
    assert_memory_equal(d, hdr, sizeof hdr - 1);
    free(d);
    expect_magic(tmp_path("fmt2.PPM"), "P6\n", 3); /* the extension is case-insensitive */

    load_img(tmp_path("fmt.png"), &png);
    load_img(tmp_path("fmt.ppm"), &ppm);
    load_img(tmp_path("fmt2.PPM"), &ppm2);
    assert_int_equal(png.w, 80);
    assert_int_equal(png.h, 48);
    /* a real picture, so equality means something */
    CHECK_INT_LT(count_black(&png), 80 * 48 / 2, "black pixels of the 80 x 48 PNG");
    expect_same_pixels(&png, &ppm);
    expect_same_pixels(&png, &ppm2);
    img_free(&png);
    img_free(&ppm);
    img_free(&ppm2);
}

/* --threads splits every shot's hemi-cube by rows: the solution must be the same bits,
 * so the dumped radiosities are the same bytes. */
static void test_threads_same_result(void **state)
{
    run_t r;
    size_t la, lb;
    char *a, *b;
    (void)state;
    need(FIXED);
    RUN(&r, FIXED, "--quiet", "--width", "16", "--height", "16", COARSE, "--dump-radiosity",
        tmp_path("t1.csv"), "-o", tmp_path("t1.ppm"), CORNELL);
    expect_status(&r, 0);
    run_free(&r);
    RUN(&r, FIXED, "--quiet", "--threads", "3", "--width", "16", "--height", "16", COARSE,
        "--dump-radiosity", tmp_path("t3.csv"), "-o", tmp_path("t3.ppm"), CORNELL);
    expect_status(&r, 0);
    run_free(&r);
    a = slurp(tmp_path("t1.csv"), &la);
    b = slurp(tmp_path("t3.csv"), &lb);
    assert_non_null(a);
    assert_non_null(b);
    /* a real solution, so equality means something */
    CHECK_INT_GT(count_lines(a), 100, "lines of the CSV");
    assert_int_equal(la, lb);
    assert_memory_equal(a, b, la);
    free(a);
    free(b);
    RUN(&r, FIXED, "--threads", "0", CORNELL);
    expect_status(&r, 2);
    run_free(&r);
}

/* ---- 4. several views --------------------------------------------------------- */

/* The default eye is at (-0.278, 0.274, 0.696) looking down -z at the box's centre.
 * CAM_L and CAM_R translate it 0.12 m left and right, looking straight ahead. */
#define CAM_L     "-0.40,0.274,0.70,-0.40,0.274,-0.28"
#define CAM_R     "-0.16,0.274,0.70,-0.16,0.274,-0.28"
/* A fixed exposure: one run with several views uses the first view's automatic
 * exposure for all, so views rendered alone only match with a fixed one. 3.0 is close
 * to the automatic exposure of the default view (3.29, printed in the PLY header). */
#define EXPOSURE  "3.0"
#define VIEW_ARGS "--quiet", "--width", "96", "--height", "96", COARSE, "--exposure", EXPOSURE

static void test_multiple_cameras(void **state)
{
    run_t r;
    img_t l, rt, l1, r1, vl, vr, vn;
    double lrx, lry, rrx, rry, lgx, lgy, rgx, rgy;
    char views[1024];
    (void)state;
    need(FIXED);
    RUN(&r, FIXED, VIEW_ARGS, "--camera", CAM_L, "-o", tmp_path("cam_l.png"), "--camera", CAM_R,
        "-o", tmp_path("cam_r.png"), CORNELL);
    expect_status(&r, 0);
    run_free(&r);
    /* Each view alone. */
    RUN(&r, FIXED, VIEW_ARGS, "--camera", CAM_L, "-o", tmp_path("cam_l1.png"), CORNELL);
    expect_status(&r, 0);
    run_free(&r);
    RUN(&r, FIXED, VIEW_ARGS, "--camera", CAM_R, "-o", tmp_path("cam_r1.png"), CORNELL);
    expect_status(&r, 0);
    run_free(&r);
    /* The same views from a --views file, with a comment, a blank line, spaces and tabs,
     * and an explicit FOV of 45 (the default) on one line; plus a narrower view. */
    snprintf(views, sizeof views,
             "# eye            look-at          [fov] output\n"
             "\n"
             "-0.40 0.274 0.70 -0.40 0.274 -0.28 45 %s\n"
             "  -0.16\t0.274 0.70 -0.16 0.274 -0.28 %s\n"
             "-0.16 0.274 0.70 -0.16 0.274 -0.28 30 %s\n",
             tmp_path("view_l.png"), tmp_path("view_r.png"), tmp_path("view_narrow.png"));
    write_text(tmp_path("views.txt"), views);
    RUN(&r, FIXED, VIEW_ARGS, "--views", tmp_path("views.txt"), "--allow-outside-paths",
        CORNELL); /* /tmp */
    expect_status(&r, 0);
    run_free(&r);

    load_img(tmp_path("cam_l.png"), &l);
    load_img(tmp_path("cam_r.png"), &rt);
    load_img(tmp_path("cam_l1.png"), &l1);
    load_img(tmp_path("cam_r1.png"), &r1);
    load_img(tmp_path("view_l.png"), &vl);
    load_img(tmp_path("view_r.png"), &vr);
    load_img(tmp_path("view_narrow.png"), &vn);
    /* Each view of the multi-view run is the view alone, and the --views file renders
     * the same pictures. */
    expect_same_pixels(&l, &l1);
    expect_same_pixels(&rt, &r1);
    expect_same_pixels(&l, &vl);
    expect_same_pixels(&rt, &vr);
    CHECK_THAT(!same_pixels(&l, &rt), "images %s and %s differ", "l", "rt");
    CHECK_THAT(!same_pixels(&rt, &vn), "images %s and %s differ", "rt", "vn"); /* the FOV is used */

    /* Moving the camera left moves the scene right in the picture: both walls'
     * centroids must move right. 0.24 m of eye motion at 0.7..1.26 m depth moves a
     * point by 0.23..0.41 of the image width; the walls also slide partly out of frame,
     * so their visible centroids move less (the test prints them). Require 0.04: any
     * real motion, but not the noise of a swapped view. */
    CHECK_INT_GT(centroid(&l, is_red, &lrx, &lry), 200, "red pixels, left camera");
    CHECK_INT_GT(centroid(&rt, is_red, &rrx, &rry), 200, "red pixels, right camera");
    CHECK_INT_GT(centroid(&l, is_green, &lgx, &lgy), 200, "green pixels, left camera");
    CHECK_INT_GT(centroid(&rt, is_green, &rgx, &rgy), 200, "green pixels, right camera");
    print_message("red wall centroid x: left camera %.3f, right camera %.3f; green: %.3f, %.3f\n",
                  lrx, rrx, lgx, rgx);
    CHECK_GT(lrx, rrx + 0.04, "red wall centroid x: left camera against right camera + 0.04");
    CHECK_GT(lgx, rgx + 0.04, "green wall centroid x: left camera against right camera + 0.04");
    /* still the left wall, and the right one */
    CHECK_LT(lrx, 0.5, "red wall centroid x, left camera");
    CHECK_LT(rrx, 0.5, "red wall centroid x, right camera");
    CHECK_GT(lgx, 0.5, "green wall centroid x, left camera");
    CHECK_GT(rgx, 0.5, "green wall centroid x, right camera");
    img_free(&l);
    img_free(&rt);
    img_free(&l1);
    img_free(&r1);
    img_free(&vl);
    img_free(&vr);
    img_free(&vn);
}

/* ---- 5. --dump-radiosity ------------------------------------------------------ */

typedef struct {
    int element, surface;
    char material[64];
    double area, c[3], rgb[3];
} csv_row;

static void test_dump_radiosity(void **state)
{
    run_t r;
    obj_scene sc;
    char e[512], *csv, *line, *next;
    csv_row *rows;
    int patches, elements, vertices, n = 0, i, f, m;
    double obj_area = 0, csv_area = 0, light_min = HUGE_VAL, other_max = 0, *mat_area;
    (void)state;
    need(FIXED);
    RUN(&r, FIXED, "--quiet", "--stats", "--width", "16", "--height", "16", COARSE,
        "--dump-radiosity", tmp_path("rad.csv"), "-o", tmp_path("rad.png"), CORNELL);
    expect_status(&r, 0);
    parse_counts(r.out, &patches, &elements, &vertices);
    run_free(&r);

    assert_int_equal(obj_load(CORNELL, &sc, NULL, NULL, e, sizeof e), 0);
    csv = slurp(tmp_path("rad.csv"), NULL);
    assert_non_null(csv);
    next = strchr(csv, '\n');
    assert_non_null(next);
    *next++ = '\0';
    assert_string_equal(csv, "element,surface,material,area,cx,cy,cz,r,g,b");
    rows = calloc((size_t)elements + 1, sizeof *rows);
    mat_area = calloc((size_t)sc.nmaterials, sizeof *mat_area);
    assert_non_null(rows);
    assert_non_null(mat_area);
    for (line = next; *line; line = next) {
        csv_row *w = &rows[n];
        int used = 0;
        next = strchr(line, '\n');
        assert_non_null(next); /* every row ends with a newline */
        *next++ = '\0';
        CHECK_INT_LT(n, elements, "CSV rows against --stats elements");
        if (sscanf(line, "%d,%d,\"%63[^\"]\",%lf,%lf,%lf,%lf,%lf,%lf,%lf%n", &w->element,
                   &w->surface, w->material, &w->area, &w->c[0], &w->c[1], &w->c[2], &w->rgb[0],
                   &w->rgb[1], &w->rgb[2], &used) != 10 ||
            line[used] != '\0')
            fail_msg("bad CSV row %d: %s", n + 1, line);
        assert_int_equal(w->element, n); /* elements in order, numbered from 0 */
        CHECK_INT_GE(w->surface, 0, "CSV row %d: surface", n);
        CHECK_INT_LT(w->surface, sc.nfaces, "CSV row %d: surface against the OBJ's faces", n);
        /* The material is the one of the OBJ face the element came from. */
        assert_string_equal(w->material, sc.materials[sc.faces[w->surface].material].name);
        CHECK_GT(w->area, 0, "CSV row %d: area", n);
        /* Centroids inside the box (x -0.556..0, y 0..0.549, z -0.559..0) + rounding. */
        CHECK_GT(w->c[0], -0.557, "CSV row %d: centroid x", n);
        CHECK_LT(w->c[0], 1e-6, "CSV row %d: centroid x", n);
        CHECK_GT(w->c[1], -1e-6, "CSV row %d: centroid y", n);
        CHECK_LT(w->c[1], 0.549, "CSV row %d: centroid y", n);
        CHECK_GT(w->c[2], -0.56, "CSV row %d: centroid z", n);
        CHECK_LT(w->c[2], 1e-6, "CSV row %d: centroid z", n);
        for (i = 0; i < 3; i++) {
            CHECK_GE(w->rgb[i], 0, "CSV row %d: radiosity channel %d", n, i);
            CHECK_THAT(isfinite(w->rgb[i]), "CSV row %d: radiosity channel %d = %g, finite", n, i,
                       w->rgb[i]);
        }
        csv_area += w->area;
        mat_area[sc.faces[w->surface].material] += w->area;
        if (strcmp(w->material, "light") == 0) {
            double s = w->rgb[0] + w->rgb[1] + w->rgb[2];
            light_min = s < light_min ? s : light_min;
        } else {
            double s = w->rgb[0] + w->rgb[1] + w->rgb[2];
            other_max = s > other_max ? s : other_max;
        }
        if (strcmp(w->material, "red") == 0)
            CHECK_GT(w->rgb[0], w->rgb[1], "CSV row %d (red): R against G", n);
        if (strcmp(w->material, "green") == 0)
            CHECK_GT(w->rgb[1], w->rgb[0], "CSV row %d (green): G against R", n);
        n++;
    }
    assert_int_equal(n, elements); /* one row per element of --stats */
    print_message("%d rows; light radiosity (r+g+b) >= %.3g, everything else <= %.3g\n", n,
                  light_min, other_max);
    CHECK_LT(light_min, HUGE_VAL, "the light's least radiosity (r+g+b): some light element");
    CHECK_GT(light_min, other_max,
             "the light's least radiosity (r+g+b) against everything else's most");

    /* The elements tile the polygons: their areas add up to the OBJ's (1e-3 relative:
     * the mesh is built in the core's fixed-point coordinates, ~1e-5 relative). */
    for (f = 0; f < sc.nfaces; f++) obj_area += obj_face_area(&sc, &sc.faces[f]);
    print_message("total area: CSV %.6f, OBJ %.6f m^2\n", csv_area, obj_area);
    CHECK_NEAR(csv_area, obj_area, 1e-3 * obj_area, "the CSV's total area against the OBJ's (m^2)");
    for (m = 0; m < sc.nmaterials; m++)
        CHECK_NEAR(mat_area[m], sc.materials[m].area, 1e-3 * obj_area,
                   "material %s: the CSV's area against the OBJ's (m^2)", sc.materials[m].name);
    free(mat_area);
    free(rows);
    free(csv);
    obj_free(&sc);
}

/* ---- 6. --export-ply ---------------------------------------------------------- */

/* Next line of *P (NUL-terminated in place), or NULL at the end. */
static char *next_line(char **p)
{
    char *s = *p, *nl;
    if (!*s) return NULL;
    nl = strchr(s, '\n');
    if (nl) {
        *nl = '\0';
        *p = nl + 1;
    } else {
        *p = s + strlen(s);
    }
    return s;
}

static void test_export_ply(void **state)
{
    run_t r;
    char *ply, *p, *l;
    int patches, elements, vertices, nv = -1, nf = -1, i, k;
    double exposure = 0;
    static const char *const props[] = {
        "property float x",   "property float y",     "property float z",
        "property uchar red", "property uchar green", "property uchar blue",
    };
    (void)state;
    need(FIXED);
    RUN(&r, FIXED, "--quiet", "--stats", "--width", "16", "--height", "16", COARSE, "--export-ply",
        tmp_path("mesh.ply"), "-o", tmp_path("mesh.png"), CORNELL);
    expect_status(&r, 0);
    parse_counts(r.out, &patches, &elements, &vertices);
    run_free(&r);

    ply = slurp(tmp_path("mesh.ply"), NULL);
    assert_non_null(ply);
    p = ply;
    assert_string_equal(next_line(&p), "ply");
    assert_string_equal(next_line(&p), "format ascii 1.0");
    l = next_line(&p);
    assert_non_null(l);
    assert_int_equal(
        sscanf(l, "comment rad radiosity, sRGB vertex colours at exposure %lf", &exposure), 1);
    CHECK_GT(exposure, 0, "the PLY header's exposure");
    l = next_line(&p);
    assert_int_equal(sscanf(l, "element vertex %d", &nv), 1);
    for (i = 0; i < 6; i++) assert_string_equal(next_line(&p), props[i]);
    l = next_line(&p);
    assert_int_equal(sscanf(l, "element face %d", &nf), 1);
    assert_string_equal(next_line(&p), "property list uchar int vertex_indices");
    assert_string_equal(next_line(&p), "end_header");
    print_message("PLY: %d vertices, %d faces; --stats: %d vertices, %d elements\n", nv, nf,
                  vertices, elements);
    assert_int_equal(nv, vertices);
    assert_int_equal(nf, elements);

    for (i = 0; i < nv; i++) {
        double x, y, z;
        int c[3], used = 0;
        l = next_line(&p);
        assert_non_null(l);
        if (sscanf(l, "%lf %lf %lf %d %d %d%n", &x, &y, &z, &c[0], &c[1], &c[2], &used) != 6 ||
            l[used] != '\0')
            fail_msg("bad PLY vertex line %d: %s", i, l);
        for (k = 0; k < 3; k++) {
            CHECK_INT_GE(c[k], 0, "PLY vertex %d: colour channel %d", i, k);
            CHECK_INT_LE(c[k], 255, "PLY vertex %d: colour channel %d", i, k);
        }
        CHECK_THAT(x > -0.557 && x < 1e-6 && y > -1e-6 && y < 0.549 && z > -0.56 && z < 1e-6,
                   "PLY vertex %d at %g %g %g: inside the box (x -0.556..0, y 0..0.549, "
                   "z -0.559..0)",
                   i, x, y, z);
    }
    for (i = 0; i < nf; i++) {
        int cnt, idx, used = 0, pos;
        l = next_line(&p);
        assert_non_null(l);
        assert_int_equal(sscanf(l, "%d%n", &cnt, &used), 1);
        CHECK_THAT(cnt == 3 || cnt == 4,
                   "PLY face %d has %d corners: elements are triangles or quads", i, cnt);
        pos = used;
        for (k = 0; k < cnt; k++) {
            assert_int_equal(sscanf(l + pos, "%d%n", &idx, &used), 1);
            CHECK_INT_GE(idx, 0, "PLY face %d: corner %d's vertex", i, k);
            CHECK_INT_LT(idx, nv, "PLY face %d: corner %d's vertex against the vertices", i, k);
            pos += used;
        }
        assert_int_equal(l[pos], '\0');
    }
    assert_null(next_line(&p)); /* nothing after the faces */
    free(ply);
}

/* ---- 7. materials and emission ------------------------------------------------ */

static void expect_material(const char *out, const char *name, const double kd[3],
                            const double ke[3])
{
    char want[64], got[64];
    double v[6];
    int i;
    const char *l = out;
    snprintf(want, sizeof want, "%s ", name);
    while (l && !starts_with(l, want)) {
        l = strchr(l, '\n');
        if (l) l++;
    }
    if (!l) fail_msg("--list-materials does not list %s:\n%s", name, out);
    assert_int_equal(
        sscanf(l, "%63s %lf %lf %lf %lf %lf %lf", got, &v[0], &v[1], &v[2], &v[3], &v[4], &v[5]),
        7);
    for (i = 0; i < 3; i++) {
        /* Printed with %.4g: 4 significant digits. */
        CHECK_NEAR(v[i], kd[i], 1e-4 * (1 + kd[i]), "material %s: Kd channel %d", name, i);
        CHECK_NEAR(v[3 + i], ke[i], 1e-4 * (1 + ke[i]), "material %s: Ke channel %d", name, i);
    }
}

static void test_list_materials(void **state)
{
    run_t r;
    static const double white[3] = {0.74, 0.73, 0.70}, red[3] = {0.62, 0.07, 0.05},
                        green[3] = {0.15, 0.45, 0.10}, lightkd[3] = {0.78, 0.78, 0.78},
                        zero[3] = {0, 0, 0}, lightke[3] = {18.0, 12.8, 4.4}, set[3] = {1, 2.5, 3};
    (void)state;
    need(FIXED);
    RUN(&r, FIXED, "--list-materials", CORNELL);
    expect_status(&r, 0);
    CHECK_THAT(has_line(r.out, "material "), "the output has a line starting \"%s\":\n%s",
               "material ", r.out);
    expect_material(r.out, "white", white, zero);
    expect_material(r.out, "red", red, zero);
    expect_material(r.out, "green", green, zero);
    expect_material(r.out, "light", lightkd, lightke);
    assert_int_equal(count_lines(r.out), 5); /* header + 4 materials */
    run_free(&r);
    /* --emit is applied before listing. */
    RUN(&r, FIXED, "--emit", "light=1,2.5,3", "--list-materials", CORNELL);
    expect_status(&r, 0);
    expect_material(r.out, "light", lightkd, set);
    run_free(&r);
}

static void test_emit_lights_dark_scene(void **state)
{
    run_t r;
    img_t im, ref;
    long black;
    (void)state;
    need(FIXED);
    /* Without an emitter: a black image, exit 0, and a warning. */
    RUN(&r, FIXED, "--width", "48", "--height", "48", "--camera", "0,0.6,3,0,0.6,0", "-o",
        tmp_path("dark.png"), DATA "dark.obj");
    expect_status(&r, 0);
    CHECK_CONTAINS(r.err, "no material emits", "rad_cli's stderr");
    run_free(&r);
    load_img(tmp_path("dark.png"), &im);
    assert_int_equal(count_black(&im), 48 * 48);
    img_free(&im);

    /* --emit makes the lamp a light: the floor and wall are lit, no warning. */
    RUN(&r, FIXED, "--width", "48", "--height", "48", "--camera", "0,0.6,3,0,0.6,0", "--emit",
        "lamp=10,10,10", "-o", tmp_path("lit.png"), DATA "dark.obj");
    expect_status(&r, 0);
    CHECK_LACKS(r.err, "no material emits", "rad_cli's stderr");
    run_free(&r);
    load_img(tmp_path("lit.png"), &im);
    black = count_black(&im);
    print_message("lit by --emit: %ld of %d pixels black\n", black, 48 * 48);
    /* The lamp, floor and wall cover about a quarter of this view (the test prints the
     * black pixels); the rest is empty space. Require 10%. */
    CHECK_INT_LT(black, 48 * 48 * 9 / 10, "black pixels of the 48 x 48 view lit by --emit");
    /* orient.obj is dark.obj with Ke 10 10 10 on the lamp in its MTL: the same picture. */
    RUN(&r, FIXED, "--quiet", "--width", "48", "--height", "48", "--camera", "0,0.6,3,0,0.6,0",
        "-o", tmp_path("lit_mtl.png"), DATA "orient.obj");
    expect_status(&r, 0);
    run_free(&r);
    load_img(tmp_path("lit_mtl.png"), &ref);
    expect_same_pixels(&im, &ref);
    img_free(&ref);
    img_free(&im);

    /* An unknown material name is an error. */
    RUN(&r, FIXED, "--emit", "nosuch=1,1,1", "-o", tmp_path("nosuch.png"), DATA "dark.obj");
    expect_status(&r, 1);
    CHECK_CONTAINS(r.err, "nosuch", "rad_cli's stderr");
    CHECK_THAT(!file_exists(tmp_path("nosuch.png")), "%s is not written", tmp_path("nosuch.png"));
    run_free(&r);
}

/* ---- 8. exit codes and messages ----------------------------------------------- */

/* --help's sections: every heading (a line at the margin ending in ':') is followed
 * by an option of its own, and no heading names a folder of the source. */
static void check_help_sections(const char *out)
{
    const char *line = out;
    int headings = 0;
    while (*line) {
        const char *end = strchr(line, '\n'), *next = end ? end + 1 : line + strlen(line);
        size_t n = (size_t)(next - line) - (end ? 1u : 0u);
        if (n > 1 && line[0] != ' ' && line[n - 1] == ':') {
            char heading[256];
            snprintf(heading, sizeof heading, "%.*s", (int)(n < 255 ? n : 255), line);
            headings++;
            CHECK_THAT(starts_with(next, "  -"), "--help's section \"%s\" has no option of its own",
                       heading);
            CHECK_LACKS(heading, "tools/", "--help's heading names a source folder");
        }
        line = next;
    }
    CHECK_INT_GE(headings, 5, "--help's sections");
}

/* Usage error: exit 2, "PROG: reason" first, the usage text, nothing on stdout. */
static void expect_usage_error_at(const char *bin, const char *prog, const char *const *args,
                                  const char *file, int line)
{
    run_t r;
    char prefix[64];
    run_args(&r, bin, args);
    snprintf(prefix, sizeof prefix, "%s: ", prog);
    if (r.status != 2 || !strstr(r.err, "usage:") || !starts_with(r.err, prefix) ||
        r.out[0] != '\0') {
        print_error("%s %s ...: status %d (expected 2)\nstdout: %s\nstderr: %s\n", bin,
                    args[0] ? args[0] : "", r.status, r.out, r.err);
        run_free(&r);
        _fail(file, line);
    }
    run_free(&r);
}
#define expect_usage_error(bin, prog, ...)                                                   \
    expect_usage_error_at((bin), (prog), (const char *const[]){__VA_ARGS__, NULL}, __FILE__, \
                          __LINE__)

/* A usage error is short: the message, the help of the option at fault (its own
 * lines only), and where the rest is; the 130-line help is for --help. */
static void test_usage_error_short(void **state)
{
    static const char *const bad[][3] = {{"--gather", "31", "  --gather RES"},
                                         {"--res", "9", "  --res N"},
                                         {"--bogus", CORNELL, NULL}};
    size_t i;
    (void)state;
    need(FIXED);
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        run_t r;
        const char *args[] = {bad[i][0], bad[i][1], CORNELL, NULL};
        run_args(&r, FIXED, args);
        print_message("%s %s: status %d, %d lines on stderr\n", bad[i][0], bad[i][1], r.status,
                      count_lines(r.err));
        CHECK_INT_EQ(r.status, 2, "exit status of a usage error");
        CHECK_CONTAINS(r.err, "rad_cli --help lists the options", "the pointer to --help");
        if (bad[i][2]) CHECK_CONTAINS(r.err, bad[i][2], "the option's own help");
        CHECK_LACKS(r.err, "--lightmap-size", "another option's help");
        CHECK_INT_LE(count_lines(r.err), 8, "lines of a usage error");
        run_free(&r);
    }
}

static void test_usage_errors(void **state)
{
    static const char *const bins[2][2] = {{FIXED, "rad_cli"}, {FLOAT, "rad_cli_float"}};
    int b;
    run_t r;
    (void)state;
    need(FIXED);
    need(FLOAT);
    for (b = 0; b < 2; b++) {
        const char *bin = bins[b][0], *prog = bins[b][1];
        const char *out = tmp_path("usage.png");
        expect_usage_error(bin, prog, "--quiet");                            /* no scene */
        expect_usage_error(bin, prog, "--bogus", CORNELL);                   /* unknown option */
        expect_usage_error(bin, prog, "--res", "7", CORNELL);                /* below 8 */
        expect_usage_error(bin, prog, "--res", "10", "--res", "9", CORNELL); /* odd */
        expect_usage_error(bin, prog, "--coarse-res", "25", CORNELL);        /* odd */
        expect_usage_error(bin, prog, "--gather", "31", CORNELL);            /* odd */
        expect_usage_error(bin, prog, "--width", "0", CORNELL);
        expect_usage_error(bin, prog, "--height", "-3", CORNELL);
        expect_usage_error(bin, prog, "--width", "12x", CORNELL);
        expect_usage_error(bin, prog, "--camera", "1,2,3,4,5", "-o", out, CORNELL); /* 5 numbers */
        expect_usage_error(bin, prog, "--camera", "1,2,3,4,5,6", CORNELL);          /* no -o */
        expect_usage_error(bin, prog, "--camera", "1,2,3,4,5,6", "--camera", "1,2,3,4,5,7", "-o",
                           out, CORNELL);
        expect_usage_error(bin, prog, "--camera", "1,2,3,4,5,6,200", "-o", out,
                           CORNELL); /* FOV out of range */
        expect_usage_error(bin, prog, "--exposure", "0", CORNELL);
        expect_usage_error(bin, prog, "--emit", "light=1,2", CORNELL);
        expect_usage_error(bin, prog, "--tol", "1", CORNELL);
        expect_usage_error(bin, prog, CORNELL, CORNELL); /* two scenes */
        expect_usage_error(bin, prog, CORNELL, "-o");    /* option without its value */
        CHECK_THAT(!file_exists(out), "%s is not written", out);
        /* --help: the usage on stdout, exit 0. */
        RUN(&r, bin, "--help");
        expect_status(&r, 0);
        CHECK_THAT(starts_with(r.out, "usage: "), "%s --help prints the usage:\n%s", bin, r.out);
        assert_string_equal(r.err, "");
        check_help_sections(r.out);
        run_free(&r);
    }
}

/* Runtime error: exit 1, exactly one line on stderr starting with PREFIX, no stdout. */
static void expect_runtime_error_at(const run_t *r, const char *prefix, const char *file, int line)
{
    if (r->status == 1 && starts_with(r->err, prefix) && count_lines(r->err) == 1 &&
        r->err[strlen(r->err) - 1] == '\n' && r->out[0] == '\0')
        return;
    print_error(
        "status %d (expected 1), stderr (expected one line starting \"%s\"):\n%s\nstdout: %s\n",
        r->status, prefix, r->err, r->out);
    _fail(file, line);
}
#define expect_runtime_error(r, prefix) expect_runtime_error_at((r), (prefix), __FILE__, __LINE__)

static void test_runtime_errors(void **state)
{
    static const char *const bins[2][2] = {{FIXED, "rad_cli"}, {FLOAT, "rad_cli_float"}};
    int b;
    run_t r;
    char want[256];
    (void)state;
    need(FIXED);
    need(FLOAT);
    for (b = 0; b < 2; b++) {
        const char *bin = bins[b][0], *prog = bins[b][1];
        /* The vertex on line 3 of bad_vertex.obj is "v 1 x 0". */
        RUN(&r, bin, "-o", tmp_path("err.png"), DATA "bad_vertex.obj");
        snprintf(want, sizeof want, "%s: " DATA "bad_vertex.obj:3: ", prog);
        expect_runtime_error(&r, want);
        run_free(&r);
        /* bad_index.obj line 5: "f 1 2 4" with 3 vertices. */
        RUN(&r, bin, "-o", tmp_path("err.png"), DATA "bad_index.obj");
        snprintf(want, sizeof want, "%s: " DATA "bad_index.obj:5: ", prog);
        expect_runtime_error(&r, want);
        CHECK_CONTAINS(r.err, "out of range", "rad_cli's stderr");
        run_free(&r);
        /* A missing file has no line to name: "PROG: FILE: reason". */
        RUN(&r, bin, "-o", tmp_path("err.png"), DATA "no_such_scene.obj");
        snprintf(want, sizeof want, "%s: " DATA "no_such_scene.obj: ", prog);
        expect_runtime_error(&r, want);
        run_free(&r);
        /* A views file line with 5 numbers: "PROG: FILE:LINE: ..." (line 2). */
        write_text(tmp_path("bad_views.txt"), "# comment\n1 2 3 4 5 out.png\n");
        RUN(&r, bin, "--views", tmp_path("bad_views.txt"), CORNELL);
        snprintf(want, sizeof want, "%s: %s:2: ", prog, tmp_path("bad_views.txt"));
        expect_runtime_error(&r, want);
        run_free(&r);
        CHECK_THAT(!file_exists(tmp_path("err.png")), "%s is not written", tmp_path("err.png"));
    }
}

static void test_unwritable_output(void **state)
{
    run_t r;
    char *before, *after;
    size_t n0, n1;
    (void)state;
    need(FIXED);
    /* A directory that does not exist: exit 1, the path in a one-line message, no file. */
    RUN(&r, FIXED, "--width", "16", "--height", "16", COARSE, "-o", "/nonexistent_dir/x.png",
        CORNELL);
    expect_runtime_error(&r, "rad_cli: ");
    CHECK_CONTAINS(r.err, "/nonexistent_dir/x.png", "rad_cli's stderr");
    CHECK_THAT(!file_exists("/nonexistent_dir/x.png"), "%s is not written",
               "/nonexistent_dir/x.png");
    run_free(&r);

    /* An unknown extension: exit 1, the path named, neither the file nor a temporary
     * file left behind in the directory. */
    RUN(&r, FIXED, "--width", "16", "--height", "16", COARSE, "-o", tmp_path("x.bmp"), CORNELL);
    expect_runtime_error(&r, "rad_cli: ");
    CHECK_CONTAINS(r.err, tmp_path("x.bmp"), "rad_cli's stderr");
    assert_int_equal(count_tmp_files("x.bmp"), 0);
    run_free(&r);

    /* A render that fails (an eye 1 km away passes the parser; the core refuses a view
     * from beyond 4 times its coordinate range) leaves an existing output as it was. */
    write_text(tmp_path("keep.png"), "not replaced\n");
    before = slurp(tmp_path("keep.png"), &n0);
    RUN(&r, FIXED, "--width", "16", "--height", "16", COARSE, "--camera", "0,0.2,1000,0,0.2,0",
        "-o", tmp_path("keep.png"), CORNELL);
    expect_runtime_error(&r, "rad_cli: ");
    CHECK_CONTAINS(r.err, tmp_path("keep.png"), "rad_cli's stderr");
    run_free(&r);
    after = slurp(tmp_path("keep.png"), &n1);
    assert_non_null(after);
    assert_int_equal(n0, n1);
    assert_memory_equal(before, after, n0);
    assert_int_equal(count_tmp_files("keep.png"), 1);
    free(before);
    free(after);
}

/* ---- 9. fixed point vs the float twin ----------------------------------------- */

typedef struct {
    double within1, within5, mean_abs, mean_signed, block_max;
    int max_diff;
} twin_diff;

static void twin_images(img_t *fx, img_t *fl)
{
    run_t a, b;
    START(&a, FIXED, "--quiet", "--width", "256", "--height", "256", "--exposure", EXPOSURE, "-o",
          tmp_path("twin_fixed.png"), CORNELL);
    START(&b, FLOAT, "--quiet", "--width", "256", "--height", "256", "--exposure", EXPOSURE, "-o",
          tmp_path("twin_float.png"), CORNELL);
    run_finish(&a);
    run_finish(&b);
    expect_status(&a, 0);
    expect_status(&b, 0);
    run_free(&a);
    run_free(&b);
    load_img(tmp_path("twin_fixed.png"), fx);
    load_img(tmp_path("twin_float.png"), fl);
    assert_int_equal(fx->w, 256);
    assert_int_equal(fl->w, 256);
    assert_int_equal(fx->h, 256);
    assert_int_equal(fl->h, 256);
}

static twin_diff compare(const img_t *a, const img_t *b)
{
    twin_diff d = {0, 0, 0, 0, 0, 0};
    size_t i, n = (size_t)a->w * (size_t)a->h * 3;
    long w1 = 0, w5 = 0;
    int bx, by, x, y, c;
    for (i = 0; i < n; i++) {
        int s = (int)a->rgb[i] - (int)b->rgb[i], m = abs(s);
        w1 += m <= 1;
        w5 += m <= 5;
        d.mean_abs += m;
        d.mean_signed += s;
        if (m > d.max_diff) d.max_diff = m;
    }
    d.within1 = (double)w1 / (double)n;
    d.within5 = (double)w5 / (double)n;
    d.mean_abs /= (double)n;
    d.mean_signed /= (double)n;
    for (by = 0; by + 16 <= a->h; by += 16)
        for (bx = 0; bx + 16 <= a->w; bx += 16)
            for (c = 0; c < 3; c++) {
                double s = 0;
                for (y = by; y < by + 16; y++)
                    for (x = bx; x < bx + 16; x++)
                        s += (double)px(a, x, y)[c] - (double)px(b, x, y)[c];
                s = fabs(s) / 256.0;
                if (s > d.block_max) d.block_max = s;
            }
    return d;
}

/* Default settings, 256x256, the same fixed exposure for both (3.0, near this view's
 * automatic exposure, so the image uses the whole 8-bit range). Target: >= 99% of
 * channels within 1 level (the test prints what it measures). Before the hemi-cube's
 * turn depended on the patch alone, equal-power lights shot in a different order in the
 * two builds, each with another turn, and this failed by far. */
static void test_twin_agreement(void **state)
{
    img_t fx, fl;
    twin_diff d;
    (void)state;
    need(FIXED);
    need(FLOAT);
    twin_images(&fx, &fl);
    d = compare(&fx, &fl);
    print_message("fixed vs float, 256x256, defaults, exposure " EXPOSURE
                  ": %.2f%% of channels within 1 level "
                  "(%.2f%% within 5), max difference %d, mean |diff| %.3f, mean diff %+.3f, worst "
                  "16x16 block %.2f\n",
                  100 * d.within1, 100 * d.within5, d.max_diff, d.mean_abs, d.mean_signed,
                  d.block_max);
    CHECK_INT_LT(count_black(&fx), 256 * 256 / 4,
                 "black pixels of the fixed build's image (a real picture)");
    CHECK_GE(d.within1, 0.99, "fraction of 8-bit channels within 1 level, fixed against float");
    /* rounding at the 8-bit step */
    CHECK_INT_LE(d.max_diff, 2, "max 8-bit difference, fixed against float");
    CHECK_LE(fabs(d.mean_signed), 0.1,
             "mean signed 8-bit difference, fixed against float (no bias)");
    img_free(&fx);
    img_free(&fl);
}

/* ---- 10. --stats and --quiet -------------------------------------------------- */

static void test_stats_and_quiet(void **state)
{
    run_t r;
    (void)state;
    need(FIXED);
    RUN(&r, FIXED, "--stats", "--quiet", "--width", "16", "--height", "16", COARSE, "-o",
        tmp_path("stats.png"), CORNELL);
    expect_status(&r, 0);
    CHECK_THAT(has_line(r.out, "patches "), "the output has a line starting \"%s\":\n%s",
               "patches ", r.out);
    CHECK_THAT(has_line(r.out, "shots "), "the output has a line starting \"%s\":\n%s", "shots ",
               r.out);
    CHECK_THAT(has_line(r.out, "time: "), "the output has a line starting \"%s\":\n%s",
               "time: ", r.out);
    CHECK_THAT(has_line(r.out, "memory: "), "the output has a line starting \"%s\":\n%s",
               "memory: ", r.out);
    assert_string_equal(r.err, ""); /* --quiet: nothing on stderr */
    run_free(&r);

    /* --quiet also silences the "no material emits" warning. */
    RUN(&r, FIXED, "--quiet", "--width", "16", "--height", "16", "-o", tmp_path("quiet_dark.png"),
        DATA "dark.obj");
    expect_status(&r, 0);
    assert_string_equal(r.err, "");
    assert_string_equal(r.out, "");
    run_free(&r);
}

/* ---- regressions -------------------------------------------------------------- */

/* Lists take exactly their values: "--exposure 1.5,junk", a trailing comma, "--camera"
 * with 8 numbers and "--emit NAME=1,2,3,4" are usage errors (they were once ignored). */
static void test_trailing_list_items(void **state)
{
    const char *out = tmp_path("trail.png");
    (void)state;
    need(FIXED);
    expect_usage_error(FIXED, "rad_cli", "--exposure", "1.5,junk", "-o", out, CORNELL);
    expect_usage_error(FIXED, "rad_cli", "--exposure", "1.5,", "-o", out, CORNELL);
    expect_usage_error(FIXED, "rad_cli", "--camera", "-0.27,0.27,1.2,-0.27,0.27,0,45,99", "-o", out,
                       CORNELL);
    expect_usage_error(FIXED, "rad_cli", "--emit", "light=1,2,3,4", "-o", out, CORNELL);
}

/* A camera looking straight down renders (up switches from +y to -z). */
static void test_camera_looking_down(void **state)
{
    run_t r;
    (void)state;
    need(FIXED);
    RUN(&r, FIXED, "--quiet", "--width", "32", "--height", "32", COARSE, "--camera",
        "-0.278,1.5,-0.28,-0.278,0,-0.28", "-o", tmp_path("down.png"), CORNELL);
    expect_status(&r, 0);
    run_free(&r);
}

/* No single-pixel cracks: the floor and the green wall are meshed independently (their
 * shared edge cut in 24 and 28 pieces), and the T-junctions once left isolated pixels
 * that no element covered (e.g. (203, 202) at 256x256); rad_render now fills them. */
static void test_render_cracks(void **state)
{
    img_t fx, fl;
    const img_t *ims[2];
    int k, x, y;
    (void)state;
    need(FIXED);
    need(FLOAT);
    twin_images(&fx, &fl);
    ims[0] = &fx;
    ims[1] = &fl;
    for (k = 0; k < 2; k++)
        for (y = 1; y < 255; y++)
            for (x = 1; x < 255; x++) {
#define BLACK(i, xx, yy) \
    (px((i), (xx), (yy))[0] == 0 && px((i), (xx), (yy))[1] == 0 && px((i), (xx), (yy))[2] == 0)
                const img_t *im = ims[k];
                if (BLACK(im, x, y) && !BLACK(im, x - 1, y) && !BLACK(im, x + 1, y) &&
                    !BLACK(im, x, y - 1) && !BLACK(im, x, y + 1))
                    fail_msg("%s: isolated black pixel at (%d, %d)", k ? "float" : "fixed", x, y);
#undef BLACK
            }
    img_free(&fx);
    img_free(&fl);
}

/* ---- lights: --sun, --point, --spot ------------------------------------------- */

/* The area-weighted mean red radiosity of --dump-radiosity's rows (CSV at PATH). */
static double csv_mean_red(const char *path, double *area_out)
{
    char *csv = slurp(path, NULL), *line;
    double sum = 0, area = 0;
    assert_non_null(csv);
    line = strchr(csv, '\n');
    assert_non_null(line);
    for (line++; *line;) {
        double a, c[3], rgb[3];
        int el, sf;
        char mat[64];
        char *next = strchr(line, '\n');
        if (next) *next++ = '\0';
        assert_int_equal(sscanf(line, "%d,%d,%63[^,],%lf,%lf,%lf,%lf,%lf,%lf,%lf", &el, &sf, mat,
                                &a, &c[0], &c[1], &c[2], &rgb[0], &rgb[1], &rgb[2]),
                         10);
        sum += rgb[0] * a;
        area += a;
        line = next ? next : line + strlen(line);
    }
    free(csv);
    *area_out = area;
    return sum / area;
}

/* A 16 x 16 floor of Kd 0.5 under --sky: its mean radiosity is rho pi L (uniform), and
 * rho pi H / 3 under a horizon-only sky (R,G,B 0 at the zenith: L = H (1 - cos t)),
 * exactly by the dome's weights (rad.h) but for the raster's coverage of the floor's
 * outline in each direction's shot (test_light.c's bound at the scene's res 192:
 * p = 16 sqrt 2 / 192, P <= 64 for every projection: 2.2% of the area); with N = 12
 * directions the same. Bad values are refused (stored rows take lights: test_relight.c). */
static void test_sky(void **state)
{
    static const struct {
        const char *val, *more, *says;
    } bad[] = {
        {"1,1", NULL, "--sky wants R,G,B[,HR,HG,HB][,N]"},
        {"1,1,1,2", NULL, "N an integer 3..768"},
        {"1,1,1,12.5", NULL, "N an integer 3..768"},
        {"1,1,1,769", NULL, "N an integer 3..768"},
        {"1,1,1,1,1", NULL, "--sky wants"},
        {"1,1,-1", NULL, "radiances >= 0"},
        {"1,1,1,1,-1,1,12", NULL, "radiances >= 0"},
    };
    static const struct {
        const char *val;
        double want;
    } good[] = {{"2,2,2", 0.5 * 3.14159265358979323846 * 2},
                {"0,0,0,2,2,2", 0.5 * 3.14159265358979323846 * 2 / 3},
                {"2,2,2,12", 0.5 * 3.14159265358979323846 * 2}};
    run_t r;
    double area, mean;
    size_t k;
    (void)state;
    need(FIXED);
    write_text(tmp_path("floor.mtl"), "newmtl floor\nKd 0.5 0.5 0.5\n");
    write_text(
        tmp_path("floor.obj"),
        "mtllib floor.mtl\nusemtl floor\nv -8 0 -8\nv -8 0 8\nv 8 0 8\nv 8 0 -8\nf 1 2 3 4\n");
    for (k = 0; k < sizeof good / sizeof good[0]; k++) {
        RUN(&r, FIXED, "--quiet", "--width", "16", "--height", "16", "--sky", good[k].val,
            "--dump-radiosity", tmp_path("sky.csv"), "-o", tmp_path("sky.png"),
            tmp_path("floor.obj"));
        expect_status(&r, 0);
        run_free(&r);
        mean = csv_mean_red(tmp_path("sky.csv"), &area);
        print_message("--sky %s: mean radiosity %.6f, the law's %.6f (%+.3f%%, bound 2.2%%)\n",
                      good[k].val, mean, good[k].want, 100 * (mean / good[k].want - 1));
        CHECK_NEAR(area, 256, 0.01, "the floor's area");
        CHECK_NEAR(mean, good[k].want, good[k].want * 0.022,
                   "the floor's mean radiosity under --sky %s", good[k].val);
    }
    for (k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        if (bad[k].more)
            RUN(&r, FIXED, "--sky", bad[k].val, bad[k].more, tmp_path("sky.ff"), "-o",
                tmp_path("bad.png"), tmp_path("floor.obj"));
        else
            RUN(&r, FIXED, "--sky", bad[k].val, "-o", tmp_path("bad.png"), tmp_path("floor.obj"));
        expect_status(&r, 2);
        CHECK_CONTAINS(r.err, bad[k].says, "rad_cli --sky %s", bad[k].val);
        run_free(&r);
    }
}

/* A 16 x 16 floor of Kd 0.5 under --sun at 60 degrees from its normal: the floor's mean
 * radiosity is rho E cos t, within the sun raster's coverage bound for its outline
 * (test_light.c: p P / sqrt 2 + 2 p^2 + P p sqrt 2 / 32 over the area, p = the
 * projection's diameter / R, R = 4 x 192 = 768): 0.62%. Under --point at height 4 over
 * its centre the floor gets I times its solid angle 4 asin(64 / 80) (within 1%: the
 * total over the plane, measured +0.02% at R 512 in test_light). Bad values are
 * refused (stored rows take lights: test_relight.c). */
static void test_lights(void **state)
{
    static const struct {
        const char *opt, *val, *more, *says;
    } bad[] = {
        {"--sun", "0,0,0,1,1,1", NULL, "--sun wants DX,DY,DZ,R,G,B"},
        {"--sun", "0,-1,0,1,1,1,20", NULL, "angular radius"},
        {"--point", "0,4,0,-1,1,1", NULL, "--point wants X,Y,Z,R,G,B"},
        {"--spot", "0,4,0,0,-1,0,1,1,1,200", NULL, "ANGLE"},
    };
    run_t r;
    double area, mean, t = 60 * 3.14159265358979323846 / 180, want;
    char sun[96];
    size_t k;
    (void)state;
    need(FIXED);
    write_text(tmp_path("floor.mtl"), "newmtl floor\nKd 0.5 0.5 0.5\n");
    write_text(
        tmp_path("floor.obj"),
        "mtllib floor.mtl\nusemtl floor\nv -8 0 -8\nv -8 0 8\nv 8 0 8\nv 8 0 -8\nf 1 2 3 4\n");
    snprintf(sun, sizeof sun, "%.9f,%.9f,0,2,2,2", sin(t), -cos(t));
    RUN(&r, FIXED, "--quiet", "--width", "16", "--height", "16", "--sun", sun, "--dump-radiosity",
        tmp_path("sun.csv"), "-o", tmp_path("sun.png"), tmp_path("floor.obj"));
    expect_status(&r, 0);
    run_free(&r);
    mean = csv_mean_red(tmp_path("sun.csv"), &area);
    want = 0.5 * 2 * cos(t);
    print_message("--sun at 60 degrees: mean radiosity %.6f, rho E cos t %.6f (%+.3f%%)\n", mean,
                  want, 100 * (mean / want - 1));
    CHECK_NEAR(area, 256, 0.01, "the floor's area");
    CHECK_NEAR(mean, want, want * 0.0062, "the floor's mean radiosity under --sun");

    /* with an angular radius of 5 degrees: its directions tilt by up to 5 degrees, so
     * cos t loses at most 1 - cos 5 = 0.38% more */
    RUN(&r, FIXED, "--quiet", "--width", "16", "--height", "16", "--sun", "0,-1,0,2,2,2,5",
        "--dump-radiosity", tmp_path("disc.csv"), "-o", tmp_path("disc.png"),
        tmp_path("floor.obj"));
    expect_status(&r, 0);
    run_free(&r);
    mean = csv_mean_red(tmp_path("disc.csv"), &area);
    print_message("--sun of angular radius 5 degrees: mean radiosity %.6f, rho E %.6f (%+.3f%%)\n",
                  mean, 1.0, 100 * (mean - 1));
    CHECK_NEAR(mean, 1.0 - 0.0019, 0.0062 + 0.0019,
               "the floor's mean radiosity under a --sun of radius 5 degrees");

    RUN(&r, FIXED, "--width", "16", "--height", "16", "--point", "0,4,0,10,10,10",
        "--dump-radiosity", tmp_path("point.csv"), "-o", tmp_path("point.png"),
        tmp_path("floor.obj"));
    expect_status(&r, 0);
    CHECK_LACKS(r.err, "no material emits", "rad_cli's stderr with a --point light");
    run_free(&r);
    mean = csv_mean_red(tmp_path("point.csv"), &area);
    want = 0.5 * 10 * 4 * asin(64.0 / 80) / 256;
    print_message("--point at height 4: mean radiosity %.6f, rho I w / A %.6f (%+.3f%%)\n", mean,
                  want, 100 * (mean / want - 1));
    CHECK_NEAR(mean, want, want * 0.01, "the floor's mean radiosity under --point");

    /* threads shoot the lights first too (rad_shot_begin): the same bits as serially */
    RUN(&r, FIXED, "--quiet", "--width", "16", "--height", "16", "--threads", "2", "--point",
        "0,4,0,10,10,10", "--dump-radiosity", tmp_path("point2.csv"), "-o", tmp_path("point2.png"),
        tmp_path("floor.obj"));
    expect_status(&r, 0);
    run_free(&r);
    {
        char *a = slurp(tmp_path("point.csv"), NULL), *b = slurp(tmp_path("point2.csv"), NULL);
        assert_non_null(a);
        assert_non_null(b);
        assert_string_equal(a, b);
        free(a);
        free(b);
    }

    /* a spot pointing away from the floor leaves it dark */
    RUN(&r, FIXED, "--quiet", "--width", "16", "--height", "16", "--spot",
        "0,4,0,0,1,0,10,10,10,30,0.2", "--dump-radiosity", tmp_path("spot.csv"), "-o",
        tmp_path("spot.png"), tmp_path("floor.obj"));
    expect_status(&r, 0);
    run_free(&r);
    CHECK_LE(csv_mean_red(tmp_path("spot.csv"), &area), 0, "the floor behind a spot's cone");

    for (k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        RUN(&r, FIXED, bad[k].opt, bad[k].val, bad[k].more ? bad[k].more : "--quiet",
            bad[k].more ? tmp_path("x.ff") : "--quiet", "-o", tmp_path("x.png"),
            tmp_path("floor.obj"));
        expect_status(&r, 2);
        CHECK_CONTAINS(r.err, bad[k].says, "rad_cli %s %s", bad[k].opt, bad[k].val);
        run_free(&r);
    }
    RUN(&r, FIXED, "--point", "0,100,0,1,1,1", "-o", tmp_path("x.png"), tmp_path("floor.obj"));
    expect_status(&r, 1);
    CHECK_CONTAINS(r.err, "light 1: its position lies beyond", "a point light far outside");
    run_free(&r);
}

/* ---- --lights FILE ---------------------------------------------------------------- */

/* Files at A and B hold the same bytes. */
static void expect_same_file(const char *a, const char *b)
{
    size_t la, lb;
    char *x = slurp(a, &la), *y = slurp(b, &lb);
    assert_non_null(x);
    assert_non_null(y);
    CHECK_INT_EQ(la, lb, "the size of %s against %s", a, b);
    if (memcmp(x, y, la) != 0) fail_msg("%s and %s differ", a, b);
    free(x);
    free(y);
}

#define LIT_ARGS "--quiet", "--width", "32", "--height", "32"

/* A lights file says the same lights as the options, to the same bits: the radiosity
 * CSV, the PLY and the image of the file's four kinds (between two options, in the
 * command line's order) equal those of the options alone. Each bad file is one line
 * "FILE:LINE:COL: what" (or "FILE: what" when it cannot be read), exit status 2, and
 * no output written. */
static void test_lights_file(void **state)
{
    static const struct {
        const char *text, *says;
    } bad[] = {
        {"{\"lights\": [{\"type\": \"sun\", \"direction\": [0,-1,0], \"irradiance\": [1,1,1],}]}",
         "bad.json:1:73: a ',' before '}'"},
        {"{\"lights\": []} []", "bad.json:1:16: '[' after the JSON value"},
        {"{\"lights\": [{\"type\": \"point\", \"position\": [0,4,0],\n \"position\": [0,4,0], "
         "\"intensity\": [1,1,1]}]}",
         "bad.json:2:2: the name \"position\" given twice in one object (first at 1:31)"},
        {"{\"lights\": [{\"type\": \"sun\", \"direction\": [0,-1,0], \"irradiance\": \"white\"}]}",
         "bad.json:1:66: lights[0].irradiance: wants an array of 3 numbers, found a string"},
        {"{\"lights\": [{\"type\": \"sun\", \"direction\": [0,-1,0], \"irradiance\": [1,1]}]}",
         "lights[0].irradiance: wants an array of 3 numbers, found 2 items"},
        {"{\"lights\": [{\"type\": \"sun\", \"direction\": [0,-1,null], \"irradiance\": [1,1,1]}]}",
         "bad.json:1:48: lights[0].direction[2]: wants a number, found null"},
        {"{\"lights\": [{\"type\": \"sun\", \"direction\": [0,-1,0], \"irradiance\": [1,1,1], "
         "\"color\": 1}]}",
         "bad.json:1:75: lights[0]: a sun has no \"color\" (it takes type, direction, irradiance, "
         "angle)"},
        {"{\"lights\": [{\"type\": \"lamp\"}]}",
         "bad.json:1:22: lights[0].type: wants \"sun\", \"point\""},
        {"{\"lights\": [{\"direction\": [0,-1,0]}]}",
         "bad.json:1:13: lights[0].type: wants \"sun\""},
        {"{\"lights\": [{\"type\": \"sun\", \"direction\": [0,0,0], \"irradiance\": [1,1,1]}]}",
         "bad.json:1:42: lights[0].direction: wants the way the light travels, not zero"},
        {"{\"lights\": [{\"type\": \"sun\", \"direction\": [0,-1,0], \"irradiance\": [1,1,1], "
         "\"angle\": 15}]}",
         "bad.json:1:84: lights[0].angle: wants the sun's angular radius in degrees, 0..14"},
        {"{\"lights\": [{\"type\": \"spot\", \"position\": [0,4,0], \"direction\": [0,-1,0], "
         "\"intensity\": [1,1,1]}]}",
         "bad.json:1:13: lights[0]: a spot wants \"angle\""},
        {"{\"lights\": [{\"type\": \"point\", \"position\": [0,4,0], \"intensity\": [1,-1,1]}]}",
         "lights[0].intensity: wants the intensity per steradian, each >= 0"},
        {"{\"lights\": [{\"type\": \"sky\", \"radiance\": [1,1,1], \"directions\": 12.5}]}",
         "lights[0].directions: wants a whole number of directions, 3..768"},
        {"{\"lights\": [{\"type\": \"sky-hdr\", \"file\": \"nothere.hdr\"}]}",
         "bad.json:1:41: lights[0].file: "},
        {"{\"lights\": [], \"suns\": []}",
         "bad.json:1:16: an unknown name \"suns\" (the file holds \"lights\")"},
        {"[{\"type\": \"sun\"}]",
         "bad.json:1:1: wants an object {\"lights\": [...]}, found an array"},
        {"{\"lights\": [{\"type\": \"sun\\u0000\"}]}", "bad.json:1:26: \\u0000 (NUL) in a string"},
        {"", "bad.json:1:1: no JSON value: the file is empty"},
    };
    static const char good[] =
        "{\"lights\": [\n"
        "  {\"type\": \"sky\", \"radiance\": [0.6, 0.7, 1.0], \"horizon\": [1, 1, 1], "
        "\"directions\": 12},\n"
        "  {\"type\": \"point\", \"position\": [2, 3, 1], \"intensity\": [4, 3, 2]},\n"
        "  {\"type\": \"spot\", \"position\": [-2, 3, 0], \"direction\": [0.2, -1, 0], "
        "\"intensity\": [9, 9, 6],\n"
        "   \"angle\": 35, \"softness\": 0.25}\n"
        "]}\n";
    const char *outs[2][3] = {{"lf.csv", "lf.ply", "lf.png"}, {"lo.csv", "lo.ply", "lo.png"}};
    run_t r;
    size_t k;
    int f;
    (void)state;
    need(FIXED);
    write_text(tmp_path("floor.mtl"),
               "newmtl floor\nKd 0.5 0.5 0.5\nnewmtl post\nKd 0.7 0.3 0.2\n");
    write_text(tmp_path("floor.obj"),
               "mtllib floor.mtl\nusemtl floor\nv -8 0 -8\nv -8 0 8\nv 8 0 8\nv 8 0 -8\n"
               "f 1 2 3 4\nusemtl post\nv -1 0 1\nv 1 0 1\nv 1 4 1\nv -1 4 1\nf 5 6 7 8\n");
    write_text(tmp_path("good.json"), good);
    RUN(&r, FIXED, LIT_ARGS, "--sun", "0.5,-1,0.2,2,2,2,0.27", "--lights", tmp_path("good.json"),
        "--point", "0,5,3,6,6,6", "--dump-radiosity", tmp_path(outs[0][0]), "--export-ply",
        tmp_path(outs[0][1]), "-o", tmp_path(outs[0][2]), tmp_path("floor.obj"));
    expect_status(&r, 0);
    run_free(&r);
    RUN(&r, FIXED, LIT_ARGS, "--sun", "0.5,-1,0.2,2,2,2,0.27", "--sky", "0.6,0.7,1.0,1,1,1,12",
        "--point", "2,3,1,4,3,2", "--spot", "-2,3,0,0.2,-1,0,9,9,6,35,0.25", "--point",
        "0,5,3,6,6,6", "--dump-radiosity", tmp_path(outs[1][0]), "--export-ply",
        tmp_path(outs[1][1]), "-o", tmp_path(outs[1][2]), tmp_path("floor.obj"));
    expect_status(&r, 0);
    run_free(&r);
    for (f = 0; f < 3; f++) expect_same_file(tmp_path(outs[0][f]), tmp_path(outs[1][f]));
    CHECK_GT(csv_mean_red(tmp_path("lf.csv"), &(double){0}), 0.1, "the lit floor's mean radiosity");

    for (k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        write_text(tmp_path("bad.json"), bad[k].text);
        RUN(&r, FIXED, "--lights", tmp_path("bad.json"), "--dump-radiosity", tmp_path("bad.csv"),
            "-o", tmp_path("bad.png"), tmp_path("floor.obj"));
        expect_status(&r, 2);
        CHECK_CONTAINS(r.err, bad[k].says, "bad lights file %zu: %s", k, bad[k].text);
        CHECK_INT_EQ(count_lines(r.err), 1, "bad lights file %zu: lines on stderr (%s)", k, r.err);
        CHECK_THAT(!file_exists(tmp_path("bad.png")) && !file_exists(tmp_path("bad.csv")),
                   "bad lights file %zu: no output written", k);
        run_free(&r);
    }
    RUN(&r, FIXED, "--lights", tmp_path("none.json"), "-o", tmp_path("bad.png"),
        tmp_path("floor.obj"));
    expect_status(&r, 2);
    CHECK_CONTAINS(r.err, "none.json: cannot open: No such file or directory",
                   "a lights file that is not there");
    run_free(&r);
    RUN(&r, FIXED, "--lights", tmp_path("good.json"), "--save-ff", tmp_path("x.ff"), "-o",
        tmp_path("ff.png"), tmp_path("floor.obj"));
    expect_status(&r, 0); /* lights work with stored rows (tests/test_relight.c measures them) */
    run_free(&r);
    RUN(&r, FIXED, "--lights", tmp_path("good.json"), "--dump-radiosity", tmp_path("good.json"),
        "-o", tmp_path("bad.png"), tmp_path("floor.obj"));
    expect_status(&r, 1);
    CHECK_CONTAINS(r.err, "would write over a --lights or --sky-hdr file",
                   "--dump-radiosity over the lights file");
    run_free(&r);
    {
        char *still = slurp(tmp_path("good.json"), NULL);
        assert_non_null(still);
        assert_string_equal(still, good);
        free(still);
    }
}

/* ---- --sky-hdr FILE[,N[,SCALE]] ------------------------------------------------------ */

/* A 64 x 32 map at PATH: grey radiance L where LIT(x, y), else black (+Y up, row 0 the
 * zenith, the middle column toward +X: tools/host/sky_map.h). */
static void write_map(const char *path, double l, int (*lit)(int x, int y))
{
    float m[3 * 64 * 32];
    char err[256];
    int x, y, c;
    for (y = 0; y < 32; y++)
        for (x = 0; x < 64; x++)
            for (c = 0; c < 3; c++) m[3 * (y * 64 + x) + c] = lit(x, y) ? (float)l : 0.0f;
    CHECK_INT_EQ(hdr_write(path, m, 64, 32, err, sizeof err), 0, "hdr_write %s (%s)", path, err);
}

static int map_all(int x, int y)
{
    return (void)x, (void)y, 1;
}
static int map_cap(int x, int y)
{
    return (void)x, y < 8;
} /* zenith angle < 45 degrees */
static int map_east(int x, int y)
{
    return y < 16 && x >= 16 && x < 48;
} /* the half toward +X */

/* The area-weighted mean red radiosity of surface SF in --dump-radiosity's CSV. */
static double csv_surface_red(const char *path, int sf_want)
{
    char *csv = slurp(path, NULL), *line;
    double sum = 0, area = 0;
    assert_non_null(csv);
    for (line = strchr(csv, '\n'); line && line[1]; line = strchr(line + 1, '\n')) {
        double a, c[3], rgb[3];
        int el, sf;
        char mat[64];
        assert_int_equal(sscanf(line + 1, "%d,%d,%63[^,],%lf,%lf,%lf,%lf,%lf,%lf,%lf", &el, &sf,
                                mat, &a, &c[0], &c[1], &c[2], &rgb[0], &rgb[1], &rgb[2]),
                         10);
        if (sf == sf_want) sum += rgb[0] * a, area += a;
    }
    free(csv);
    return sum / area;
}

/* Red radiosities of every element of CSV at PATH into V (at most N); the count. */
static int csv_reds(const char *path, double *v, int n)
{
    char *csv = slurp(path, NULL), *line;
    int k = 0;
    assert_non_null(csv);
    for (line = strchr(csv, '\n'); line && line[1] && k < n; line = strchr(line + 1, '\n')) {
        double a, c[3];
        int el, sf;
        char mat[64];
        assert_int_equal(sscanf(line + 1, "%d,%d,%63[^,],%lf,%lf,%lf,%lf,%lf", &el, &sf, mat, &a,
                                &c[0], &c[1], &c[2], &v[k]),
                         8);
        k++;
    }
    free(csv);
    return k;
}

/* --sky-hdr against closed forms (floor Kd 0.5):
 * - a uniform map of L against --sky L: the same cells (tools/host/sky_map.h), each sun
 *   along the direction the core computes in Q30 integers, here in doubles and then
 *   Q16: they differ by about 2^-16 radians, which moves the floor's outline (16 units
 *   across, pixels of 0.12) by 0.002 pixel a shot and shifts a few pixels from one
 *   element to its neighbour: the floor's total within 1e-4, each element (about 32
 *   pixels a shot) within 0.5% (one pixel in a few of the 192 shots); the float twin
 *   against the fixed build the same (their directions round apart as much);
 * - a cap of zenith angles below 45 degrees: a floor gets pi L sin^2 45 = pi L / 2, the
 *   cap's edge cutting cells changing nothing on it (every cell's light integrated);
 *   with SCALE 0.5 half that;
 * - the half of the sky toward +X (east): a wall facing +X gets pi L / 2, one facing -X
 *   nothing (every lit direction lies behind it);
 * the last two within the raster's coverage of the outline, test_sky's 2.2% (the same bound:
 * test_light.c's p P / sqrt 2 over the area, p P the same for the 4 x 4 walls in their
 * smaller window). A lights file's "sky-hdr" gives the option's bits; bad values and
 * bad maps are one line and status 2, no output. */
static void test_sky_hdr(void **state)
{
    static const struct {
        const char *val, *says;
    } bad[] = {
        {"map.hdr,2", "--sky-hdr wants FILE[,N[,SCALE]]"},
        {"map.hdr,192,0", "--sky-hdr wants FILE[,N[,SCALE]]"},
        {",192", "--sky-hdr wants FILE[,N[,SCALE]]"},
        {"trunc.hdr", "trunc.hdr: truncated or corrupt pixel data"},
        {"huge.hdr",
         "huge.hdr: truncated or corrupt pixel data: shorter than the header's size needs"},
        {"notmap.hdr", "notmap.hdr: not a Radiance HDR"},
        {"missing.hdr", "missing.hdr: cannot open"},
    };
    enum { MAXEL = 4096 };
    static double a[MAXEL], b[MAXEL];
    const double pi = 3.14159265358979323846;
    double mean, worst = 0, ta = 0, tb = 0;
    run_t r;
    size_t k;
    int n, nb, i;
    char path[400];
    (void)state;
    need(FIXED);
    write_text(tmp_path("floor.mtl"), "newmtl floor\nKd 0.5 0.5 0.5\n");
    write_text(
        tmp_path("floor.obj"),
        "mtllib floor.mtl\nusemtl floor\nv -8 0 -8\nv -8 0 8\nv 8 0 8\nv 8 0 -8\nf 1 2 3 4\n");
    write_text(tmp_path("walls.obj"),
               "mtllib floor.mtl\nusemtl floor\nv 1 0 2\nv 1 0 -2\nv 1 4 -2\nv 1 4 2\n"
               "f 1 2 3 4\nv -1 0 -2\nv -1 0 2\nv -1 4 2\nv -1 4 -2\nf 5 6 7 8\n");
    write_map(tmp_path("map.hdr"), 2.0, map_all);
    write_map(tmp_path("cap.hdr"), 2.0, map_cap);
    write_map(tmp_path("east.hdr"), 2.0, map_east);

    RUN(&r, FIXED, LIT_ARGS, "--sky-hdr", tmp_path("map.hdr"), "--dump-radiosity",
        tmp_path("hdr.csv"), "-o", tmp_path("hdr.png"), tmp_path("floor.obj"));
    expect_status(&r, 0);
    run_free(&r);
    RUN(&r, FIXED, LIT_ARGS, "--sky", "2,2,2", "--dump-radiosity", tmp_path("sky.csv"), "-o",
        tmp_path("sky.png"), tmp_path("floor.obj"));
    expect_status(&r, 0);
    run_free(&r);
    n = csv_reds(tmp_path("hdr.csv"), a, MAXEL);
    nb = csv_reds(tmp_path("sky.csv"), b, MAXEL);
    CHECK_INT_EQ(n, nb, "elements under --sky-hdr and --sky");
    for (i = 0; i < n; i++) {
        worst = fmax(worst, fabs(a[i] / b[i] - 1));
        ta += a[i];
        tb += b[i];
    }
    print_message(
        "--sky-hdr of a uniform map against --sky: elements within %.3f%%, the floor %+.4f%%\n",
        100 * worst, 100 * (ta / tb - 1));
    CHECK_LE(worst, 0.005,
             "the largest relative difference of an element's radiosity, --sky-hdr against --sky");
    CHECK_NEAR(ta / tb, 1, 1e-4, "the floor's radiosity, --sky-hdr against --sky");

    /* the float twin on the same map: its suns' directions round apart by as much */
    need(FLOAT);
    RUN(&r, FLOAT, LIT_ARGS, "--sky-hdr", tmp_path("map.hdr"), "--dump-radiosity",
        tmp_path("hdrf.csv"), "-o", tmp_path("hdrf.png"), tmp_path("floor.obj"));
    expect_status(&r, 0);
    run_free(&r);
    CHECK_INT_EQ(csv_reds(tmp_path("hdrf.csv"), b, MAXEL), n,
                 "elements under --sky-hdr, float twin");
    for (i = 0, worst = 0, tb = 0; i < n; i++) {
        worst = fmax(worst, fabs(a[i] / b[i] - 1));
        tb += b[i];
    }
    print_message(
        "--sky-hdr, fixed against the float twin: elements within %.3f%%, the floor %+.4f%%\n",
        100 * worst, 100 * (ta / tb - 1));
    CHECK_LE(worst, 0.005,
             "the largest relative difference of an element's radiosity, fixed against float");
    CHECK_NEAR(ta / tb, 1, 1e-4, "the floor's radiosity, fixed against float");

    snprintf(path, sizeof path, "%s,192,0.5", tmp_path("cap.hdr"));
    RUN(&r, FIXED, LIT_ARGS, "--sky-hdr", path, "--dump-radiosity", tmp_path("cap.csv"), "-o",
        tmp_path("cap.png"), tmp_path("floor.obj"));
    expect_status(&r, 0);
    run_free(&r);
    mean = csv_surface_red(tmp_path("cap.csv"), 0);
    print_message(
        "--sky-hdr of a 45 degree cap, SCALE 0.5: the floor %.6f, rho pi L / 2 %.6f (%+.3f%%)\n",
        mean, 0.5 * pi / 2, 100 * (mean / (0.5 * pi / 2) - 1));
    CHECK_NEAR(mean, 0.5 * pi / 2, 0.5 * pi / 2 * 0.022,
               "the floor under a cap of 45 degrees at SCALE 0.5");

    RUN(&r, FIXED, LIT_ARGS, "--sky-hdr", tmp_path("east.hdr"), "--dump-radiosity",
        tmp_path("east.csv"), "-o", tmp_path("east.png"), tmp_path("walls.obj"));
    expect_status(&r, 0);
    run_free(&r);
    mean = csv_surface_red(tmp_path("east.csv"), 0);
    print_message("--sky-hdr lit toward +X: the wall facing +X %.6f, rho pi L / 2 %.6f (%+.3f%%); "
                  "facing -X %.6f\n",
                  mean, 0.5 * pi, 100 * (mean / (0.5 * pi) - 1),
                  csv_surface_red(tmp_path("east.csv"), 1));
    CHECK_NEAR(mean, 0.5 * pi, 0.5 * pi * 0.022,
               "the wall facing +X (east) under the eastern half of the sky");
    /* Not exactly 0: back faces shadow lights a quarter pixel behind the lit faces, which
     * lets light through along contact edges, at most a row of pixels along each
     * (docs/library.md, lights): measured 1.0e-4 against the lit wall's 1.57. */
    CHECK_LE(csv_surface_red(tmp_path("east.csv"), 1), 1e-3 * 0.5 * pi,
             "the wall facing -X (west) under the eastern half");

    /* a lights file's "sky-hdr", its map named from the file's folder: the same bits */
    write_text(tmp_path("sky.json"),
               "{\"lights\": [{\"type\": \"sky-hdr\", \"file\": \"map.hdr\"}]}");
    RUN(&r, FIXED, LIT_ARGS, "--lights", tmp_path("sky.json"), "--dump-radiosity",
        tmp_path("file.csv"), "-o", tmp_path("file.png"), tmp_path("floor.obj"));
    expect_status(&r, 0);
    run_free(&r);
    expect_same_file(tmp_path("file.csv"), tmp_path("hdr.csv"));

    write_text(tmp_path("trunc.hdr"), "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 2\nabcdefgh");
    write_text(tmp_path("huge.hdr"),
               "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 32768 +X 32768\n\2\2\200\0");
    write_text(tmp_path("notmap.hdr"), "P6\n1 1\n255\nabc");
    for (k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        snprintf(path, sizeof path, "%s", bad[k].val[0] == ',' ? bad[k].val : tmp_path(bad[k].val));
        RUN(&r, FIXED, "--sky-hdr", path, "--dump-radiosity", tmp_path("bad.csv"), "-o",
            tmp_path("bad.png"), tmp_path("floor.obj"));
        expect_status(&r, 2);
        CHECK_CONTAINS(r.err, bad[k].says, "--sky-hdr %s", bad[k].val);
        if (bad[k].says[0] !=
            '-') /* a bad map: one line; a bad value: the usage follows, as for every option */
            CHECK_INT_EQ(count_lines(r.err), 1, "--sky-hdr %s: lines on stderr (%s)", bad[k].val,
                         r.err);
        CHECK_THAT(!file_exists(tmp_path("bad.png")) && !file_exists(tmp_path("bad.csv")),
                   "--sky-hdr %s: no output", bad[k].val);
        run_free(&r);
    }
    setenv("RAD_MEMORY_BUDGET", "10000", 1); /* the 64 x 32 map's floats take 24,576 bytes */
    RUN(&r, FIXED, "--sky-hdr", tmp_path("map.hdr"), "-o", tmp_path("bad.png"),
        tmp_path("floor.obj"));
    unsetenv("RAD_MEMORY_BUDGET");
    expect_status(&r, 2);
    CHECK_CONTAINS(r.err, "map.hdr: image too large for the memory budget",
                   "a map over the memory budget");
    run_free(&r);
    RUN(&r, FIXED, "--sky-hdr", tmp_path("map.hdr"), "--save-ff", tmp_path("x.ff"), "-o",
        tmp_path("ff.png"), tmp_path("floor.obj"));
    expect_status(&r, 0); /* a map's suns are lights: they work with stored rows */
    run_free(&r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cornell_box),
        cmocka_unit_test(test_orientation),
        cmocka_unit_test(test_ppm_matches_png),
        cmocka_unit_test(test_threads_same_result),
        cmocka_unit_test(test_multiple_cameras),
        cmocka_unit_test(test_dump_radiosity),
        cmocka_unit_test(test_export_ply),
        cmocka_unit_test(test_list_materials),
        cmocka_unit_test(test_emit_lights_dark_scene),
        cmocka_unit_test(test_usage_errors),
        cmocka_unit_test(test_usage_error_short),
        cmocka_unit_test(test_runtime_errors),
        cmocka_unit_test(test_unwritable_output),
        cmocka_unit_test(test_twin_agreement),
        cmocka_unit_test(test_stats_and_quiet),
        cmocka_unit_test(test_trailing_list_items),
        cmocka_unit_test(test_camera_looking_down),
        cmocka_unit_test(test_render_cracks),
        cmocka_unit_test(test_lights),
        cmocka_unit_test(test_sky),
        cmocka_unit_test(test_lights_file),
        cmocka_unit_test(test_sky_hdr),
    };
    return cmocka_run_group_tests_name("cli", tests, group_setup, group_teardown);
}
