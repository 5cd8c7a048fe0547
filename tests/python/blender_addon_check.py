"""The add-on inside Debian's Blender, headless (test_blender.py runs it):

    blender -b --factory-startup --python blender_addon_check.py -- ZIP DLA3D BUST.stl WORK [RENDER.png]

It installs ZIP with Blender's own installer, with dla3d's compiled module out of reach and
DLA3D's folder on the PATH, grows in the bust through the operator (pumping the timer by hand:
headless Blender runs none), and checks what it made against the CLI's own files. It prints
"dla3d add-on: ..." lines and exits non-zero on the first failed check.
"""

import json
import os
import subprocess
import sys
import time

# The compiled module must not be what the add-on runs on: a None entry makes `import dla3d` fail.
sys.modules["dla3d"] = None

import bpy  # noqa: E402
import numpy as np  # noqa: E402

ZIP, DLA3D, BUST, WORK = sys.argv[sys.argv.index("--") + 1:][:4]
RENDER = (sys.argv[sys.argv.index("--") + 1:] + [None] * 5)[4]
os.environ["PATH"] = os.path.dirname(DLA3D) + os.pathsep + os.environ.get("PATH", "")


def check(condition, message):
    if not condition:
        print("dla3d add-on: FAILED:", message, flush=True)
        sys.exit(1)


bpy.ops.preferences.addon_install(filepath=ZIP)
bpy.ops.preferences.addon_enable(module="dla3d_blender")
import dla3d_blender  # noqa: E402
from dla3d_blender import core  # noqa: E402

check(dla3d_blender.__file__.startswith(bpy.utils.user_resource("SCRIPTS")), "installed where Blender installs add-ons")
check(dla3d_blender._state["description"] is not None, f"the options were read: {dla3d_blender._state['error']}")

# Every model, every option the panel shows, as a property.
scene = bpy.context.scene
for model in dla3d_blender._state["description"]["models"]:
    options = getattr(scene.dla3d, core.identifier(model["name"]))
    for option in core.panel_options(model):
        check(hasattr(options, core.identifier(option["name"])), f"{model['name']} {option['name']} in the panel")
breakdown = scene.dla3d.breakdown
check(breakdown.bl_rna.properties["field"].type == "ENUM", "a word from a list is an enum")
eta = breakdown.bl_rna.properties["eta"]
check(eta.type == "FLOAT" and eta.hard_min == 0 and eta.hard_max == 10 and eta.default == 1.0,
      "a number keeps its range and the library's default")

# A preset sets its options.
scene.dla3d.model = "breakdown"
scene.dla3d.preset = "lightning"
check(dla3d_blender.apply_preset(scene.dla3d) is None, "the lightning preset applies")
check(breakdown.eta != 1.0, f"the lightning preset set eta ({breakdown.eta})")
print(f"dla3d add-on: the lightning preset sets eta {breakdown.eta:g}", flush=True)
dla3d_blender.reset_options(scene.dla3d, "breakdown")

# The bust, selected; the run grows in it.
bpy.ops.object.select_all(action="SELECT")
bpy.ops.object.delete()
bpy.ops.import_mesh.stl(filepath=BUST)
bust = bpy.context.selected_objects[0]
bpy.context.view_layer.objects.active = bust
# An object of the user's that happens to bear the live view's name is left alone.
bystander = bpy.data.objects.new(dla3d_blender.LIVE_NAME, bpy.data.meshes.new("bystander"))
scene.collection.objects.link(bystander)
scene.dla3d.model = "grow"
scene.dla3d.grow.particles = 30000
scene.dla3d.grow.rng_seed = 5
bpy.ops.dla3d.grow()
run = dla3d_blender._state["run"]
check(run is not None, "the operator started a run")
seen = []
while dla3d_blender.pump() is not None:
    live = bpy.data.objects.get(dla3d_blender._state["live"][0]) if dla3d_blender._state["live"] else None
    if live is not None and len(live.data.vertices):
        seen.append(len(live.data.vertices))
    time.sleep(0.02)
