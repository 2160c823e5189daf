/* SPDX-License-Identifier: MIT */
/* rad host glue: the element mesh and its solution as PLY (tools/formats/ply.h). Built
 * once per build of the core, like host/scene.c (float twin: scf_export_ply). */
#ifndef RAD_TOOLS_PLY_EXPORT_H
#define RAD_TOOLS_PLY_EXPORT_H

#include <stddef.h>

#include "formats/ply.h"
#include "host/scene.h"

/* Writes PATH in FORMAT (ply.h) from S: the core's vertices (caller units) with the
 * colours RGB (3 per vertex, linear, caller units: sc_shade's radiosity, or any other
 * per-vertex colour) and their surface's unit normal, a face per element. The header's
 * comment names the colours and EXPOSURE (the images'; PLY_ASCII_SRGB's colours are
 * encoded at it). Returns the vertices written, or -1 with "PATH: what" in err. */
int sc_export_ply(sc_solver *s, const double *rgb, const char *path, int format, double exposure,
                  char *err, size_t errlen);

#define RAD_TWIN_PLY_EXPORT /* the float twin's names of the above (generated): */
#include "host/scene_float.h"

#endif
