"""Run inside Blender (test_blender.py): install and enable the add-on, grow in an icosphere
with its operator, and check the curves (with links too), the tube mesh, the solid and the
leaves it makes.

    blender -b --factory-startup --python blender_addon_check.py -- ADDON PYTHONPATH [RENDER.png]
"""

import sys

import bpy
import mathutils
import numpy as np

addon, module_path = sys.argv[sys.argv.index("--") + 1:][:2]
render = sys.argv[sys.argv.index("--") + 3:][:1]
sys.path.insert(0, module_path)
import dla3d  # noqa: E402

bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.preferences.addon_install(filepath=addon)
bpy.ops.preferences.addon_enable(module="dla3d_blender")

RADIUS = 10.0
bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=3, radius=RADIUS, location=(0, 0, 0))
sphere = bpy.context.active_object
settings = bpy.context.scene.dla3d
settings.model, settings.count, settings.rng_seed, settings.seeds = "grow", 3000, 4, 2
settings.output = 'CURVES'
assert bpy.ops.dla3d.grow() == {'FINISHED'}
curves = [o for o in bpy.context.scene.objects if o.type == 'CURVES']
assert len(curves) == 1, curves
data = curves[0].data

# The structure the module grows for the same options: what the operator should have made.
from dla3d_blender import grow_options  # noqa: E402
bpy.context.view_layer.objects.active = sphere
options = grow_options(settings, sphere, bpy.context.evaluated_depsgraph_get())
expected = dla3d.grow(**options)
ids, starts = expected.strands()
assert len(data.curves) == len(starts) - 1, (len(data.curves), len(starts) - 1)
assert len(data.points) == len(ids), (len(data.points), len(ids))
positions = np.empty(len(data.points) * 3)
data.points.foreach_get("position", positions)
positions = positions.reshape(-1, 3)
np.testing.assert_allclose(positions, expected.positions[ids], atol=1e-4)
# Every point inside the sphere (the icosphere's faces lie within RADIUS of its centre).
assert np.linalg.norm(positions, axis=1).max() < RADIUS, np.linalg.norm(positions, axis=1).max()
radius = np.empty(len(data.points))
data.points.foreach_get("radius", radius)
look = expected.radius
assert look.min() > 0 and abs(radius.min() - look.min()) < 1e-5 and abs(radius.max() - look.max()) < 1e-5
# With a mesh the taper runs from 3 spacings at the seed to 0.05 at the tips.
assert look.max() <= 3.0 * expected.spacing + 1e-6 and look.min() >= 0.05 * expected.spacing - 1e-6
age = np.empty(len(data.points))
data.attributes["age"].data.foreach_get("value", age)
np.testing.assert_allclose(age, expected.age[ids], atol=1e-6)
assert age.min() == 0.0 and age.max() == 1.0

# The tube mesh, with the age per vertex.
settings.output, settings.sides = 'MESH', 6
bpy.context.view_layer.objects.active = sphere
assert bpy.ops.dla3d.grow() == {'FINISHED'}
tubes = [o for o in bpy.context.scene.objects if o.type == 'MESH' and o is not sphere]
assert len(tubes) == 1
vertices, _normals, faces = expected.tubes(sides=6)
assert len(tubes[0].data.vertices) == len(vertices) and len(tubes[0].data.polygons) == len(faces)
assert "age" in tubes[0].data.attributes
# Its UV map: each face corner has its vertex's texture coordinates, v turned up as Blender's.
expected_tubes = expected.tubes(sides=6)
uv_layer = tubes[0].data.uv_layers.active
assert uv_layer is not None and uv_layer.name == "UVMap"
corner_uv = np.empty(2 * len(tubes[0].data.loops))
uv_layer.data.foreach_get("uv", corner_uv)
want = expected_tubes.uv[expected_tubes.faces.ravel()].astype(np.float64)
want[:, 1] = 1.0 - want[:, 1]
assert np.isfinite(corner_uv).all() and np.allclose(corner_uv.reshape(-1, 2), want, atol=1e-5)
# The solid: one closed mesh, with the age per vertex.
settings.output, settings.voxel = 'SOLID', 0.1  # the tips (0.05 spacings) drawn 0.15 across
bpy.context.view_layer.objects.active = sphere
assert bpy.ops.dla3d.grow() == {'FINISHED'}
solids = [o for o in bpy.context.scene.objects if o.type == 'MESH' and o not in (sphere, tubes[0])]
assert len(solids) == 1
solid = expected.solid(solid_voxel=0.1)
# Grown in Blender's own copy of the sphere, the structure matches to 1e-4 (above), and its solid
# to within a few vertices of the thousands.
made = np.array([len(solids[0].data.vertices), len(solids[0].data.polygons)])
assert (np.abs(made - [len(solid.vertices), len(solid.faces)]) <= 1e-3 * made).all(), (made, len(solid.faces))
assert "age" in solids[0].data.attributes
import bmesh  # noqa: E402
closed = bmesh.new()
closed.from_mesh(solids[0].data)
assert all(edge.is_manifold for edge in closed.edges), "the solid has an open or non-manifold edge"
closed.free()
solids[0].hide_render = True