grown = bpy.data.objects.get("dla3d grow")
check(grown is not None, f"the structure was imported ({dla3d_blender._state['error']})")
count = len(grown.data.vertices)
partial = [n for n in seen if n < count]
check(partial, f"partial states before the end (seen {seen[:5]}, then {count})")
check(bpy.data.objects.get(dla3d_blender.LIVE_NAME) == bystander and not bystander.data.vertices,
      "the user's object of the live view's name is untouched")
print(f"dla3d add-on: {len(seen)} live updates, {len(partial)} partial (first {partial[0]}), {count} at the end",
      flush=True)

# The same options on the CLI give the same CSV, and the object holds its points and links.
reference = os.path.join(WORK, "cli")
argv = [DLA3D, f"--stl={os.path.join(run.folder, 'stl.ply')}", "--particles=30000", "--rng-seed=5", "-q",
        "--formats", "csv", "-o", reference]
subprocess.run(argv, check=True)
with open(reference + ".csv", "rb") as a, open(run.prefix + ".csv", "rb") as b:
    check(a.read() == b.read(), "the add-on's run wrote the CLI's CSV, byte for byte")
columns = core.read_csv(reference + ".csv")
points = np.empty(count * 3, np.float32)
grown.data.vertices.foreach_get("co", points)
expected = np.column_stack([columns["x"], columns["y"], columns["z"]]).astype(np.float32)
check(count == len(expected) and np.array_equal(points.reshape(-1, 3), expected), "the object's points are the CSV's")
edges = np.empty(len(grown.data.edges) * 2, np.int32)
grown.data.edges.foreach_get("vertices", edges)
links = {(int(p), int(c)) for p, c in edges.reshape(-1, 2)}
check(links == {(int(p), i) for i, p in enumerate(columns["parent"]) if p >= 0}, "an edge from each particle's parent")
for name in ("id", "age", "radius", "depth", "seed", "order"):
    attribute = grown.data.attributes.get(name)
    check(attribute is not None and attribute.domain == "POINT", f"the {name} attribute")
    values = np.empty(count, np.float32 if attribute.data_type == "FLOAT" else np.int32)
    attribute.data.foreach_get("value", values)
    check(np.allclose(values, columns[name], rtol=1e-6, atol=1e-6), f"the {name} attribute is the CSV's")
print("dla3d add-on: the CSV, points, links and attributes match the CLI's", flush=True)

# Grow over time: fewer points at a middle frame than at the last.
modifier = grown.modifiers.get("Grow over time")
check(modifier is not None and modifier.node_group is not None, "the Grow over time modifier")


def shown_at(frame):
    scene.frame_set(frame)
    evaluated = grown.evaluated_get(bpy.context.evaluated_depsgraph_get())
    return len(evaluated.to_mesh().vertices)


