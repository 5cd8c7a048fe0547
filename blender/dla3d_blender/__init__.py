"""dla3d's Blender add-on: grows DLA, trees, discharges and aggregates in and around the
selected mesh by running the `dla3d` command, live in the viewport.

It never imports dla3d's compiled module: it runs the `dla3d` executable (found on the PATH or
set in the preferences), builds its panel from `dla3d options`, reads the run's stream as it
grows, and imports the CSV it writes with every column as a named attribute. The "Grow over
time" node group animates growth. Pure Python and numpy, for Blender 3.4 to 5.x: a legacy
add-on before 4.2 (`bl_info`), an extension from 4.2 (`blender_manifest.toml`). See
docs/blender.md.
"""

bl_info = {
    "name": "dla3d",
    "author": "dla3d",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "View3D > Sidebar > dla3d",
    "description": "Grow DLA, trees, discharges and aggregates with the dla3d command, live in the viewport",
    "doc_url": "https://github.com/dla3d/dla3d/blob/main/docs/blender.md",
    "category": "Add Curve",
}

import os
import tempfile
import time

import bpy
import numpy as np

from . import core, nodes

#: The live objects' name while a run grows ("dla3d growth", "dla3d growth 2"...), and the
#: particles each shows.
LIVE_NAME = "dla3d growth"
LIVE_CHUNK = 50000
#: Seconds between two looks at the stream: more than ten updates a second, while the live
#: object takes little time to update.
PUMP_SECONDS = 0.06

# What the add-on knows between calls: the option description, the classes made from it, the
# run that grows, and the last message.
_state = {"description": None, "path": None, "warning": None, "error": None, "classes": [], "run": None,
          "live": [], "shown": 0, "settings": None, "presets": {}}


# ------------------------------------------------------------------------------------------
# Properties made from the description


def _label(option):
    return option["name"].lstrip("-").replace("-", " ").capitalize()


def _tooltip(option):
    text = option["help"]
    if option.get("unit"):
        text += f" ({option['unit']})"
    return f"{text}. {option['name']}"


def _int_limit(value):
    return max(-(2 ** 31) + 1, min(2 ** 31 - 1, int(value)))


def _number_limits(option, default):
    """Hard limits that hold the range, the default and any special value; soft ones the range."""
    limits = {}
    low, high = option.get("min"), option.get("max")
    special = option.get("special", {}).get("value")
    for key, bound, pick in (("min", low, min), ("max", high, max)):
        if bound is None:
            continue
        hard = pick(bound, default) if special is None else pick(bound, default, special)
        limits[key] = hard
        limits["soft_" + key] = bound
    if option["kind"] == "integer":
        limits = {k: _int_limit(v) for k, v in limits.items()}
    return limits


def _property(option):
    """The Blender property that holds one option."""
    kind, default = option["kind"], option["default"]
    common = {"name": _label(option), "description": _tooltip(option)}
    if option["type"] == core.MESH_FILE:
        return bpy.props.PointerProperty(type=bpy.types.Object, poll=lambda _, obj: obj.type == "MESH", **common)
    if kind == "flag":
        value = core.flag_default(option)
        if value is None:  # the command decides unless asked
            return bpy.props.EnumProperty(items=[("default", "Default", "as dla3d decides"), ("on", "On", ""),
                                                 ("off", "Off", "")], default="default", **common)
        return bpy.props.BoolProperty(default=value, **common)
    if kind == "word" and option.get("choices"):
        choices = option["choices"]
        return bpy.props.EnumProperty(items=[(c, c, "") for c in choices],
                                      default=default if default in choices else choices[0], **common)
    if kind in ("integer", "real") and core.number_default(option) is None:
        common["description"] += " (empty: dla3d chooses)"
        return bpy.props.StringProperty(default="", **common)
    if kind == "integer":
        value = _int_limit(core.number_default(option))
        return bpy.props.IntProperty(default=value, **_number_limits(option, value), **common)
    if kind == "real":
        value = core.number_default(option)
        return bpy.props.FloatProperty(default=value, precision=4, **_number_limits(option, value), **common)
    return bpy.props.StringProperty(default=default, subtype="FILE_PATH" if kind == "file" else "NONE", **common)


