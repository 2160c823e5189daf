/* SPDX-License-Identifier: MIT */
/* rad host glue: the solution on the input's own meshes, exported as glTF 2.0
 * (tools/formats/gltf.h). Built once per build of the core, like host/scene.c (float
 * twin: scf_corner_light, scf_export_gltf). */
#ifndef RAD_TOOLS_GLTF_EXPORT_H
#define RAD_TOOLS_GLTF_EXPORT_H

#include "bake/lightmap.h"
#include "formats/gltf.h"
#include "formats/obj.h"
#include "formats/texture.h"
#include "host/fgather.h"
#include "host/scene.h"

/* For every face corner of SC (sc->nindices of them): the light arriving there, linear
 * RGB in caller units, into RGB[3 * corner], and the element area it was averaged over
 * into WEIGHT[corner] (0 when the face has no element). The light arriving at an element
 * is its radiosity (with the ambient term) less its emission, over its reflectance per
 * channel (0 where the reflectance is 0); at a corner, the area-weighted mean over the
 * elements of the corner's face that have a vertex there (the nearest element if none
 * has). A face that emits gets its radiosity itself, to be shown with a base colour of 1.
 * S must have been made from POLYS (N of them, tags = face indices: polys_from_obj).
 * Returns 0, or -1 when out of memory. */
int sc_corner_light(sc_solver *s, const obj_scene *sc, const sc_poly *polys, int n, double *rgb,
                    double *weight);
/* The same, the light arriving at each element's vertex gathered by FG (NULL: the
 * element's own, as sc_corner_light) on the faces that do not emit; PROGRESS (NULL:
 * none) gets the fraction of the faces done every SC_EXPORT_EVERY faces. 0 or -1. */
int sc_corner_light_fg(sc_solver *s, sc_fgather *fg, const obj_scene *sc, const sc_poly *polys,
                       int n, double *rgb, double *weight, sc_fraction_fn progress, void *pctx);

#define SC_EXPORT_EVERY 1024

/* Writes PATH (.glb) from the solved S of SC's POLYS (N) with the textures MAPS
 * (tex_load_materials; NULL: none): _LIGHT the light from sc_corner_light_fg with FG
 * (NULL: the elements'), COLOR_0 that over a scale (gltf.h): the largest channel at
 * the corners of faces that do not emit (of every face when all emit), at least 1, so
 * that only emitters brighter than the lit surfaces clamp; a material's
 * baseColorFactor is 1 where it emits (COLOR_0 is then its radiosity), else Kd, or 1
 * for a texture with Kd 0 (texture.h's rule), each at most TEX_RHO_MAX; its
 * baseColorTexture is its map_Kd file when MAPS holds it. Warnings (a texture left out)
 * go to WARN. Returns 0, or -1 with "PATH: what" in err. */
int sc_export_gltf(sc_solver *s, const obj_scene *sc, const sc_poly *polys, int n,
                   const tex_image *maps, sc_fgather *fg, const char *path, gltf_warn_fn warn,
                   void *ctx, char *err, size_t errlen);

/* sc_export_gltf with the lightmap LM (NULL: none) baked over POLYS: TEXCOORD_1 each
 * corner's place on the atlas (lm_corner_uvs), the atlas embedded as PNG (lm_png) and
 * named in the extras of every material that does not emit (gltf_input); COLOR_0's
 * scale into *COLOR_SCALE (NULL: not wanted); PROGRESS (NULL: none) the export's
 * fraction (its faces' corners, then 1 before the file is written). */
int sc_export_gltf_lightmap(sc_solver *s, const obj_scene *sc, const sc_poly *polys, int n,
                            const tex_image *maps, sc_fgather *fg, const lm_atlas *lm,
                            double *color_scale, const char *path, gltf_warn_fn warn, void *ctx,
                            sc_fraction_fn progress, void *pctx, char *err, size_t errlen);

#define RAD_TWIN_GLTF_EXPORT /* the float twin's names of the above (generated): */
#include "host/scene_float.h"

#endif