middle, last = shown_at((scene.frame_start + scene.frame_end) // 2), shown_at(scene.frame_end)
check(0 < middle < last, f"the middle frame shows fewer tube vertices ({middle}) than the last ({last})")
print(f"dla3d add-on: Grow over time shows {middle} tube vertices at the middle frame, {last} at the last", flush=True)

# Imported as curves, with Grow over time after it: the same reveal.
scene.dla3d.result = "CURVES"
scene.dla3d.grow.particles = 3000
bpy.ops.dla3d.grow()
while dla3d_blender.pump() is not None:
    time.sleep(0.02)
curved = bpy.data.objects.get(dla3d_blender._state["last"])
check([m.name for m in curved.modifiers] == ["dla3d curves", "Grow over time"], "curves, then Grow over time")
grown, kept = curved, grown  # shown_at() looks at `grown`
middle, last = shown_at((scene.frame_start + scene.frame_end) // 2), shown_at(scene.frame_end)
check(0 < middle < last, f"as curves too, the middle frame shows fewer ({middle}) than the last ({last})")
grown = kept
scene.dla3d.result = "MESH"
print(f"dla3d add-on: as curves, Grow over time shows {middle} and {last} tube vertices", flush=True)

# A second selected object is the discharge's target electrode: a plane under the bust.
bpy.ops.object.select_all(action="DESELECT")
bpy.ops.mesh.primitive_plane_add(size=4.0 * max(bust.dimensions), location=(0, 0, bust.location.z - bust.dimensions.z))
plane = bpy.context.active_object
bust.select_set(True)
bpy.context.view_layer.objects.active = bust
scene.dla3d.model = "breakdown"
picked = dla3d_blender.meshes_of_the_run(bpy.context, dla3d_blender._model("breakdown"), scene.dla3d.breakdown)
check(picked.get("--stl") == bust and picked.get("--target-mesh") == plane, f"the bust and the target: {picked}")
scene.dla3d.model = "grow"
picked = dla3d_blender.meshes_of_the_run(bpy.context, dla3d_blender._model("grow"), scene.dla3d.grow)
check(picked.get("--stl") == bust and picked.get("--seed-mesh") == plane, f"the bust and the seed mesh: {picked}")
bpy.data.objects.remove(plane)
print("dla3d add-on: a second selected object is the target electrode, or the seed mesh", flush=True)

# A spark that strikes: its channel, current and light, and Grow over time follows the leader.
bpy.context.view_layer.objects.active = None
bpy.ops.object.select_all(action="DESELECT")
scene.dla3d.model = "breakdown"
scene.dla3d.preset = "spark"
check(dla3d_blender.apply_preset(scene.dla3d) is None, "the spark preset applies")
bpy.ops.dla3d.grow()
while dla3d_blender.pump() is not None:
    time.sleep(0.02)
spark = bpy.data.objects.get(dla3d_blender._state["last"])
check(spark is not None and spark.name.startswith("dla3d breakdown"), f"the spark grew ({dla3d_blender._state['error']})")
check(all(spark.data.attributes.get(a) is not None for a in ("channel", "current", "light")), "a discharge's attributes")
spark_modifier = spark.modifiers["Grow over time"]
reveal = spark_modifier[dla3d_blender.nodes.input_identifier(spark_modifier.node_group, "Reveal by")]
check(reveal == "light", f"a discharge is revealed by its light ({reveal})")
print(f"dla3d add-on: the spark struck with {len(spark.data.vertices)} particles, revealed by {reveal}", flush=True)
dla3d_blender.reset_options(scene.dla3d, "breakdown")
scene.dla3d.model = "grow"

# Loops: the links beyond the tree are edges too.
scene.dla3d.grow.particles = 2000
scene.dla3d.grow.links = "2"
bpy.context.view_layer.objects.active = None
bpy.ops.dla3d.grow()
while dla3d_blender.pump() is not None:
    time.sleep(0.02)
looped = bpy.data.objects.get(dla3d_blender._state["last"])
check(looped is not None and len(looped.data.edges) > len(looped.data.vertices) - 1,
      f"links beyond the tree are edges ({len(looped.data.edges)} edges, {len(looped.data.vertices)} points)")
print(f"dla3d add-on: with --links 2, {len(looped.data.edges)} edges over {len(looped.data.vertices)} points",
      flush=True)
scene.dla3d.grow.property_unset("links")

# A run stopped keeps what grew.
scene.dla3d.grow.property_unset("particles")
scene.dla3d.grow.particles = 3000000
bpy.context.view_layer.objects.active = None
bpy.ops.dla3d.grow()
run = dla3d_blender._state["run"]
while dla3d_blender._state["shown"] < dla3d_blender.LIVE_CHUNK + 10000 and dla3d_blender.pump() is not None:
    time.sleep(0.02)
# The live view in chunks: the first full, the second its part, with the parents it hangs from.
shown = dla3d_blender._state["shown"]
first, second = (bpy.data.objects.get(name) for name in dla3d_blender._state["live"][:2])
check(first is not None and len(first.data.vertices) == dla3d_blender.LIVE_CHUNK, "the first live chunk is full")
check(second is not None and len(second.data.vertices) >= shown - dla3d_blender.LIVE_CHUNK and
      len(second.data.edges) == shown - dla3d_blender.LIVE_CHUNK, f"the second chunk shows the rest of {shown}")
dla3d_blender.stop()
while dla3d_blender.pump() is not None:
    time.sleep(0.02)
stopped = bpy.data.objects.get(dla3d_blender._state["last"])
with open(run.prefix + ".json") as f:
    record = json.load(f)
check(stopped is not None and shown <= len(stopped.data.vertices) < 3000001, "a stopped run's structure is kept")
check(not [o for o in bpy.data.objects if o.get("dla3d_live")], "the live view gives way to the result")
check(record.get("complete") is False, "the record says the structure is incomplete")
print(f"dla3d add-on: stopped with {len(stopped.data.vertices)} particles kept", flush=True)

# A missing dla3d: one line, from the preferences and from the operator.
preferences = bpy.context.preferences.addons["dla3d_blender"].preferences
preferences.dla3d_path = "/nonexistent/dla3d"
error = dla3d_blender._state["error"]
check(error and "\n" not in error and "not an executable" in error, f"a missing dla3d refused in one line: {error}")
try:
    bpy.ops.dla3d.grow()
    check(False, "the operator grew without dla3d")
except RuntimeError as refused:
    check("not an executable" in str(refused), f"the operator says why: {refused}")
print(f"dla3d add-on: refused: {error}", flush=True)
preferences.dla3d_path = DLA3D
check(dla3d_blender._state["description"] is not None, "found again")

if RENDER:
    # One frame of the growth animation in Cycles, framed on the structure.
    scene = bpy.context.scene
    grown = bpy.data.objects.get("dla3d grow")
    for other in scene.objects:  # the bust and the stopped run's structure
        other.hide_render = other is not grown
    material = bpy.data.materials.new("dla3d glow")
    material.use_nodes = True
    principled = material.node_tree.nodes.get("Principled BSDF")
    principled.inputs["Base Color"].default_value = (0.9, 0.55, 0.2, 1.0)
    modifier = grown.modifiers["Grow over time"]
    modifier[dla3d_blender.nodes.input_identifier(modifier.node_group, "Material")] = material
    scene.frame_set(int(scene.frame_start + 0.7 * (scene.frame_end - scene.frame_start)))
    corners = np.array([grown.matrix_world @ v.co for v in grown.data.vertices])
    centre, size = (corners.min(0) + corners.max(0)) / 2, float(np.max(corners.max(0) - corners.min(0)))
    camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    scene.collection.objects.link(camera)
    camera.location = (centre[0], centre[1] - 2.2 * size, centre[2] + 0.3 * size)
    direction = camera.location - type(camera.location)(centre)
    camera.rotation_euler = direction.to_track_quat("Z", "Y").to_euler()
    scene.camera = camera
    light = bpy.data.objects.new("light", bpy.data.lights.new("light", "SUN"))
    light.data.energy = 4.0
    light.rotation_euler = (0.6, 0.2, 0.8)
    scene.collection.objects.link(light)
    scene.world = scene.world or bpy.data.worlds.new("world")
    scene.world.use_nodes = True
    scene.world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.02, 0.02, 0.03, 1.0)
    scene.render.engine = "CYCLES"
    scene.cycles.samples = 32
    scene.cycles.use_denoising = False  # Debian's Blender is built without OpenImageDenoise
    scene.cycles.device = "CPU"
    scene.render.resolution_x, scene.render.resolution_y = 640, 480
    scene.render.filepath = RENDER
    bpy.ops.render.render(write_still=True)
    image = bpy.data.images.load(RENDER)
    pixels = np.array(image.pixels[:], np.float32).reshape(image.size[1], image.size[0], 4)[:, :, :3].sum(axis=2)
    lit = np.argwhere(np.abs(pixels - pixels[0, 0]) > 0.1)  # unlike the world's colour in the corner
    check(len(lit) > 0.01 * pixels.size, f"the render shows the structure ({len(lit)} lit pixels)")
    rows, cols = lit[:, 0], lit[:, 1]
    check(rows.min() > 0 and cols.min() > 0 and rows.max() < pixels.shape[0] - 1 and cols.max() < pixels.shape[1] - 1,
          "the structure is framed: no lit pixel on the border")
    print(f"dla3d add-on: rendered frame {scene.frame_current} to {RENDER}, {len(lit)} lit pixels", flush=True)

print("dla3d add-on: every check passed", flush=True)
