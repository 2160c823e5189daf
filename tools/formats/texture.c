/* SPDX-License-Identifier: MIT */
/* texture — diffuse textures for the host tools. See texture.h.
 *
 * stb_image comes from the system's libstb (Debian libstb-dev) rather than from a copy
 * compiled here with STB_IMAGE_IMPLEMENTATION: one copy of the decoder, updated with the
 * distribution's security fixes, and none of its 7,000 lines under our -Werror, lint and
 * static analysis. What we need from a private copy (a pixel limit, no stdio) we do
 * ourselves: the size is read with stbi_info_from_memory and checked before decoding,
 * and the file is read through file_io. */
#include "formats/texture.h"

#include "formats/file_io.h"

#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include <dirent.h>
#include <errno.h>

#include <stb/stb_image.h>

static void put_err(char *err, size_t errlen, const char *name, const char *what)
{
    if (err && errlen) snprintf(err, errlen, "%s: %s", name, what);
}

/* stb_image's reason for a failure, printable: for an unknown PNG chunk it is built from
   the chunk's four bytes, which may be anything (a newline among them: found by
   fuzz_mtl_texture). */
static const char *reason(char out[32])
{
    const char *r = stbi_failure_reason();
    size_t i;
    for (i = 0; r && r[i] && i < 31; i++) out[i] = r[i] >= ' ' && r[i] <= '~' ? r[i] : '?';
    out[i] = '\0';
    return out;
}

static void build_row_sums(tex_image *t);

/* ---- the formats accepted -------------------------------------------------------------
   stb_image 2.27 (Debian's) crashes on a 16-bit PGM and loops forever on a truncated
   .hdr (CVE-2021-42716, CVE-2021-42715), and fills what a truncated BMP or TGA lacks
   with zeros (black walls, no word). So only PNG, JPEG, BMP and TGA reach it, each
   recognised here from its bytes, and a file must hold what its header implies: for
   uncompressed BMP and TGA the pixel bytes, for RLE TGA every packet (walked), for
   JPEG the segments up to the end-of-image marker (walked; the entropy-coded data
   cannot hold one). PNG needs no more: its chunks and zlib stream are checked by stb
   (a cut file fails to decode). stb then sees only data its format test recognises
   first: PNG, JPEG and BMP by their magic, TGA by byte 1 (colour map type) 0 or 1,
   which no other format stb knows starts with. */

enum { FMT_PNG = 1, FMT_JPEG, FMT_BMP, FMT_TGA };

static unsigned le16(const unsigned char *p)
{
    return p[0] | (unsigned)p[1] << 8;
}

static unsigned long le32(const unsigned char *p)
{
    return le16(p) | (unsigned long)le16(p + 2) << 16;
}

/* What a refused file seems to be, for the message. */
static const char *other_format(const unsigned char *d, size_t n)
{
    if (n >= 4 && !memcmp(d, "GIF8", 4)) return "GIF";
    if (n >= 4 && !memcmp(d, "8BPS", 4)) return "PSD";
    if (n >= 2 && !memcmp(d, "#?", 2)) return "Radiance HDR";
    if (n >= 2 && d[0] == 'P' && d[1] >= '1' && d[1] <= '7') return "PNM";
    if (n >= 4 && !memcmp(d, "S\x80\xf6\x34", 4)) return "Softimage PIC";
    return "unknown";
}

/* A TGA header, strictly (TGA has no magic): colour-mapped types with a map of 8-bit
   indices, true colour of 15, 16, 24 or 32 bits, grey of 8 or 16, no interleaving. */
static int tga_header(const unsigned char *d, size_t n)
{
    unsigned cmtype, type, cmlen, cmbits, bits;
    if (n < 18) return 0;
    cmtype = d[1], type = d[2], cmlen = le16(d + 5), cmbits = d[7], bits = d[16];
    if (le16(d + 12) < 1 || le16(d + 14) < 1 || (d[17] & 0xc0) || (d[17] & 15) > 8) return 0;
    if (type == 1 || type == 9)
        return cmtype == 1 && le16(d + 3) == 0 && cmlen >= 1 && bits == 8 &&
               (cmbits == 15 || cmbits == 16 || cmbits == 24 || cmbits == 32);
    if (cmtype != 0 || le16(d + 3) || cmlen || cmbits) return 0;
    if (type == 2 || type == 10) return bits == 15 || bits == 16 || bits == 24 || bits == 32;
    return (type == 3 || type == 11) && (bits == 8 || bits == 16);
}

static int sniff(const unsigned char *d, size_t n)
{
    if (n >= 8 && !memcmp(d, "\x89PNG\r\n\x1a\n", 8)) return FMT_PNG;
    if (n >= 3 && d[0] == 0xff && d[1] == 0xd8 && d[2] == 0xff) return FMT_JPEG;
    if (n >= 2 && d[0] == 'B' && d[1] == 'M') return FMT_BMP;
    return tga_header(d, n) ? FMT_TGA : 0;
}

/* Is the JPEG whole: marker segments by their lengths, entropy-coded data to the next
   marker (0xff 0x00 is a stuffed byte, 0xff 0xd0-d7 a restart), up to end-of-image? */
static const char *jpeg_whole(const unsigned char *d, size_t n)
{
    size_t i = 2;
    for (;;) {
        unsigned m;
        while (i < n && d[i] == 0xff && i + 1 < n && d[i + 1] == 0xff) i++; /* fill bytes */
        if (i + 1 >= n) return "truncated: no end-of-image marker";
        if (d[i] != 0xff) return "corrupt: a marker expected";
        m = d[i + 1];
        if (m == 0xd9) return NULL;
        if (m == 0x01 || (m >= 0xd0 && m <= 0xd7)) {
            i += 2;
            continue;
        }
        if (i + 4 > n || (size_t)((d[i + 2] << 8 | d[i + 3]) + 2) > n - i)
            return "truncated within a segment";
        i += (size_t)(d[i + 2] << 8 | d[i + 3]) + 2;
        if (m == 0xda)
            while (i + 1 < n &&
                   !(d[i] == 0xff && d[i + 1] != 0 && !(d[i + 1] >= 0xd0 && d[i + 1] <= 0xd7)))
                i++;
    }
}

/* Does the BMP or TGA hold what its header implies (W x H texels, from stb_image's
   header read)? NULL, or what is wrong. Sizes in 64 bits: W, H < 2^15 here. */
