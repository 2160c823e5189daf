/* SPDX-License-Identifier: MIT */
/* rad host glue: rendered views with the textures' detail. Built once per build of the
 * core, like host/scene.c (float twin: scf_render_textured). */
#ifndef RAD_TOOLS_TEX_RENDER_H
#define RAD_TOOLS_TEX_RENDER_H

#include "formats/obj.h"
#include "formats/texture.h"
#include "host/scene.h"

/* Gives every element of a textured face (a material with a map, texture coordinates,
 * no emission) of more than one element the reflectance of the texture's mean over its
 * own UV footprint: its corners mapped to UV as below (uv_at), tex_polygon_mean over
 * them, texture.h's rule (sc_set_element_rho). Untextured faces keep their surface's,
 * and a scene without textured faces is not touched (its bits stay). Call before the
 * first solve. Returns the elements set, or -1 with err. */
int sc_texture_elements(sc_solver *s, const obj_scene *sc, const tex_image *maps, char *err,
                        size_t errlen);

/* As sc_render, then every pixel of a textured surface that does not emit is multiplied
 * by the texture there over the reflectance the solution used there: B x rho(texel) /
 * rho(element), rho(element) interpolated from the vertices as B is (each vertex the
 * area-weighted mean of its surface's elements around it; the surface's reflectance
 * when elements have none of their own), since the light arriving, B / rho(element), is
 * what the solution knows at that scale (texture.h's rule gives rho(texel)). The pixel's surface and texture coordinates come
 * from two more renders of the same view (sc_render_values): the surface's number, and
 * each core vertex's coordinates in its face's texture (barycentric in the face's
 * triangle that holds it best), and with elements' own reflectances one of those, so
 * three or four renders in all. S was made from SC's faces
 * (polys_from_obj_tex, tags = faces) with MAPS (tex_load_materials). 0 or -1 with err. */
int sc_render_textured(sc_solver *s, const obj_scene *sc, const tex_image *maps,
                       const sc_camera *cam, int ambient, int w, int h, float *rgb, char *err,
                       size_t errlen);

/* The second half of sc_render_textured: RGB, a render of CAM (w x h) by any means,
 * gets the textures' detail. 0 or -1 with err. */
int sc_texture_detail(sc_solver *s, const obj_scene *sc, const tex_image *maps,
                      const sc_camera *cam, int w, int h, float *rgb, char *err, size_t errlen);

/* Per pixel of CAM's w x h view: the core surface drawn there, -1 where none (or a
 * crack filled from its neighbours), from a render of each surface's number. 0 or -1
 * with err. */
int sc_render_surfaces(sc_solver *s, const sc_camera *cam, int w, int h, int *surface, char *err,
                       size_t errlen);

#define RAD_TWIN_TEX_RENDER /* the float twin's names of the above (generated): */
#include "host/scene_float.h"

#endif
