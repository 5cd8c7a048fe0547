# Imports a dla3d glb with leaves (--leaf) into an empty Blender scene and prints one JSON line
# after "DLA3D ": each leaf object's name, world location, and the world direction of its
# mesh's stem axis (glTF's +Y, Blender's +Z after the importer's turn) with that axis's length
# (the leaf's scale); and how many meshes the leaf objects use between them. With OUT.png, it
# also renders the tree with its leaves in Cycles (docs/look.md's picture is made so).
#   blender -b --factory-startup --python-exit-code 1 --python blender_leaves.py -- \
#       TREE.glb [OUT.png WIDTH HEIGHT SAMPLES]
import json
import os
import sys

import bpy
import mathutils
import numpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cycles_render  # noqa: E402  (tests/clients/cycles_render.py)

args = sys.argv[sys.argv.index("--") + 1:]
bpy.ops.wm.read_factory_settings(use_empty=True)
if not hasattr(numpy, "bool"):  # Blender 3.4's glTF importer with Debian's numpy 1.24
    numpy.bool = bool
bpy.ops.preferences.addon_enable(module="io_scene_gltf2")
bpy.ops.import_scene.gltf(filepath=args[0])

tree = bpy.data.objects["dla"]
leaves = [o for o in bpy.context.scene.objects if o.type == "MESH" and o.name.startswith("leaf ")]
found = []
for o in leaves:
    stem = o.matrix_world.to_3x3() @ mathutils.Vector((0.0, 0.0, 1.0))
    found.append([o.name, *o.matrix_world.translation, *stem.normalized(), stem.length])
print("DLA3D " + json.dumps({"meshes": len({o.data.name for o in leaves}),
                             "parent": leaves[0].parent.name if leaves and leaves[0].parent else "",
                             "leaves": found}))
if len(args) > 1:
    width, height, samples = (int(a) for a in args[2:5])
    cycles_render.render(tree, args[1], width, height, samples, view=(0.3, -1.0, 0.35), distance=2.6,
                         sky=(0.35, 0.38, 0.42), also=leaves)