# Leaves: linked duplicates of a leaf object at every second tip, along the branch, as large as
# the room around it.
bpy.ops.mesh.primitive_plane_add(size=0.5, location=(30, 0, 0))
leaf = bpy.context.active_object
settings.output, settings.leaf, settings.leaf_every = 'CURVES', leaf, 2
bpy.context.view_layer.objects.active = sphere
assert bpy.ops.dla3d.grow() == {'FINISHED'}
bpy.context.view_layer.objects.active = sphere
leafy = dla3d.grow(**grow_options(settings, sphere, bpy.context.evaluated_depsgraph_get()))
points = leafy.instances()
assert len(points.positions) > 20 and len(points.positions) == len(points.particle)
assert len(points.positions) < (leafy.tip.sum() + 1) // 2 + 1
copies = [o for o in bpy.context.scene.objects if o.data is leaf.data and o is not leaf]
assert len(copies) == len(points.positions), (len(copies), len(points.positions))
assert all(copy.parent is not None and copy.parent.name.endswith("leaves") for copy in copies)
by_place = sorted(copies, key=lambda o: tuple(o.matrix_world.translation))
order = np.lexsort(points.positions.T[::-1])
for copy, k in zip(by_place, order):
    matrix = copy.matrix_world
    np.testing.assert_allclose(matrix.translation, points.positions[k], atol=1e-4)
    stem = matrix.to_3x3() @ mathutils.Vector((0, 0, 1))
    assert abs(stem.length - points.scale[k]) < 1e-4 * points.scale[k] + 1e-6, (stem.length, points.scale[k])
    assert stem.normalized().dot(mathutils.Vector(points.directions[k])) > 1 - 1e-5
settings.leaf = None
for placed in copies + [leaf] + [o for o in bpy.context.scene.objects if o.name.endswith("leaves")]:
    placed.hide_render = True
[o for o in bpy.context.scene.objects if o.type == 'CURVES' and o is not curves[0]][0].hide_render = True

# Links: a curve of two points each after the strands.
settings.output, settings.links = 'CURVES', 2.0
bpy.context.view_layer.objects.active = sphere
assert bpy.ops.dla3d.grow() == {'FINISHED'}
looped = [o for o in bpy.context.scene.objects if o.type == 'CURVES' and o is not curves[0] and not o.hide_render]
assert len(looped) == 1
bpy.context.view_layer.objects.active = sphere
linked = dla3d.grow(**grow_options(settings, sphere, bpy.context.evaluated_depsgraph_get()))
assert len(linked.links) > 0
assert len(looped[0].data.curves) == len(linked.strands()[1]) - 1 + len(linked.links), len(looped[0].data.curves)
looped[0].hide_render = True

print(f"dla3d add-on: {len(data.curves)} curves, {len(data.points)} points, radii "
      f"{radius.min():.4f}-{radius.max():.4f}; {len(vertices)} tube vertices")

if render:
    # The picture of docs/python.md: the curves in a glass sphere, by Cycles.
    tubes[0].hide_render = True
    glass = bpy.data.materials.new("glass")
    glass.use_nodes = True
    bsdf = glass.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Alpha"].default_value = 0.12  # a faint skin, so the branches show through
    bsdf.inputs["Roughness"].default_value = 0.1
    sphere.data.materials.append(glass)
    sphere.data.polygons.foreach_set("use_smooth", [True] * len(sphere.data.polygons))
    wood = bpy.data.materials.new("branches")
    wood.use_nodes = True
    wood.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (0.8, 0.35, 0.1, 1)
    curves[0].data.materials.append(wood)
    bpy.ops.object.camera_add(location=(0, -40, 0), rotation=(1.5708, 0, 0))
    bpy.context.scene.camera = bpy.context.active_object
    bpy.ops.object.light_add(type='SUN', rotation=(0.6, 0.3, 0.8))
    bpy.context.active_object.data.energy = 4
    world = bpy.data.worlds.new("world")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.6, 0.65, 0.7, 1)
    bpy.context.scene.world = world
    scene = bpy.context.scene
    scene.render.engine = 'CYCLES'
    scene.cycles.device = 'CPU'
    scene.cycles.samples = 64
    scene.cycles.use_denoising = False  # Debian's Blender has no OpenImageDenoise
    scene.view_layers[0].cycles.denoising_store_passes = False
    scene.render.resolution_x, scene.render.resolution_y = 640, 480
    scene.render.filepath = render[0]
    bpy.ops.render.render(write_still=True)
