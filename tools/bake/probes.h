/* SPDX-License-Identifier: MIT */
/* probes — light probes: the radiosity seen from points of a grid over the scene (or
 * read from a file) in L2 spherical harmonics, written as JSON (uses malloc, stdio).
 *
 * A probe inside geometry (in a wall, a closed box) sees the back faces of what holds
 * it: 26 rays from it (the directions of a cube's faces, edges and corners, turned by
 * the rotation of rows (1, 2, 2) / 3, (2, 1, -2) / 3, (-2, 2, -1) / 3 so that none runs
 * along the edges of a scene built on its axes) are followed to the first polygon they
 * meet, and a probe whose rays meet back faces more than half the time is flagged
 * "inside": its light is what the inside of the geometry shows, to be ignored or
 * replaced by a neighbour's.
 *
 * Points files: one probe a line, "X Y Z" (world units), blank lines and lines starting
 * with # ignored; at most PR_MAX_PROBES; read through file_io (FIO_LIMIT_TEXT). Errors
 * are one line, "FILE:LINE: what is wrong" or "PATH: what", in a caller buffer.
 */
#ifndef RAD_TOOLS_PROBES_H
#define RAD_TOOLS_PROBES_H

#include <stddef.h>

#include "host/scene.h"

#define PR_MAX_GRID   256 /* probes along one axis of a grid */
#define PR_MAX_PROBES 1000000

/* The nine SH coefficients (rad_gather_sh's order, 3 channels each) seen from P. */
typedef int (*pr_gather_fn)(void *ctx, const double p[3], double sh[9][3]);

typedef struct {
    double p[3];
    double sh[9][3];
    double back; /* fraction of the 26 rays that met a back face first */
    int inside;  /* back > 0.5 */
} pr_probe;

/* Parses "NX,NY,NZ" (each 1..PR_MAX_GRID, at most PR_MAX_PROBES in all). 0, or -1 with
 * err. */
int pr_parse_grid(const char *text, int dims[3], char *err, size_t errlen);
/* The points of a grid of DIMS over the box around POLYS: the centres of its cells
 * (so no probe lies on the box's walls). A malloc'd array of 3 DIMS products. */
double *pr_grid_points(const sc_poly *polys, int n, const int dims[3]);
/* Reads PATH's points into a malloc'd array of 3 *N doubles. NULL with err. */
double *pr_read_points(const char *path, int *n, char *err, size_t errlen);
/* Flags and gathers N probes at PTS into OUT. 0, or -1 with err (a gather failed: a
 * point outside the scene's frame, or FN stopped). */
int pr_bake(const sc_poly *polys, int npolys, const double *pts, int n, pr_gather_fn fn, void *ctx,
            pr_probe *out, char *err, size_t errlen);
/* Writes the probes as JSON (DIMS: the grid's, or NULL for points read from a file):
 * {"format": "rad-probes-1", "sh_order": [...], "grid": [nx, ny, nz] or null,
 *  "probes": [{"p": [x, y, z], "inside": false, "back": f, "sh": [[r, g, b] x 9]}, ...]}
 * through file_io (atomic). 0, or -1 with err. */
int pr_write_json(const char *path, const pr_probe *pr, int n, const int *dims, char *err,
                  size_t errlen);

#endif
