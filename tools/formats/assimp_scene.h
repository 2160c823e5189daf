/* SPDX-License-Identifier: MIT */
/* assimp_scene — every scene format assimp reads (glTF 2.0 .gltf/.glb, FBX, COLLADA .dae,
 * 3DS, PLY, ...) into the same obj_scene the OBJ reader fills, so the solve, the views,
 * the bake and the exports take them unchanged. Built only where pkg-config finds assimp
 * (Debian libassimp-dev: RAD_HAVE_ASSIMP); elsewhere assimp_scene_load refuses with a
 * message saying how to get it. rad_cli reads .obj with its own reader (obj.h) and every
 * other extension with this one.
 *
 * What is kept:
 *   - every mesh of every node, its vertices moved by the node's transform and its
 *     parents' (normals by the inverse transpose; a mirroring transform reverses the
 *     faces' winding, so their front stays where the file put it); faces of fewer than
 *     three vertices (points, lines) are left out and counted in unknown_statements;
 *     each node's name is the faces' object name (obj_face.object); the hierarchy as
 *     obj_scene.nodes (names, parents, local and world transforms: what --export-gltf
 *     writes back), less the root assimp adds above several roots (no mesh, the
 *     identity);
 *   - the first texture coordinate set (assimp gives it with v up, as OBJ), the second
 *     (glTF's TEXCOORD_1, FBX's and COLLADA's second channel) per corner as
 *     obj_scene.uv2, the lightmap's UVs under --lightmap-uv, and the normals;
 *   - per material: the base colour (glTF baseColorFactor, else the diffuse colour) as
 *     Kd, the base colour or diffuse texture as map_Kd (a file beside the scene, or the
 *     bytes of an image the file holds: obj_map.data, named "SCENE/texture N
 *     (embedded)"; raw texels are not read: a warning, and the colour),
 *     the emissive colour times its intensity where the importer gives one (assimp
 *     5.2 reads no KHR_materials_emissive_strength: a glTF's emission is at most 1)
 *     as Ke, in the units of an MTL's Ke. Names are the file's, made unique with "#N".
 *   - the file's lights (glTF's KHR_lights_punctual, FBX, COLLADA, 3DS): directional,
 *     point and spot, placed by the node of their name, colour times intensity (glTF:
 *     candela for point and spot, lux for directional, taken as the units of Ke, whose
 *     exitance is then lux), a spot's cone from its half angles (glTF) or its full
 *     angles halved (assimp's rule for the other formats); ambient and area lights are
 *     left out and counted in unknown_statements. A glTF light's range is not used:
 *     light falls off as 1 / r^2.
 * Units are the file's: metres in glTF (its specification), metres in FBX (assimp
 * converts from centimetres: AI_CONFIG_FBX_CONVERT_TO_M), as written in the others.
 *
 * Every file assimp opens (the scene, a .gltf's buffers, an .mtl) is read through
 * file_io (fio_read_all: regular files only, at most FIO_LIMIT_OBJ bytes), so a FIFO,
 * a device or a huge file is refused as for an OBJ, and files outside the scene's
 * folder are refused as the OBJ reader refuses them (obj_opts). Errors are one line,
 * "FILE: what is wrong" (a file assimp cannot read: "FILE: not readable as a scene: "
 * and assimp's own words, as "Chunk is too large" for a cut .3ds); warnings go to WARN
 * in the OBJ reader's form.
 */
#ifndef RAD_TOOLS_ASSIMP_SCENE_H
#define RAD_TOOLS_ASSIMP_SCENE_H

#include <stddef.h>

#include "formats/obj.h"

#ifdef __cplusplus
extern "C" {
#endif

/* 1 if this build reads other formats through assimp, else 0. */
int assimp_scene_available(void);
/* 1 if PATH is to be read by assimp_scene_load: its extension is not .obj (any case),
 * and it is not "-" (standard input, which obj_load_opts reads as OBJ). */
int assimp_scene_wants(const char *path);
/* Loads PATH into *SC (cleared first) as described above, with obj_load_opts's OPTS
 * (NULL: the defaults): unless opts->allow_outside, a file the scene names outside its
 * folder (a buffer, a library: refused, the scene not loaded; a texture: a warning, and
 * the material keeps its colour) is not read. Returns 0, or -1 with the message in err
 * and *SC empty. */
int assimp_scene_load(const char *path, const obj_opts *opts, obj_scene *sc, obj_warn_fn warn,
                      void *ctx, char *err, size_t errlen);

#ifdef __cplusplus
}
#endif

#endif
