/* SPDX-License-Identifier: MIT */
/* Tests for textures: tools/formats/texture.c (decoding, sRGB, sampling, means over a
 * UV triangle, hostile files) and the OBJ/MTL parts that feed it in tools/formats/obj.c
 * (vt, vn, o, g, map_Kd). Every image is generated here and written with img_write. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "check.h"
#include "formats/image.h"
#include "formats/obj.h"
#include "formats/texture.h"
#include "host/polys.h"
#include "host/tex_render.h"
#include "scenes.h"
#include "tmpdir.h"
#include "warnings.h"

TMPDIR_GROUP("texture")

/* ---- helpers ------------------------------------------------------------------- */

static void near_at(double a, double b, double eps, const char *expr, const char *file, int line)
{
    if (fabs(a - b) <= eps) return;
    print_error("%s = %.17g, expected %.17g (+-%g)\n", expr, a, b, eps);
    _fail(file, line);
}
#define assert_near(a, b, eps) near_at((a), (b), (eps), #a, __FILE__, __LINE__)

static void write_bytes(const char *path, const void *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(data, 1, n, f), n);
    assert_int_equal(fclose(f), 0);
}

static unsigned char *read_bytes(const char *path, size_t *n)
{
    FILE *f = fopen(path, "rb");
    unsigned char *d;
    long len;
    assert_non_null(f);
    assert_int_equal(fseek(f, 0, SEEK_END), 0);
    len = ftell(f);
    assert_true(len > 0);
    rewind(f);
    d = malloc((size_t)len);
    assert_non_null(d);
    assert_int_equal(fread(d, 1, (size_t)len, f), (size_t)len);
    fclose(f);
    *n = (size_t)len;
    return d;
}

/* The asymmetric test image: W x H, texel (x, y) = (10 + 40x, 20 + 60y, 7 + 11x + 29y),
   so a flip, a transpose or a channel swap changes some texel. */
#define AW 5
#define AH 3
static void asymmetric(unsigned char *rgb)
{
    int x, y;
    for (y = 0; y < AH; y++)
        for (x = 0; x < AW; x++) {
            unsigned char *p = rgb + 3 * (y * AW + x);
            p[0] = (unsigned char)(10 + 40 * x);
            p[1] = (unsigned char)(20 + 60 * y);
            p[2] = (unsigned char)(7 + 11 * x + 29 * y);
        }
}

/* An image of W x H whose texel bytes are given, written as PNG to NAME; loaded back. */
static void make_texture(const char *name, const unsigned char *rgb, int w, int h, tex_image *t)
{
    char err[512];
    assert_int_equal(img_write(tmp_path(name), rgb, w, h, err, sizeof err), 0);
    if (tex_load(tmp_path(name), t, err, sizeof err)) {
        print_error("%s\n", err);
        fail();
    }
}