static const char *holds_pixels(int fmt, const unsigned char *d, size_t n, int w, int h,
                                char why[96])
{
    unsigned long long need;
    if (fmt == FMT_BMP) {
        unsigned long dib = n >= 18 ? le32(d + 14) : 0,
                      comp = dib >= 40 && n >= 34 ? le32(d + 30) : 0;
        unsigned bits = dib == 12 ? (n >= 26 ? le16(d + 24) : 0) : (n >= 30 ? le16(d + 28) : 0);
        if (comp != 0 && comp != 3) return "BMP compression other than none or bit fields";
        need = le32(d + 10) + ((unsigned long long)w * bits + 31) / 32 * 4 * (unsigned long long)h;
    } else if (fmt == FMT_TGA) {
        unsigned px = (d[16] + 7u) / 8;
        unsigned long long at = 18ull + d[0] + le16(d + 5) * ((d[7] + 7ull) / 8),
                           left = (unsigned long long)w * h;
        if (d[2] < 9)
            need = at + left * px;
        else { /* RLE: a packet's header, then one pixel (run) or count pixels (raw) */
            while (left > 0 && at < n) {
                unsigned long long c = (d[at] & 0x7fu) + 1u;
                at += 1 + (d[at] & 0x80 ? 1 : c) * px;
                left -= c < left ? c : left;
            }
            need = left ? (unsigned long long)n + 1 : at;
        }
    } else
        return fmt == FMT_JPEG ? jpeg_whole(d, n) : NULL;
    if (need <= n) return NULL;
    snprintf(why, 96, "truncated: its header implies %llu bytes, the file holds %zu", need, n);
    return why;
}

static void empty(tex_image *t)
{
    memset(t, 0, sizeof *t);
    t->scale[0] = t->scale[1] = 1.0;
}

/* What decoding a W x H map keeps: its 8-bit RGB and its row sums (build_row_sums). */
static double map_bytes(int w, int h)
{
    return 3.0 * w * h + 3.0 * sizeof(double) * h * ((double)(w / TEX_ROW_BLOCK) + 2);
}

/* Everything tex_decode checks before decoding: 0 with the declared size in *W, *H, or
   -1 with err. */
static int probe(const unsigned char *data, size_t size, const char *name, int *w, int *h,
                 char *err, size_t errlen)
{
    int comp, fmt;
    char what[160], why[32], why2[96];
    const char *bad;
    if (size == 0 || size > (size_t)0x7fffffff) {
        put_err(err, errlen, name, size ? "larger than 2 GiB" : "empty file");
        return -1;
    }
    if (!(fmt = sniff(data, size))) {
        snprintf(what, sizeof what, "not a PNG, JPEG, BMP or TGA image (format: %s)",
                 other_format(data, size));
        put_err(err, errlen, name, what);
        return -1;
    }
    if (!stbi_info_from_memory(data, (int)size, w, h, &comp)) {
        snprintf(what, sizeof what, "not an image stb_image reads (%s)", reason(why));
        put_err(err, errlen, name, what);
        return -1;
    }
    if (*w < 1 || *h < 1 || *w > TEX_MAX_SIDE || *h > TEX_MAX_SIDE ||
        (long)*w > TEX_MAX_PIXELS / *h) {
        snprintf(what, sizeof what,
                 "declares %d x %d texels, beyond the limits of %d a side and %ld in all", *w, *h,
                 TEX_MAX_SIDE, TEX_MAX_PIXELS);
        put_err(err, errlen, name, what);
        return -1;
    }
    if ((bad = holds_pixels(fmt, data, size, *w, *h, why2)) != NULL) {
        put_err(err, errlen, name, bad);
        return -1;
    }
    return 0;
}

int tex_decode(const unsigned char *data, size_t size, const char *name, tex_image *out, char *err,
               size_t errlen)
{
    int w, h, comp;
    char what[160], why[32];
    empty(out);
    if (probe(data, size, name, &w, &h, err, errlen)) return -1;
    out->rgb = stbi_load_from_memory(data, (int)size, &out->w, &out->h, &comp, 3);
    if (!out->rgb || out->w != w || out->h != h) {
        snprintf(what, sizeof what, "cannot decode (%s)", out->rgb ? "size changed" : reason(why));
        tex_free(out);
        put_err(err, errlen, name, what);
        return -1;
    }
    build_row_sums(out);
    return 0;
}

int tex_load(const char *path, tex_image *out, char *err, size_t errlen)
{
    char *data;
    size_t size;
    int rc;
    empty(out);
    if (fio_read_all(path, FIO_LIMIT_IMAGE, &data, &size, err, errlen)) return -1;
    rc = tex_decode((const unsigned char *)data, size, path, out, err, errlen);
    free(data);
    return rc;
}

void tex_free(tex_image *t)
{
    if (!t) return;
    if (!t->borrowed) {
        stbi_image_free(t->rgb);
        free(t->row_sums);
    }
    empty(t);
}

/* ---- sampling ------------------------------------------------------------------ */

double tex_srgb_decode(double s)
{
    s = s < 0 ? 0 : s > 1 ? 1 : s;
    return s <= 0.04045 ? s / 12.92 : pow((s + 0.055) / 1.055, 2.4);
}

/* tex_srgb_decode(i / 255.0) for every byte i, printed to 17 digits (a constant table:
   no initialisation to race on; test_texture checks it against the function). */