def _groups(model):
    groups = []
    for option in core.panel_options(model):
        if option["type"] != core.MESH_FILE and option["group"] not in groups:
            groups.append(option["group"])
    return groups


def _model_class(model):
    annotations = {core.identifier(o["name"]): _property(o) for o in core.panel_options(model)}
    for k, _ in enumerate(_groups(model)):
        annotations[f"show_group_{k}"] = bpy.props.BoolProperty(name="Show", default=k == 0)
    return type(f"DLA3D_PG_{core.identifier(model['name'])}", (bpy.types.PropertyGroup,),
                {"__annotations__": annotations})


def _model_items(_self, _context):
    return _state["model_items"]


def _preset_items(self, _context):
    return _state["presets"].get(self.model, [("none", "None", "")])


def _settings_class(description):
    _state["model_items"] = [(m["name"], m["name"].capitalize(), m["summary"]) for m in description["models"]]
    _state["presets"] = {
        m["name"]: [("none", "None", "")] + [(p["name"], p["name"], p["summary"]) for p in m["presets"]]
        for m in description["models"]}
    annotations = {
        "model": bpy.props.EnumProperty(name="Model", items=_model_items, description="What grows"),
        "preset": bpy.props.EnumProperty(name="Preset", items=_preset_items,
                                         description="A named set of options for the model (dla3d MODEL --preset)"),
        "result": bpy.props.EnumProperty(
            name="Result", default="MESH", description="What the structure is imported as",
            items=[("MESH", "Mesh", "a vertex a particle and an edge to its parent, the CSV's columns as attributes"),
                   ("CURVES", "Curves", "the same mesh shown as curves by a Mesh to Curve modifier, the attributes "
                                        "on their points")]),
        "animate": bpy.props.BoolProperty(name="Grow over time", default=True,
                                          description="Add the Grow over time node group: the structure appears "
                                                      "in its attach order from the scene's first frame to its last"),
    }
    for m in description["models"]:
        annotations[core.identifier(m["name"])] = bpy.props.PointerProperty(type=_state["model_classes"][m["name"]])
    return type("DLA3D_PG_settings", (bpy.types.PropertyGroup,), {"__annotations__": annotations})


def _unregister_described():
    if hasattr(bpy.types.Scene, "dla3d"):
        del bpy.types.Scene.dla3d
    for cls in reversed(_state["classes"]):
        bpy.utils.unregister_class(cls)
    _state["classes"] = []


def load_description(preferred=None):
    """Reads `dla3d options` and makes the panel's properties from it. On failure the add-on
    stays registered, and the panel shows the one-line error."""
    if preferred is None:
        preferred = _preferences().dla3d_path if _preferences() else ""
    _unregister_described()
    _state.update(description=None, error=None, warning=None, path=None)
    try:
        path = core.find_dla3d(preferred)
        _, warning = core.version_of(path)
        description = core.read_description(path)
    except core.Missing as missing:
        _state["error"] = str(missing)
        return False
    _state["model_classes"] = {m["name"]: _model_class(m) for m in description["models"]}
    classes = list(_state["model_classes"].values()) + [_settings_class(description)]
    for cls in classes:
        bpy.utils.register_class(cls)
    _state["classes"] = classes
    bpy.types.Scene.dla3d = bpy.props.PointerProperty(type=classes[-1])
    _state.update(description=description, path=path, warning=warning)
    return True


def _model(name):
    return next(m for m in _state["description"]["models"] if m["name"] == name)


def _preferences():
    addon = bpy.context.preferences.addons.get(__package__)
    return addon.preferences if addon else None


# ------------------------------------------------------------------------------------------
# Meshes in and structures out


