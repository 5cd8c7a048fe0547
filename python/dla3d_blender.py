"""dla3d's Blender add-on: grows a structure inside or around the selected mesh object.

Install it from Edit > Preferences > Add-ons > Install..., with the dla3d Python module
importable by Blender's Python (docs/python.md). The panel is in the 3D Viewport's sidebar
(N), tab "dla3d".
"""

bl_info = {
    "name": "dla3d",
    "author": "dla3d",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "View3D > Sidebar > dla3d",
    "description": "Grow DLA, space colonization or aggregates inside or around a mesh",
    "doc_url": "https://github.com/dla3d/dla3d/blob/main/docs/python.md",
    "category": "Add Curve",
}

import bpy
import mathutils
import numpy as np

# Models that grow in or around a mesh; ballistic and Eden grow free, at the object's origin.
MODELS = [
    ("grow", "DLA", "Diffusion-limited aggregation"),
    ("colonize", "Space colonization", "Branches grow towards attractors scattered in the mesh"),
    ("drop", "Random drop", "Ballistic aggregation of particles dropped on the structure"),
    ("ballistic", "Ballistic", "Ballistic aggregation from random lines (no mesh)"),
    ("eden", "Eden", "The Eden model on a lattice (no mesh)"),
    ("breakdown", "Discharge", "The dielectric breakdown model: lightning and Lichtenberg figures around the mesh"),
]
MESH_MODELS = {"grow", "colonize", "drop", "breakdown"}


class DLA3DSettings(bpy.types.PropertyGroup):
    model: bpy.props.EnumProperty(name="Model", items=MODELS, default="grow")
    side: bpy.props.EnumProperty(
        name="Side", default="inside",
        items=[("inside", "Inside", "Grow inside the mesh"), ("outside", "Around", "Grow around the mesh")])
    count: bpy.props.IntProperty(name="Particles", default=5000, min=10, soft_max=200000,
                                 description="Particles (nodes, sites) to grow")
    seeds: bpy.props.IntProperty(name="Seeds", default=1, min=1, max=100,
                                 description="DLA: seeds placed deep in the mesh, far apart")
    eta: bpy.props.FloatProperty(name="Eta", default=2.0, min=0.0, max=10.0,
                                 description="Discharge: the field's exponent; 1 is DLA, 2 to 4 lightning")
    field: bpy.props.EnumProperty(
        name="Field", default="walkers",
        items=[("walkers", "Walkers", "Discharge: the exact field of random walkers; slower as eta grows"),
               ("conductor", "Conductor", "Discharge: charges that hold the structure at one potential; fast at "
                                          "any eta, blind to the mesh"),
               ("charges", "Charges", "Discharge: equal point charges; fastest, denser than the model")])
    rng_seed: bpy.props.IntProperty(name="Random seed", default=1, min=0,
                                    description="The same seed grows the same structure")
    radius: bpy.props.EnumProperty(
        name="Radius", default="taper",
        items=[("taper", "Taper", "Thick at the seed, thin at the tips"),
               ("pipe", "Pipe", "Thicker where more grows beyond"),
               ("uniform", "Uniform", "One radius")])
    output: bpy.props.EnumProperty(
        name="Result", default="CURVES",
        items=[("CURVES", "Curves", "A curves object: one poly curve per strand, radius and age per point"),
               ("MESH", "Tube mesh", "Tubes along the strands, with the age per vertex"),
               ("SOLID", "Solid", "One watertight surface for 3D printing, with the age per vertex")])
    sides: bpy.props.IntProperty(name="Tube sides", default=8, min=3, max=64)
    voxel: bpy.props.FloatProperty(name="Voxel", default=0.0, min=0.0, max=100.0,
                                   description="Solid: the voxel's edge, in spacings; 0: a third of the "
                                               "thinnest branch (fine, and slow for fine tips)")
    smooth: bpy.props.FloatProperty(name="Smooth", default=0.0, min=0.0, max=100.0,
                                    description="Solid: round inner corners to this radius, in spacings")
    leaf: bpy.props.PointerProperty(
        name="Leaf", type=bpy.types.Object, poll=lambda self, obj: obj.type == 'MESH',
        description="A mesh object placed at the tips as linked duplicates: its stem at its origin, "
                    "pointing along its local Z, within a unit sphere; each copy points along its branch, "
                    "scaled to the room around it")
    leaf_every: bpy.props.IntProperty(name="Every", default=1, min=1, max=1000000,
                                      description="A leaf at one tip in this many, in the order they grew")
    links: bpy.props.FloatProperty(name="Links", default=0.0, min=0.0, max=100.0,
                                   description="Join branches into loops: link each particle to an earlier one "
                                               "within this many spacings (Eden: its lattice neighbours; "
                                               "colonize: closed venation); 0: a tree")


