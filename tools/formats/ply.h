/* SPDX-License-Identifier: MIT */
/* ply — a mesh with vertex colours as a PLY file (Turk's polygon file format), in one
 * of two forms (uses malloc and stdio):
 *
 *   PLY_ASCII_SRGB     "format ascii 1.0": x y z (%.7g) and uchar red green blue, the
 *                      linear colour times EXPOSURE, clamped and sRGB-encoded as the
 *                      images are (image.h's tonemap); every vertex as given.
 *   PLY_BINARY_LINEAR  "format binary_little_endian 1.0": float x y z, nx ny nz, red
 *                      green blue (the linear colour itself), vertices welded: two are
 *                      one when the nine floats written for them are equal bit for bit
 *                      (-0 written as +0), so a vertex keeps one normal and one colour
 *                      and faces that differ in either keep their own vertex.
 *
 * Faces are "property list uchar int vertex_indices", 3 or 4 indices each. Binary
 * values that are not finite are written as 0, beyond float's range as its largest.
 * Written atomically through file_io.h (fio_out): the old file stays intact on any
 * error.
 */
#ifndef RAD_TOOLS_PLY_H
#define RAD_TOOLS_PLY_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define PLY_ASCII_SRGB    0
#define PLY_BINARY_LINEAR 1

typedef struct {
    int nv, nf;
    const double *pos;    /* nv x 3 */
    const double *rgb;    /* nv x 3, linear */
    const double *normal; /* nv x 3, unit (PLY_BINARY_LINEAR only) */
    const int *face;      /* nf x 4 vertex ids in [0, nv); face[4 f + 3] < 0: a triangle */
    const char *comment;  /* a "comment" line of the header (no newline), or NULL */
} ply_mesh;

/* Writes M to PATH in FORMAT (EXPOSURE scales PLY_ASCII_SRGB's colours). Returns the
 * vertices written (welded ones counted once), or -1 with "PATH: what" in err. */
int ply_write(const char *path, const ply_mesh *m, int format, double exposure, char *err,
              size_t errlen);

#ifdef __cplusplus
}
#endif

#endif
