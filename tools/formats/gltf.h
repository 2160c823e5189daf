/* SPDX-License-Identifier: MIT */
/* gltf — glTF 2.0 binary (.glb) export of an OBJ scene's own meshes, for engines
 * (uses malloc and stdio).
 *
 * What is written: the scene's nodes (obj_scene.nodes: a file read through assimp) with
 * their names, children and matrices, each node's faces its mesh in the node's frame (a
 * mirroring node's triangles wound as the file wound them: glTF turns them back); or,
 * without nodes (an OBJ), a node and a mesh per OBJ object or group (faces with the same o and
 * g names, in the order they first appear; faces before any o or g form "(default)"),
 * a primitive per material in each mesh, triangles (faces of 4 vertices as the fan
 * (0,1,2)(0,2,3), larger ones ear-clipped by obj_triangulate), and vertices welded per
 * (position, normal, texture coordinate, material): two corners are one vertex when
 * they have the same OBJ position and texture coordinate indices, the same normal
 * (their vn, else the face's unit normal) and the same material. Attributes: POSITION
 * (with min and max), NORMAL (unit), TEXCOORD_0 (the MTL's -s / -o applied, v flipped
 * to glTF's top-left origin; (0, 0) for a corner without one) when the primitive has
 * texture coordinates, COLOR_0 and _LIGHT when the caller gives corner colours: a welded
 * vertex's colour is the weighted mean of its corners', _LIGHT (float VEC3, an
 * application-specific attribute) that linear light as given, COLOR_0 (float VEC3) it
 * divided by the caller's scale and clamped to [0, 1] (glTF 2.0 3.7.2.1: COLOR_n
 * values are in [0, 1]), the scale in every material's extras as "colorScale"
 * (COLOR_0 x colorScale = _LIGHT where COLOR_0 < 1), TEXCOORD_1 when the
 * caller gives a lightmap UV per corner (see gltf_input). Materials: the
 * caller's baseColorFactor, baseColorTexture when the caller gives the texture file
 * (PNG or JPEG embedded in the binary chunk as they are; another format, such as BMP or
 * TGA, re-encoded as PNG from the caller's decoded image; without one it is left out
 * with a warning and the factor alone stays), KHR_materials_unlit (the colours are
 * lighting already computed; the materials a lightmap shows are lit by emission
 * instead: gltf_input). Names are JSON-escaped; bytes that are not UTF-8 become '?'.
 *
 * Layout: the 12-byte header, a JSON chunk padded with spaces and a BIN chunk padded
 * with zeros, both to 4 bytes; every bufferView starts at a multiple of 4 in the BIN
 * chunk. Written atomically through a temporary file renamed over PATH.
 */
#ifndef RAD_TOOLS_GLTF_H
#define RAD_TOOLS_GLTF_H

#include <stddef.h>

#include "formats/obj.h"
#include "formats/texture.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef void (*gltf_warn_fn)(void *ctx, const char *msg);

typedef struct {
    const obj_scene *sc;
    /* sc->nindices x 3 linear RGB, one per face corner, and their weights (e.g. the
       area they stand for; NULL: equal). NULL colours: no COLOR_0. */
    const double *corner_rgb;
    const double *corner_weight;
    /* The light one unit of COLOR_0 stands for (<= 0: 1). */
    double color_scale;
    /* sc->nmaterials x 3: each material's baseColorFactor (NULL: Kd). */
    const double *base_color;
    /* sc->nmaterials texture file paths (NULL, or a NULL entry: no texture). The
       sampler wraps (REPEAT) unless the material's map_kd.clamp. */
    const char *const *texture;
    /* sc->nmaterials decoded textures (NULL, or an entry without rgb: none): a texture
       file neither PNG nor JPEG is embedded as these pixels encoded as PNG. */
    const tex_image *texture_image;
    gltf_warn_fn warn;
    void *ctx;
    /* sc->nindices x 2: each face corner's lightmap UV, glTF's convention ([0, 1], origin
       at the image's top left), written as TEXCOORD_1 (with min and max); vertices are
       welded per that UV too. NULL: no TEXCOORD_1. */
    const double *corner_uv1;
    /* The lightmap, PNG bytes embedded as an image with a texture (CLAMP_TO_EDGE,
       LINEAR), and the light a texel stands for: SCALE times its sRGB-decoded value.
       A material whose LIGHTMAP_USE flag is set (NULL: every one) names it in its
       extras: "lightmap": {"index": texture, "texCoord": 1, "scale": SCALE}, and shows
       it where importers look (Blender, three.js, Godot, glTFast): not unlit, a black
       baseColorFactor (its texture kept), emissiveTexture the lightmap on TEXCOORD_1,
       emissiveFactor LIGHTMAP_FACTOR, KHR_materials_emissive_strength SCALE: the light
       leaving, reflectance x light arriving. */
    const unsigned char *lightmap_png;
    size_t lightmap_png_size;
    double lightmap_scale;
    const unsigned char *lightmap_use;
    /* sc->nmaterials x 3: the emissiveFactor of the materials the lightmap shows (NULL:
       their base colour). */
    const double *lightmap_factor;
} gltf_input;

/* Writes the scene IN to PATH as .glb. Returns 0, or -1 with a one-line message
 * "PATH: what is wrong" in err (PATH untouched). */
int gltf_write(const char *path, const gltf_input *in, char *err, size_t errlen);

#ifdef __cplusplus
}
#endif

#endif
