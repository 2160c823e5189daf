/* SPDX-License-Identifier: MIT */
/* texture — diffuse textures (MTL map_Kd) for the host tools: decoded with stb_image
 * (Debian libstb-dev, linked as libstb), sampled in linear light.
 *
 * Decoding is bounded before it starts: the file is read through file_io (at most
 * FIO_LIMIT_IMAGE bytes), stbi_info_from_memory reads the declared size from the header,
 * and an image of more than TEX_MAX_PIXELS is refused without being decoded (a
 * decompression bomb declares a huge size in a small file). The format comes from the
 * content (PNG, JPEG, BMP, TGA only: tex_decode), never from the file name. Pixels are kept as the file's 8-bit sRGB (3 bytes a
 * texel) and decoded to linear on sampling, through the IEC 61966-2-1 formula.
 *
 * Coordinates: (u, v) = (0, 0) is the image's bottom-left corner, (1, 1) its top-right
 * (OBJ's convention; row 0 of the decoded image is its top). Texel (x, y) has its centre
 * at ((x + 0.5) / w, 1 - (y + 0.5) / h). Sampling is bilinear between texel centres,
 * wrapped (repeat) or clamped to the edge.
 *
 * Reflectance (the rule the tools follow): a texel's reflectance is its linear value
 * times Kd when Kd is not all zero, else the texture alone (exporters write Kd 0 0 0
 * beside map_Kd), each channel kept at most TEX_RHO_MAX. A map that cannot be used is
 * one warning naming the MTL line and the file, and the material keeps its Kd (0.5 grey
 * if Kd is 0: obj_map_fallback).
 *
 * Errors are one line, "PATH: what is wrong", copied into a caller buffer (which may be
 * NULL or of length 0).
 */
#ifndef RAD_TOOLS_TEXTURE_H
#define RAD_TOOLS_TEXTURE_H

#include <stddef.h>

#include "formats/obj.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Largest image decoded: 2^26 texels (8192 x 8192), 192 MiB as 8-bit RGB; stb_image
 * needs about as much again while it decodes. */
#define TEX_MAX_PIXELS   (1L << 26)
/* Longest side decoded: 16384 texels (a 4 x 2^24 PNG of 423 KB took 1 GB, its row sums
 * mostly: 48 bytes a row however narrow). */
#define TEX_MAX_SIDE     16384
/* What one scene's maps may take together: each distinct file's bytes while it decodes
 * plus its decoded texels (3 bytes) and row sums (1.5 bytes a texel + 48 a row),
 * 1 GiB: three maps of 8192 x 8192. A map past what is left is refused unread. */
#define TEX_BUDGET       (1024.0 * 1024 * 1024)
/* Largest reflectance a texel gives: the core's largest below 1 (Q16.16). */
#define TEX_RHO_MAX      (65535.0 / 65536.0)
/* A triangle's mean is taken over at most TEX_MEAN_MAX_DIV^2 samples (see
 * tex_triangle_mean). */
#define TEX_MEAN_MAX_DIV 64
#define TEX_ROW_BLOCK    16

typedef struct {
    int w, h;
    unsigned char *rgb;         /* w * h * 3 bytes of sRGB, row 0 at the top; NULL: no image */
    int clamp;                  /* 1: coordinates clamped to the edge texels; 0: wrapped */
    double offset[2], scale[2]; /* (u, v) used = (u, v) * scale + offset (map -o, -s) */
    int borrowed;               /* 1: rgb belongs to another map (the same file): not freed here */
    /* The sums of each row's linear texels at every TEX_ROW_BLOCK-th texel: (y nb + b) 3 + k
       holds channel k of row y's texels x < b TEX_ROW_BLOCK, nb = w / TEX_ROW_BLOCK + 1
       (1.5 bytes a texel beside rgb's three); NULL if memory ran out (means then sample).
       Shared with rgb by a borrowed map. */
    double *row_sums;
} tex_image;

typedef void (*tex_warn_fn)(void *ctx, const char *msg); /* "MTL:LINE: text" */

/* Decodes SIZE bytes of PNG, JPEG, BMP or TGA into *out, as 8-bit RGB (alpha dropped,
 * grey expanded, 16-bit reduced). The format is recognised from the bytes before stb_image
 * sees them (PNG, JPEG, BMP by magic; TGA by a strict header check: colour-mapped with
 * 8-bit indices, true colour 15/16/24/32 bits, grey 8/16); anything else (GIF, PSD, HDR,
 * PNM: stb_image 2.27 crashes or hangs on some) is refused naming the format it seems to
 * be. A BMP or TGA must hold the bytes its header implies (RLE TGA: every packet,
 * walked), a JPEG its segments up to the end-of-image marker; else "truncated: ...".
 * NAME is used in messages. Returns 0, or -1 with err and *out empty. */
