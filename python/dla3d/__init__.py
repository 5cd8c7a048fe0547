"""dla3d from Python: every growth model as a function, its options as keyword arguments.

    import dla3d
    result = dla3d.grow(particles=20000, rng_seed=7)
    result.positions            # (N, 3) float64, sharing the structure's memory
    result.write("cluster", formats=["glb", "pov"])

Keyword arguments set the library's run options; they are spelled as the command line's, with
dashes as underscores: ``dla3d.grow(stl="bust.stl", seeds=2)`` grows what ``dla3d --stl
bust.stl --seeds 2`` does, checked by the library with the same one-line messages, raised as
ValueError with the options spelled as keywords. See docs/python.md.
"""

import numbers
import warnings

import numpy as np

from . import _core
from ._core import Result

__all__ = ["grow", "colonize", "drop", "ballistic", "eden", "breakdown", "command_args", "Result", "Tubes", "ensemble"]

# Options of the files, which Result.write() takes instead: a model function writes nothing.
_WRITE_ONLY = {"output", "o", "formats", "quiet", "q"}
# The command line's own: from Python a stopped run returns what grew, and help is help().
_CLI_ONLY = {"checkpoint", "checkpoint_every", "resume", "help", "h", "version"}
# Options that name a mesh file, and may be given (V, 3) vertices and (F, 3) faces instead.
_MESH_OPTIONS = {"stl", "mesh", "collide", "seed_mesh", "target_mesh"}
# Flags that are on unless turned off: False is --no-FLAG on the command line.
_ON_BY_DEFAULT = {"scene_mesh", "stop_at_strike"}


class Tubes(tuple):
    """The tube mesh of the look: unpacks as (vertices, normals, faces), float32 (V, 3), float32
    (V, 3) unit normals and uint32 (F, 3) triangles; `particle` is the particle each vertex
    belongs to, for its age or any other attribute. `uv` is float32 (V, 2) texture coordinates
    as in the glb: u once around a tube from 0 to 1 (a ring's last vertex repeats its first at
    u = 1), v along the strand from its seed in uv_scales, going on from the parent's at a branch
    point. `tangent` is float32 (V, 4), the glb's TANGENT: the unit direction of rising u and 1."""

    def __new__(cls, vertices, normals, faces, particle, uv, tangent):
        tubes = super().__new__(cls, (vertices, normals, faces))
        tubes.particle = particle
        tubes.uv = uv
        tubes.tangent = tangent
        return tubes

    vertices = property(lambda self: self[0])
    normals = property(lambda self: self[1])
    faces = property(lambda self: self[2])


def _tubes(result, sides=None, tolerance=None, min_branch=None, uv_scale=None):
    """The tube mesh of the look, as the glTF's: see Tubes. `sides`, `tolerance` (spacings),
    `min_branch` and `uv_scale` (scene units; 0 for the base circumference) are --tube-sides,
    --tube-tolerance, --tube-min-branch and --uv-scale; None takes the run's."""
    return Tubes(*result._tubes(sides, tolerance, min_branch, uv_scale))


Result.tubes = _tubes


class Instances(tuple):
    """The instancing points of the run's options (instances, tips_within, tips_every,
    tips_exclude_paint), as PREFIX_tips.ply and the glb's leaves have them: unpacks as
    (positions, directions, scale), float64 (N, 3), (N, 3) unit directions from each parent and
    (N,) scales (half the gap to the nearest other point, at most the distance to the mesh);
    `particle` is each point's particle."""

    def __new__(cls, positions, directions, scale, particle):
        points = super().__new__(cls, (positions, directions, scale))
        points.particle = particle
        return points

    positions = property(lambda self: self[0])
    directions = property(lambda self: self[1])
    scale = property(lambda self: self[2])


Result.instances = lambda result: Instances(*result._instances())
Result.instances.__doc__ = Instances.__doc__


class Solid(tuple):
    """The watertight solid of a structure: (vertices, faces) unpack as float32 (V, 3) and uint32
    (F, 3) arrays of a closed, outward-facing triangle mesh, in millimetres with print_size,
    else in scene units. `particle` is each vertex's nearest particle (for colours and
    attributes) and `measures` a dict: volume, area, shells, thinnest_wall, thickened, voxel,
    scale (mesh units per scene unit) and origin (a point p of the structure lies at
    (p - origin) * scale in the mesh)."""

    def __new__(cls, vertices, faces, particle, measures):
        solid = super().__new__(cls, (vertices, faces))
        solid.particle = particle
        solid.measures = measures
        return solid

    vertices = property(lambda self: self[0])
    faces = property(lambda self: self[1])


def _solid(result, **options):
    """The structure's watertight solid: see Solid and docs/solid.md. The keywords are the run's
    (and dla3d's) solid options, which they default to: solid_shape ("branches", "spheres",
    "cubes"), solid_voxel and solid_smooth (spacings), solid_adaptivity, print_size and
    min_wall (mm), solid_join (bool) and solid_memory (MB)."""
    return Solid(*result._solid(options))


Result.solid = _solid


