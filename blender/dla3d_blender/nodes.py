"""The bundled node group, "Grow over time": the structure revealed in its attach order (its
`age` attribute; a discharge's `light`, its stepped leader) as the frame advances, as tubes of
its own radii. One modifier makes a growth animation.

Blender 3.4 to 5.x build node groups alike but for their sockets: 4.0 replaced
`NodeTree.inputs`/`outputs` with `NodeTree.interface.new_socket()` (Blender 4.0's Python API
notes), so both are looked for. Nodes with a socket per data type in 3.x (Named Attribute's
output, Curve Circle's inputs) are linked by their enabled socket, which is the one socket of
that name from 4.0.
"""

import bpy

GROUP_NAME = "Grow over time"
CURVES_NAME = "dla3d curves"


def _new_socket(group, in_out, socket_type, name):
    if hasattr(group, "interface"):  # Blender 4.0 and later
        return group.interface.new_socket(name=name, in_out=in_out, socket_type=socket_type)
    return (group.inputs if in_out == "INPUT" else group.outputs).new(socket_type, name)


def _socket(sockets, name):
    """The enabled socket called `name`: in 3.x a node may hold one of that name per data type."""
    return next(s for s in sockets if s.name == name and getattr(s, "enabled", True))


def _math(group, operation, a, b):
    node = group.nodes.new("ShaderNodeMath")
    node.operation = operation
    for k, value in enumerate((a, b)):
        if isinstance(value, (int, float)):
            node.inputs[k].default_value = value
        else:
            group.links.new(value, node.inputs[k])
    return node


def _named_attribute(group, name):
    node = group.nodes.new("GeometryNodeInputNamedAttribute")
    node.data_type = "FLOAT"
    _socket(node.inputs, "Name").default_value = name
    return _socket(node.outputs, "Attribute")