int tex_decode(const unsigned char *data, size_t size, const char *name, tex_image *out, char *err,
               size_t errlen);
/* Reads PATH (file_io, at most FIO_LIMIT_IMAGE bytes) and decodes it as above. */
int tex_load(const char *path, tex_image *out, char *err, size_t errlen);
/* Frees the pixels (unless borrowed) and empties *t. NULL-safe and idempotent. */
void tex_free(tex_image *t);

/* The sRGB transfer function's inverse (IEC 61966-2-1) for s in [0, 1]. */
double tex_srgb_decode(double s);
/* Texel (x, y)'s linear RGB (x, y inside the image). */
void tex_texel(const tex_image *t, int x, int y, double rgb[3]);
/* Bilinear sample at (u, v) (before the map's scale and offset), linear RGB. */
void tex_sample(const tex_image *t, double u, double v, double rgb[3]);
/* The area-weighted mean of the bilinear texture over the triangle UV[0..2] of
 * texture space (an element's footprint). Up to TEX_MEAN_MAX_DIV / 4 texels across:
 * the mean of samples at the centroids of the n^2 congruent triangles that split it, n
 * about four a texel along its longest edge (exact for a texture linear over the
 * triangle). Larger: integrated exactly along lines of constant v, two a texel row,
 * from the row sums (a sampling lattice coarser than the texels would beat with any
 * period of the image); the sampler again if they are missing or the footprint spans
 * more than 65,536 texel rows, and for a footprint of no area (two or three equal vt,
 * vt on a line: thinner than 1e-6 of its longest edge), whose samples then lie along
 * its segment (at a point: the texel sample there). Never fails: every mean (here and
 * in tex_polygon_mean) is finite and in [0, 1], as a convex combination of texels is;
 * wrapped coordinates are moved by whole periods first, so u, v of +-1e6 or negative
 * give the 0..1 layout's mean. */
void tex_triangle_mean(const tex_image *t, const obj_vec2 uv[3], double rgb[3]);
/* Values tex_polygon_mean keeps for the elements of a lattice, which share edges: a
 * caller's, of any content at first (it clears itself for another image). */
#define TEX_MEMO_ENTRIES 256
typedef struct {
    double x, y0, y1, g[3];
    int used;
} tex_memo_entry;
typedef struct {
    const void *image;
    tex_memo_entry e[TEX_MEMO_ENTRIES];
} tex_memo;

/* The area-weighted mean over the convex polygon POS[0 .. N-1] (3 or 4 corners, in
 * space) of texture coordinates UV: tex_triangle_mean over the fan from corner 0, each
 * triangle weighted by its area in space (the map from a face to UV is affine on each,
 * so area in UV is area on the face). A face's or an element's footprint. A quad
 * whose footprint is a rectangle along the texel axes is integrated exactly instead,
 * from the row sums, a row integral a texel row and edge; MEMO (NULL: none) keeps the
 * edges' for the next elements. */
void tex_polygon_mean(const tex_image *t, const double (*pos)[3], const obj_vec2 *uv, int n,
                      tex_memo *memo, double rgb[3]);
/* The mean of the texels, linear: the bilinear texture's mean over a period (each
 * texel's tent integrates to one texel) when wrapped. */
void tex_image_mean(const tex_image *t, double rgb[3]);
/* The reflectance rule above: TEXEL (linear) times KD, or TEXEL alone if KD is 0. */
void tex_reflectance(const double kd[3], const double texel[3], double rho[3]);

/* Loads every material's map_Kd into maps[0 .. sc->nmaterials - 1] (maps[i].rgb NULL
 * when material i has none or it fails), the files decoded on THREADS threads (1 or
 * less: the calling thread; the results and warnings are the same). Materials naming
 * the same file (the same device and inode, however spelt: ./a.png, a.png, a link)
 * share one decoded image (the first one's; the others borrow it: free them all
 * together, in any order). The files are read and their headers checked in material
 * order first, each charged to the scene's TEX_BUDGET: a map past what is left is
 * refused undecoded. A name that does not exist is matched ignoring case in its folder
 * (the file found replaces map_kd.path, with one warning "MTL:LINE: map_Kd: FILE: no
 * such file; using FOUND (the name differs in case)", counted in sc->nwarnings). A
 * failure is one warning per material naming the file, "MTL:LINE: map_Kd: FILE: reason;
 * using Kd R G B" (counted in sc->nwarnings), in material order, and obj_map_fallback
 * on the material. Returns the number of textures loaded. */
int tex_load_materials(obj_scene *sc, tex_image *maps, tex_warn_fn warn, void *ctx, int threads);

#ifdef __cplusplus
}
#endif

#endif