/* clang-format off: a table, four entries a row */
static const double byte_linear[256] = {
    0,
    0.00030352698354883752,
    0.00060705396709767503,
    0.00091058095064651249,
    0.0012141079341953501,
    0.0015176349177441874,
    0.001821161901293025,
    0.0021246888848418626,
    0.0024282158683907001,
    0.0027317428519395373,
    0.0030352698354883748,
    0.0033465357638991608,
    0.0036765073240474359,
    0.0040247170184963066,
    0.0043914420374102934,
    0.0047769534806937292,
    0.005181516702338386,
    0.0056053916242027229,
    0.0060488330228570539,
    0.0065120907925944752,
    0.0069954101872653869,
    0.0074990320432261753,
    0.0080231929853849943,
    0.0085681256180693069,
    0.0091340587022207872,
    0.0097212173202378491,
    0.010329823029626936,
    0.010960094006488246,
    0.011612245179743885,
    0.012286488356915872,
    0.012983032342173012,
    0.013702083047289686,
    0.014443843596092545,
    0.015208514422912709,
    0.015996293365509631,
    0.016807375752887384,
    0.017641954488384078,
    0.018500220128379697,
    0.019382360956935723,
    0.020288563056652401,
    0.021219010376003555,
    0.022173884793387381,
    0.02315336617811041,
    0.024157632448504756,
    0.02518685962736163,
    0.026241221894849898,
    0.027320891639074894,
    0.028426039504420793,
    0.0295568344378088,
    0.030713443732993635,
    0.031896033073011532,
    0.033104766570885055,
    0.03433980680868217,
    0.035601314875020343,
    0.036889450401100039,
    0.038204371595346502,
    0.039546235276732837,
    0.040915196906853191,
    0.042311410620809675,
    0.043735029256973465,
    0.045186204385675541,
    0.046665086336880095,
    0.048171824226889419,
    0.049706565984127232,
    0.051269458374043238,
    0.052860647023180246,
    0.054480276442442369,
    0.056128490049600091,
    0.057805430191067229,
    0.059511238162981199,
    0.061246054231617608,
    0.063010017653167674,
    0.064803266692905773,
    0.066625938643772892,
    0.068478169844400166,
    0.070360095696595876,
    0.072271850682317479,
    0.074213568380149628,
    0.076185381481307851,
    0.078187421805186327,
    0.080219820314468324,
    0.082282707129814794,
    0.084376211544148816,
    0.086500462036549763,
    0.088655586285772942,
    0.090841711183407683,
    0.093058962846687451,
    0.095307466630964705,
    0.097587347141862457,
    0.099898728247113891,
    0.10224173308810132,
    0.10461648409110419,
    0.10702310297826761,
    0.10946171077829933,
    0.1119324278369056,
    0.11443537382697373,
    0.11697066775851084,
    0.11953842798834562,
    0.12213877222960187,
    0.12477181756095049,
    0.12743768043564743,
    0.13013647669036429,
    0.13286832155381798,
    0.13563332965520566,
    0.13843161503245183,
    0.14126329114027164,
    0.14412847085805777,
    0.14702726649759498,
    0.14995978981060856,
    0.15292615199615017,
    0.1559264637078274,
    0.15896083506088041,
    0.16202937563911099,
    0.16513219450166761,
    0.16826940018969075,
    0.17144110073282259,
    0.17464740365558504,
    0.17788841598362912,
    0.18116424424986022,
    0.184474994500441,
    0.18782077230067787,
    0.19120168274079138,
    0.1946178304415758,
    0.19806931955994886,
    0.20155625379439707,
    0.20507873639031693,
    0.20863687014525575,
    0.21223075741405523,
    0.21586050011389926,
    0.21952619972926921,
    0.2232279573168085,
    0.22696587351009836,
    0.23074004852434915,
    0.23455058216100522,
    0.238397573812271,
    0.24228112246555486,
    0.24620132670783548,
    0.25015828472995344,
    0.25415209433082675,
    0.25818285292159582,
    0.26225065752969623,
    0.26635560480286247,
    0.27049779101306581,
    0.27467731206038465,
    0.2788942634768104,
    0.28314874042999211,
    0.28744083772691748,
    0.29177064981753587,
    0.29613827079832111,
    0.3005437944157765,
    0.30498731406988627,
    0.30946892281750854,
    0.31398871337571754,
    0.31854677812509186,
    0.32314320911295075,
    0.32777809805654218,
    0.33245153634617935,
    0.33716361504833037,
    0.34191442490866092,
    0.3467040563550296,
    0.35153259950043936,
    0.35640014414594351,
    0.3613067797835095,
    0.36625259559883949,
    0.37123768047414912,
    0.3762621229909065,
    0.38132601143253014,
    0.38642943378704903,
    0.39157247774972326,
    0.39675523072562685,
    0.40197777983219579,
    0.4072402119017367,
    0.41254261348390375,
    0.41788507084813747,
    0.42326766998607168,
    0.42869049661390662,
    0.43415363617474895,
    0.43965717384091879,
    0.44520119451622786,
    0.45078578283822346,
    0.45641102318040466,
    0.46207699965440707,
    0.46778379611215898,
    0.47353149614800955,
    0.4793201831008268,
    0.48514994005607037,
    0.49102084984783562,
    0.49693299506087041,
    0.50288645803256871,
    0.50888132085493376,
    0.51491766537652139,
    0.5209955732043543,
    0.52711512570581309,
    0.53327640401050524,
    0.53947948901210718,
    0.5457244613701866,
    0.55201140151200012,
    0.55834038963426791,
    0.56471150570492923,
    0.57112482946487308,
    0.57758044042965062,
    0.5840784178911641,
    0.59061884091933692,
    0.59720178836376336,
    0.60382733885533779,
    0.61049557080786476,
    0.61720656241965111,
    0.62396039167507611,
    0.63075713634614683,
    0.63759687399403264,
    0.64447968197058214,
    0.65140563741982416,
    0.65837481727944847,
    0.66538729828227205,
    0.67244315695768753,
    0.67954246963309384,
    0.6866853124353135,
    0.69387176129198991,
    0.70110189193297312,
    0.70837577989168676,
    0.71569350050648073,
    0.72305512892196933,
    0.73046074009035367,
    0.73791040877273084,
    0.74540420954038744,
    0.75294221677607787,
    0.76052450467529242,
    0.76815114724750699,
    0.7758222183174236,
    0.78353779152619352,
    0.79129794033263023,
    0.79910273801440901,
    0.8069522576692516,
    0.81484657221610124,
    0.82278575439628354,
    0.83076987677465464,
    0.83879901174074001,
    0.84687323150985805,
    0.85499260812423383,
    0.86315721345410235,
    0.87136711919879717,
    0.87962239688783173,
    0.88792311788196632,
    0.89626935337426639,
    0.90466117439114957,
    0.9130986517934192,
    0.92158185627729461,
    0.93011085837542373,
    0.938685728457888,
    0.94730653673319987,
    0.95597335324928612,
    0.96468624789446511,
    0.97344529039841254,
    0.98225055033311715,
    0.99110209711382979,
    1,
};
/* clang-format on */

void tex_texel(const tex_image *t, int x, int y, double rgb[3])
{
    const unsigned char *p = t->rgb + ((size_t)y * (size_t)t->w + (size_t)x) * 3;
    int k;
    for (k = 0; k < 3; k++) rgb[k] = byte_linear[p[k]];
}