def mesh_arrays(obj, depsgraph):
    """The evaluated object's triangles in world space: (V, 3) vertices and (F, 3) faces."""
    evaluated = obj.evaluated_get(depsgraph)
    mesh = evaluated.to_mesh()
    try:
        mesh.calc_loop_triangles()
        vertices = np.empty(len(mesh.vertices) * 3, dtype=np.float64)
        mesh.vertices.foreach_get("co", vertices)
        vertices = vertices.reshape(-1, 3)
        faces = np.empty(len(mesh.loop_triangles) * 3, dtype=np.int64)
        mesh.loop_triangles.foreach_get("vertices", faces)
    finally:
        evaluated.to_mesh_clear()
    matrix = np.array(obj.matrix_world)
    vertices = vertices @ matrix[:3, :3].T + matrix[:3, 3]
    return vertices, faces.reshape(-1, 3)


def grow_options(settings, obj, depsgraph):
    """The model's keyword arguments for dla3d."""
    model = settings.model
    options = {"rng_seed": settings.rng_seed, "radius": settings.radius}
    if settings.links > 0:
        if model == "colonize":
            options.update(venation="closed", influence=8.0)
        else:
            options["links"] = "lattice" if model == "eden" else settings.links
    if settings.leaf is not None:
        options["tips_every"] = settings.leaf_every
    uses_mesh = model in MESH_MODELS and obj is not None and obj.type == 'MESH'
    arrays = mesh_arrays(obj, depsgraph) if uses_mesh else None
    if model == "grow":
        options["particles"] = settings.count
        if arrays is not None:
            options.update(stl=arrays, side=settings.side, seeds=settings.seeds)
    elif model == "colonize":
        options["max_nodes"] = settings.count
        if arrays is not None:
            if settings.side == "inside":
                options["stl"] = arrays
            else:
                options["collide"] = arrays
    elif model == "drop":
        options["particles"] = settings.count
        if arrays is not None:
            options.update(stl=arrays, side=settings.side)
    elif model == "breakdown":
        options.update(particles=settings.count, eta=settings.eta, field=settings.field)
        if arrays is not None:
            options.update(stl=arrays, side=settings.side, seeds=settings.seeds)
    elif model == "ballistic":
        options["particles"] = settings.count
    else:
        options["sites"] = settings.count
    return options


def make_curves(result, name):
    """A curves object: one poly curve per strand and per link, with the look's radius and the age
    per point."""
    ids, starts = result.strands()
    # Each link a curve of two points after the strands.
    links = result.links
    ids = np.concatenate([ids, links.ravel()]).astype(np.int64)
    starts = np.concatenate([starts, starts[-1] + 2 * np.arange(1, len(links) + 1)])
    curve = bpy.data.curves.new(name, 'CURVE')
    curve.dimensions = '3D'
    positions = result.positions
    radius = result.radius
    for k in range(len(starts) - 1):
        strand = ids[starts[k]:starts[k + 1]]
        spline = curve.splines.new('POLY')
        spline.points.add(len(strand) - 1)
        co = np.ones((len(strand), 4))
        co[:, :3] = positions[strand]
        spline.points.foreach_set("co", co.ravel())
        spline.points.foreach_set("radius", radius[strand])
    obj = bpy.data.objects.new(name, curve)
    bpy.context.scene.collection.objects.link(obj)
    # The curves type holds attributes for geometry nodes; the legacy curve it comes from cannot.
    for other in bpy.context.view_layer.objects:
        other.select_set(False)
    bpy.context.view_layer.objects.active = obj
    obj.select_set(True)
    bpy.ops.object.convert(target='CURVES')
    obj = bpy.context.view_layer.objects.active
    age = obj.data.attributes.new("age", 'FLOAT', 'POINT')
    age.data.foreach_set("value", result.age[ids])
    return obj


def make_tube_mesh(result, name, sides):
    """A mesh of the look's tubes, with the age of each vertex's particle and a UV map: u around
    each tube, v along the strands (docs/look.md), as the glb imports."""
    tubes = result.tubes(sides=sides)
    obj = make_mesh(result, name, tubes.vertices, tubes.faces, tubes.particle)
    uv = tubes.uv.astype(np.float64)
    uv[:, 1] = 1.0 - uv[:, 1]  # Blender's v counts up from the image's foot, glTF's down from its head
    corners = tubes.faces.ravel()
    obj.data.uv_layers.new(name="UVMap").data.foreach_set("uv", uv[corners].ravel())
    return obj


def make_leaves(result, name, leaf):
    """Linked duplicates of `leaf` at the tips (Result.instances()), under an empty: each with
    its local Z along the branch and scaled by the tip's scale, as the glb's leaves."""
    parent = bpy.data.objects.new(name, None)
    bpy.context.scene.collection.objects.link(parent)
    positions, directions, scales = result.instances()
    up = mathutils.Vector((0.0, 0.0, 1.0))
    for position, direction, scale in zip(positions, directions, scales):
        copy = bpy.data.objects.new(leaf.name, leaf.data)  # sharing the leaf's mesh: edit one, all change
        turn = up.rotation_difference(mathutils.Vector(direction)).to_matrix().to_4x4()
        copy.matrix_world = mathutils.Matrix.Translation(position) @ turn @ mathutils.Matrix.Scale(scale, 4)
        copy.parent = parent
        bpy.context.scene.collection.objects.link(copy)
    return parent