def grow_over_time():
    """The node group, made once a file."""
    group = bpy.data.node_groups.get(GROUP_NAME)
    if group is not None:
        return group
    group = bpy.data.node_groups.new(GROUP_NAME, "GeometryNodeTree")
    if hasattr(group, "is_modifier"):  # 4.0 and later list only modifier groups in the Add menu
        group.is_modifier = True
    _new_socket(group, "INPUT", "NodeSocketGeometry", "Geometry")
    for name, value in (("Start frame", 1.0), ("End frame", 250.0), ("Radius scale", 1.0)):
        _new_socket(group, "INPUT", "NodeSocketFloat", name).default_value = value
    _new_socket(group, "INPUT", "NodeSocketString", "Reveal by").default_value = "age"
    resolution = _new_socket(group, "INPUT", "NodeSocketInt", "Resolution")
    resolution.default_value = 8
    resolution.min_value = 3
    _new_socket(group, "INPUT", "NodeSocketMaterial", "Material")
    _new_socket(group, "OUTPUT", "NodeSocketGeometry", "Geometry")

    nodes, links = group.nodes, group.links
    given = nodes.new("NodeGroupInput")
    result = nodes.new("NodeGroupOutput")
    time = nodes.new("GeometryNodeInputSceneTime")
    # The share of the structure shown: 0 at the start frame, 1 at the end frame.
    elapsed = _math(group, "SUBTRACT", _socket(time.outputs, "Frame"), _socket(given.outputs, "Start frame"))
    span = _math(group, "SUBTRACT", _socket(given.outputs, "End frame"), _socket(given.outputs, "Start frame"))
    share = _math(group, "DIVIDE", elapsed.outputs[0], span.outputs[0])
    share.use_clamp = True
    # Hidden: the particles past that share by the attribute revealed by: their age (attach
    # order scaled to [0, 1]), or a discharge's light (when the leader reaches them, 1 at the strike).
    reveal = group.nodes.new("GeometryNodeInputNamedAttribute")
    reveal.data_type = "FLOAT"
    links.new(_socket(given.outputs, "Reveal by"), _socket(reveal.inputs, "Name"))
    later = _math(group, "GREATER_THAN", _socket(reveal.outputs, "Attribute"), share.outputs[0])
    hide = nodes.new("GeometryNodeDeleteGeometry")
    hide.domain = "POINT"
    links.new(_socket(given.outputs, "Geometry"), _socket(hide.inputs, "Geometry"))
    links.new(later.outputs[0], _socket(hide.inputs, "Selection"))
    # Tubes of the particles' radii along the links to their parents: a mesh's edges made
    # curves, joined to the curves of a result imported as curves.
    parts = nodes.new("GeometryNodeSeparateComponents")
    links.new(_socket(hide.outputs, "Geometry"), _socket(parts.inputs, "Geometry"))
    curves = nodes.new("GeometryNodeMeshToCurve")
    links.new(_socket(parts.outputs, "Mesh"), _socket(curves.inputs, "Mesh"))
    joined = nodes.new("GeometryNodeJoinGeometry")
    links.new(_socket(parts.outputs, "Curve"), _socket(joined.inputs, "Geometry"))
    links.new(_socket(curves.outputs, "Curve"), _socket(joined.inputs, "Geometry"))
    radius = _math(group, "MULTIPLY", _named_attribute(group, "radius"), _socket(given.outputs, "Radius scale"))
    set_radius = nodes.new("GeometryNodeSetCurveRadius")
    links.new(_socket(joined.outputs, "Geometry"), _socket(set_radius.inputs, "Curve"))
    links.new(radius.outputs[0], _socket(set_radius.inputs, "Radius"))
    profile = nodes.new("GeometryNodeCurvePrimitiveCircle")
    links.new(_socket(given.outputs, "Resolution"), _socket(profile.inputs, "Resolution"))
    _socket(profile.inputs, "Radius").default_value = 1.0
    tubes = nodes.new("GeometryNodeCurveToMesh")
    links.new(_socket(set_radius.outputs, "Curve"), _socket(tubes.inputs, "Curve"))
    links.new(_socket(profile.outputs, "Curve"), _socket(tubes.inputs, "Profile Curve"))
    material = nodes.new("GeometryNodeSetMaterial")
    links.new(_socket(tubes.outputs, "Mesh"), _socket(material.inputs, "Geometry"))
    links.new(_socket(given.outputs, "Material"), _socket(material.inputs, "Material"))
    links.new(_socket(material.outputs, "Geometry"), _socket(result.inputs, "Geometry"))
    for k, node in enumerate(nodes):
        node.location = (200 * (k % 8), -200 * (k // 8))
    return group


def to_curves():
    """The node group that shows a mesh of points and parent edges as curves, attributes kept."""
    group = bpy.data.node_groups.get(CURVES_NAME)
    if group is not None:
        return group
    group = bpy.data.node_groups.new(CURVES_NAME, "GeometryNodeTree")
    if hasattr(group, "is_modifier"):
        group.is_modifier = True
    _new_socket(group, "INPUT", "NodeSocketGeometry", "Geometry")
    _new_socket(group, "OUTPUT", "NodeSocketGeometry", "Geometry")
    given, result = group.nodes.new("NodeGroupInput"), group.nodes.new("NodeGroupOutput")
    curves = group.nodes.new("GeometryNodeMeshToCurve")
    group.links.new(_socket(given.outputs, "Geometry"), _socket(curves.inputs, "Mesh"))
    group.links.new(_socket(curves.outputs, "Curve"), _socket(result.inputs, "Geometry"))
    result.location = (400, 0)
    curves.location = (200, 0)
    return group


def add_to_curves(obj):
    """`obj`'s points and edges as curves, by a modifier."""
    modifier = obj.modifiers.new(CURVES_NAME, "NODES")
    modifier.node_group = to_curves()
    return modifier


def input_identifier(group, name):
    """The identifier a modifier keys the group's input `name` by (`mod[identifier] = value`)."""
    sockets = ([item for item in group.interface.items_tree if getattr(item, "in_out", "") == "INPUT"]
               if hasattr(group, "interface") else group.inputs)
    return next(s.identifier for s in sockets if s.name == name)


def add_grow_over_time(obj, start, end, reveal_by="age", material=None):
    """The node group as a modifier of `obj`, revealing it by the attribute `reveal_by` from
    frame `start` to `end`."""
    group = grow_over_time()
    modifier = obj.modifiers.new(GROUP_NAME, "NODES")
    modifier.node_group = group
    modifier[input_identifier(group, "Start frame")] = float(start)
    modifier[input_identifier(group, "End frame")] = float(end)
    modifier[input_identifier(group, "Reveal by")] = reveal_by
    if material is not None:
        modifier[input_identifier(group, "Material")] = material
    return modifier
