# Imports one of dla3d's files into an empty Blender scene and prints what Blender made of it
# as one JSON line: vertices, edges, faces, bounds (min, max), the attribute names, and the
# bounds of the active UV map's coordinates (uv: u min, v min, u max, v max; NaN without one).
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
uv = [float("inf")] * 2 + [float("-inf")] * 2
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
    if m.uv_layers.active is not None:
        import numpy
        coords = numpy.empty(2 * len(m.loops))
        m.uv_layers.active.data.foreach_get("uv", coords)
        coords = coords.reshape(-1, 2)
        if not numpy.isfinite(coords).all():
            raise SystemExit("a UV coordinate is not finite")
        uv = [min(uv[0], coords[:, 0].min()), min(uv[1], coords[:, 1].min()),
              max(uv[2], coords[:, 0].max()), max(uv[3], coords[:, 1].max())]
if uv[0] == float("inf"):
    uv = [float("nan")] * 4
print("DLA3D " + json.dumps({"objects": len(meshes), "vertices": vertices, "edges": edges, "faces": faces,
                            "min": lo, "max": hi, "uv": uv, "attributes": sorted(attributes)}))
