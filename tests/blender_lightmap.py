# SPDX-License-Identifier: MIT
# Run by tests/test_gltf.c as: blender -b --factory-startup --python-exit-code 1
#   --python tests/blender_lightmap.py -- FILE.glb
# Imports FILE.glb with Blender's own glTF importer and reports, one line
# "lightmap: MATERIALS STRENGTH", how many materials show the image named "lightmap"
# through their Principled BSDF's Emission, sampled on the second UV map, and the
# Emission Strength they got (each such material's must be the same). Anything else
# (an import error, a material that shows it otherwise) raises: a non-zero exit.
import sys

import bpy
import numpy

# Debian's blender 3.4 importer uses numpy.bool, which numpy 1.24 removed (the
# package's bug, not the file's): give it back before importing.
if not hasattr(numpy, "bool"):
    numpy.bool = bool

path = sys.argv[sys.argv.index("--") + 1]
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=path)


def upstream(node, seen):
    """Every node feeding NODE, NODE included."""
    if node.name in seen:
        return
    seen[node.name] = node
    for inp in node.inputs:
        for link in inp.links:
            upstream(link.from_node, seen)


second_uv = set()
for obj in bpy.data.objects:
    if obj.type == "MESH" and len(obj.data.uv_layers) >= 2:
        second_uv.add(obj.data.uv_layers[1].name)
lit, strengths = 0, set()
for mat in bpy.data.materials:
    if not mat.node_tree:
        continue
    for node in mat.node_tree.nodes:
        if node.type != "BSDF_PRINCIPLED":
            continue
        seen = {}
        for link in node.inputs["Emission"].links:
            upstream(link.from_node, seen)
        images = [n for n in seen.values() if n.type == "TEX_IMAGE" and n.image and n.image.name == "lightmap"]
        if not images:
            continue
        uvs = [n.uv_map for n in seen.values() if n.type == "UVMAP"]
        if not uvs or not set(uvs) <= second_uv:
            raise SystemExit("%s: the lightmap not on the second UV map (%r, second %r)" % (mat.name, uvs, second_uv))
        lit += 1
        strengths.add(round(node.inputs["Emission Strength"].default_value, 5))
if len(strengths) > 1:
    raise SystemExit("different emission strengths %r" % sorted(strengths))
print("lightmap: %d %.9g" % (lit, strengths.pop() if strengths else 0))
