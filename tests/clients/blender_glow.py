# Uses a discharge's .vdb as an artist would for a glow: imports it as a volume, gives it a
# material whose emission is its density grid (no scattering, no absorption), and renders it with
# Cycles on a black sky. Prints one JSON line after "DLA3D ": the grids and the volume's bounds.
#   blender -b --factory-startup --python-exit-code 1 --python blender_glow.py -- BOLT.vdb OUT.png \
#       [WIDTH HEIGHT SAMPLES]
# 200 x 150 with 16 samples unless given (docs/breakdown.md's recipe is this material).
import json
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cycles_render  # noqa: E402  (tests/clients/cycles_render.py)

args = sys.argv[sys.argv.index("--") + 1:]
vdb, out = args[:2]
width, height, samples = (int(a) for a in (args[2:] or [200, 150, 16]))
bpy.ops.wm.read_factory_settings(use_empty=True)

bpy.ops.object.volume_import(filepath=vdb)
volume = [o for o in bpy.context.scene.objects if o.type == "VOLUME"][0]
volume.data.grids.load()
result = {"grids": sorted(g.name for g in volume.data.grids),
          "size": max(volume.dimensions)}

glow = bpy.data.materials.new("glow")
glow.use_nodes = True
nodes, links = glow.node_tree.nodes, glow.node_tree.links
nodes.clear()
density = nodes.new("ShaderNodeAttribute")
density.attribute_name = "density"
strength = nodes.new("ShaderNodeMath")
strength.operation = "MULTIPLY"
strength.inputs[1].default_value = 40.0
emission = nodes.new("ShaderNodeEmission")
emission.inputs["Color"].default_value = (0.7, 0.8, 1.0, 1.0)
output = nodes.new("ShaderNodeOutputMaterial")
links.new(density.outputs["Fac"], strength.inputs[0])
links.new(strength.outputs["Value"], emission.inputs["Strength"])
links.new(emission.outputs["Emission"], output.inputs["Volume"])
volume.data.materials.append(glow)
cycles_render.render(volume, out, width, height, samples, sky=(0.0, 0.0, 0.0))

print("DLA3D " + json.dumps(result))
