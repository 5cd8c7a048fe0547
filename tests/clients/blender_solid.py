# Hands dla3d's solid to Blender as an artist or a maker would: imports the STL and the glb as
# meshes and runs the 3D-Print Toolbox's solid and intersection checks on them, imports the
# .vdb as a volume and lists its grids, and renders the solid and the volume with Cycles.
# Prints one JSON line after "DLA3D ".
#   blender -b --factory-startup --python-exit-code 1 --python blender_solid.py -- \
#       SOLID.stl SOLID.glb SOLID.vdb OUT [WIDTH HEIGHT SAMPLES]
# writes OUT_solid.png (the glb, in its vertex colours if it has them) and OUT_volume.png, 200 x
# 150 with 16 samples unless given (docs/solid.md's pictures are made by it too).
import json
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cycles_render  # noqa: E402  (tests/clients/cycles_render.py; Blender has a module "cycles")

args = sys.argv[sys.argv.index("--") + 1:]
stl, glb, vdb, out = args[:4]
width, height, samples = (int(a) for a in (args[4:] or [200, 150, 16]))
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.preferences.addon_enable(module="object_print3d_utils")
from object_print3d_utils import operators  # noqa: E402  (enabled just above)

result = {}


def meshes():
    return [o for o in bpy.context.scene.objects if o.type == "MESH"]


def checked(obj, name):
    """The toolbox's counts for one mesh: non-manifold edges, bad contiguous edges, faces that
    intersect."""
    info = []
    operators.MESH_OT_print3d_check_solid.main_check(obj, info)
    operators.MESH_OT_print3d_check_intersections.main_check(obj, info)
    counts = [len(found[1]) for _, found in info]
    result[name + "_non_manifold"], result[name + "_bad_contiguous"], result[name + "_intersecting"] = counts
    result[name + "_faces"] = len(obj.data.polygons)


bpy.ops.import_mesh.stl(filepath=stl)
result["stl_objects"] = len(meshes())
checked(meshes()[0], "stl")
solid = meshes()[0]

import numpy  # noqa: E402
if not hasattr(numpy, "bool"):  # Blender 3.4's glTF importer with Debian's numpy 1.24
    numpy.bool = bool
bpy.ops.preferences.addon_enable(module="io_scene_gltf2")
before = set(meshes())
bpy.ops.import_scene.gltf(filepath=glb)
imported = [o for o in meshes() if o not in before]
result["glb_objects"] = len(imported)
checked(imported[0], "glb")
solid.hide_render = True
solid = imported[0]

bpy.ops.object.volume_import(filepath=vdb)
volume = [o for o in bpy.context.scene.objects if o.type == "VOLUME"][0]
volume.data.grids.load()
result["grids"] = sorted(g.name for g in volume.data.grids)


def render(visible, path):
    cycles_render.render(visible, path, width, height, samples)


# Bark, or the vertex colours (--color-by) where the glb has them.
material = bpy.data.materials.new("bark")
material.use_nodes = True
bsdf = next((n for n in material.node_tree.nodes if n.type == "BSDF_PRINCIPLED"), None)
if bsdf is None:
    bsdf = material.node_tree.nodes.new("ShaderNodeBsdfPrincipled")
    surface = next(n for n in material.node_tree.nodes if n.type == "OUTPUT_MATERIAL")
    material.node_tree.links.new(bsdf.outputs["BSDF"], surface.inputs["Surface"])
bsdf.inputs["Base Color"].default_value = (0.8, 0.55, 0.3, 1.0)
bsdf.inputs["Roughness"].default_value = 0.5
colours = [c.name for c in getattr(solid.data, "color_attributes", [])]
if colours:
    attribute = material.node_tree.nodes.new("ShaderNodeAttribute")
    attribute.attribute_name = colours[0]
    material.node_tree.links.new(attribute.outputs["Color"], bsdf.inputs["Base Color"])
solid.data.materials.clear()
solid.data.materials.append(material)
render(solid, out + "_solid.png")

smoke = bpy.data.materials.new("smoke")
smoke.use_nodes = True
nodes = smoke.node_tree.nodes
nodes.clear()
principled = nodes.new("ShaderNodeVolumePrincipled")
principled.inputs["Density"].default_value = 20.0
principled.inputs["Color"].default_value = (0.9, 0.9, 1.0, 1.0)
output = nodes.new("ShaderNodeOutputMaterial")
smoke.node_tree.links.new(principled.outputs["Volume"], output.inputs["Volume"])
volume.data.materials.append(smoke)
render(volume, out + "_volume.png")

print("DLA3D " + json.dumps(result))
