/* SPDX-License-Identifier: MIT */
/* rad host glue: rendered views with the textures' detail. Built once per build of the
 * core, like host/scene.c (float twin: scf_render_textured). */
#ifndef RAD_TOOLS_TEX_RENDER_H
#define RAD_TOOLS_TEX_RENDER_H

#include "formats/obj.h"
#include "formats/texture.h"
#include "host/scene.h"

/* As sc_render, then every pixel of a textured surface that does not emit is multiplied
 * by the texture there over the surface's reflectance: B x rho(texel) / rho(surface),
 * since the light arriving, B / rho(surface), is what the solution knows at that scale
 * (texture.h's rule gives rho(texel)). The pixel's surface and texture coordinates come
 * from two more renders of the same view (sc_render_values): the surface's number, and
 * each core vertex's coordinates in its face's texture (barycentric in the face's
 * triangle that holds it best), so three renders in all. S was made from SC's faces
 * (obj_to_polys_tex, tags = faces) with MAPS (tex_load_materials). 0 or -1 with err. */
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

#ifndef RAD_HOST_FLOAT_NAMES
int scf_texture_detail(scf_solver *s, const obj_scene *sc, const tex_image *maps,
                       const sc_camera *cam, int w, int h, float *rgb, char *err, size_t errlen);
int scf_render_surfaces(scf_solver *s, const sc_camera *cam, int w, int h, int *surface, char *err,
                        size_t errlen);
int scf_render_textured(scf_solver *s, const obj_scene *sc, const tex_image *maps,
                        const sc_camera *cam, int ambient, int w, int h, float *rgb, char *err,
                        size_t errlen);
#endif

#endif
