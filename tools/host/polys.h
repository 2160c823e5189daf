/* SPDX-License-Identifier: MIT */
/* rad host glue: an OBJ scene as the core's polygons. Faces of 3 or 4 vertices go as
 * they are (the core splits non-planar quads); larger ones are ear-clipped into
 * triangles. Kd becomes reflectance, Ke emission; each polygon's tag is its OBJ face
 * index. */
#ifndef RAD_TOOLS_POLYS_H
#define RAD_TOOLS_POLYS_H

#include "formats/obj.h"
#include "formats/texture.h"
#include "host/scene.h"

typedef void (*polys_warn_fn)(void *ctx, int line, const char *msg);

/* A malloc'd array of *N polygons (free it), or NULL when out of memory. Degenerate
 * polygons are skipped with a warning naming their OBJ line. */
sc_poly *polys_from_obj(const obj_scene *sc, int *n, polys_warn_fn warn, void *ctx);
/* The same, with the diffuse textures MAPS[material] (tools/formats/texture.h; NULL, or
 * a map without pixels: none): a face with texture coordinates whose material has one
 * gets, per polygon, the reflectance of the texture's mean over the polygon's UV
 * footprint (texture.h's rule applied to the mean, the same as to each texel below
 * TEX_RHO_MAX since it is linear there); a face without texture coordinates, that of
 * the image's mean (tex_image_mean). A surface per face, not per element: a surface
 * per element would make every element a patch (CornellBox-Original: 3,958 patches
 * instead of 278, as many more hemi-cubes to shoot); sc_texture_elements
 * (host/tex_render.h) then gives each element of a textured face the mean over its own
 * footprint. */
sc_poly *polys_from_obj_tex(const obj_scene *sc, const tex_image *maps, int *n, polys_warn_fn warn,
                            void *ctx);

/* Faces wound against their vertex normals turned round. A face is one-sided: it
 * receives and shows light on the side its winding faces (counter-clockwise). A face
 * most of whose corners with a vn (more than half of them) have a vn against its
 * geometric (Newell) normal, vn . n < 0, has its corners reversed (positions, vt and
 * vn together: each triangle of a larger face then turns with it). Faces without vn
 * are left as they are. Returns the count turned; *AREA (may be NULL) their share of
 * the scene's face area, 0..1. */
int polys_orient_by_normals(obj_scene *sc, double *area);

/* Two-sided faces: face F + N (N the faces before the call) becomes a copy of face F
 * with its corners reversed and its vn negated (new normals appended), so that both
 * sides of every face receive and show light as two one-sided faces back to back,
 * each with an element mesh, a lightmap chart and glTF faces of its own. Materials'
 * areas and face counts are left as the input's. 0, or -1 out of memory (the scene
 * unchanged). */
int polys_two_sided(obj_scene *sc);

/* The polygons of one material, for sc_set_surfaces: a tag (an OBJ face index, as
 * polys_from_obj sets it) matches when its face has material MATERIAL. */
typedef struct {
    const obj_scene *sc;
    int material;
} polys_material_match;

/* An sc_tag_match_fn over CTX, an polys_material_match: nonzero for the material's tags. */
int polys_match_material(void *ctx, int tag);

#endif