def make_solid(result, name, voxel, smooth):
    """The structure's watertight solid (docs/solid.md), with the age of each vertex's nearest
    particle."""
    solid = result.solid(solid_voxel=voxel, solid_smooth=smooth)
    return make_mesh(result, name, solid.vertices, solid.faces, solid.particle)


def make_mesh(result, name, vertices, faces, particle):
    """A triangle mesh object with the age of each vertex's particle."""
    mesh = bpy.data.meshes.new(name)
    mesh.vertices.add(len(vertices))
    mesh.vertices.foreach_set("co", vertices.ravel())
    mesh.loops.add(faces.size)
    mesh.loops.foreach_set("vertex_index", faces.ravel().astype(np.int32))
    mesh.polygons.add(len(faces))
    mesh.polygons.foreach_set("loop_start", np.arange(0, faces.size, 3, dtype=np.int32))
    mesh.polygons.foreach_set("loop_total", np.full(len(faces), 3, dtype=np.int32))
    mesh.update()
    mesh.validate()
    age = mesh.attributes.new("age", 'FLOAT', 'POINT')
    age.data.foreach_set("value", result.age[particle])
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    return obj


class DLA3D_OT_grow(bpy.types.Operator):
    """Grow inside or around the selected mesh object"""
    bl_idname = "dla3d.grow"
    bl_label = "Grow"
    bl_options = {'REGISTER', 'UNDO'}

    def execute(self, context):
        import dla3d
        settings = context.scene.dla3d
        obj = context.active_object
        if settings.model in MESH_MODELS and (obj is None or obj.type != 'MESH'):
            self.report({'ERROR'}, "select a mesh object to grow in or around")
            return {'CANCELLED'}
        wm = context.window_manager
        wm.progress_begin(0, 1)
        try:
            options = grow_options(settings, obj, context.evaluated_depsgraph_get())

            def progress(done, total):
                wm.progress_update(done / max(total, 1))

            result = getattr(dla3d, settings.model)(progress=progress, **options)
        except ValueError as error:
            self.report({'ERROR'}, str(error))
            return {'CANCELLED'}
        finally:
            wm.progress_end()
        name = f"dla3d {settings.model}"
        try:
            made = (make_curves(result, name) if settings.output == 'CURVES'
                    else make_tube_mesh(result, name, settings.sides) if settings.output == 'MESH'
                    else make_solid(result, name, settings.voxel, settings.smooth))
        except ValueError as error:  # a solid too large for the memory it may take
            self.report({'ERROR'}, str(error))
            return {'CANCELLED'}
        leaves = make_leaves(result, name + " leaves", settings.leaf) if settings.leaf is not None else None
        if settings.model not in MESH_MODELS and obj is not None:
            for placed in (made, leaves) if leaves is not None else (made,):
                placed.location = obj.matrix_world.translation
        self.report({'INFO'}, f"grew {len(result)} particles" + ("" if result.complete else " (stopped)"))
        return {'FINISHED'}


class DLA3D_PT_panel(bpy.types.Panel):
    bl_label = "dla3d"
    bl_space_type = 'VIEW_3D'
    bl_region_type = 'UI'
    bl_category = "dla3d"

    def draw(self, context):
        settings = context.scene.dla3d
        layout = self.layout
        layout.prop(settings, "model")
        if settings.model in MESH_MODELS:
            layout.prop(settings, "side")
        layout.prop(settings, "count")
        if settings.model in ("grow", "breakdown"):
            layout.prop(settings, "seeds")
        if settings.model == "breakdown":
            layout.prop(settings, "eta")
            layout.prop(settings, "field")
        layout.prop(settings, "rng_seed")
        layout.prop(settings, "links")
        layout.prop(settings, "radius")
        layout.prop(settings, "output")
        if settings.output == 'MESH':
            layout.prop(settings, "sides")
        if settings.output == 'SOLID':
            layout.prop(settings, "voxel")
            layout.prop(settings, "smooth")
        layout.prop(settings, "leaf")
        if settings.leaf is not None:
            layout.prop(settings, "leaf_every")
        layout.operator(DLA3D_OT_grow.bl_idname)


CLASSES = (DLA3DSettings, DLA3D_OT_grow, DLA3D_PT_panel)


def register():
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.Scene.dla3d = bpy.props.PointerProperty(type=DLA3DSettings)


def unregister():
    del bpy.types.Scene.dla3d
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)


if __name__ == "__main__":
    register()