/* Texel index along an axis of N texels for texel-centre coordinate i (any integer). */
static int wrap_index(const tex_image *t, double i, int n)
{
    if (t->clamp) return i < 0 ? 0 : i >= n ? n - 1 : (int)i;
    i = fmod(i, (double)n);
    return (int)(i < 0 ? i + n : i);
}

void tex_sample(const tex_image *t, double u, double v, double rgb[3])
{
    double x, y, fx, fy, c[4][3];
    int x0, y0, x1, y1, k;
    u = u * t->scale[0] + t->offset[0];
    v = v * t->scale[1] + t->offset[1];
    if (!isfinite(u) || !isfinite(v)) u = v = 0;
    /* Wrapped coordinates first, so that floor below stays within int range. */
    if (!t->clamp) {
        u -= floor(u);
        v -= floor(v);
    }
    x = u * t->w - 0.5;
    y = (1.0 - v) * t->h - 0.5;
    if (t->clamp) {
        x = x < -1 ? -1 : x > t->w ? t->w : x;
        y = y < -1 ? -1 : y > t->h ? t->h : y;
    }
    fx = floor(x);
    fy = floor(y);
    x0 = wrap_index(t, fx, t->w);
    x1 = wrap_index(t, fx + 1, t->w);
    y0 = wrap_index(t, fy, t->h);
    y1 = wrap_index(t, fy + 1, t->h);
    fx = x - fx;
    fy = y - fy;
    tex_texel(t, x0, y0, c[0]);
    tex_texel(t, x1, y0, c[1]);
    tex_texel(t, x0, y1, c[2]);
    tex_texel(t, x1, y1, c[3]);
    for (k = 0; k < 3; k++)
        rgb[k] = (c[0][k] * (1 - fx) + c[1][k] * fx) * (1 - fy) +
                 (c[2][k] * (1 - fx) + c[3][k] * fx) * fy;
}

/* The longest edge of the triangle UV in texels (NaN for UVs whose differences are). */
static double footprint(const tex_image *t, const obj_vec2 uv[3])
{
    double longest = 0;
    int i;
    for (i = 0; i < 3; i++) {
        const obj_vec2 *a = &uv[i], *b = &uv[(i + 1) % 3];
        double du = (b->u - a->u) * t->scale[0] * t->w, dv = (b->v - a->v) * t->scale[1] * t->h;
        double len = sqrt(du * du + dv * dv);
        longest = len > longest || isnan(len) ? len : longest;
    }
    return longest;
}

/* Subdivisions of a triangle: about four a texel along its longest edge. The midpoint
   rule is exact where the bilinear texture is linear and errs at its kinks (texel
   centres), by O(1/n^2): test_triangle_mean measured 0.069%, 0.018% and 0.0047% of
   the mean at 2, 4 and 8 a texel. */
static int divisions(const tex_image *t, const obj_vec2 uv[3])
{
    double longest = ceil(4 * footprint(t, uv));
    return !(longest >= 1) ? 1 : longest > TEX_MEAN_MAX_DIV ? TEX_MEAN_MAX_DIV : (int)longest;
}

/* ---- the mean over a large footprint, along lines ------------------------------------
   Coordinates are texel centres, x = u w - 1/2 and y = (1 - v) h - 1/2 as in tex_sample.
   Along a line of constant y the bilinear texture is (1 - fy) R_j + fy R_j+1, R_j the
   linear interpolant of row j (j = floor y, fy = y - j), and the integral of R_j from
   0 to x is exact from the row sums: over whole texels it is the trapezoid sum S(k) =
   sum_{i<k} (c_i + c_i+1) / 2 = P(k) + (c_k - c_0) / 2, P the box sum, and a period adds
   P(w). Between texel rows and vertices the integrand is linear in y but where the
   line's ends cross texel columns, so the midpoint rule in y, two lines a texel row,
   errs only along the triangle's edges. The mean is the integral over the area those
   lines measure, so a uniform texture gives its colour exactly. */

#define MEAN_MAX_ROWS    65536.0 /* texel rows a footprint may span (the cost: lines) */
#define MEAN_LINES_A_ROW 2       /* the edges' error falls as 1 / lines^2 */

/* Adds the linear values of row Y's texels X0 .. X1 - 1 to S. */
static void add_texels(const tex_image *t, int y, int x0, int x1, double s[3])
{
    const unsigned char *p = t->rgb + ((size_t)y * (size_t)t->w + (size_t)x0) * 3;
    int x;
    for (x = x0; x < x1; x++, p += 3) {
        s[0] += byte_linear[p[0]];
        s[1] += byte_linear[p[1]];
        s[2] += byte_linear[p[2]];
    }
}

/* Entries a row holds: the sums before every TEX_ROW_BLOCK-th texel, then the row's. */
static size_t row_entries(const tex_image *t)
{
    return (size_t)t->w / TEX_ROW_BLOCK + 2;
}

static void build_row_sums(tex_image *t)
{
    size_t nb = row_entries(t), b;
    double *r = malloc((size_t)t->h * nb * 3 * sizeof *r);
    int y;
    t->row_sums = r;
    for (y = 0; r && y < t->h; y++) {
        double *row = &r[3 * (size_t)y * nb];
        row[0] = row[1] = row[2] = 0;
        for (b = 1; b < nb; b++) {
            int x0 = (int)(b - 1) * TEX_ROW_BLOCK, x1 = b + 1 < nb ? x0 + TEX_ROW_BLOCK : t->w;
            memcpy(&row[3 * b], &row[3 * (b - 1)], 3 * sizeof *row);
            add_texels(t, y, x0 < t->w ? x0 : t->w, x1 < t->w ? x1 : t->w, &row[3 * b]);
        }
    }
}

/* S(k) = P(k) + (c_k - c_0) / 2 of row Y for 0 <= k <= w (c_w = c_0) into S. */
static void trapezoid_sum(const tex_image *t, int y, int k, double s[3])
{
    const double *row = &t->row_sums[3 * (size_t)y * row_entries(t)];
    const unsigned char *p = t->rgb + (size_t)y * (size_t)t->w * 3;
    int b = k / TEX_ROW_BLOCK, i;
    if (k == t->w) { /* a whole row: c_w = c_0 */
        memcpy(s, &row[3 * (row_entries(t) - 1)], 3 * sizeof *s);
        return;
    }
    memcpy(s, &row[3 * b], 3 * sizeof *s);
    add_texels(t, y, b * TEX_ROW_BLOCK, k, s);
    for (i = 0; i < 3; i++) s[i] += 0.5 * (byte_linear[p[3 * k + i]] - byte_linear[p[i]]);
}