def write_ply(obj, path, depsgraph):
    """`obj` as dla3d reads it: its evaluated mesh, world transform applied, triangulated, with
    the active colour attribute as vertex colours (for --seed-paint and the other paints)."""
    evaluated = obj.evaluated_get(depsgraph)
    mesh = evaluated.to_mesh()
    try:
        mesh.transform(obj.matrix_world)
        mesh.calc_loop_triangles()
        count = len(mesh.vertices)
        points = np.empty(count * 3, np.float32)
        mesh.vertices.foreach_get("co", points)
        triangles = np.empty(len(mesh.loop_triangles) * 3, np.int32)
        mesh.loop_triangles.foreach_get("vertices", triangles)
        colours = _vertex_colours(mesh)
    finally:
        evaluated.to_mesh_clear()
    header = ["ply", "format binary_little_endian 1.0", f"element vertex {count}", "property float x",
              "property float y", "property float z"]
    if colours is not None:
        header += ["property uchar red", "property uchar green", "property uchar blue"]
    header += [f"element face {len(triangles) // 3}", "property list uchar int vertex_indices", "end_header"]
    vertex = np.dtype([("p", "<f4", 3)] + ([("c", "u1", 3)] if colours is not None else []))
    rows = np.empty(count, vertex)
    rows["p"] = points.reshape(-1, 3)
    if colours is not None:
        rows["c"] = colours
    faces = np.empty(len(triangles) // 3, np.dtype([("n", "u1"), ("v", "<i4", 3)]))
    faces["n"] = 3
    faces["v"] = triangles.reshape(-1, 3)
    with open(path, "wb") as f:
        f.write(("\n".join(header) + "\n").encode("ascii"))
        f.write(rows.tobytes())
        f.write(faces.tobytes())


def _vertex_colours(mesh):
    """The active colour attribute as 8-bit sRGB a vertex (averaged over a face corner's), or None."""
    attributes = getattr(mesh, "color_attributes", None)  # 3.2 and later
    active = getattr(attributes, "active_color", None) if attributes is not None else None
    if active is None:
        return None
    values = np.empty(len(active.data) * 4, np.float32)
    try:
        active.data.foreach_get("color_srgb", values)  # what Vertex Paint shows
    except (AttributeError, TypeError):
        active.data.foreach_get("color", values)
    values = values.reshape(-1, 4)[:, :3]
    if active.domain == "CORNER":
        corners = np.empty(len(mesh.loops), np.int32)
        mesh.loops.foreach_get("vertex_index", corners)
        sums = np.zeros((len(mesh.vertices), 3))
        np.add.at(sums, corners, values)
        counts = np.maximum(np.bincount(corners, minlength=len(mesh.vertices)), 1)
        values = sums / counts[:, None]
    return np.clip(np.round(values * 255.0), 0, 255).astype(np.uint8)


def _fill_mesh(mesh, positions, parents, links=None):
    """Points and the links to their parents, then any other links (loops), as a mesh of
    vertices and edges."""
    mesh.clear_geometry()
    count = len(positions)
    mesh.vertices.add(count)
    mesh.vertices.foreach_set("co", np.ascontiguousarray(positions, np.float32).ravel())
    children = np.nonzero((parents >= 0) & (parents < count))[0]
    edges = np.column_stack([parents[children], children])
    if links is not None and len(links):
        edges = np.concatenate([edges, links])
    mesh.edges.add(len(edges))
    mesh.edges.foreach_set("vertices", edges.astype(np.int32).ravel())
    mesh.update()


def structure_object(name, columns, collection, links=None):
    """The CSV's structure as a mesh object: a vertex a particle, an edge to its parent, an
    edge for each of `links` (the loops of PREFIX_links.csv, rows a, b), and each other column
    as a point attribute of its name: id (the attach order), age (the same scaled to [0, 1]),
    radius, depth, seed, Strahler order, and a discharge's channel, current and light."""
    mesh = bpy.data.meshes.new(name)
    positions = np.column_stack([columns["x"], columns["y"], columns["z"]])
    _fill_mesh(mesh, positions, np.asarray(columns["parent"], np.int64), links)
    for column, values in columns.items():
        if column in ("x", "y", "z", "parent"):
            continue
        integer = values.dtype.kind == "i"
        attribute = mesh.attributes.new(column, "INT" if integer else "FLOAT", "POINT")
        attribute.data.foreach_set("value", values.astype(np.int32 if integer else np.float32))
    obj = bpy.data.objects.new(name, mesh)
    collection.objects.link(obj)
    return obj


# ------------------------------------------------------------------------------------------
# Runs


def _live_chunk(k):
    """The live object that shows particles [k, k + 1) * LIVE_CHUNK, made when first needed:
    only the last one changes as a run grows, so a look costs the same at any size. Found again
    by the name Blender gave it, and made afresh if undo took it away."""
    names = _state["live"]
    obj = bpy.data.objects.get(names[k]) if k < len(names) else None
    if obj is None or obj.type != "MESH" or not obj.get("dla3d_live"):
        name = LIVE_NAME if k == 0 else f"{LIVE_NAME} {k + 1}"
        obj = bpy.data.objects.new(name, bpy.data.meshes.new(name))
        obj["dla3d_live"] = True  # what _remove_live() takes away, and nothing of the user's
        bpy.context.scene.collection.objects.link(obj)
        names[k:k + 1] = [obj.name] if k < len(names) else [None] * (k - len(names)) + [obj.name]
    return obj


def _show_live(run, shown, arrived):
    """The live objects updated from particle `shown` on to `arrived`."""
    offset = max(shown, 0) // LIVE_CHUNK * LIVE_CHUNK
    positions, parents = run.snapshot(offset)
    for base in range(offset, arrived, LIVE_CHUNK):
        own = positions[base - offset:base - offset + LIVE_CHUNK]
        parent = parents[base - offset:base - offset + LIVE_CHUNK].astype(np.int64)
        # A parent in an earlier chunk is shown again here, so that its edge can be drawn.
        outside = (parent >= 0) & (parent < base)
        earlier = np.unique(parent[outside])
        local = parent - base
        local[outside] = len(own) + np.searchsorted(earlier, parent[outside])
        local[parent < 0] = -1  # a seed
        _fill_mesh(_live_chunk(base // LIVE_CHUNK).data, np.concatenate([own, run.positions_of(earlier)]),
                   np.concatenate([local, np.full(len(earlier), -1, np.int64)]))


def _remove_live():
    for obj in [o for o in bpy.data.objects if o.get("dla3d_live")]:
        mesh = obj.data
        bpy.data.objects.remove(obj)
        if mesh is not None and mesh.users == 0:
            bpy.data.meshes.remove(mesh)


def start(context):
    """Starts a run of the panel's model and options; the live object shows it as it grows.
    Returns None, or a one-line error."""
    if _state["run"] is not None:
        return "dla3d: a run is growing; stop it first"
    if _state["description"] is None and not load_description():
        return _state["error"]
    settings = context.scene.dla3d
    model = _model(settings.model)
    options = getattr(settings, core.identifier(model["name"]))
    folder = tempfile.mkdtemp(prefix="dla3d_blender_")
    run_words = []
    for name, obj in meshes_of_the_run(context, model, options).items():
        path = os.path.join(folder, f"{core.identifier(name)}.ply")
        write_ply(obj, path, context.evaluated_depsgraph_get())
        run_words.append(f"{name}={path}")
    for option in core.panel_options(model):
        if option["type"] != core.MESH_FILE:
            run_words += core.option_words(option, getattr(options, core.identifier(option["name"])))
    try:
        _state["run"] = core.Run(_state["path"], model, run_words, folder)
    except OSError as error:
        return f"dla3d: {_state['path']} does not run ({error.strerror})"
    _remove_live()
    _state.update(shown=0, live=[], settings=(settings.model, settings.result, settings.animate), error=None)
    if not bpy.app.timers.is_registered(pump):  # persistent: a run outlives a file opened meanwhile
        bpy.app.timers.register(pump, first_interval=PUMP_SECONDS, persistent=True)
    return None


def meshes_of_the_run(context, model, options):
    """Each mesh option's object: its picker's; else the active object for the main option
    (`--stl`), and a second selected mesh object for the first other option left empty (a
    discharge's target electrode, DLA's seed mesh)."""
    chosen = {o["name"]: getattr(options, core.identifier(o["name"])) for o in core.mesh_options(model)}
    main = core.main_mesh_option(model)
    active = context.active_object
    if main is not None and chosen[main["name"]] is None and active is not None and active.type == "MESH":
        chosen[main["name"]] = active
    if main is not None and chosen[main["name"]] is not None:  # a second object beside the main one
        used = {obj.name for obj in chosen.values() if obj is not None}
        others = [obj for obj in context.selected_objects
                  if obj.type == "MESH" and obj.name not in used and "dla3d_record" not in obj and "dla3d_live" not in obj]
        empty = [name for name, obj in chosen.items() if obj is None]
        if others and empty:
            chosen[empty[0]] = others[0]
    return {name: obj for name, obj in chosen.items() if obj is not None}


def _status(text):
    workspace = getattr(bpy.context, "workspace", None)
    if workspace is not None:
        workspace.status_text_set(text)


def pump():
    """One look at the run: the live object updated with what arrived, the status bar, and
    the result imported when the run ends. Blender's timer calls it; headless Blender, which
    runs no timers, calls it by hand. Returns the seconds to the next look, or None at the end."""
    run = _state["run"]
    if run is None:
        return None
    finished = run.finished
    arrived = run.arrived()
    took = 0.0
    if arrived > _state["shown"]:
        began = time.perf_counter()
        _show_live(run, _state["shown"], arrived)
        _state["shown"] = arrived
        took = time.perf_counter() - began
    if not finished:
        _status(run.status())
        # A large structure takes a while to show: look less often, so Blender stays responsive.
        return max(PUMP_SECONDS, 2.0 * took)
    _finish(run)
    return None


def _finish(run):
    code = run.wait()
    _state["run"] = None
    _status(None)
    csv = run.prefix + ".csv"
    if not os.path.exists(csv):
        _state["error"] = run.error() or f"dla3d ended with code {code} and wrote no structure"
        return
    model, result, animate = _state["settings"]
    columns = core.read_csv(csv)
    links_csv = run.prefix + "_links.csv"
    links = None
    if os.path.exists(links_csv):
        table = core.read_csv(links_csv)
        links = np.column_stack([table["a"], table["b"]]) if len(table["a"]) else None
    scene = bpy.context.scene
    _remove_live()
    obj = structure_object(f"dla3d {model}", columns, scene.collection, links)
    obj["dla3d_record"] = run.prefix + ".json"
    if result == "CURVES":
        nodes.add_to_curves(obj)
    if animate:  # a discharge that struck lights up as its leader steps down
        nodes.add_grow_over_time(obj, scene.frame_start, scene.frame_end, "light" if "light" in columns else "age")
    _state["error"] = run.error() if code != 0 else None
    _state["last"] = obj.name


def stop():
    """Ends the run as Ctrl-C does: what grew is kept and imported."""
    if _state["run"] is not None:
        _state["run"].stop()


# ------------------------------------------------------------------------------------------
# Operators, panel and preferences


class DLA3D_OT_grow(bpy.types.Operator):
    """Grow with dla3d: the selected mesh object is the mesh; Esc or Stop ends the run, keeping what grew"""
    bl_idname = "dla3d.grow"
    bl_label = "Grow"

    def execute(self, context):
        error = start(context)
        if error:
            self.report({"ERROR"}, error)
            return {"CANCELLED"}
        return {"FINISHED"}

    def invoke(self, context, event):
        if self.execute(context) != {"FINISHED"}:
            return {"CANCELLED"}
        context.window_manager.modal_handler_add(self)  # to hear Esc; the timer does the work
        return {"RUNNING_MODAL"}

    def modal(self, context, event):
        if _state["run"] is None:
            return {"FINISHED"}
        if event.type == "ESC" and event.value == "PRESS":
            stop()
        return {"PASS_THROUGH"}  # the viewport, undo and the rest stay the user's


class DLA3D_OT_stop(bpy.types.Operator):
    """End the run as Ctrl-C does, keeping what grew"""
    bl_idname = "dla3d.stop"
    bl_label = "Stop"

    def execute(self, context):
        stop()
        return {"FINISHED"}


class DLA3D_OT_apply_preset(bpy.types.Operator):
    """Set the model's options as the preset does (dla3d MODEL --preset NAME)"""
    bl_idname = "dla3d.apply_preset"
    bl_label = "Apply"

    def execute(self, context):
        error = apply_preset(context.scene.dla3d)
        if error:
            self.report({"ERROR"}, error)
            return {"CANCELLED"}
        return {"FINISHED"}


def reset_options(settings, model_name):
    """The model's options back to their defaults, but its mesh pickers."""
    model = _model(model_name)
    options = getattr(settings, core.identifier(model_name))
    for option in core.panel_options(model):
        if option["type"] != core.MESH_FILE:
            options.property_unset(core.identifier(option["name"]))


def apply_preset(settings):
    """The preset's options set in the panel; the rest back to their defaults. A one-line error, or None."""
    model = _model(settings.model)
    options = getattr(settings, core.identifier(model["name"]))
    preset = next((p for p in model["presets"] if p["name"] == settings.preset), None)
    if preset is None:
        return None
    reset_options(settings, model["name"])
    by_name = {o["name"]: o for o in core.panel_options(model)}
    for name, value in preset["options"]:
        option = by_name.get(name)
        if option is None:
            continue
        key = core.identifier(name)
        try:
            if option["kind"] == "flag":
                current = getattr(options, key)
                setattr(options, key, "on" if isinstance(current, str) else True)
            elif option["kind"] == "integer":
                setattr(options, key, int(value))
            elif option["kind"] == "real":
                setattr(options, key, float(value))
            else:
                setattr(options, key, value)
        except (TypeError, ValueError) as error:
            return f"dla3d: preset {preset['name']}: {name} {value}: {error}"
    return None


class DLA3D_OT_reload(bpy.types.Operator):
    """Find dla3d again and read its options"""
    bl_idname = "dla3d.reload"
    bl_label = "Find dla3d"

    def execute(self, context):
        if not load_description():
            self.report({"ERROR"}, _state["error"])
            return {"CANCELLED"}
        return {"FINISHED"}


class DLA3D_PT_panel(bpy.types.Panel):
    bl_label = "dla3d"
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "dla3d"

    def draw(self, context):
        layout = self.layout
        if _state["description"] is None:
            layout.label(text=_state["error"] or "dla3d: not loaded", icon="ERROR")
            layout.operator("dla3d.reload")
            return
        if _state["warning"]:
            layout.label(text=_state["warning"], icon="INFO")
        settings = context.scene.dla3d
        layout.prop(settings, "model")
        model = _model(settings.model)
        options = getattr(settings, core.identifier(model["name"]))
        if model["presets"]:
            row = layout.row(align=True)
            row.prop(settings, "preset")
            row.operator("dla3d.apply_preset")
        picked = meshes_of_the_run(context, model, options)
        for option in core.mesh_options(model):
            row = layout.row()
            row.prop(options, core.identifier(option["name"]))
            if getattr(options, core.identifier(option["name"])) is None and option["name"] in picked:
                row.label(text=picked[option["name"]].name)
        for k, group in enumerate(_groups(model)):
            box = layout.box()
            shown = getattr(options, f"show_group_{k}")
            box.prop(options, f"show_group_{k}", text=group, emboss=False,
                     icon="TRIA_DOWN" if shown else "TRIA_RIGHT")
            if shown:
                for option in core.panel_options(model):
                    if option["group"] == group and option["type"] != core.MESH_FILE:
                        box.prop(options, core.identifier(option["name"]))
        layout.prop(settings, "result")
        layout.prop(settings, "animate")
        if _state["run"] is None:
            layout.operator("dla3d.grow", icon="PLAY")
        else:
            layout.label(text=_state["run"].status())
            layout.operator("dla3d.stop", icon="CANCEL")
        if _state["error"]:
            layout.label(text=_state["error"], icon="ERROR")


class DLA3D_AP_preferences(bpy.types.AddonPreferences):
    bl_idname = __package__

    dla3d_path: bpy.props.StringProperty(
        name="dla3d", subtype="FILE_PATH", default="",
        description="The dla3d executable; empty: the first on the PATH",
        update=lambda self, _context: None if load_description(self.dla3d_path) else None)

    def draw(self, context):
        self.layout.prop(self, "dla3d_path")
        self.layout.label(text=_state["error"] or f"dla3d: {_state['path']}")


CLASSES = (DLA3D_OT_grow, DLA3D_OT_stop, DLA3D_OT_apply_preset, DLA3D_OT_reload, DLA3D_PT_panel,
           DLA3D_AP_preferences)


def register():
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    load_description()


def unregister():
    stop()
    if bpy.app.timers.is_registered(pump):
        bpy.app.timers.unregister(pump)
    _unregister_described()
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