/* The IEC 61966-2-1 decoding, written out here again (the reference). */
static double srgb_reference(double c)
{
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

static void expect_refused(const char *path, const char *what);

/* ---- tests: decoding ----------------------------------------------------------- */

static void assert_asymmetric(const tex_image *t)
{
    int x, y, k;
    unsigned char want[AW * AH * 3];
    asymmetric(want);
    assert_int_equal(t->w, AW);
    assert_int_equal(t->h, AH);
    for (y = 0; y < AH; y++)
        for (x = 0; x < AW; x++)
            for (k = 0; k < 3; k++)
                if (t->rgb[3 * (y * AW + x) + k] != want[3 * (y * AW + x) + k]) {
                    print_error("texel (%d, %d) channel %d: %d, expected %d\n", x, y, k,
                                t->rgb[3 * (y * AW + x) + k], want[3 * (y * AW + x) + k]);
                    fail();
                }
}

/* PNG, and a PNG named .jpg: decoded by content, texel for texel; PPM refused (not a
   format textures ship in: test_formats). */
static void test_decode_asymmetric(void **state)
{
    unsigned char rgb[AW * AH * 3];
    tex_image t;
    char err[512];
    size_t n;
    unsigned char *png;
    (void)state;
    asymmetric(rgb);
    make_texture("a.png", rgb, AW, AH, &t);
    assert_asymmetric(&t);
    assert_int_equal(t.clamp, 0);
    assert_near(t.scale[0], 1, 0);
    tex_free(&t);
    assert_null(t.rgb);
    tex_free(&t); /* idempotent */
    assert_int_equal(img_write(tmp_path("a.ppm"), rgb, AW, AH, NULL, 0), 0);
    expect_refused(tmp_path("a.ppm"), "not a PNG, JPEG, BMP or TGA image (format: PNM)");
    png = read_bytes(tmp_path("a.png"), &n);
    write_bytes(tmp_path("png_named.jpg"), png, n);
    free(png);
    assert_int_equal(tex_load(tmp_path("png_named.jpg"), &t, err, sizeof err), 0);
    assert_asymmetric(&t);
    tex_free(&t);
}

/* Every byte's linear value against the formula, and the formula's own fixed points. */
static void test_srgb_decode(void **state)
{
    unsigned char rgb[256 * 3];
    tex_image t;
    double worst = 0, lin[3];
    int i;
    (void)state;
    for (i = 0; i < 256; i++) rgb[3 * i] = rgb[3 * i + 1] = rgb[3 * i + 2] = (unsigned char)i;
    make_texture("ramp.png", rgb, 256, 1, &t);
    for (i = 0; i < 256; i++) {
        double want = srgb_reference(i / 255.0);
        tex_texel(&t, i, 0, lin);
        worst = fmax(worst, fabs(lin[0] - want));
        assert_near(lin[1], lin[0], 0);
        assert_near(tex_srgb_decode(i / 255.0), want, 1e-15);
    }
    print_message("sRGB table against the formula: worst %.3g\n", worst);
    assert_true(worst <= 1e-15); /* 17 printed digits round-trip a double */
    assert_near(tex_srgb_decode(0), 0, 0);
    assert_near(tex_srgb_decode(1), 1, 1e-15);
    assert_near(tex_srgb_decode(0.5), 0.21404114048223255, 1e-15); /* ((0.555/1.055)^2.4 */
    assert_near(tex_srgb_decode(-1), 0, 0);
    assert_near(tex_srgb_decode(2), 1, 1e-15);
    tex_free(&t);
}

/* ---- tests: sampling ----------------------------------------------------------- */

/* At a texel's centre the sample is the texel; half-way, the mean of two; across the
   u = 0 seam, the last column and the first; v = 1 is row 0 (the top). */
static void test_sample_bilinear(void **state)
{
    unsigned char rgb[AW * AH * 3];
    tex_image t;
    double s[3], a[3], b[3];
    int x, y, k;
    (void)state;
    asymmetric(rgb);
    make_texture("s.png", rgb, AW, AH, &t);
    for (y = 0; y < AH; y++)
        for (x = 0; x < AW; x++) {
            tex_sample(&t, (x + 0.5) / AW, 1 - (y + 0.5) / AH, s);
            tex_texel(&t, x, y, a);
            for (k = 0; k < 3; k++) assert_near(s[k], a[k], 1e-12);
        }
    tex_sample(&t, 2.0 / AW, 1 - 0.5 / AH, s); /* between columns 1 and 2 of row 0 */
    tex_texel(&t, 1, 0, a);
    tex_texel(&t, 2, 0, b);
    for (k = 0; k < 3; k++) assert_near(s[k], 0.5 * (a[k] + b[k]), 1e-12);
    tex_sample(&t, 0, 1 - 1.5 / AH, s); /* u = 0: half column 4, half column 0 (row 1) */
    tex_texel(&t, AW - 1, 1, a);
    tex_texel(&t, 0, 1, b);
    for (k = 0; k < 3; k++) assert_near(s[k], 0.5 * (a[k] + b[k]), 1e-12);
    tex_sample(&t, 3 + 0.5 / AW, -2 + 1 - 0.5 / AH, a); /* wrapped whole periods away */
    tex_texel(&t, 0, 0, b);
    for (k = 0; k < 3; k++) assert_near(a[k], b[k], 1e-12);
    t.clamp = 1; /* clamped: u = 0 is column 0 alone */
    tex_sample(&t, -5, 1 - 1.5 / AH, s);
    tex_texel(&t, 0, 1, b);
    for (k = 0; k < 3; k++) assert_near(s[k], b[k], 1e-12);
    t.clamp = 0;
    t.scale[0] = 2;                              /* -s 2: u = 0.25 reads u = 0.5 */
    t.offset[1] = 0.5;                           /* -o 0 0.5 */
    tex_sample(&t, 0.25, 1 - 0.5 / AH - 0.5, s); /* reads (0.5, 1 - 0.5 / AH): texel (2, 0) */
    tex_texel(&t, 2, 0, b);
    for (k = 0; k < 3; k++) assert_near(s[k], b[k], 1e-12);
    tex_free(&t);
}

/* The mean over the UV triangle (0,0) (1,0) (0,1) of a texture that varies along u only
   (one row, 8 columns of known linear values): its analytic value is the integral of
   f(u) 2 (1 - u) over [0, 1], f the wrapped linear interpolation between texel centres,
   worked out here by Simpson's rule on each linear piece (exact for these quadratics). */
static double piece_integral(double u0, double u1, double f0, double f1)
{
    double um = 0.5 * (u0 + u1), fm = 0.5 * (f0 + f1);
    return (u1 - u0) / 6 * (f0 * 2 * (1 - u0) + 4 * fm * 2 * (1 - um) + f1 * 2 * (1 - u1));
}

static void test_triangle_mean(void **state)
{
    static const unsigned char bytes[8] = {0, 255, 40, 200, 90, 10, 160, 120};
    const obj_vec2 tri[3] = {{0, 0}, {1, 0}, {0, 1}}, tri2[3] = {{1, 1}, {0, 1}, {1, 0}};
    unsigned char rgb[8 * 3];
    double f[8], want = 0, got[3], got2[3], texel_mean = 0, err1, err2;
    tex_image t;
    int i;
    (void)state;
    for (i = 0; i < 8; i++) {
        rgb[3 * i] = rgb[3 * i + 1] = rgb[3 * i + 2] = bytes[i];
        f[i] = srgb_reference(bytes[i] / 255.0);
        texel_mean += f[i] / 8;
    }
    make_texture("row.png", rgb, 8, 1, &t);
    /* Pieces: [0, 1/16] from the wrap (f7 to f0 across the seam), then centre to centre. */
    want += piece_integral(0, 1.0 / 16, 0.5 * (f[7] + f[0]), f[0]);
    for (i = 0; i < 7; i++) want += piece_integral((i + 0.5) / 8, (i + 1.5) / 8, f[i], f[i + 1]);
    want += piece_integral(15.0 / 16, 1, f[7], 0.5 * (f[7] + f[0]));
    tex_triangle_mean(&t, tri, got);
    err1 = fabs(got[0] - want);
    /* The other half of the unit square: both halves together are one period, whose
       mean is exactly the mean of the texels (each texel's tent integrates to 1 texel). */
    tex_triangle_mean(&t, tri2, got2);
    err2 = fabs(0.5 * (got[0] + got2[0]) - texel_mean);
    print_message("mean over the triangle %.6f (analytic %.6f, error %.2g); over the square "
                  "%.6f (texels %.6f, error %.2g)\n",
                  got[0], want, err1, 0.5 * (got[0] + got2[0]), texel_mean, err2);
    /* The midpoint rule is exact on linear pieces and errs at the kinks (texel centres)
       by O(1/n^2), n = 33 here (4 a texel on the 8.06-texel hypotenuse): measured 1.8e-4
       and 2.0e-4, and 6.9e-4 / 1.2e-5 at 2 / 16 a texel, as 1/n^2 predicts. The bound
       is 2.5 times the measurement, so losing the density or the order fails it. */
    assert_true(err1 <= 5e-4);
    assert_true(err2 <= 5e-4);
    assert_near(got[1], got[0], 0);
    tex_free(&t);
}

/* A uniform texture's mean is its colour, whatever the footprint (wraps, slivers). */
static void test_uniform_mean(void **state)
{
    unsigned char rgb[16 * 8 * 3];
    const obj_vec2 feet[3][3] = {{{0, 0}, {1, 0}, {0, 1}},
                                 {{-3.2, 7.1}, {40.5, 7.3}, {12, -19}},
                                 {{0.1, 0.1}, {0.1000001, 0.1}, {0.1, 0.1000001}}};
    double want[3], got[3];
    tex_image t;
    int i, k;
    (void)state;
    for (i = 0; i < 16 * 8; i++) {
        rgb[3 * i] = 200;
        rgb[3 * i + 1] = 100;
        rgb[3 * i + 2] = 30;
    }
    make_texture("uniform.png", rgb, 16, 8, &t);
    tex_texel(&t, 3, 5, want);
    for (i = 0; i < 3; i++) {
        tex_triangle_mean(&t, feet[i], got);
        for (k = 0; k < 3; k++)
            assert_near(got[k], want[k], 1e-12); /* sums of 4096 equal values: rounding */
    }
    tex_free(&t);
}

static void test_reflectance_rule(void **state)
{
    const double black[3] = {0, 0, 0}, kd[3] = {0.5, 1, 0.2}, white[3] = {1, 1, 1};
    const double texel[3] = {0.8, 0.4, 0.6};
    double rho[3];
    (void)state;
    tex_reflectance(black, texel, rho); /* Kd 0: the texture alone */
    assert_near(rho[0], 0.8, 0);
    assert_near(rho[1], 0.4, 0);
    assert_near(rho[2], 0.6, 0);
    tex_reflectance(kd, texel, rho); /* else the texture times Kd */
    assert_near(rho[0], 0.4, 1e-16);
    assert_near(rho[1], 0.4, 0);
    assert_near(rho[2], 0.12, 1e-16);
    tex_reflectance(white, white, rho); /* kept below 1 */
    assert_near(rho[0], TEX_RHO_MAX, 0);
    assert_true(rho[2] < 1);
}

/* ---- tests: hostile files ------------------------------------------------------ */

/* Each must fail with a one-line message naming the file and saying what: never crash,
   never hang, and leave *out empty. */
static void expect_refused(const char *path, const char *what)
{
    tex_image t;
    char err[512];
    int rc = tex_load(path, &t, err, sizeof err);
    print_message("%s\n", rc ? err : "(accepted)");
    assert_int_equal(rc, -1);
    assert_null(t.rgb);
    assert_int_equal(t.w, 0);
    assert_non_null(strstr(err, path));
    assert_non_null(strstr(err, what));
    assert_null(strchr(err, '\n'));
}

static void put_be32(unsigned char *p, unsigned v)
{
    p[0] = (unsigned char)(v >> 24);
    p[1] = (unsigned char)(v >> 16);
    p[2] = (unsigned char)(v >> 8);
    p[3] = (unsigned char)v;
}

static void test_hostile_images(void **state)
{
    unsigned char rgb[AW * AH * 3], *png;
    size_t n;
    (void)state;
    asymmetric(rgb);
    assert_int_equal(img_write(tmp_path("ok.png"), rgb, AW, AH, NULL, 0), 0);
    png = read_bytes(tmp_path("ok.png"), &n);
    /* A bomb: the IHDR declares 10000 x 10000 (bytes 16-23) in a file of ~100 bytes:
       1e8 texels, past TEX_MAX_PIXELS and within stb_image's own 2^30-byte limit, so
       ours refuses it; 100000 x 100000 stb_image refuses itself. */
    put_be32(png + 16, 10000);
    put_be32(png + 20, 10000);
    write_bytes(tmp_path("bomb.png"), png, n);
    expect_refused(tmp_path("bomb.png"), "declares 10000 x 10000 texels");
    put_be32(png + 16, 100000);
    put_be32(png + 20, 100000);
    write_bytes(tmp_path("bomb2.png"), png, n);
    expect_refused(tmp_path("bomb2.png"), "not an image");
    put_be32(png + 16, AW);
    put_be32(png + 20, AH);
    write_bytes(tmp_path("cut.png"), png, n / 2); /* the header whole, the pixels cut */
    expect_refused(tmp_path("cut.png"), "cannot decode");
    write_bytes(tmp_path("cut_header.png"), png, 12);
    expect_refused(tmp_path("cut_header.png"), "not an image");
    free(png);
    write_bytes(tmp_path("zero.png"), "", 0);
    expect_refused(tmp_path("zero.png"), "empty file");
    write_bytes(tmp_path("text.png"), "newmtl x\nKd 1 1 1\n", 18);
    expect_refused(tmp_path("text.png"), "not a PNG, JPEG, BMP or TGA image (format: unknown)");
    expect_refused(tmp_path("missing.png"), "No such file");
    expect_refused(tmpdir, "is a directory");
}

/* ---- tests: OBJ and MTL -------------------------------------------------------- */

static void write_text(const char *name, const char *text)
{
    write_bytes(tmp_path(name), text, strlen(text));
}

/* vt, vn and their indices (negative ones too), v//vn, and o / g names per face. */
static void test_obj_uv_groups(void **state)
{
    obj_scene sc;
    warnings w = {0};
    char err[512];
    const char *text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                       "vt 0 0\nvt 1 0\nvt 1 1 0.5\nvt 0.25\n"
                       "vn 0 0 1\nvn 0 0 2\n"
                       "o lamp\ng shade\n"
                       "f 1/1/1 2/2/2 3/3/1\n"
                       "f -4/-4 -3/-3 -1/-1\n"
                       "g\nf 1//2 3//1 4//2\n"
                       "o desk\ng top legs\nf 1 2 3 4\n"
                       "f 1/1 2/9 3/3\n";
    (void)state;
    assert_int_equal(
        obj_parse(text, strlen(text), "uv.obj", NULL, &sc, collect, &w, err, sizeof err), 0);
    assert_int_equal(sc.nuvs, 4);
    assert_near(sc.uvs[2].v, 1, 0);
    assert_near(sc.uvs[3].u, 0.25, 0);
    assert_near(sc.uvs[3].v, 0, 0); /* v defaults to 0 */
    assert_int_equal(sc.nnormals, 2);
    assert_near(sc.normals[1].z, 2, 0);
    assert_int_equal(sc.nfaces, 5);
    /* face 0: v/vt/vn */
    assert_int_equal(sc.uv_indices[0], 0);
    assert_int_equal(sc.uv_indices[2], 2);
    assert_int_equal(sc.normal_indices[1], 1);
    /* face 1: negative indices count back from the last vt */
    assert_int_equal(sc.indices[sc.faces[1].first], 0);
    assert_int_equal(sc.uv_indices[sc.faces[1].first], 0);
    assert_int_equal(sc.uv_indices[sc.faces[1].first + 2], 3);
    assert_int_equal(sc.normal_indices[sc.faces[1].first], -1);
    /* face 2: v//vn has no texture coordinates */
    assert_int_equal(sc.uv_indices[sc.faces[2].first], -1);
    assert_int_equal(sc.normal_indices[sc.faces[2].first], 1);
    /* face 4: vt 9 does not exist: warned, and the whole face has none */
    assert_int_equal(w.n, 1);
    assert_string_equal(w.msg[0], "uv.obj:20: texture coordinate index 9 out of range (4 "
                                  "defined so far): ignored");
    assert_int_equal(sc.uv_indices[sc.faces[4].first], -1);
    assert_int_equal(sc.uv_indices[sc.faces[4].first + 2], -1);
    /* names */
    assert_int_equal(sc.nnames, 4);
    assert_string_equal(sc.names[sc.faces[0].object], "lamp");
    assert_string_equal(sc.names[sc.faces[0].group], "shade");
    assert_int_equal(sc.faces[1].group, sc.faces[0].group);
    assert_int_equal(sc.faces[2].group, -1);
    assert_string_equal(sc.names[sc.faces[2].object], "lamp");
    assert_string_equal(sc.names[sc.faces[3].object], "desk");
    assert_string_equal(sc.names[sc.faces[3].group], "top legs");
    assert_int_equal(sc.unknown_statements, 0);
    obj_free(&sc);
}

/* map_Kd with options, a name with spaces, a path relative to the MTL's folder. */
static void test_mtl_map_kd(void **state)
{
    obj_scene sc;
    warnings w = {0};
    char err[512], want[400];
    unsigned char rgb[AW * AH * 3];
    tex_image maps[4];
    int i;
    (void)state;
    asymmetric(rgb);
    assert_int_equal(mkdir(tmp_path("mats"), 0700), 0);
    assert_int_equal(mkdir(tmp_path("mats/tex"), 0700), 0);
    assert_int_equal(img_write(tmp_path("mats/tex/my wood.png"), rgb, AW, AH, NULL, 0), 0);
    write_text("mats/m.mtl", "newmtl wood\nKd 0 0 0\n"
                             "map_Kd -s 2 3 -o 0.5 -blendu off -bm 0.3 -clamp on -mm 0 1 "
                             "-imfchan l tex/my wood.png\n"
                             "newmtl broken\nKd 0 0 0\nmap_Kd tex\\missing.png\n"
                             "newmtl bad_option\nKd 0 0 0\nmap_Kd -s\n"
                             "newmtl tinted\nKd 0.2 0.3 0.4\nmap_Kd -clamp maybe tex/x.png\n");
    write_text("scene.obj", "mtllib mats/m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                            "usemtl wood\nf 1 2 3\nusemtl broken\nf 1 2 3\n");
    assert_int_equal(obj_load(tmp_path("scene.obj"), &sc, collect, &w, err, sizeof err), 0);
    assert_int_equal(sc.nmaterials, 4);
    /* parse-time warnings: -s without values, -clamp maybe */
    for (i = 0; i < w.n && i < 4; i++) print_message("%s\n", w.msg[i]);
    assert_int_equal(w.n, 2);
    snprintf(want, sizeof want, "%s:9: map_Kd -s needs 1 value: statement ignored",
             tmp_path("mats/m.mtl"));
    assert_string_equal(w.msg[0], want);
    snprintf(want, sizeof want, "%s:12: map_Kd -clamp needs 1 value: statement ignored",
             tmp_path("mats/m.mtl"));
    assert_string_equal(w.msg[1], want);
    {
        const obj_map *m = &sc.materials[0].map_kd;
        snprintf(want, sizeof want, "%s", tmp_path("mats/tex/my wood.png"));
        assert_string_equal(m->path, want);
        assert_int_equal(m->line, 3);
        assert_near(m->scale[0], 2, 0);
        assert_near(m->scale[1], 3, 0);
        assert_near(m->offset[0], 0.5, 0);
        assert_near(m->offset[1], 0, 0);
        assert_int_equal(m->clamp, 1);
    }
    snprintf(want, sizeof want, "%s", tmp_path("mats/tex/missing.png"));
    assert_string_equal(sc.materials[1].map_kd.path, want); /* backslash read as a slash */
    assert_null(sc.materials[2].map_kd.path);
    assert_near(sc.materials[2].kd[0], OBJ_FALLBACK_KD, 0); /* a malformed map: grey */
    assert_near(sc.materials[3].kd[2], 0.4, 0);             /* keeps its Kd */
    /* Loading: the wood decodes; the missing file is one warning naming the MTL line and
       the file, and grey; decoded on 3 threads (two files), as on one. */
    w.n = 0;
    assert_int_equal(tex_load_materials(&sc, maps, collect, &w, 3), 1);
    assert_asymmetric(&maps[0]);
    assert_int_equal(maps[0].clamp, 1);
    assert_near(maps[0].scale[1], 3, 0);
    assert_null(maps[1].rgb);
    assert_int_equal(w.n, 1);
    snprintf(want, sizeof want,
             "%s:6: map_Kd: %s: cannot open: No such file or directory; using Kd 0.5 0.5 0.5",
             tmp_path("mats/m.mtl"), tmp_path("mats/tex/missing.png"));
    assert_string_equal(w.msg[0], want);
    assert_near(sc.materials[1].kd[1], OBJ_FALLBACK_KD, 0);
    tex_free(&maps[0]);
    obj_free(&sc);
}

/* ---- tests: reflectance of textured faces and the solution --------------------- */

/* A room (walls), a block in it and a lamp under the ceiling, every face with texture
   coordinates 0 0, 1 0, 1 1, 0 1 at its corners, written as NAME with mtllib MTL. */
static void write_room(const char *name, const char *mtl)
{
    static const char *const mats[3] = {"walls", "block", "lamp"};
    sc_poly p[13];
    char text[8192];
    size_t used;
    int n = box(p, -1, -1, -1, 1, 1, 1, 1), i, k, v = 0;
    n += box(p + n, -0.5, -1, -0.4, 0.1, -0.3, 0.3, 0);
    p[n++] = quad(-0.3, 0.98, -0.3, 0.3, 0.98, -0.3, 0.3, 0.98, 0.3, -0.3, 0.98, 0.3);
    used = (size_t)snprintf(text, sizeof text, "mtllib %s\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n", mtl);
    for (i = 0; i < n; i++) {
        used += (size_t)snprintf(text + used, sizeof text - used, "usemtl %s\n",
                                 mats[i < 6    ? 0
                                      : i < 12 ? 1
                                               : 2]);
        for (k = 0; k < 4; k++)
            used += (size_t)snprintf(text + used, sizeof text - used, "v %.17g %.17g %.17g\n",
                                     p[i].v[k][0], p[i].v[k][1], p[i].v[k][2]);
        used += (size_t)snprintf(text + used, sizeof text - used, "f %d/1 %d/2 %d/3 %d/4\n", v + 1,
                                 v + 2, v + 3, v + 4);
        v += 4;
    }
    assert_true(used < sizeof text);
    write_text(name, text);
}

typedef struct {
    obj_scene sc;
    tex_image maps[8];
    sc_poly *p;
    int n;
} textured;

static void load_textured(const char *name, textured *t)
{
    char err[512];
    assert_int_equal(obj_load(tmp_path(name), &t->sc, NULL, NULL, err, sizeof err), 0);
    assert_true(t->sc.nmaterials <= 8);
    tex_load_materials(&t->sc, t->maps, NULL, NULL, 1);
    t->p = polys_from_obj_tex(&t->sc, t->maps, &t->n, NULL, NULL);
    assert_non_null(t->p);
}

static void free_textured(textured *t)
{
    int i;
    for (i = 0; i < t->sc.nmaterials; i++) tex_free(&t->maps[i]);
    free(t->p);
    obj_free(&t->sc);
}

/* Largest relative difference, per element above 1% of the brightest, between two
   solutions of the same mesh (fixed build, or the float twin if FLOAT). */
static double solution_difference(const textured *a, const textured *b, int use_float)
{
    sc_opts o = {.max_element = 0.25, .res = 64};
    char err[512];
    double worst = 0, peak = 0, ra[3], rb[3];
    int e, k, ne, pass;
    sc_stats sa, sb;
    for (pass = 0; pass < 2; pass++) {
        void *x = use_float ? (void *)scf_create(a->p, a->n, &o, NULL, NULL, err, sizeof err)
                            : (void *)sc_create(a->p, a->n, &o, NULL, NULL, err, sizeof err);
        void *y = use_float ? (void *)scf_create(b->p, b->n, &o, NULL, NULL, err, sizeof err)
                            : (void *)sc_create(b->p, b->n, &o, NULL, NULL, err, sizeof err);
        assert_non_null(x);
        assert_non_null(y);
        /* A's elements each the mean of their own footprint, as rad_cli has them */
        assert_true((use_float ? scf_texture_elements(x, &a->sc, a->maps, err, sizeof err)
                               : sc_texture_elements(x, &a->sc, a->maps, err, sizeof err)) >= 0);
        if (use_float) {
            scf_solve(x, 100000, 1e-4, NULL, NULL);
            scf_solve(y, 100000, 1e-4, NULL, NULL);
            scf_get_stats(x, &sa);
            scf_get_stats(y, &sb);
        } else {
            sc_solve(x, 100000, 1e-4, NULL, NULL);
            sc_solve(y, 100000, 1e-4, NULL, NULL);
            sc_get_stats(x, &sa);
            sc_get_stats(y, &sb);
        }
        assert_int_equal(sa.elements, sb.elements);
        ne = sa.elements;
        for (e = 0; e < ne; e++) {
            if (use_float) {
                scf_element_rgb(x, e, 1, ra);
                scf_element_rgb(y, e, 1, rb);
            } else {
                sc_element_rgb(x, e, 1, ra);
                sc_element_rgb(y, e, 1, rb);
            }
            for (k = 0; k < 3; k++)
                if (pass == 0)
                    peak = fmax(peak, rb[k]);
                else if (rb[k] > 0.01 * peak)
                    worst = fmax(worst, fabs(ra[k] / rb[k] - 1));
        }
        if (use_float) {
            scf_destroy(x);
            scf_destroy(y);
        } else {
            sc_destroy(x);
            sc_destroy(y);
        }
    }
    return worst;
}

/* A uniformly coloured texture gives the solution of the same colour in Kd: walls by
   the texture alone (Kd 0), the block by texture times Kd. */
static void test_uniform_texture_solution(void **state)
{
    unsigned char walls[4 * 4 * 3], block[2 * 2 * 3];
    double lw[3], lb[3], kd_block[3] = {0.5, 0.8, 1.0}, rho[3];
    char mtl[1024];
    textured a, b;
    int i, k;
    (void)state;
    for (i = 0; i < 16; i++) {
        walls[3 * i] = 200;
        walls[3 * i + 1] = 150;
        walls[3 * i + 2] = 90;
    }
    for (i = 0; i < 4; i++) {
        block[3 * i] = 60;
        block[3 * i + 1] = 230;
        block[3 * i + 2] = 120;
    }
    assert_int_equal(img_write(tmp_path("walls.png"), walls, 4, 4, NULL, 0), 0);
    assert_int_equal(img_write(tmp_path("block.png"), block, 2, 2, NULL, 0), 0);
    write_text("tex.mtl", "newmtl walls\nKd 0 0 0\nmap_Kd walls.png\n"
                          "newmtl block\nKd 0.5 0.8 1\nmap_Kd block.png\n"
                          "newmtl lamp\nKd 0 0 0\nKe 10 10 10\n");
    for (k = 0; k < 3; k++) {
        lw[k] = srgb_reference(walls[k] / 255.0);
        lb[k] = srgb_reference(block[k] / 255.0) * kd_block[k];
    }
    snprintf(mtl, sizeof mtl,
             "newmtl walls\nKd %.17g %.17g %.17g\nnewmtl block\nKd %.17g %.17g "
             "%.17g\nnewmtl lamp\nKd 0 0 0\nKe 10 10 10\n",
             lw[0], lw[1], lw[2], lb[0], lb[1], lb[2]);
    write_text("kd.mtl", mtl);
    write_room("room_tex.obj", "tex.mtl");
    write_room("room_kd.obj", "kd.mtl");
    load_textured("room_tex.obj", &a);
    load_textured("room_kd.obj", &b);
    assert_int_equal(a.n, b.n);
    for (i = 0; i < a.n; i++)
        for (k = 0; k < 3; k++) {
            rho[k] = b.p[i].rho[k];
            assert_near(a.p[i].rho[k], rho[k], 1e-12); /* 4096 equal terms summed */
        }
    {
        double fixed = solution_difference(&a, &b, 0), flt = solution_difference(&a, &b, 1);
        print_message("uniform texture against Kd, per element: fixed %.3g%%, float %.3g%%\n",
                      100 * fixed, 100 * flt);
        assert_true(fixed <= 0.001); /* the goal: 0.1% */
        assert_true(flt <= 0.001);
    }
    free_textured(&a);
    free_textured(&b);
}

/* A face's reflectance is the mean of its footprint: half black, half white in linear
   light gives 0.5 (a period: exact but for the midpoint rule's 1/n^2 at the kinks);
   a face of the material without texture coordinates keeps Kd. */
static void test_face_reflectance(void **state)
{
    static const unsigned char bw[2 * 3] = {0, 0, 0, 255, 255, 255};
    textured t;
    int i;
    (void)state;
    assert_int_equal(img_write(tmp_path("bw.png"), bw, 2, 1, NULL, 0), 0);
    write_text("bw.mtl", "newmtl bw\nKd 0 0 0\nmap_Kd bw.png\n"
                         "newmtl tinted\nKd 0.2 0.4 0.6\nmap_Kd bw.png\n");
    write_text("bw.obj", "mtllib bw.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                         "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.25 0\nvt 0.75 1\n"
                         "usemtl bw\nf 1/1 2/2 3/3 4/4\nf 1 2 3\n"
                         "usemtl tinted\nf 1/1 2/2 3/3 4/4\n"
                         "usemtl bw\nf 1/5 2/5 3/6\n");
    load_textured("bw.obj", &t);
    assert_int_equal(t.n, 4);
    for (i = 0; i < 3; i++)
        print_message("face %d: rho %.9f %.9f %.9f\n", i, t.p[i].rho[0], t.p[i].rho[1],
                      t.p[i].rho[2]);
    /* Bound: the midpoint rule at 4 a texel (test_triangle_mean); here the two halves'
       samples mirror each other about u = 0.5, and 0.5 comes out to 1e-9. */
    assert_near(t.p[0].rho[0], 0.5, 2e-4);
    assert_near(t.p[0].rho[2], t.p[0].rho[0], 0);
    assert_near(t.p[1].rho[1], 0.5, 1e-15); /* no vt: the image's mean, 0.5 */
    assert_near(t.p[2].rho[1], 0.4 * t.p[0].rho[1], 1e-15);
    assert_true(t.p[3].rho[0] < t.p[0].rho[0]); /* u 0.25 to 0.75 leans on the black texel */
    free_textured(&t);
}

/* ---- tests: rendered views with the texture's detail --------------------------- */

typedef struct {
    textured t;
    sc_solver *s;
} solved;

static void solve_textured(const char *name, solved *x)
{
    sc_opts o = {.max_element = 0.25, .res = 64};
    char err[512];
    load_textured(name, &x->t);
    x->s = sc_create(x->t.p, x->t.n, &o, NULL, NULL, err, sizeof err);
    assert_non_null(x->s);
    sc_solve(x->s, 100000, 1e-4, NULL, NULL);
}

static void free_solved(solved *x)
{
    sc_destroy(x->s);
    free_textured(&x->t);
}

/* A room of white walls (Kd 0.7) whose floor (map "split": Kd 0 0 0) has u = (z + 1) / 2,
   and the lamp of write_room, as NAME. */
static void write_split_room(const char *name)
{
    sc_poly p[7];
    char text[4096];
    size_t used;
    int n = box(p, -1, -1, -1, 1, 1, 1, 1), i, k;
    p[n++] = quad(-0.3, 0.98, -0.3, 0.3, 0.98, -0.3, 0.3, 0.98, 0.3, -0.3, 0.98, 0.3);
    write_text("split.mtl", "newmtl split\nKd 0 0 0\nmap_Kd split.png\n"
                            "newmtl white\nKd 0.7 0.7 0.7\nnewmtl lamp\nKd 0 0 0\nKe 10 10 10\n");
    used =
        (size_t)snprintf(text, sizeof text, "mtllib split.mtl\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n");
    for (i = 0; i < n; i++) {
        used += (size_t)snprintf(text + used, sizeof text - used, "usemtl %s\n",
                                 i == 0  ? "split"
                                 : i < 6 ? "white"
                                         : "lamp");
        for (k = 0; k < 4; k++)
            used += (size_t)snprintf(text + used, sizeof text - used, "v %.17g %.17g %.17g\n",
                                     p[i].v[k][0], p[i].v[k][1], p[i].v[k][2]);
        used += (size_t)snprintf(text + used, sizeof text - used,
                                 i == 0 ? "f -4/1 -3/2 -2/3 -1/4\n" : "f -4 -3 -2 -1\n");
    }
    assert_true(used < sizeof text);
    write_text(name, text);
}

/* The area-weighted mean green over red of the elements of OBJ face F. */
static double face_green_over_red(sc_solver *s, int f)
{
    sc_stats st;
    double g = 0, r = 0, rgb[3];
    int e;
    sc_get_stats(s, &st);
    for (e = 0; e < st.elements; e++)
        if (sc_element_tag(s, e) == f) {
            sc_element_rgb(s, e, 1, rgb);
            r += sc_element_area(s, e) * rgb[0];
            g += sc_element_area(s, e) * rgb[1];
        }
    return g / r;
}

/* Reflectance per element: a floor half red, half white (a 64 x 4 map, columns 0..31
   red) under a lamp. Each floor element gets its own footprint's mean: 8 texel columns
   a 0.25 element; the bilinear map blends red and white only within half a texel of
   the halves' border and of the wrap at u = 0, which adds at most (white - red) / 4
   over 1/128 of u to an element 1/8 wide, (white - red) / 64, plus Q16.16's rounding.
   The wall beside the red half (z = -1) then gets more red than the one beside the
   white (z = +1): its green over red is lower. With the face's one mean (no call) the
   room is symmetric about z = 0 and the two walls agree to the solve's noise. */
static void test_element_reflectance(void **state)
{
    unsigned char map[64 * 4 * 3];
    const unsigned char red[3] = {230, 60, 50}, white[3] = {235, 235, 235};
    double lr[3], lw[3], worst = 0, ratio[2][2];
    char err[512];
    int i, k, e, pass, set = 0;
    (void)state;
    for (i = 0; i < 64 * 4; i++) memcpy(&map[3 * i], i % 64 < 32 ? red : white, 3);
    for (k = 0; k < 3; k++) {
        lr[k] = tex_srgb_decode(red[k] / 255.0);
        lw[k] = tex_srgb_decode(white[k] / 255.0);
    }
    assert_int_equal(img_write(tmp_path("split.png"), map, 64, 4, NULL, 0), 0);
    write_split_room("split.obj");
    for (pass = 0; pass < 2; pass++) {
        solved x;
        sc_opts o = {.max_element = 0.25, .res = 64};
        sc_stats st;
        load_textured("split.obj", &x.t);
        x.s = sc_create(x.t.p, x.t.n, &o, NULL, NULL, err, sizeof err);
        assert_non_null(x.s);
        if (pass == 1) {
            set = sc_texture_elements(x.s, &x.t.sc, x.t.maps, err, sizeof err);
            CHECK_INT_EQ(set, 64, "floor elements given their own reflectance (8 x 8)");
        }
        sc_solve(x.s, 100000, 1e-4, NULL, NULL);
        sc_get_stats(x.s, &st);
        for (e = 0; pass == 1 && e < st.elements; e++) {
            double c[3], rho[3];
            if (sc_element_tag(x.s, e) != 0) continue;
            sc_element_centroid(x.s, e, c);
            sc_element_rho(x.s, e, rho);
            for (k = 0; k < 3; k++) {
                double want = c[2] < 0 ? lr[k] : lw[k];
                worst = fmax(worst, fabs(rho[k] - want) / (fabs(lw[k] - lr[k]) / 64 + 1.0 / 65536));
            }
        }
        ratio[pass][0] = face_green_over_red(x.s, 4); /* z = -1: beside the red half */
        ratio[pass][1] = face_green_over_red(x.s, 5); /* z = +1: beside the white half */
        sc_destroy(x.s);
        free_textured(&x.t);
    }
    print_message(
        "per-element reflectance: floor elements off their half's colour by %.3f of the bound "
        "(|white - red| / 64 + 2^-16); wall green/red beside red %.4f, beside white %.4f (one mean "
        "a face: %.4f, %.4f)\n",
        worst, ratio[1][0], ratio[1][1], ratio[0][0], ratio[0][1]);
    CHECK_LE(worst, 1.0,
             "floor element reflectance off its half's colour, over |white - red| / 64 + 2^-16");
    /* symmetric: the two walls' shots differ by the order they come in only */
    CHECK_LE(fabs(ratio[0][0] / ratio[0][1] - 1), 0.005,
             "one mean a face: the walls' green/red disagree");
    CHECK_LE(ratio[1][0], 0.97 * ratio[1][1],
             "the wall beside the red half: green/red against the white side's");
}

#define RW 96
#define RH 96
static const sc_camera room_view = {{0, 0, 0.9}, {0, 0, -1}, {0, 1, 0}, 60};

/* The room of test_uniform_texture_solution (its files) seen with texture detail
   against the same colours in Kd seen plainly: per pixel, rho(texel) / rho(surface) is
   1 up to the surface's Q16.16 reflectance, 2^-17 / rho: the smallest reflectance here
   is the block's red, 0.5 x sRGB(60) = 0.0226, so 3.4e-4 (measured 2.3e-4). */
static void test_render_uniform(void **state)
{
    static float a[RW * RH * 3], b[RW * RH * 3];
    solved x, y;
    char err[512];
    double worst = 0, peak = 0;
    int i;
    (void)state;
    solve_textured("room_tex.obj", &x);
    solve_textured("room_kd.obj", &y);
    assert_int_equal(
        sc_render_textured(x.s, &x.t.sc, x.t.maps, &room_view, 1, RW, RH, a, err, sizeof err), 0);
    assert_int_equal(sc_render(y.s, &room_view, 1, RW, RH, b, err, sizeof err), 0);
    for (i = 0; i < RW * RH * 3; i++) peak = fmax(peak, b[i]);
    for (i = 0; i < RW * RH * 3; i++)
        if (b[i] > 0.01 * peak) worst = fmax(worst, fabs(a[i] / b[i] - 1));
    print_message("uniform texture rendered with detail against Kd: worst pixel %.3g\n", worst);
    assert_true(worst <= 1.0 / 131072 / (0.5 * srgb_reference(60 / 255.0)) + 1e-6);
    free_solved(&x);
    free_solved(&y);
}

/* The back wall (u along +x) textured black | white: the black texel's centre (u =
   0.25) renders dark and the white one's (u = 0.75) bright, in that order (a flip of u
   swaps them); without detail both are the wall's mean. */
static void test_render_detail(void **state)
{
    static const unsigned char bw[2 * 3] = {0, 0, 0, 255, 255, 255};
    static float a[RW * RH * 3], b[RW * RH * 3];
    solved x;
    char err[512];
    /* u = 0.25 and 0.75 on the wall z = -1, 1.9 away, seen at 60 degrees: x = -+0.5
       over a half-width of 1.9 tan 30 = 1.097. */
    int row = RH / 2, dark = (int)((1 - 0.5 / 1.097) / 2 * RW), bright = RW - 1 - dark;
    (void)state;
    assert_int_equal(img_write(tmp_path("bw2.png"), bw, 2, 1, NULL, 0), 0);
    write_text("bw2.mtl", "newmtl walls\nKd 0.6 0.6 0.6\nnewmtl back\nKd 0 0 0\nmap_Kd bw2.png\n"
                          "newmtl block\nKd 0.5 0.5 0.5\nnewmtl lamp\nKd 0 0 0\nKe 10 10 10\n");
    {
        /* room.obj of write_room, with the back wall (the box's -z face) in "back" */
        char text[8192];
        FILE *f;
        size_t n;
        write_room("bw2_base.obj", "bw2.mtl");
        f = fopen(tmp_path("bw2_base.obj"), "rb");
        assert_non_null(f);
        n = fread(text, 1, sizeof text - 1, f);
        fclose(f);
        text[n] = '\0';
        {
            char *m = strstr(text, "usemtl walls"), out[8300];
            int k;
            for (k = 0; k < 4 && m; k++) /* box(): face 4 is -z */
                m = strstr(m + 1, "usemtl walls");
            assert_non_null(m);
            snprintf(out, sizeof out, "%.*susemtl back %s", (int)(m - text), text, m + 12);
            write_text("bw2.obj", out);
        }
    }
    solve_textured("bw2.obj", &x);
    assert_int_equal(
        sc_render_textured(x.s, &x.t.sc, x.t.maps, &room_view, 1, RW, RH, a, err, sizeof err), 0);
    assert_int_equal(sc_render(x.s, &room_view, 1, RW, RH, b, err, sizeof err), 0);
    print_message("back wall: u = 0.25 %.4f, u = 0.75 %.4f (plain %.4f, %.4f)\n",
                  a[3 * (row * RW + dark)], a[3 * (row * RW + bright)], b[3 * (row * RW + dark)],
                  b[3 * (row * RW + bright)]);
    /* Texture detail: the dark texel's pixel reads within a pixel of u = 0.25, where the
       bilinear texture rises 2 a unit of u: a pixel is 1/44 of u here, so below 5% of the
       bright one. The bright one is about twice the plain mean (texel 1 over mean 0.5). */
    assert_true(a[3 * (row * RW + dark)] < 0.05 * a[3 * (row * RW + bright)]);
    assert_true(a[3 * (row * RW + bright)] > 1.8 * b[3 * (row * RW + bright)]);
    assert_true(fabs(b[3 * (row * RW + dark)] / b[3 * (row * RW + bright)] - 1) < 0.05);
    free_solved(&x);
}

/* ---- tests: large footprints and unusual maps --------------------------------------- */

/* Bricks of 16 x 8 texels (mortar white, each brick its own colour) in a 64 x 64 map. */
static void bricks(unsigned char *rgb)
{
    int x, y, k;
    for (y = 0; y < 64; y++)
        for (x = 0; x < 64; x++) {
            int row = y / 8, col = (x + (row % 2) * 8) / 16,
                mortar = y % 8 == 0 || (x + (row % 2) * 8) % 16 == 0;
            for (k = 0; k < 3; k++)
                rgb[3 * (64 * y + x) + k] =
                    (unsigned char)(mortar ? 250 : 30 + (37 * row + 53 * col + 71 * k) % 160);
        }
}

/* A footprint more than TEX_MEAN_MAX_DIV / 4 texels across is integrated along lines:
   the two halves of a square of whole periods (2 x 2, then 6 x 6 with -s 3 and -o 0.25)
   give the image's mean, since each line is exact across and the diagonal's share of
   one half is the other's; a sampling lattice of 64 a side beat with the bricks'
   period (a wall of this kind measured 36% dark). Clamped, a uniform map far past its
   edges is its colour. */
static void test_large_footprint_mean(void **state)
{
    static const obj_vec2 lo[3] = {{0, 0}, {2, 0}, {2, 2}}, hi[3] = {{0, 0}, {2, 2}, {0, 2}};
    static const obj_vec2 far[3] = {{-1, -1}, {3, -1}, {3, 3}};
    unsigned char rgb[64 * 64 * 3];
    tex_image t;
    double want[3], a[3], b[3], worst = 0;
    int pass, k;
    (void)state;
    bricks(rgb);
    make_texture("bricks.png", rgb, 64, 64, &t);
    tex_image_mean(&t, want);
    for (pass = 0; pass < 2; pass++) {
        if (pass) {
            t.scale[0] = t.scale[1] = 3;
            t.offset[0] = t.offset[1] = 0.25;
        }
        tex_triangle_mean(&t, lo, a);
        tex_triangle_mean(&t, hi, b);
        for (k = 0; k < 3; k++) worst = fmax(worst, fabs(0.5 * (a[k] + b[k]) - want[k]) / want[k]);
        print_message("bricks, %s: halves %.6f and %.6f, their mean against the image's %.6f\n",
                      pass ? "-s 3 -o 0.25" : "2 x 2 periods", a[0], b[0], want[0]);
    }
    CHECK_LE(worst, 1e-9,
             "two halves of whole periods against the image's mean, relative (rounding only: "
             "some 10^4 lines of sums below 10^3)");
    tex_free(&t);
    memset(rgb, 0, sizeof rgb);
    for (k = 0; k < 64 * 64; k++) {
        rgb[3 * k] = 200;
        rgb[3 * k + 1] = 90;
        rgb[3 * k + 2] = 10;
    }
    make_texture("flat.png", rgb, 64, 64, &t);
    t.clamp = 1;
    tex_triangle_mean(&t, far, a);
    tex_texel(&t, 0, 0, want);
    for (k = 0; k < 3; k++) assert_near(a[k], want[k], 1e-12);
    tex_free(&t);
}

/* The integral of a texel's tent (1 - |t|, centred at 0) over [a, b]. */
static double tent_integral(double a, double b)
{
    double lo = fmax(a, -1), hi = fmin(b, 1), s = 0;
    if (!(hi > lo)) return 0;
    if (lo < 0) /* the rising side: 1 + t */
        s += (fmin(hi, 0) - lo) * (1 + 0.5 * (fmin(hi, 0) + lo));
    if (hi > 0) /* the falling side: 1 - t */
        s += (hi - fmax(lo, 0)) * (1 - 0.5 * (hi + fmax(lo, 0)));
    return s;
}

/* A rectangle footprint along the texel axes is integrated exactly (mean_of_rect):
   against the bilinear texture's integral as a sum over texels of the colour times the
   tents' integrals in x and in y (separable; wrapped texel indices), to rounding
   (1e-12: a few thousand terms near 1); whole periods give the image's mean; the memo
   of shared edges changes no bit. */
static void test_rect_mean(void **state)
{
    static const double pos[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    const obj_vec2 rect[4] = {{0.13, 0.21}, {0.71, 0.21}, {0.71, 0.93}, {0.13, 0.93}};
    const obj_vec2 periods[4] = {{-1, 0}, {1, 0}, {1, 3}, {-1, 3}};
    unsigned char rgb[64 * 64 * 3];
    tex_image t;
    tex_memo *memo = malloc(sizeof *memo);
    double got[3], again[3], want[3] = {0, 0, 0}, mean[3], x0, x1, y0, y1, worst = 0;
    int i, j, k;
    (void)state;
    assert_non_null(memo);
    memo->image = NULL;
    bricks(rgb);
    make_texture("bricks_rect.png", rgb, 64, 64, &t);
    x0 = 0.13 * 64 - 0.5;
    x1 = 0.71 * 64 - 0.5;
    y0 = (1 - 0.93) * 64 - 0.5; /* v up, rows down */
    y1 = (1 - 0.21) * 64 - 0.5;
    for (j = (int)floor(y0) - 1; j <= (int)floor(y1) + 2; j++)
        for (i = (int)floor(x0) - 1; i <= (int)floor(x1) + 2; i++) {
            double w = tent_integral(x0 - i, x1 - i) * tent_integral(y0 - j, y1 - j), c[3];
            tex_texel(&t, (i % 64 + 64) % 64, (j % 64 + 64) % 64, c);
            for (k = 0; k < 3; k++) want[k] += w * c[k] / ((x1 - x0) * (y1 - y0));
        }
    tex_polygon_mean(&t, pos, rect, 4, NULL, got);
    tex_polygon_mean(&t, pos, rect, 4, memo, again);
    tex_polygon_mean(&t, pos, rect, 4, memo, again); /* from the memo */
    for (k = 0; k < 3; k++) worst = fmax(worst, fabs(got[k] - want[k]));
    print_message(
        "rectangle footprint: %.9f against the texels' tent sum %.9f (worst channel %.2g)\n",
        got[0], want[0], worst);
    CHECK_LE(worst, 1e-12, "rectangle footprint's mean against the separable tent sum");
    assert_memory_equal(got, again, sizeof got);
    tex_image_mean(&t, mean);
    tex_polygon_mean(&t, pos, periods, 4, memo, got);
    for (k = 0; k < 3; k++)
        CHECK_NEAR(got[k], mean[k], 1e-12,
                   "2 x 3 whole periods against the image's mean, channel %d", k);
    tex_free(&t);
    free(memo);
}

/* Writes a W x H PNG of COLOR_TYPE and DEPTH from ROWS (packed, big-endian 16-bit). */
static void write_png(const char *name, int w, int h, int color_type, int depth,
                      const unsigned char *rows, size_t stride)
{
    FILE *f = fopen(tmp_path(name), "wb");
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png_create_info_struct(png);
    int y;
    assert_true(f && png && info);
    if (setjmp(png_jmpbuf(png))) fail_msg("libpng could not write %s", name);
    png_init_io(png, f);
    png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, depth, color_type, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (y = 0; y < h; y++) png_write_row(png, (png_const_bytep)(rows + (size_t)y * stride));
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    assert_int_equal(fclose(f), 0);
}

static void expect_texel(const tex_image *t, int x, int y, const unsigned char want[3],
                         const char *what)
{
    double c[3];
    int k;
    tex_texel(t, x, y, c);
    for (k = 0; k < 3; k++)
        if (fabs(c[k] - tex_srgb_decode(want[k] / 255.0)) > 1e-15)
            fail_msg("%s texel (%d, %d) channel %d: %.17g, want byte %u (%.17g)", what, x, y, k,
                     c[k], want[k], tex_srgb_decode(want[k] / 255.0));
}

/* 16-bit RGB keeps each sample's high byte, grey + alpha its grey (alpha dropped); a
   1 x 1 map is its texel everywhere, over any footprint; UVs far out (1e29) and a
   footprint of 192,000 texel rows (past the lines' limit) take the sampler and give
   values inside the texels' range. */
static void test_unusual_maps(void **state)
{
    static const unsigned char rgb16[2 * 6] = {0x12, 0x34, 0xab, 0xcd, 0x00, 0xff,
                                               0xff, 0x01, 0x80, 0x00, 0x7f, 0xff};
    static const unsigned char ga[2 * 2] = {0x40, 0x00, 0xc8, 0xff};
    static const unsigned char want16[2][3] = {{0x12, 0xab, 0x00}, {0xff, 0x80, 0x7f}};
    static const unsigned char wantga[2][3] = {{0x40, 0x40, 0x40}, {0xc8, 0xc8, 0xc8}};
    static const obj_vec2 wide[3] = {{0, 0}, {50, 0}, {0, 50}},
                          huge[3] = {{0, 0}, {1e29, 0}, {0, 1e29}};
    static const obj_vec2 tall[3] = {{0, 0}, {1, 0}, {0, 3000}};
    unsigned char one[3] = {10, 200, 90}, rgb[64 * 64 * 3];
    tex_image t;
    char err[512];
    double c[3], lo[3] = {1, 1, 1}, hi[3] = {0, 0, 0};
    int x, y, k, i;
    (void)state;
    write_png("rgb16.png", 2, 1, PNG_COLOR_TYPE_RGB, 16, rgb16, sizeof rgb16);
    assert_int_equal(tex_load(tmp_path("rgb16.png"), &t, err, sizeof err), 0);
    for (x = 0; x < 2; x++) expect_texel(&t, x, 0, want16[x], "16-bit RGB");
    tex_free(&t);
    write_png("ga.png", 1, 2, PNG_COLOR_TYPE_GRAY_ALPHA, 8, ga, 2);
    assert_int_equal(tex_load(tmp_path("ga.png"), &t, err, sizeof err), 0);
    for (y = 0; y < 2; y++) expect_texel(&t, 0, y, wantga[y], "grey + alpha");
    tex_free(&t);

    make_texture("one.png", one, 1, 1, &t);
    tex_sample(&t, 0.3, -7.9, c);
    for (k = 0; k < 3; k++) assert_near(c[k], tex_srgb_decode(one[k] / 255.0), 1e-15);
    tex_triangle_mean(&t, wide, c);
    for (k = 0; k < 3; k++) assert_near(c[k], tex_srgb_decode(one[k] / 255.0), 1e-12);
    tex_free(&t);

    bricks(rgb);
    make_texture("bricks2.png", rgb, 64, 64, &t);
    for (y = 0; y < 64; y++)
        for (x = 0; x < 64; x++) {
            tex_texel(&t, x, y, c);
            for (k = 0; k < 3; k++) {
                lo[k] = fmin(lo[k], c[k]);
                hi[k] = fmax(hi[k], c[k]);
            }
        }
    for (i = 0; i < 2; i++) {
        tex_triangle_mean(&t, i ? tall : huge, c);
        for (k = 0; k < 3; k++)
            if (!(c[k] >= lo[k] && c[k] <= hi[k]))
                fail_msg("%s footprint: channel %d = %g, outside the texels' %g .. %g",
                         i ? "tall" : "far", k, c[k], lo[k], hi[k]);
    }
    tex_free(&t);
}

/* ---- tests: tiling and degenerate footprints never fail -------------------------------- */

/* A 64 x 64 map black for x < 32, a warm grey beyond: wide black areas, and the wrap's
   seam at u = 0 runs from grey to black. */
static void half_black(tex_image *t)
{
    unsigned char rgb[64 * 64 * 3];
    int i;
    for (i = 0; i < 64 * 64; i++) {
        rgb[3 * i] = (unsigned char)(i % 64 < 32 ? 0 : 200);
        rgb[3 * i + 1] = (unsigned char)(i % 64 < 32 ? 0 : 180);
        rgb[3 * i + 2] = (unsigned char)(i % 64 < 32 ? 0 : 150);
    }
    make_texture("half_black.png", rgb, 64, 64, t);
}

/* Each channel of a mean inside [0, 1]: a convex combination of texels. */
static void expect_mean_in_range(const double c[3], const char *what, int i)
{
    int k;
    for (k = 0; k < 3; k++)
        if (!(c[k] >= 0 && c[k] <= 1))
            fail_msg("%s %d: channel %d = %.17g, outside [0, 1]", what, i, k, c[k]);
}

/* A floor tiled as DCC tools export it (u, v from -2.6 to 3.6) cut in 24 x 24 elements,
   as quads and as triangle pairs (16.5 texels across: past 16, the lines' path), against
   each element's footprint moved by whole periods into the 0..1 layout, and against it
   moved 10^6 periods. The same texels in the same order, so only the coordinates'
   rounding differs: u - floor(u) to 2^-52 at the 0..1 layout's 1 (x 64 texels, x the
   bilinear texture's steepest slope, 1 a texel: 1.4e-14) plus the row sums' rounding
   (some 10^3 terms below 1: 1e-13): bound 1e-12. At 10^6 periods u is known to
   2^-33 (1.2e-10, 7.5e-9 texel): bound 1e-7. Today's row sums went below 0 over the
   black columns across the seam, which the core refuses ("reflectance must be finite
   and >= 0"). */
static void test_tiled_floor(void **state)
{
    static const double pos[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    tex_image t;
    double worst = 0, worst_far = 0;
    int i, j, k, tri, n = 0;
    (void)state;
    half_black(&t);
    for (j = 0; j < 24; j++)
        for (i = 0; i < 24; i++)
            for (tri = 0; tri < 3; tri++) {
                double u0 = -2.6 + 6.2 * i / 24, u1 = -2.6 + 6.2 * (i + 1) / 24;
                double v0 = -2.6 + 6.2 * j / 24, v1 = -2.6 + 6.2 * (j + 1) / 24, a[3], b[3], c[3];
                double su = floor(u0), sv = floor(v0);
                obj_vec2 uv[4] = {{u0, v0}, {u1, v0}, {u1, v1}, {u0, v1}}, one[4], far[4];
                const obj_vec2 *feet[3] = {uv, one, far};
                int nc = tri ? 3 : 4, f;
                if (tri == 2) { /* the other half of the cell */
                    uv[1] = uv[2];
                    uv[2] = uv[3];
                }
                for (k = 0; k < 4; k++) {
                    one[k].u = uv[k].u - su;
                    one[k].v = uv[k].v - sv;
                    far[k].u = one[k].u + 1e6;
                    far[k].v = one[k].v - 1e6;
                }
                for (f = 0; f < 3; f++)
                    tex_polygon_mean(&t, pos, feet[f], nc, NULL, f == 0 ? a : f == 1 ? b : c);
                expect_mean_in_range(a, "tiled element", n);
                expect_mean_in_range(c, "element 10^6 periods off", n);
                for (k = 0; k < 3; k++) {
                    worst = fmax(worst, fabs(a[k] - b[k]));
                    worst_far = fmax(worst_far, fabs(c[k] - b[k]));
                }
                n++;
            }
    print_message(
        "tiled floor, %d elements: off the 0..1 layout by %.3g at most, 10^6 periods off by %.3g\n",
        n, worst, worst_far);
    CHECK_LE(worst, 1e-12, "tiled element against its 0..1 footprint");
    CHECK_LE(worst_far, 1e-7, "element 10^6 periods off against its 0..1 footprint");
    tex_free(&t);
}

/* Footprints of no area: two equal vt (a real level's door), three equal, three on a
   line, each short and long (300 texels along v: past the lines' threshold), as
   triangles and in quads: the mean of the texture along the segment, inside the
   texels' range; a point gives the texel sample there. A triangle 0.01 texel wide and
   17 .. 4,000 texels tall over the black half (across the seam and not) is black: 0
   to rounding, never below. Today the lines divided rounding by rounding (-0.58, 4.4). */
static void test_degenerate_footprints(void **state)
{
    static const double pos[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    tex_image t;
    double c[3], s[3], worst_tall = 0;
    int i, k;
    (void)state;
    half_black(&t);
    for (i = 0; i < 400; i++) {
        double u = -3 + 0.0173 * i, v = 2 - 0.031 * i, len = i % 2 ? 300.0 / 64 : 0.05;
        obj_vec2 two[4] = {{u, v}, {u, v}, {u + 0.01 * i / 400, v + len}, {u, v + len}};
        obj_vec2 line3[3] = {{u, v}, {u + 0.1, v + len}, {u + 0.2, v + 2 * len}};
        obj_vec2 point[3] = {{u, v}, {u, v}, {u, v}};
        tex_triangle_mean(&t, two, c);
        expect_mean_in_range(c, "two equal vt", i);
        tex_polygon_mean(&t, pos, two, 4, NULL, c);
        expect_mean_in_range(c, "quad with two equal vt", i);
        tex_triangle_mean(&t, line3, c);
        expect_mean_in_range(c, "vt on a line", i);
        tex_triangle_mean(&t, point, c);
        tex_sample(&t, u, v, s);
        for (k = 0; k < 3; k++)
            CHECK_NEAR(c[k], s[k], 0, "three equal vt against the sample there, footprint %d", i);
    }
    for (i = 0; i < 200; i++) { /* black columns: x 0 .. 31 wrap to the seam at u = 0 */
        double x = 1.5 + 0.13 * i, h = 17 + 20 * i, v = -1 + 0.37 * i;
        obj_vec2 tall[3] = {{x / 64, v}, {(x + 0.01) / 64, v}, {(x + 0.01) / 64, v + h / 64}};
        obj_vec2 seam[3] = {{-0.5 / 64, v}, {0.5 / 64, v}, {0.5 / 64, v + h / 64}};
        tex_triangle_mean(&t, tall, c);
        expect_mean_in_range(c, "tall black triangle", i);
        for (k = 0; k < 3; k++) worst_tall = fmax(worst_tall, c[k]);
        tex_triangle_mean(&t, seam, c);
        expect_mean_in_range(c, "tall triangle on the seam", i);
    }
    print_message("tall black triangles: mean at most %.3g\n", worst_tall);
    CHECK_LE(worst_tall, 1e-12, "tall triangle over black texels (rounding of sums below 4,000)");
    tex_free(&t);
}

/* The user's room: a floor of two triangles tiled from -2.6 to 3.6 over the half-black
   map, elements of 0.3 (the scene 4 wide): every element gets a reflectance (today the
   call failed with "element N: reflectance must be finite and >= 0"), the black half's
   within 2^-16 of 0. */
static void test_tiled_room(void **state)
{
    sc_opts o = {.max_element = 0.3, .res = 64};
    tex_image t;
    textured x;
    sc_solver *s;
    sc_stats st;
    char err[512];
    int set, e, k;
    (void)state;
    half_black(&t);
    tex_free(&t);
    write_text("tiled.mtl",
               "newmtl floor\nKd 0 0 0\nmap_Kd half_black.png\nnewmtl wall\nKd 0.6 0.6 0.6\n"
               "newmtl light\nKd 0 0 0\nKe 5 5 5\n");
    write_text("tiled.obj",
               "mtllib tiled.mtl\nv 0 0 0\nv 4 0 0\nv 4 0 4\nv 0 0 4\nv 0 3 0\nv 4 3 0\n"
               "v 4 3 4\nv 0 3 4\nv 1.5 2.99 1.5\nv 2.5 2.99 1.5\nv 2.5 2.99 2.5\nv 1.5 2.99 2.5\n"
               "vt -2.6 -2.6\nvt 3.6 -2.6\nvt 3.6 3.6\nvt -2.6 3.6\nusemtl floor\n"
               "f 1/1 4/4 3/3\nf 1/1 3/3 2/2\nusemtl wall\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\n"
               "f 3 4 8 7\nf 4 1 5 8\nusemtl light\nf 9 10 11 12\n");
    load_textured("tiled.obj", &x);
    s = sc_create(x.p, x.n, &o, NULL, NULL, err, sizeof err);
    assert_non_null(s);
    set = sc_texture_elements(s, &x.sc, x.maps, err, sizeof err);
    if (set < 0) fail_msg("sc_texture_elements: %s", err);
    sc_get_stats(s, &st);
    print_message("tiled room: %d floor elements given their footprint's reflectance\n", set);
    CHECK_INT_GT(set, 100, "floor elements with their own reflectance");
    for (e = 0; e < st.elements; e++) {
        double rho[3];
        sc_element_rho(s, e, rho);
        expect_mean_in_range(rho, "element reflectance", e);
        for (k = 0; k < 3; k++) CHECK_LE(rho[k], TEX_RHO_MAX, "element %d reflectance", e);
    }
    sc_destroy(s);
    free_textured(&x);
}

/* ---- tests: the formats accepted ------------------------------------------------------- */

/* 4 x 3 texels, texel (x, y) (row 0 at the top) = (50 x + 20, 70 y + 10, 200 - 30 x). */
static void texel_bytes(int x, int y, unsigned char c[3])
{
    c[0] = (unsigned char)(50 * x + 20);
    c[1] = (unsigned char)(70 * y + 10);
    c[2] = (unsigned char)(200 - 30 * x);
}

static void expect_accepted(const char *name, const unsigned char *d, size_t n)
{
    tex_image t;
    char err[512];
    int x, y;
    write_bytes(tmp_path(name), d, n);
    if (tex_load(tmp_path(name), &t, err, sizeof err)) fail_msg("%s refused: %s", name, err);
    assert_int_equal(t.w, 4);
    assert_int_equal(t.h, 3);
    for (y = 0; y < 3; y++)
        for (x = 0; x < 4; x++) {
            unsigned char c[3];
            texel_bytes(x, y, c);
            expect_texel(&t, x, y, c, name);
        }
    tex_free(&t);
}

static void expect_refused_bytes(const char *name, const void *d, size_t n, const char *what)
{
    write_bytes(tmp_path(name), d, n);
    expect_refused(tmp_path(name), what);
}

/* Only PNG, JPEG, BMP and TGA reach stb_image, recognised by their bytes; a BMP or TGA
   (plain and RLE) must hold the pixels its header declares, a JPEG reach its end
   marker. Today a 16-bit PGM crashed stb_image 2.27, a truncated HDR hung it, and a
   header-only BMP or cut TGA came out black with no warning. */
static void test_formats(void **state)
{
    static const char pgm16[] = "P5\n2 1\n65535\n\x12\x34\x56\x78";
    static const char hdr[] = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8 +X 8\n\x02\x02\x00";
    static const char gif[] = "GIF89a\x04\x00\x03\x00\x80\x00\x00";
    static const char psd[] = "8BPS\x00\x01\x00\x00\x00\x00\x00\x00\x00\x03";
    unsigned char bmp[54 + 3 * 16], tga[18 + 36], rle[18 + 3 * 4 * 4], jpg[160];
    size_t nr = 18, nj = 0;
    int x, y, k;
    tex_image t;
    char err[512];
    (void)state;
    expect_refused_bytes("deep.pgm", pgm16, sizeof pgm16 - 1,
                         "not a PNG, JPEG, BMP or TGA image (format: PNM)");
    expect_refused_bytes("cut.hdr", hdr, sizeof hdr - 1, "(format: Radiance HDR)");
    expect_refused_bytes("a.gif", gif, sizeof gif - 1, "(format: GIF)");
    expect_refused_bytes("a.psd", psd, sizeof psd - 1, "(format: PSD)");

    /* BMP: 24 bits, bottom-up rows of 12 bytes (4-byte aligned already), BGR */
    memset(bmp, 0, sizeof bmp);
    bmp[0] = 'B', bmp[1] = 'M', bmp[2] = (unsigned char)sizeof bmp, bmp[10] = 54, bmp[14] = 40;
    bmp[18] = 4, bmp[22] = 3, bmp[26] = 1, bmp[28] = 24;
    for (y = 0; y < 3; y++)
        for (x = 0; x < 4; x++) {
            unsigned char c[3], *p = bmp + 54 + 12 * (2 - y) + 3 * x;
            texel_bytes(x, y, c);
            p[0] = c[2], p[1] = c[1], p[2] = c[0];
        }
    expect_accepted("ok.bmp", bmp, 54 + 36);
    expect_refused_bytes("header_only.bmp", bmp, 54,
                         "truncated: its header implies 90 bytes, the file holds 54");
    expect_refused_bytes("cut.bmp", bmp, 80,
                         "truncated: its header implies 90 bytes, the file holds 80");

    /* TGA type 2: 24 bits, bottom-up (descriptor 0), BGR */
    memset(tga, 0, sizeof tga);
    tga[2] = 2, tga[12] = 4, tga[14] = 3, tga[16] = 24;
    memcpy(rle, tga, 18);
    rle[2] = 10;
    for (y = 0; y < 3; y++) {
        for (x = 0; x < 4; x++) {
            unsigned char c[3], *p = tga + 18 + 12 * (2 - y) + 3 * x;
            texel_bytes(x, y, c);
            p[0] = c[2], p[1] = c[1], p[2] = c[0];
        }
    }
    for (y = 0; y < 3; y++) { /* RLE: a raw packet of 4 a file row (texels all differ) */
        rle[nr++] = 3;
        memcpy(rle + nr, tga + 18 + 12 * y, 12);
        nr += 12;
    }
    expect_accepted("ok.tga", tga, sizeof tga);
    expect_accepted("ok_rle.tga", rle, nr);
    expect_refused_bytes("header_only.tga", tga, 18,
                         "truncated: its header implies 54 bytes, the file holds 18");
    expect_refused_bytes("cut.tga", tga, 40, "truncated");
    expect_refused_bytes("cut_rle.tga", rle, nr - 5, "truncated");
    tga[1] = 1; /* a colour map type without a map: not a TGA this strict reading takes */
    expect_refused_bytes("odd.tga", tga, sizeof tga, "(format: unknown)");

    /* JPEG: 8 x 8 grey, baseline, one DC category-7 code of 80 (quantiser 1: grey 138) */
    {
        static const unsigned char head[] = {0xff, 0xd8, 0xff, 0xdb, 0x00, 0x43, 0x00};
        static const unsigned char tail[] = {
            0xff, 0xc0, 0x00, 0x0b, 0x08, 0x00, 0x08, 0x00, 0x08, 0x01, 0x01, 0x11,
            0x00, 0xff, 0xc4, 0x00, 0x14, 0x00, 0x01, 0,    0,    0,    0,    0,
            0,    0,    0,    0,    0,    0,    0,    0,    0,    0,    0x07, 0xff,
            0xc4, 0x00, 0x14, 0x10, 0x01, 0,    0,    0,    0,    0,    0,    0,
            0,    0,    0,    0,    0,    0,    0,    0,    0x00, 0xff, 0xda, 0x00,
            0x08, 0x01, 0x01, 0x00, 0x00, 0x3f, 0x00, 0x50, 0x7f, 0xff, 0xd9};
        memcpy(jpg, head, sizeof head);
        memset(jpg + sizeof head, 1, 64);
        memcpy(jpg + sizeof head + 64, tail, sizeof tail);
        nj = sizeof head + 64 + sizeof tail;
    }
    write_bytes(tmp_path("grey.jpg"), jpg, nj);
    if (tex_load(tmp_path("grey.jpg"), &t, err, sizeof err)) fail_msg("grey.jpg refused: %s", err);
    assert_int_equal(t.w, 8);
    for (k = 0; k < 3; k++) CHECK_INT_EQ(t.rgb[k], 138, "JPEG grey texel, channel %d", k);
    tex_free(&t);
    expect_refused_bytes("cut.jpg", jpg, nj - 4, "truncated: no end-of-image marker");
}

/* ---- tests: one decode a file, one budget a scene, names ignoring case --------------- */

/* Loads the scene NAME (a triangle a material) and its maps into MAPS, warnings into W. */
static void load_maps(const char *name, obj_scene *sc, tex_image *maps, int nmax, warnings *w)
{
    char err[512];
    assert_int_equal(obj_load(tmp_path(name), sc, NULL, NULL, err, sizeof err), 0);
    assert_true(sc->nmaterials <= nmax);
    tex_load_materials(sc, maps, collect, w, 2);
}

static void free_maps(obj_scene *sc, tex_image *maps)
{
    int i;
    for (i = 0; i < sc->nmaterials; i++) tex_free(&maps[i]);
    obj_free(sc);
}

/* One file named four ways (a.png, ./a.png, sub/../a.png, a symbolic link to it) is
   decoded once: the four maps share one pixels pointer (today: four decodes, four
   copies: a 423 KB PNG of 4 x 2^24 texels took 1 GB a spelling). That PNG is now
   refused before decoding, by its side; and a scene's maps past TEX_BUDGET are refused
   unread: four PNGs each declaring 16384 x 4096 texels in 100 bytes (288 MiB decoded:
   192 of texels, 96 of row sums): the first three are charged (and fail to decode:
   their pixels are missing), the fourth is over the budget. */
static void test_map_identity_and_budget(void **state)
{
    static const char *const names[4] = {"a.png", "./a.png", "sub/../a.png", "link.png"};
    unsigned char rgb[AW * AH * 3], *png;
    char text[1024];
    size_t used = 0, n;
    obj_scene sc;
    tex_image maps[4];
    warnings w = {0};
    int i;
    (void)state;
    asymmetric(rgb);
    assert_int_equal(mkdir(tmp_path("ids"), 0700), 0);
    assert_int_equal(mkdir(tmp_path("ids/sub"), 0700), 0);
    assert_int_equal(img_write(tmp_path("ids/a.png"), rgb, AW, AH, NULL, 0), 0);
    assert_int_equal(symlink("a.png", tmp_path("ids/link.png")), 0);
    for (i = 0; i < 4; i++)
        used += (size_t)snprintf(text + used, sizeof text - used,
                                 "newmtl m%d\nKd 0 0 0\nmap_Kd %s\n", i, names[i]);
    write_text("ids/m.mtl", text);
    write_text("ids/s.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\n"
                            "usemtl m0\nf 1/1 2/1 3/1\nusemtl m1\nf 1/1 2/1 3/1\n"
                            "usemtl m2\nf 1/1 2/1 3/1\nusemtl m3\nf 1/1 2/1 3/1\n");
    load_maps("ids/s.obj", &sc, maps, 4, &w);
    CHECK_INT_EQ(w.n, 0, "warnings loading one file named four ways");
    for (i = 1; i < 4; i++) {
        CHECK_THAT(maps[i].rgb == maps[0].rgb, "%s shares a.png's decoded pixels", names[i]);
        CHECK_INT_EQ(maps[i].borrowed, 1, "%s borrowed", names[i]);
    }
    assert_asymmetric(&maps[3]);
    free_maps(&sc, maps);

    png = read_bytes(tmp_path("ids/a.png"), &n);
    put_be32(png + 16, 4);
    put_be32(png + 20, 1u << 24);
    write_bytes(tmp_path("ids/tall.png"), png, n);
    expect_refused(tmp_path("ids/tall.png"),
                   "declares 4 x 16777216 texels, beyond the limits of 16384 a side");
    put_be32(png + 16, 16384);
    put_be32(png + 20, 4096);
    used = 0;
    for (i = 0; i < 4; i++) {
        char name[64];
        snprintf(name, sizeof name, "ids/big%d.png", i);
        png[30] = (unsigned char)i; /* distinct files (the IHDR's CRC, which stb ignores) */
        write_bytes(tmp_path(name), png, n);
        used += (size_t)snprintf(text + used, sizeof text - used,
                                 "newmtl b%d\nKd 0.1 0.2 0.3\nmap_Kd big%d.png\n", i, i);
    }
    free(png);
    write_text("ids/big.mtl", text);
    write_text("ids/big.obj", "mtllib big.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\n"
                              "usemtl b0\nf 1/1 2/1 3/1\nusemtl b1\nf 1/1 2/1 3/1\n"
                              "usemtl b2\nf 1/1 2/1 3/1\nusemtl b3\nf 1/1 2/1 3/1\n");
    memset(&w, 0, sizeof w);
    load_maps("ids/big.obj", &sc, maps, 4, &w);
    for (i = 0; i < w.n && i < 4; i++) print_message("%s\n", w.msg[i]);
    CHECK_INT_EQ(w.n, 4, "warnings for four maps that cannot be used");
    for (i = 0; i < 3; i++)
        CHECK_CONTAINS(w.msg[i], "cannot decode", "map %d, within the budget", i);
    CHECK_CONTAINS(
        w.msg[3],
        "16384 x 4096 texels need 288 MiB, over what is left of the scene's texture budget",
        "the fourth map");
    CHECK_CONTAINS(w.msg[3], "; using Kd 0.1 0.2 0.3", "the fourth map's fallback");
    for (i = 0; i < 4; i++) assert_null(maps[i].rgb);
    free_maps(&sc, maps);
}

/* map_Kd names Wood.PNG, the folder holds wood.png: that file is used, with one warning
   saying so (Windows exports on a case-sensitive file system; today: missing, Kd). A
   name matching nothing still falls back. */
static void test_map_case(void **state)
{
    unsigned char rgb[AW * AH * 3];
    char want[1024];
    obj_scene sc;
    tex_image maps[2];
    warnings w = {0};
    int n;
    (void)state;
    asymmetric(rgb);
    assert_int_equal(mkdir(tmp_path("case"), 0700), 0);
    assert_int_equal(mkdir(tmp_path("case/tex"), 0700), 0);
    assert_int_equal(img_write(tmp_path("case/tex/wood.png"), rgb, AW, AH, NULL, 0), 0);
    write_text(
        "case/m.mtl",
        "newmtl wood\nKd 0 0 0\nmap_Kd tex/Wood.PNG\nnewmtl none\nKd 0 0 0\nmap_Kd tex/Oak.png\n");
    write_text("case/s.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\n"
                             "usemtl wood\nf 1/1 2/1 3/1\nusemtl none\nf 1/1 2/1 3/1\n");
    load_maps("case/s.obj", &sc, maps, 2, &w);
    for (n = 0; n < w.n && n < 4; n++) print_message("%s\n", w.msg[n]);
    CHECK_INT_EQ(w.n, 2, "warnings: the case match and the missing oak");
    snprintf(want, sizeof want,
             "%s:3: map_Kd: %s: no such file; using %s (the name differs in case)",
             tmp_path("case/m.mtl"), tmp_path("case/tex/Wood.PNG"), tmp_path("case/tex/wood.png"));
    assert_string_equal(w.msg[0], want);
    CHECK_CONTAINS(w.msg[1], "Oak.png: cannot open", "the name that matches nothing");
    assert_non_null(maps[0].rgb);
    assert_asymmetric(&maps[0]);
    assert_string_equal(sc.materials[0].map_kd.path, tmp_path("case/tex/wood.png"));
    assert_null(maps[1].rgb);
    free_maps(&sc, maps);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_decode_asymmetric),
        cmocka_unit_test(test_srgb_decode),
        cmocka_unit_test(test_sample_bilinear),
        cmocka_unit_test(test_triangle_mean),
        cmocka_unit_test(test_uniform_mean),
        cmocka_unit_test(test_reflectance_rule),
        cmocka_unit_test(test_hostile_images),
        cmocka_unit_test(test_obj_uv_groups),
        cmocka_unit_test(test_mtl_map_kd),
        cmocka_unit_test(test_uniform_texture_solution),
        cmocka_unit_test(test_face_reflectance),
        cmocka_unit_test(test_render_uniform),
        cmocka_unit_test(test_render_detail),
        cmocka_unit_test(test_large_footprint_mean),
        cmocka_unit_test(test_unusual_maps),
        cmocka_unit_test(test_element_reflectance),
        cmocka_unit_test(test_rect_mean),
        cmocka_unit_test(test_tiled_floor),
        cmocka_unit_test(test_degenerate_footprints),
        cmocka_unit_test(test_tiled_room),
        cmocka_unit_test(test_formats),
        cmocka_unit_test(test_map_identity_and_budget),
        cmocka_unit_test(test_map_case),
    };
    return cmocka_run_group_tests(tests, group_setup, group_teardown);
}
