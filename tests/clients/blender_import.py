# Imports one of dla3d's files into an empty Blender scene and prints what Blender made of it
# as one JSON line: vertices, edges, faces, bounds (min, max) and the attribute names.
#   blender -b --factory-startup --python-exit-code 1 --python blender_import.py -- FILE
import json
import sys

import bpy

path = sys.argv[sys.argv.index("--") + 1]
bpy.ops.wm.read_factory_settings(use_empty=True)
if path.endswith(".glb"):
    import numpy
    if not hasattr(numpy, "bool"):  # Blender 3.4's glTF importer with Debian's numpy 1.24
        numpy.bool = bool
    bpy.ops.preferences.addon_enable(module="io_scene_gltf2")
    bpy.ops.import_scene.gltf(filepath=path)
elif path.endswith(".obj"):
    bpy.ops.import_scene.obj(filepath=path)
elif path.endswith(".ply"):
    bpy.ops.import_mesh.ply(filepath=path)
else:
    raise SystemExit(f"cannot import {path}")

meshes = [o for o in bpy.context.scene.objects if o.type == "MESH"]
vertices = edges = faces = 0
lo = [float("inf")] * 3
hi = [float("-inf")] * 3
attributes = set()
for o in meshes:
    m = o.data
    vertices += len(m.vertices)
    edges += len(m.edges)
    faces += len(m.polygons)
    for v in m.vertices:
        p = o.matrix_world @ v.co
        for a in range(3):
            lo[a] = min(lo[a], p[a])
            hi[a] = max(hi[a], p[a])
    attributes.update(a.name for a in m.attributes)
    attributes.update(c.name for c in getattr(m, "color_attributes", []))
print("DLA3D " + json.dumps({"objects": len(meshes), "vertices": vertices, "edges": edges, "faces": faces,
                            "min": lo, "max": hi, "attributes": sorted(attributes)}))
