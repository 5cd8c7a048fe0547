# The Cycles set-up of the client scripts that render (blender_solid.py, blender_texture.py),
# imported from their folder: a camera framing one object, a sun and a plain sky.
import bpy
import mathutils


def render(visible, path, width, height, samples, view=(1.0, -1.4, 0.9), distance=2.8, sky=(0.05, 0.05, 0.06),
           also=()):
    """A Cycles render of `visible` alone (and the objects `also` names), framed by a camera
    looking at its bounding box from `view`, `distance` times the box's half diagonal away."""
    scene = bpy.context.scene
    shown = {visible.name} | {o.name for o in also}
    for o in scene.objects:
        if o.type in {"MESH", "VOLUME"}:
            o.hide_render = o.name not in shown
    corners = [visible.matrix_world @ mathutils.Vector(c) for c in visible.bound_box]
    centre = sum(corners, mathutils.Vector()) / 8
    size = max((c - centre).length for c in corners)
    camera = bpy.data.objects.get("camera") or bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    if camera.name not in scene.objects:
        scene.collection.objects.link(camera)
    camera.location = centre + mathutils.Vector(view).normalized() * size * distance
    camera.rotation_euler = (centre - camera.location).to_track_quat("-Z", "Y").to_euler()
    scene.camera = camera
    if not bpy.data.objects.get("sun"):
        sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
        sun.data.energy = 4.0
        sun.rotation_euler = (0.7, 0.2, 0.5)
        scene.collection.objects.link(sun)
    world = bpy.data.worlds.new("sky")
    world.color = sky
    scene.world = world
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = samples
    scene.cycles.use_denoising = False  # Debian's Blender has no OpenImageDenoise
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
