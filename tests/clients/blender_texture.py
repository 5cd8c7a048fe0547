# Textures dla3d's tube glb as an artist would: imports it, puts an image texture on the bark
# through its UV map (an orange and teal checker, CELLS cells around each tube and a square
# cell's length along it) and renders it with Cycles.
#   blender -b --factory-startup --python-exit-code 1 --python blender_texture.py -- \
#       TREE.glb OUT.png [WIDTH HEIGHT SAMPLES CELLS]
# 240 x 180 with 16 samples and 4 cells unless given (docs/look.md's picture is made by it too).
# Prints one JSON line after "DLA3D ": the UV maps the mesh came with.
import json
import os
import sys

import bpy
import numpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cycles_render  # noqa: E402  (tests/clients/cycles_render.py; Blender has a module "cycles")

args = sys.argv[sys.argv.index("--") + 1:]
glb, out = args[:2]
width, height, samples, cells = (int(a) for a in (args[2:] or [240, 180, 16, 4]))
bpy.ops.wm.read_factory_settings(use_empty=True)
if not hasattr(numpy, "bool"):  # Blender 3.4's glTF importer with Debian's numpy 1.24
    numpy.bool = bool
bpy.ops.preferences.addon_enable(module="io_scene_gltf2")
bpy.ops.import_scene.gltf(filepath=glb)
tree = next(o for o in bpy.context.scene.objects if o.type == "MESH")

# The checker: `cells` squares across the image, which repeats along the branches.
size = 16 * cells
image = bpy.data.images.new("checker", size, size)
ij = numpy.indices((size, size)) // 16
orange, teal = numpy.array([0.9, 0.35, 0.05, 1.0]), numpy.array([0.05, 0.55, 0.6, 1.0])
pixels = numpy.where(((ij[0] + ij[1]) % 2 == 0)[..., None], orange, teal)
image.pixels.foreach_set(pixels.astype(numpy.float32).ravel())
image.pack()

material = bpy.data.materials.new("bark")
material.use_nodes = True
nodes = material.node_tree.nodes
bsdf = next(n for n in nodes if n.type == "BSDF_PRINCIPLED")
texture = nodes.new("ShaderNodeTexImage")
texture.image = image
texture.interpolation = "Closest"
coordinates = nodes.new("ShaderNodeUVMap")
coordinates.uv_map = tree.data.uv_layers.active.name if tree.data.uv_layers.active else ""
material.node_tree.links.new(coordinates.outputs["UV"], texture.inputs["Vector"])
material.node_tree.links.new(texture.outputs["Color"], bsdf.inputs["Base Color"])
bsdf.inputs["Roughness"].default_value = 0.6
tree.data.materials.clear()
tree.data.materials.append(material)

cycles_render.render(tree, out, width, height, samples, view=(0.3, -1.0, 0.4), distance=3.2, sky=(0.2, 0.2, 0.2))

print("DLA3D " + json.dumps({"uv_maps": [layer.name for layer in tree.data.uv_layers]}))