def _word(value):
    """A value as the command line writes it: numbers exact, vectors comma-separated."""
    if isinstance(value, numbers.Integral) and not isinstance(value, (bool, np.bool_)):
        return str(int(value))
    if isinstance(value, numbers.Real):
        return repr(float(value))  # the shortest text that reads back as the same double
    if isinstance(value, (list, tuple, np.ndarray)) and all(isinstance(v, numbers.Real) for v in value):
        return ",".join(_word(v) for v in value)
    return str(value)


def _is_mesh(value):
    return (isinstance(value, (tuple, list)) and len(value) == 2 and
            all(isinstance(a, np.ndarray) or hasattr(a, "__array__") for a in value) and
            np.ndim(value[0]) == 2 and np.ndim(value[1]) == 2)


def command_args(model, options):
    """The dla3d command line's words (without "dla3d") that grow what `model` grows with
    keyword `options`: what a result records as its command. Meshes given as arrays stand as
    <stl arrays>, which only Python can hand over."""
    args = [] if model == "grow" else [model]
    for key, value in options.items():
        flag = ("-" if len(key) == 1 else "--") + key.replace("_", "-")
        if value is False and key in _ON_BY_DEFAULT:
            args.append("--no-" + key.replace("_", "-"))
            continue
        if value is None or value is False:
            continue
        if value is True:
            args.append(flag)
            continue
        # Options that repeat (seed_at, root_at, seed_mesh) take a list of values.
        if key in _MESH_OPTIONS and _is_mesh(value):
            values = [value]
        elif isinstance(value, np.ndarray) and value.ndim == 2:
            values = list(value)
        elif key == "rotate" and isinstance(value, (list, tuple)) and len(value) == 2:
            values = [f"{value[0]},{_word(value[1])}"]
        elif key == "target_plane" and isinstance(value, (list, tuple)) and len(value) == 2:
            values = [f"{value[0]}={_word(value[1])}"]
        elif isinstance(value, (list, tuple)) and value and all(
                isinstance(v, (list, tuple, np.ndarray, str)) for v in value):
            values = list(value)
        else:
            values = [value]
        for item in values:
            args += [flag, f"<{key} arrays>" if key in _MESH_OPTIONS and _is_mesh(item) else _word(item)]
    return args


def _check_keywords(model, options):
    for key in options:
        if key in _WRITE_ONLY:
            raise ValueError(f"{key} is an argument of Result.write(), not of {model}()")
        if key in _CLI_ONLY:
            raise ValueError(f"{key} is an option of the dla3d command line, not of {model}()")


def _command(model, options):
    words = []
    for word in command_args(model, options):
        plain = word and all(c.isalnum() or c in "_-+=.,:/@%" for c in word)
        words.append(word if plain else "'" + word.replace("'", "'\\''") + "'")
    return " ".join(["dla3d"] + words)


def _run(model, progress, options):
    if progress is not None and not callable(progress):
        raise ValueError("progress is not callable: give a function of (done, total)")
    _check_keywords(model, options)
    result = _core.grow_run(model, options, _command(model, options), progress)
    if result.stopped_by.startswith("error: "):
        # As dla3d keeps the files of a run that failed part way: what grew, and a warning.
        warnings.warn(f"{model}(): {result.stopped_by[7:]}; the result holds the {len(result)} particles "
                      "grown before it", RuntimeWarning, stacklevel=3)
    return result


def grow(progress=None, **options):
    """DLA, as `dla3d [options]`: in or around a mesh (stl="bust.stl", or stl=(V, F) arrays)."""
    return _run("grow", progress, options)


def colonize(progress=None, **options):
    """Space colonization, as `dla3d colonize [options]`."""
    return _run("colonize", progress, options)


def drop(progress=None, **options):
    """Random-drop ballistic aggregation, as `dla3d drop [options]`."""
    return _run("drop", progress, options)


def ballistic(progress=None, **options):
    """Ballistic aggregation, as `dla3d ballistic [options]`."""
    return _run("ballistic", progress, options)


def eden(progress=None, **options):
    """The Eden model on a lattice, as `dla3d eden [options]`."""
    return _run("eden", progress, options)


def breakdown(progress=None, **options):
    """The dielectric breakdown model, as `dla3d breakdown [options]`: eta=3 and
    target_plane=("y", -60) grow a bolt to the ground."""
    return _run("breakdown", progress, options)


def ensemble(model, count, seeds=1, client=None, **options):
    """Grows `count` clusters on a Dask cluster and measures them: see dla3d.ensemble."""
    from .ensemble import run_ensemble
    return run_ensemble(model, count, seeds, client=client, **options)



def _model_function(name, summary):
    def run(progress=None, **options):
        return _run(name, progress, options)
    run.__name__ = run.__qualname__ = name
    run.__doc__ = f"{summary[0].upper()}{summary[1:]}, as `dla3d {name} [options]`."
    return run


# A model registered in the library without a function above (one described whole, dla/run/run.h)
# is a function all the same.
for _name, _summary in _core.models():
    if _name not in globals():
        globals()[_name] = _model_function(_name, _summary)
        __all__.append(_name)