/* W times the integral of row Y's interpolant from 0 to X, added to OUT. */
static void row_integral(const tex_image *t, int y, double x, double w, double out[3])
{
    double q = 0, s[3], per[3] = {0, 0, 0}, c0[3], c1[3], f;
    int i, k;
    if (t->clamp && (x <= 0 || x >= t->w - 1)) { /* constant past the edge texels */
        i = x <= 0 ? 0 : t->w - 1;
        tex_texel(t, i, y, c0);
        if (x <= 0)
            s[0] = s[1] = s[2] = 0;
        else
            trapezoid_sum(t, y, i, s);
        for (k = 0; k < 3; k++) out[k] += w * (s[k] + c0[k] * (x - i));
        return;
    }
    if (!t->clamp) {
        q = floor(x / t->w);
        x -= q * t->w;
        if (!(x >= 0 && x < t->w)) x = 0; /* rounding at a period's end */
        if (q != 0) trapezoid_sum(t, y, t->w, per);
    }
    i = (int)x;
    f = x - i;
    trapezoid_sum(t, y, i, s);
    tex_texel(t, i, y, c0);
    tex_texel(t, i + 1 < t->w ? i + 1 : t->clamp ? i : 0, y, c1);
    for (k = 0; k < 3; k++)
        out[k] += w * (q * per[k] + s[k] + c0[k] * f + 0.5 * (c1[k] - c0[k]) * f * f);
}

static int row_index(const tex_image *t, double j)
{
    if (t->clamp) return j < 0 ? 0 : j >= t->h ? t->h - 1 : (int)j;
    j = fmod(j, (double)t->h);
    return (int)(j < 0 ? j + t->h : j);
}

/* Where the line at height AT crosses the triangle X, Y: [*A, *B]; 0 if it does not. */
static int crossing(const double *x, const double *y, double at, double *a, double *b)
{
    int i, n = 0;
    for (i = 0; i < 3; i++) {
        int j = (i + 1) % 3;
        if ((y[i] <= at) != (y[j] <= at)) {
            double c = x[i] + (at - y[i]) / (y[j] - y[i]) * (x[j] - x[i]);
            *a = n ? fmin(*a, c) : c;
            *b = n ? fmax(*b, c) : c;
            n++;
        }
    }
    return n == 2;
}

/* The line at height AT, weight W: its integral into SUM, its length into *LEN. */
static void line(const tex_image *t, const double *x, const double *y, double at, double w,
                 double sum[3], double *len)
{
    double a, b, j = floor(at), fy = at - j, acc[3] = {0, 0, 0};
    int r0 = row_index(t, j), r1 = row_index(t, j + 1), k;
    if (!crossing(x, y, at, &a, &b)) return;
    row_integral(t, r0, b, 1 - fy, acc);
    row_integral(t, r1, b, fy, acc);
    row_integral(t, r0, a, fy - 1, acc);
    row_integral(t, r1, a, -fy, acc);
    for (k = 0; k < 3; k++) sum[k] += w * acc[k];
    *len += w * (b - a);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* The mean over UV along lines into RGB: 0, or -1 (no row sums, too many rows, no
   area) for the sampler to take it. Pieces end at texel rows and at the middle vertex,
   where the integrand's slope in y changes; each gets two lines a texel row. */
static int mean_by_lines(const tex_image *t, const obj_vec2 uv[3], double rgb[3])
{
    double x[3], y[3], ys[3], sum[3] = {0, 0, 0}, len = 0, at;
    int i, k;
    for (i = 0; i < 3; i++) {
        x[i] = (uv[i].u * t->scale[0] + t->offset[0]) * t->w - 0.5;
        y[i] = (1.0 - (uv[i].v * t->scale[1] + t->offset[1])) * t->h - 0.5;
        if (!(fabs(x[i]) < 1e15 && fabs(y[i]) < 1e15)) return -1;
    }
    if (!t->clamp) { /* whole periods off, so that the row integrals' sums stay small */
        double qx = floor(fmin(x[0], fmin(x[1], x[2])) / t->w) * t->w;
        double qy = floor(fmin(y[0], fmin(y[1], y[2])) / t->h) * t->h;
        for (i = 0; i < 3; i++) {
            x[i] -= qx;
            y[i] -= qy;
        }
    }
    for (i = 0; i < 3; i++) ys[i] = y[i];
    qsort(ys, 3, sizeof ys[0], cmp_double);
    if (!t->row_sums || !(ys[2] - ys[0] > 0 && ys[2] - ys[0] <= MEAN_MAX_ROWS)) return -1;
    for (at = ys[0]; at < ys[2];) {
        double next = fmin(floor(at) + 1, ys[2]);
        int n;
        if (at < ys[1] && ys[1] < next) next = ys[1];
        n = (int)ceil(MEAN_LINES_A_ROW * (next - at));
        for (i = 0; i < n; i++)
            line(t, x, y, at + (i + 0.5) * (next - at) / n, (next - at) / n, sum, &len);
        at = next;
    }
    if (!(len > 0)) return -1;
    for (k = 0; k < 3; k++) rgb[k] = sum[k] / len;
    return 0;
}

/* Twice the area of the triangle UV in texels (NaN for UVs whose differences are). */
static double uv_area2(const tex_image *t, const obj_vec2 uv[3])
{
    double au = (uv[1].u - uv[0].u) * t->scale[0] * t->w,
           av = (uv[1].v - uv[0].v) * t->scale[1] * t->h;
    double bu = (uv[2].u - uv[0].u) * t->scale[0] * t->w,
           bv = (uv[2].v - uv[0].v) * t->scale[1] * t->h;
    return fabs(au * bv - av * bu);
}

/* A triangle of UV thinner than SLIVER times its longest edge (twice its area below
   SLIVER longest^2), two equal vt among them, maps its face onto a segment or a point
   of the texture: the lines would divide sums by a length that is rounding (measured:
   means of -2.4 and 4.4 over a black and white map). The sampler's centroids lie on
   that segment, spread as the face's area is: the mean along it, and at a point the
   texel there. */
#define SLIVER 1e-6

/* Every mean is a convex combination of texels, each in [0, 1], so a value outside is
   rounding's (the row sums' differences: -4e-15 measured over black texels across the
   wrap's seam, which the core refuses as a negative reflectance): kept to [0, 1]. NaN
   (UVs whose differences overflow) takes the sample at corner 0. Nothing here fails. */
static void settle(const tex_image *t, const obj_vec2 *uv, double rgb[3])
{
    int k;
    if (isnan(rgb[0]) || isnan(rgb[1]) || isnan(rgb[2])) tex_sample(t, uv[0].u, uv[0].v, rgb);
    for (k = 0; k < 3; k++) rgb[k] = rgb[k] > 0 ? rgb[k] < 1 ? rgb[k] : 1 : 0;
}

/* Splitting each edge in n splits the triangle into n^2 congruent triangles: n(n+1)/2
   pointing like it, with centroids at barycentric ((i + 1/3) / n, (j + 1/3) / n), and
   n(n-1)/2 pointing the other way, centroids at ((i + 2/3) / n, (j + 2/3) / n). Equal
   areas make the mean of their centroid samples the midpoint rule. */
void tex_triangle_mean(const tex_image *t, const obj_vec2 uv[3], double rgb[3])
{
    int n = divisions(t, uv), i, j, k, up;
    double sum[3] = {0, 0, 0}, longest = footprint(t, uv);
    if (4 * longest > TEX_MEAN_MAX_DIV && !(uv_area2(t, uv) <= SLIVER * longest * longest) &&
        mean_by_lines(t, uv, rgb) == 0) {
        settle(t, uv, rgb);
        return;
    }
    for (up = 0; up < 2; up++)
        for (i = 0; i < n; i++)
            for (j = 0; j + i < n - up; j++) {
                double a = (i + (up ? 2.0 : 1.0) / 3) / n, b = (j + (up ? 2.0 : 1.0) / 3) / n;
                double s[3];
                tex_sample(t, uv[0].u + a * (uv[1].u - uv[0].u) + b * (uv[2].u - uv[0].u),
                           uv[0].v + a * (uv[1].v - uv[0].v) + b * (uv[2].v - uv[0].v), s);
                for (k = 0; k < 3; k++) sum[k] += s[k];
            }
    for (k = 0; k < 3; k++) rgb[k] = sum[k] / ((double)n * n);
    settle(t, uv, rgb);
}

static double tri_area(const double a[3], const double b[3], const double c[3])
{
    double u[3], v[3], n[3];
    int k;
    for (k = 0; k < 3; k++) {
        u[k] = b[k] - a[k];
        v[k] = c[k] - a[k];
    }
    n[0] = u[1] * v[2] - u[2] * v[1];
    n[1] = u[2] * v[0] - u[0] * v[2];
    n[2] = u[0] * v[1] - u[1] * v[0];
    return 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

/* The integral of the texel-centred tent over [j - 1, j + 1] from -infinity to j + T. */
static double tent_below(double t)
{
    if (t <= -1) return 0;
    if (t <= 0) return 0.5 * (1 + t) * (1 + t);
    if (t < 1) return 1 - 0.5 * (1 - t) * (1 - t);
    return 1;
}

/* G(X) = sum_j W_j (integral of R_j from 0 to X) for the rows of [Y0, Y1] (W_j: the
   row's tent integrated over it) into G: through MEMO (NULL: none), where neighbouring
   elements share their edges' values. */
static void rect_edge(const tex_image *t, double y0, double y1, double x, tex_memo *memo,
                      double g[3])
{
    tex_memo_entry *m = NULL;
    double j;
    if (memo) {
        uint64_t key[3], h = 1469598103934665603u;
        int i;
        if (memo->image != t) {
            memset(memo, 0, sizeof *memo);
            memo->image = t;
        }
        memcpy(&key[0], &x, 8);
        memcpy(&key[1], &y0, 8);
        memcpy(&key[2], &y1, 8);
        for (i = 0; i < 3; i++) h = (h ^ key[i]) * 1099511628211u;
        m = &memo->e[(h >> 32) % TEX_MEMO_ENTRIES];
        if (m->used && m->x == x && m->y0 == y0 && m->y1 == y1) {
            memcpy(g, m->g, sizeof m->g);
            return;
        }
    }
    g[0] = g[1] = g[2] = 0;
    for (j = floor(y0); j <= floor(y1) + 1; j++) {
        double w = tent_below(y1 - j) - tent_below(y0 - j);
        if (w > 0) row_integral(t, row_index(t, j), x, w, g);
    }
    if (m) {
        m->used = 1;
        m->x = x;
        m->y0 = y0;
        m->y1 = y1;
        memcpy(m->g, g, sizeof m->g);
    }
}

/* The mean over UV[0..3] when it is a rectangle with sides along the texel axes (a wall's
   element, the common case), exactly: the bilinear texture between y0 and y1 is the sum
   of the rows' interpolants R_j times the tents' integrals W_j over [y0, y1], so the
   integral is G(x1) - G(x0) (rect_edge), one row integral a texel row and edge (a
   footprint of r rows: 2 r + 4, not the lines' 8 a row on each of two triangles; a
   lattice's elements share their edges' through MEMO). 0, or -1 (not such a rectangle,
   no row sums, too many rows) for the general path. */
static int mean_of_rect(const tex_image *t, const obj_vec2 uv[4], tex_memo *memo, double rgb[3])
{
    double x[4], y[4], x0, x1, y0, y1, g0[3], g1[3], wsum = 0, j;
    int i, k;
    for (i = 0; i < 4; i++) {
        x[i] = (uv[i].u * t->scale[0] + t->offset[0]) * t->w - 0.5;
        y[i] = (1.0 - (uv[i].v * t->scale[1] + t->offset[1])) * t->h - 0.5;
        if (!(fabs(x[i]) < 1e15 && fabs(y[i]) < 1e15)) return -1;
    }
    /* sides alternately along x and y: corners 0, 2 opposite, 1 and 3 each sharing x
       with one of them and y with the other (to a billionth of the side), apart */
    x0 = fmin(x[0], x[2]);
    x1 = fmax(x[0], x[2]);
    y0 = fmin(y[0], y[2]);
    y1 = fmax(y[0], y[2]);
    if (!t->row_sums || !(x1 - x0 > 0 && y1 - y0 > 0 && y1 - y0 <= MEAN_MAX_ROWS)) return -1;
    for (i = 1; i < 4; i += 2) {
        double ex = 1e-9 * (x1 - x0), ey = 1e-9 * (y1 - y0);
        int a = fabs(x[i] - x[0]) <= ex && fabs(y[i] - y[2]) <= ey;
        int b = fabs(x[i] - x[2]) <= ex && fabs(y[i] - y[0]) <= ey;
        if (!a && !b) return -1;
    }
    if (fabs(x[1] - x[3]) <= 1e-9 * (x1 - x0)) return -1; /* 1 and 3 the same corner */
    if (!t->clamp) { /* whole periods off: the row integrals need none of their own */
        double q = floor(x0 / t->w) * t->w, qy = floor(y0 / t->h) * t->h;
        x0 -= q;
        x1 -= q;
        y0 -= qy;
        y1 -= qy;
    }
    for (j = floor(y0); j <= floor(y1) + 1; j++) wsum += tent_below(y1 - j) - tent_below(y0 - j);
    if (!(wsum > 0)) return -1;
    rect_edge(t, y0, y1, x0, memo, g0);
    rect_edge(t, y0, y1, x1, memo, g1);
    for (k = 0; k < 3; k++) rgb[k] = (g1[k] - g0[k]) / (wsum * (x1 - x0));
    settle(t, uv, rgb);
    return 0;
}

void tex_polygon_mean(const tex_image *t, const double (*pos)[3], const obj_vec2 *uv, int n,
                      tex_memo *memo, double rgb[3])
{
    double total = 0;
    int k, tri;
    if (n == 4 && mean_of_rect(t, uv, memo, rgb) == 0) return;
    rgb[0] = rgb[1] = rgb[2] = 0;
    for (tri = 0; tri + 2 < n; tri++) {
        double part[3], a = tri_area(pos[0], pos[tri + 1], pos[tri + 2]);
        obj_vec2 foot[3];
        foot[0] = uv[0];
        foot[1] = uv[tri + 1];
        foot[2] = uv[tri + 2];
        tex_triangle_mean(t, foot, part);
        a = a > 0 ? a : 1e-300; /* a sliver still counts, by its own mean */
        for (k = 0; k < 3; k++) rgb[k] += a * part[k];
        total += a;
    }
    for (k = 0; k < 3; k++) rgb[k] /= total;
    settle(t, uv, rgb);
}

void tex_image_mean(const tex_image *t, double rgb[3])
{
    double sum[3] = {0, 0, 0}, c[3];
    int x, y, k;
    for (y = 0; y < t->h; y++)
        for (x = 0; x < t->w; x++) {
            tex_texel(t, x, y, c);
            for (k = 0; k < 3; k++) sum[k] += c[k];
        }
    for (k = 0; k < 3; k++) rgb[k] = sum[k] / ((double)t->w * t->h);
}

void tex_reflectance(const double kd[3], const double texel[3], double rho[3])
{
    int k, black = kd[0] == 0 && kd[1] == 0 && kd[2] == 0;
    for (k = 0; k < 3; k++) {
        double r = black ? texel[k] : texel[k] * kd[k];
        rho[k] = r < TEX_RHO_MAX ? r : TEX_RHO_MAX;
    }
}

/* ---- materials ----------------------------------------------------------------- */

static void warn_map(obj_material *m, const char *why, tex_warn_fn warn, void *ctx)
{
    char msg[1024];
    obj_map_fallback(m);
    if (!warn) return;
    snprintf(msg, sizeof msg, "%s:%d: map_Kd: %s; using Kd %.3g %.3g %.3g", m->map_kd.mtl,
             m->map_kd.line, why, m->kd[0], m->kd[1], m->kd[2]);
    warn(ctx, msg);
}

/* The decoding of one file, for a thread: MAT the material that names it first; DATA
 * its bytes (read and checked by probe on the calling thread), NULL once RC is set. */
typedef struct {
    const char *path;
    int mat, rc;
    char *data;
    size_t size;
    dev_t dev;
    ino_t ino;
    int known; /* dev, ino set (stat succeeded) */
    char err[768];
} tex_job;

typedef struct {
    tex_job *jobs;
    tex_image *maps;
    int njobs, threads, rank;
} tex_crew;

static void *decode_jobs(void *arg)
{
    const tex_crew *c = arg;
    int k;
    for (k = c->rank; k < c->njobs; k += c->threads) {
        tex_job *j = &c->jobs[k];
        if (!j->data) continue;
        j->rc = tex_decode((const unsigned char *)j->data, j->size, j->path, &c->maps[j->mat],
                           j->err, sizeof j->err);
        free(j->data);
        j->data = NULL;
    }
    return NULL;
}
/* Each job decoded, on THREADS threads (the files are independent; a thread that
 * cannot start leaves its jobs to the calling thread). Returns -1 without memory. */
static int decode_all(tex_job *jobs, int njobs, tex_image *maps, int threads)
{
    tex_crew *c;
    pthread_t *tid;
    int t, n = threads < njobs ? threads : njobs, *started;
    if (n < 1) n = 1;
    c = calloc((size_t)n, sizeof *c);
    tid = calloc((size_t)n, sizeof *tid);
    started = calloc((size_t)n, sizeof *started);
    if (!c || !tid || !started) {
        free(c);
        free(tid);
        free(started);
        return -1;
    }
    for (t = 0; t < n; t++) {
        c[t].jobs = jobs;
        c[t].maps = maps;
        c[t].njobs = njobs;
        c[t].threads = n;
        c[t].rank = t;
    }
    for (t = 1; t < n; t++) started[t] = pthread_create(&tid[t], NULL, decode_jobs, &c[t]) == 0;
    decode_jobs(&c[0]);
    for (t = 1; t < n; t++) {
        if (started[t])
            pthread_join(tid[t], NULL);
        else
            decode_jobs(&c[t]);
    }
    free(c);
    free(tid);
    free(started);
    return 0;
}

/* PATH, which does not exist: the entry of its folder whose name is PATH's last part
 * but for case (the first in byte order if several), as a new string; NULL if none. */
static char *case_match(const char *path)
{
    const char *slash = strrchr(path, '/'), *base = slash ? slash + 1 : path;
    size_t dirlen = slash ? (size_t)(slash - path) : 0;
    char *dir = slash ? malloc(dirlen + 2) : NULL, *best = NULL, *out = NULL;
    DIR *d;
    struct dirent *e;
    if (slash && !dir) return NULL;
    if (dir) { /* "/x.png": the root */
        memcpy(dir, path, dirlen ? dirlen : 1);
        dir[dirlen ? dirlen : 1] = '\0';
    }
    d = opendir(dir ? dir : ".");
    free(dir);
    while (d && (e = readdir(d)) != NULL)
        if (!strcasecmp(e->d_name, base) && (!best || strcmp(e->d_name, best) < 0)) {
            free(best);
            best = malloc(strlen(e->d_name) + 1);
            if (best) strcpy(best, e->d_name);
        }
    if (d) closedir(d);
    if (best && (out = malloc(dirlen + strlen(best) + 2)) != NULL)
        snprintf(out, dirlen + strlen(best) + 2, "%.*s%s%s", (int)dirlen, path, slash ? "/" : "",
                 best);
    free(best);
    return out;
}

/* The job for material I's map: an earlier one naming the same file (the same device
 * and inode, whatever the spelling: ./a.png, a.png, a link; the same string when stat
 * fails), or a new one, read and probed here in material order so that the budget
 * (*SPENT of TEX_BUDGET bytes) is charged alike on any number of threads. */
/* The bytes of M's map into J (as fio_read_all gives them, a NUL after): a copy of the
 * ones the scene file held, else its file's. 0, or -1 with J's err. */
static int read_map(const obj_material *m, tex_job *j)
{
    if (!m->map_kd.data)
        return fio_read_all(j->path, FIO_LIMIT_IMAGE, &j->data, &j->size, j->err, sizeof j->err);
    if (!(j->data = malloc(m->map_kd.size + 1))) {
        snprintf(j->err, sizeof j->err, "%s: out of memory", j->path);
        return -1;
    }
    memcpy(j->data, m->map_kd.data, m->map_kd.size);
    j->data[m->map_kd.size] = '\0';
    j->size = m->map_kd.size;
    return 0;
}

static int job_for(obj_material *m, tex_job *jobs, int *njobs, int i, double *spent, char *note,
                   size_t notelen)
{
    struct stat st;
    tex_job *j = &jobs[*njobs];
    int k, w, h;
    double cost;
    char *alt;
    note[0] = '\0';
    if (!m->map_kd.data && stat(m->map_kd.path, &st) != 0 && errno == ENOENT &&
        (alt = case_match(m->map_kd.path)) != NULL) {
        snprintf(note, notelen,
                 "%s:%d: map_Kd: %s: no such file; using %s (the name differs in case)",
                 m->map_kd.mtl, m->map_kd.line, m->map_kd.path, alt);
        free(m->map_kd.path);
        m->map_kd.path = alt;
    }
    memset(j, 0, sizeof *j);
    j->path = m->map_kd.path;
    j->mat = i;
    j->known = !m->map_kd.data && stat(j->path, &st) == 0; /* embedded: shared by name */
    j->dev = j->known ? st.st_dev : 0;
    j->ino = j->known ? st.st_ino : 0;
    for (k = 0; k < *njobs; k++)
        if (j->known ? jobs[k].known && jobs[k].dev == j->dev && jobs[k].ino == j->ino
                     : !jobs[k].known && !strcmp(jobs[k].path, j->path))
            return k;
    (*njobs)++;
    if (read_map(m, j) ||
        probe((const unsigned char *)j->data, j->size, j->path, &w, &h, j->err, sizeof j->err)) {
        j->rc = -1;
    } else if ((cost = map_bytes(w, h) + (double)j->size) > TEX_BUDGET - *spent) {
        snprintf(j->err, sizeof j->err,
                 "%s: %d x %d texels need %.0f MiB, over what is left of the scene's "
                 "texture budget (%.0f of %.0f MiB, TEX_BUDGET)",
                 j->path, w, h, cost / 1048576, (TEX_BUDGET - *spent) / 1048576,
                 TEX_BUDGET / 1048576.0);
        j->rc = -1;
    } else
        *spent += cost;
    if (j->rc) {
        free(j->data);
        j->data = NULL;
    }
    return *njobs - 1;
}

int tex_load_materials(obj_scene *sc, tex_image *maps, tex_warn_fn warn, void *ctx, int threads)
{
    tex_job *jobs = calloc((size_t)(sc->nmaterials > 0 ? sc->nmaterials : 1), sizeof *jobs);
    int *job_of = calloc((size_t)(sc->nmaterials > 0 ? sc->nmaterials : 1), sizeof *job_of);
    int i, njobs = 0, loaded = 0;
    double spent = 0;
    for (i = 0; i < sc->nmaterials; i++) empty(&maps[i]);
    for (i = 0; jobs && job_of && i < sc->nmaterials; i++) {
        char note[1024];
        job_of[i] = -1;
        if (!sc->materials[i].map_kd.path) continue;
        job_of[i] = job_for(&sc->materials[i], jobs, &njobs, i, &spent, note, sizeof note);
        if (note[0]) {
            sc->nwarnings++;
            if (warn) warn(ctx, note);
        }
    }
    if (!jobs || !job_of || decode_all(jobs, njobs, maps, threads) < 0) {
        for (i = 0; i < sc->nmaterials; i++) tex_free(&maps[i]);
        for (i = 0; jobs && i < njobs; i++) free(jobs[i].data);
        for (i = 0; i < sc->nmaterials; i++)
            if (sc->materials[i].map_kd.path) {
                sc->nwarnings++;
                warn_map(&sc->materials[i], "out of memory", warn, ctx);
            }
        free(jobs);
        free(job_of);
        return 0;
    }
    /* In material order, as one thread would: the warnings, each a material's own line. */
    for (i = 0; i < sc->nmaterials; i++) {
        obj_material *m = &sc->materials[i];
        const tex_job *j = job_of[i] >= 0 ? &jobs[job_of[i]] : NULL;
        if (!j) continue;
        if (j->rc) {
            sc->nwarnings++;
            warn_map(m, j->err, warn, ctx);
            continue;
        }
        if (j->mat != i) {
            maps[i] = maps[j->mat];
            maps[i].borrowed = 1;
        }
        maps[i].clamp = m->map_kd.clamp;
        memcpy(maps[i].offset, m->map_kd.offset, sizeof maps[i].offset);
        memcpy(maps[i].scale, m->map_kd.scale, sizeof maps[i].scale);
        loaded++;
    }
    free(jobs);
    free(job_of);
    return loaded;
}
