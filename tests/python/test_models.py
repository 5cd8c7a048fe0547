"""The module's growth functions: every model, the arrays against the CLI's files for the same
seed, argument checking, meshes as arrays, the look, progress, Ctrl-C and the GIL."""

import json
import os
import resource
import signal
import subprocess
import sys
import textwrap
import threading
import time

import numpy as np
import pytest

import dla3d

LEAF = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples", "leaf.glb")

# Every model, small, and what the CLI calls its count.
MODELS = [
    ("grow", {"particles": 3000, "rng_seed": 5}),
    ("grow", {"particles": 2000, "seed_at": [(-20, 0, 0), (20, 0, 0)], "radius": "pipe"}),
    ("colonize", {"max_nodes": 3000, "rng_seed": 2}),
    ("drop", {"particles": 2000, "rng_seed": 3}),
    ("ballistic", {"particles": 2000, "rng_seed": 4}),
    ("eden", {"sites": 2000, "rng_seed": 6}),
    # Discharges: to the ground past the strike, to a point, struck, in 2D, and by the point-charge fields.
    ("breakdown", {"particles": 800, "eta": 2, "target_plane": ("y", -20), "stop_at_strike": False, "rng_seed": 7}),
    ("breakdown", {"particles": 3000, "eta": 3, "target_point": (0, -15, 0), "dimensions": 2}),
    ("breakdown", {"particles": 2000, "eta": 6, "field": "charges", "target_plane": ("y", -40), "rng_seed": 3}),
    ("breakdown", {"particles": 2000, "eta": 3, "field": "conductor", "target_plane": ("y", -40), "rng_seed": 3}),
    # Loops: links beside the tree, closed venation and the lattice graph.
    ("grow", {"particles": 2000, "links": (2.5, 2)}),
    ("colonize", {"max_nodes": 2000, "venation": "closed", "influence": 8.0, "dimensions": 2}),
    ("eden", {"sites": 1000, "links": "lattice", "lattice": "hex"}),
    # Aggregates of clusters: diffusing in a box, and tuned to a law, of monomers of many sizes.
    ("aggregate", {"monomers": 400, "rng_seed": 8}),
    ("aggregate", {"monomers": 300, "mode": "tuned", "df": 2.0, "kf": 1.4, "sizes": "lognormal", "spread": 1.3,
                   "overlap": 0.1}),
]
COLUMNS = "id,x,y,z,parent,seed,radius,age,depth,descendants,order,tip"


def test_every_registered_model_is_a_function_and_grown_here():
    """The library registers each model once (dla/run/run.h); Python and this file follow it."""
    registered = dla3d._core.models()
    assert [name for name, _ in registered][0] == "grow"
    for name, summary in registered:
        assert callable(getattr(dla3d, name)) and name in dla3d.__all__, name
        assert summary.startswith("grow"), summary
        assert name in {model for model, _ in MODELS}, f"{name} is not among this file's MODELS"


def grown(model, options):
    return getattr(dla3d, model)(**options)


def expect_tree(result, model="grow", options=None):
    """Parents come earlier, seeds first; every particle is in its parent's seed's tree; each
    branch is as long as `model` makes it (with `options`, its keywords); and DLA's, drop's,
    ballistic's and the breakdown model's particles stick at contact, a spacing from the parent and no nearer any other."""
    n = len(result)
    parent, seed = result.parent, result.seed
    assert result.positions.shape == (n, 3) and parent.shape == seed.shape == (n,)
    k = result.seed_count
    assert k >= 1 and (parent[:k] == -1).all() and (seed[:k] == np.arange(k)).all()
    assert (parent[k:] >= 0).all() and (parent[k:] < np.arange(k, n)).all()
    assert (seed[k:] == seed[parent[k:]]).all()
    assert np.isfinite(result.positions).all()
    # Links beside the tree: two particles each, earlier first, none a tree edge.
    links = result.links
    assert links.shape == (len(links), 2)
    assert ((0 <= links[:, 0]) & (links[:, 0] < links[:, 1]) & (links[:, 1] < n)).all()
    assert not (parent[links[:, 1]] == links[:, 0]).any()
    expect_branch_lengths(result, model, options or {})


def expect_branch_lengths(result, model, options):
    n, k, spacing = len(result), result.seed_count, result.spacing
    if n == k:
        return
    positions, parent = result.positions, result.parent
    length = np.linalg.norm(positions[k:] - positions[parent[k:]], axis=1)
    slack = 1e-6 * spacing
    if model in ("grow", "drop", "ballistic", "breakdown"):
        if options.get("constraint") == "clip":  # a clipped branch ends short of the mesh
            assert ((length > 0) & (length <= spacing + slack)).all(), length.max()
        else:
            assert np.allclose(length, spacing, rtol=1e-6, atol=0), (length.min(), length.max())
        # No grown particle nearer than a spacing to any other (a sample of 2,000 beyond 4,000).
        grown_ids = np.arange(k, n)
        if len(grown_ids) > 4000:
            grown_ids = np.random.default_rng(1).choice(grown_ids, 2000, replace=False)
        for chunk in np.array_split(grown_ids, max(1, len(grown_ids) // 500)):
            d = np.linalg.norm(positions[chunk, None, :] - positions[None, :, :], axis=2)
            d[np.arange(len(chunk)), chunk] = np.inf
            assert d.min() >= spacing - slack, d.min()
    elif model == "aggregate":  # a monomer touches its parent, sintered by `overlap`, and overlaps no other more
        radii, keep = result.radii, 1.0 - options.get("overlap", 0.0)
        assert radii.shape == (n,) and (radii > 0).all()
        np.testing.assert_allclose(length, keep * (radii[k:] + radii[parent[k:]]), rtol=1e-7)
        d = np.linalg.norm(positions[:, None, :] - positions[None, :, :], axis=2)
        least = keep * (radii[:, None] + radii[None, :])
        np.fill_diagonal(d, np.inf)
        assert (d >= least * (1 - 1e-7)).all()
    elif model == "eden":  # a site hangs from the nearest occupied site of its mask
        assert ((length >= spacing - slack) & (length <= 8 * np.sqrt(3) * spacing + slack)).all()
    elif model == "colonize" and "collide" not in options:  # a step, moved by the noise
        noise = options.get("noise", (0.0, 0.0))
        amplitude = noise[0] if isinstance(noise, tuple) else 0.0
        assert ((length > 0) & (length <= spacing + np.sqrt(3) * amplitude + slack)).all(), length.max()


@pytest.mark.parametrize("model,options", MODELS)
def test_every_model_grows_a_tree(model, options):
    result = grown(model, options)
    assert result.complete and result.stopped_by == ""
    expect_tree(result, model, options)
    # The attributes agree with the tree.
    n, k = len(result), result.seed_count
    depth = result.depth
    assert (depth[:k] == 0).all() and (depth[k:] == depth[result.parent[k:]] + 1).all()
    children = np.bincount(result.parent[k:], minlength=n)
    assert (result.tip == (children == 0)).all()
    assert (result.order[result.tip] == 1).all()
    assert result.descendants[:k].sum() + k == n
    age = result.age
    assert age[k] == 0 and (len(result) == k + 1 or age[-1] == 1) and (np.diff(age[k:]) >= 0).all()
    assert (result.radius > 0).all()


@pytest.mark.parametrize("model,options", MODELS)
def test_arrays_are_the_clis_csv_for_the_same_seed(model, options, cli, tmp_path):
    result = grown(model, options)
    # The command it reports is the CLI's for the same structure.
    words = result.command.split()[1:]
    cli(*words, "-q", "--formats", "csv", "-o", str(tmp_path / "cli"))
    table = np.loadtxt(tmp_path / "cli.csv", delimiter=",", skiprows=1)
    # A discharge that struck its target has its current, channel and light besides.
    struck = result.strike >= 0
    assert open(tmp_path / "cli.csv").readline().strip() == COLUMNS + (",current,channel,light" if struck else "")
    assert len(table) == len(result)
    np.testing.assert_array_equal(table[:, 1:4], result.positions)
    np.testing.assert_array_equal(table[:, 4], result.parent)
    np.testing.assert_array_equal(table[:, 5], result.seed)
    np.testing.assert_array_equal(table[:, 6].astype(np.float32), result.radius)  # the shortest float text
    np.testing.assert_array_equal(table[:, 7].astype(np.float32), result.age)
    np.testing.assert_array_equal(table[:, 8], result.depth)
    np.testing.assert_array_equal(table[:, 9], result.descendants)
    np.testing.assert_array_equal(table[:, 10], result.order)
    np.testing.assert_array_equal(table[:, 11], result.tip)
    if struck:
        np.testing.assert_array_equal(table[:, 12].astype(np.float32), result.current)
        np.testing.assert_array_equal(table[:, 13], result.channel)
        np.testing.assert_array_equal(table[:, 14].astype(np.float32), result.light)
        assert result.channel[result.strike] and result.current[result.strike] == 1 and result.light[result.strike] == 1
    else:
        assert not result.channel.any() and (result.light == result.age).all()
    # The links, and the CLI's PREFIX_links.csv.
    assert result.links.dtype == np.int32 and result.links.shape == (len(result.links), 2)
    looped = "links" in options or "venation" in options
    assert (len(result.links) > 0) == looped
    if looped:
        links = np.loadtxt(tmp_path / "cli_links.csv", delimiter=",", skiprows=1, dtype=np.int32, ndmin=2)
        np.testing.assert_array_equal(links, result.links)
        assert 0 < result.cycles <= len(result.links)
    # And what the module writes is the CLI's, byte for byte.
    result.write(str(tmp_path / "py"), formats=["csv", "ply", "pov"])
    cli(*words, "-q", "--formats", "csv,ply,pov", "-o", str(tmp_path / "cli"))
    for name in ["csv", "ply", "inc", "_growth.inc"]:
        suffix = name if name.startswith("_") else "." + name
        assert (tmp_path / f"py{suffix}").read_bytes() == (tmp_path / f"cli{suffix}").read_bytes(), name


def test_the_particle_arrays_share_the_structures_memory():
    result = dla3d.grow(particles=500)
    positions, parent, seed = result.positions, result.parent, result.seed
    assert not positions.flags.owndata and not positions.flags.writeable
    # One particle is 32 bytes: its centre, then its parent and seed, as the C++ Particle is.
    base = positions.__array_interface__["data"][0]
    assert positions.strides == (32, 8)
    assert parent.__array_interface__["data"][0] == base + 24
    assert seed.__array_interface__["data"][0] == base + 28
    assert np.shares_memory(result.depth, result.depth)  # from the attributes, not copied each time
    assert result.depth.__array_interface__["data"][0] == result.depth.__array_interface__["data"][0]
    # The arrays keep the structure alive after the result is gone.
    del result
    assert positions.shape == (501, 3) and parent[1] == 0


# The library checks the options and names them in its messages; Python spells them as
# keywords, dla3d as flags. Where the CLI reads the same values, it prints the same line.
@pytest.mark.parametrize("options,python,cli_line", [
    ({"particles": -1}, "particles=-1 is not in [0, 2e+09]", "--particles -1 is not in [0, 2e+09]"),
    ({"spawn": "cube"}, "spawn='cube' is not one of sphere, disk, box, inside, radial, surface",
     "--spawn 'cube' is not one of sphere, disk, box, inside, radial, surface"),
    ({"seed_at": (1, 2)}, "seed_at='1,2' is not 3 comma-separated numbers", "--seed-at '1,2' is not 3 comma-separated numbers"),
    ({"stickiness": 0}, "stickiness=0 is not in [0.0001, 1]", "--stickiness 0 is not in [0.0001, 1]"),
    ({"radius": "boundary"}, "radius boundary measures to a constraint mesh: give one with stl",
     "--radius boundary measures to a constraint mesh: give one with --stl"),
    ({"seed_paint": "red"}, "seed_paint seeds the painted part of a mesh: give one with stl",
     "--seed-paint seeds the painted part of a mesh: give one with --stl"),
    ({"stl": "x.stl", "seed_paint": "zz"}, "seed_paint='zz': the colour is not a name", "--seed-paint 'zz': the colour is not a name"),
    ({"fill": 0.5}, "fill fills a mesh's volume: give one with stl", "--fill fills a mesh's volume: give one with --stl"),
])
def test_bad_options_are_the_librarys_line_spelled_for_python(options, python, cli_line, cli):
    with pytest.raises(ValueError) as raised:
        dla3d.grow(**options)
    assert str(raised.value).startswith(python), str(raised.value)
    assert "`" not in str(raised.value) and "--" not in str(raised.value)
    words = dla3d.command_args("grow", options)
    done = cli(*words, "-q", "-o", "/tmp/dla3d_python_refused", check=False)
    assert done.returncode == 2
    assert done.stderr.startswith("dla3d: error: " + (cli_line or python)), done.stderr


# An option that only means something with another, given without it: the library refuses it
# for Python and dla3d alike.
@pytest.mark.parametrize("model,options,python,cli_line", [
    ("grow", {"fill_distance": 5}, "fill_distance is for fill", "--fill-distance is for --fill"),
    ("drop", {"side": "outside"}, "side and constraint say how stl's mesh constrains growth: give one",
     "--side and --constraint say how --stl's mesh constrains growth: give one"),
    ("eden", {"mask": "B"}, "mask and mask_threshold are for mode drop",
     "--mask and --mask-threshold are for --mode drop"),
    ("colonize", {"attractor_box": (0, 0, 0, 1, 1, 1)}, "attractor_box is for attractors_in box, not sphere",
     "--attractor-box is for --attractors-in box, not sphere"),
])
def test_an_option_without_the_one_it_serves_is_refused_alike(model, options, python, cli_line, cli):
    with pytest.raises(ValueError) as raised:
        getattr(dla3d, model)(**options)
    assert str(raised.value) == python
    done = cli(*dla3d.command_args(model, options), "-q", "-o", "/tmp/dla3d_python_refused", check=False)
    assert done.returncode == 2
    assert done.stderr == f"dla3d: error: {cli_line}\n", done.stderr


def test_a_missing_file_is_an_os_error():
    with pytest.raises(OSError, match="cannot read '/no/such/mesh.stl'"):
        dla3d.grow(stl="/no/such/mesh.stl")


@pytest.mark.parametrize("call,message", [
    (lambda: dla3d.grow(bogus=1), "bogus is not an option of grow()"),
    (lambda: dla3d.eden(particles=10), "particles is not an option of eden()"),
    (lambda: dla3d.grow(formats=["csv"]), "formats is an argument of Result.write()"),
    (lambda: dla3d.grow(checkpoint="x.ck"), "checkpoint is an option of the dla3d command line"),
    (lambda: dla3d.grow(progress=3), "progress is not callable"),
    (lambda: dla3d.grow(seed_at=[(0, 0, 0), object()]), "is not a string or a number"),
    (lambda: dla3d.grow(particles=10).write("/tmp/dla3d_py_x", formats=["gif"]), "'gif' is not one of"),
    (lambda: dla3d.grow(particles=10).write("/no/such/dir/x", formats=["csv"]), "cannot write"),
    (lambda: dla3d.grow(particles=10).tubes(sides=2), "sides=2 is not in [3, 64]"),
    (lambda: dla3d.grow(particles=10, tube_sides=2**32 + 8), "tube_sides=4294967304 is not in [3, 64]"),
    (lambda: dla3d.grow(particles=10, lod=2).write("/tmp/dla3d_py_x", formats=["csv"]),
     "lod=2 writes levels of the glb: add glb to formats"),
    (lambda: dla3d.grow(particles=10, leaf=LEAF).write("/tmp/dla3d_py_x", formats=["csv"]),
     "leaf places leaves in the glb: add glb to formats"),
    (lambda: dla3d.grow(particles=10, leaf=__file__).write("/tmp/dla3d_py_x", formats=["glb"]),
     "is not a binary glTF (.glb)"),
    (lambda: dla3d.grow(particles=10, leaf=3), "leaf=3 is not a string"),
    (lambda: dla3d.grow(particles=10).tubes(uv_scale=-1), "uv_scale=-1 is not in [1e-09, 1e+09] (0: the base circumference)"),
])
def test_misuse_is_one_clear_line(call, message):
    with pytest.raises(ValueError) as raised:
        call()
    assert message in str(raised.value) and "\n" not in str(raised.value)


def test_a_mesh_as_arrays_grows_as_the_same_mesh_from_a_file(sphere_mesh, tmp_path):
    vertices, faces = sphere_mesh
    result = dla3d.grow(stl=(vertices, faces), particles=2000, seeds=2)
    expect_tree(result)
    assert result.seed_count == 2
    # Every particle inside the sphere's mesh (whose faces are within 10 of its centre).
    assert np.linalg.norm(result.positions, axis=1).max() < 10.0
    # The same mesh in a file: the same structure.
    off = tmp_path / "sphere.off"
    lines = ["OFF", f"{len(vertices)} {len(faces)} 0"] + [" ".join(repr(float(c)) for c in v) for v in vertices]
    lines += ["3 " + " ".join(str(i) for i in f) for f in faces]
    off.write_text("\n".join(lines) + "\n")
    from_file = dla3d.grow(stl=str(off), particles=2000, seeds=2)
    np.testing.assert_array_equal(result.positions, from_file.positions)
    # Around it, nothing inside.
    around = dla3d.grow(stl=(vertices, faces), side="outside", particles=1000)
    assert np.linalg.norm(around.positions, axis=1).min() > 9.0
    with pytest.raises(ValueError, match="face [0-9]+ names vertex 99, not one of its 99"):
        dla3d.grow(stl=(vertices[:99], faces))


# drop and colonize take DLA's mesh controls as keywords: seeds (colonize: roots) on the mesh,
# and DLA's fill and shell refused with why.
def test_drop_and_colonize_take_the_mesh_controls(sphere_mesh):
    for name, options in [("drop", {"particles": 100}),
                          ("colonize", {"attractors_in": "mesh", "attractors": 400, "max_nodes": 50000})]:
        model = getattr(dla3d, name)
        three = model(stl=sphere_mesh, spacing=0.5, seeds=3, **options)
        assert three.seed_count == 3
        surface = model(stl=sphere_mesh, spacing=0.5, seed_surface=True, **options)
        assert surface.seed_count > 100
        radii = np.linalg.norm(surface.positions[:surface.seed_count], axis=1)
        assert (radii < 10).all() and (radii > 9).all()  # half a spacing inside the surface
        expect_tree(three, name, options)
    with pytest.raises(ValueError, match="^fill grows DLA until a mesh is full; drop grows to its count, particles$"):
        dla3d.drop(fill=0.5)
    with pytest.raises(ValueError, match="^shell keeps DLA's walkers near a surface; colonization"):
        dla3d.colonize(shell=3)
    with pytest.raises(ValueError, match="seeds places seeds in a mesh given with stl; without one, use root_at"):
        dla3d.colonize(seeds=2)


def test_tubes_and_strands_follow_the_look(cli, tmp_path):
    result = dla3d.grow(particles=1500, rng_seed=3)
    tubes = result.tubes(sides=6)
    vertices, normals, faces = tubes
    particle = tubes.particle
    assert tubes.vertices is vertices and tubes.faces is faces
    assert vertices.dtype == np.float32 and faces.dtype == np.uint32
    assert vertices.shape == normals.shape and particle.shape == (len(vertices),)
    assert faces.max() < len(vertices)
    np.testing.assert_allclose(np.linalg.norm(normals, axis=1), 1.0, atol=1e-5)
    # Every vertex lies within its particle's radius of it, or of the branch point a strand
    # starts at, a spacing away.
    distance = np.linalg.norm(vertices - result.positions[particle], axis=1)
    assert (distance <= result.radius[particle] * 1.01 + result.spacing + 1e-4).all()
    # Texture coordinates around and along; tangents of unit length across the normals.
    uv, tangent = tubes.uv, tubes.tangent
    assert uv.dtype == np.float32 and uv.shape == (len(vertices), 2) and tangent.shape == (len(vertices), 4)
    assert uv[:, 0].min() == 0 and uv[:, 0].max() == 1 and uv[:, 1].min() == 0
    np.testing.assert_allclose(np.linalg.norm(tangent[:, :3], axis=1), 1.0, atol=1e-5)
    np.testing.assert_allclose(np.einsum("ij,ij->i", tangent[:, :3], normals), 0.0, atol=1e-5)
    assert (tangent[:, 3] == 1).all()
    # v is the length along the tree in uv_scales: half the scale, twice the v.
    finer = result.tubes(sides=6, uv_scale=0.5)
    coarser = result.tubes(sides=6, uv_scale=1.0)
    np.testing.assert_allclose(finer.uv[:, 1], 2 * coarser.uv[:, 1], rtol=1e-5)
    # The OBJ the CLI writes has the same tubes.
    cli(*result.command.split()[1:], "-q", "--formats", "obj", "--tube-sides", "6", "-o", str(tmp_path / "t"))
    obj_vertices = sum(1 for line in open(tmp_path / "t.obj") if line.startswith("v "))
    obj_uvs = [line.split()[1:] for line in open(tmp_path / "t.obj") if line.startswith("vt ")]
    np.testing.assert_allclose(np.array(obj_uvs, dtype=float), np.c_[uv[:, 0], 1 - uv[:, 1]], atol=1e-5)
    obj_faces = sum(1 for line in open(tmp_path / "t.obj") if line.startswith("f "))
    assert (obj_vertices, obj_faces) == (len(vertices), len(faces))
    ids, starts = result.strands()
    assert starts[0] == 0 and starts[-1] == len(ids) and len(starts) - 1 == result.tip.sum()
    for k in range(len(starts) - 1):  # each strand runs down the tree, from parent to child
        strand = ids[starts[k]:starts[k + 1]]
        assert (result.parent[strand[1:]] == strand[:-1]).all()


def test_the_callback_sees_progress_and_stops_growth(tmp_path):
    seen = []

    def progress(done, total):
        seen.append((done, total))
        return done < 20000

    result = dla3d.grow(particles=10**7, progress=progress)
    assert not result.complete and result.stopped_by == "callback"
    assert seen and seen[-1][1] == 10**7 and 20000 <= len(result) < 10**7
    expect_tree(result)
    # What grew writes as an incomplete run.
    result.write(str(tmp_path / "part"), formats=["json"])
    record = json.loads((tmp_path / "part.json").read_text())
    assert record["stopped_by"] == "callback" and record["complete"] is False
    assert record["timings"]["grow_seconds"] > 0 and record["command"] == result.command

    def fails(done, total):
        raise RuntimeError("from the callback")

    with pytest.raises(RuntimeError, match="from the callback"):
        dla3d.grow(particles=10**7, progress=fails)


def test_growth_that_fails_part_way_returns_what_grew_with_a_warning(tmp_path):
    with pytest.warns(RuntimeWarning, match="no free start .* the result holds the"):
        result = dla3d.grow(spawn="box", box=(-2, -2, -2, 2, 2, 2), particles=1000)
    assert not result.complete and result.stopped_by.startswith("error: no free start")
    assert 1 < len(result) < 1001 and "stopped by error" in repr(result)
    expect_tree(result)
    result.write(str(tmp_path / "filled"), formats=["json"])
    assert '"complete": false' in (tmp_path / "filled.json").read_text()


def test_other_python_threads_run_while_it_grows():
    # A thread that counts as fast as it can. Between two progress calls, while the C++ grows,
    # only a released GIL lets it count: growth stops once it has counted between three pairs.
    count = [0]
    done = threading.Event()

    def counter():
        while not done.is_set():
            count[0] += 1

    between = []
    last = [None]

    def progress(grown, total):
        if last[0] is not None and count[0] > last[0]:
            between.append(count[0] - last[0])
        going_on = len(between) < 3
        last[0] = count[0]  # as this call returns to the growth
        return going_on

    thread = threading.Thread(target=counter)
    thread.start()
    try:
        result = dla3d.grow(particles=10**8, progress=progress)
    finally:
        done.set()
        thread.join()
    assert len(between) == 3, between
    assert result.stopped_by == "callback"


def test_ctrl_c_returns_what_grew(tmp_path):
    script = textwrap.dedent(f"""
        import signal, sys, dla3d
        signal.signal(signal.SIGINT, signal.default_int_handler)  # as in an interactive session
        def progress(done, total):  # says when growth is under way, with more than 1000 grown
            if done > 1000 and not progress.said:
                progress.said = True
                print("growing", flush=True)
        progress.said = False
        result = dla3d.grow(particles=10**8, progress=progress)
        print(len(result), result.complete, result.stopped_by, flush=True)
        result.write({str(tmp_path / "stopped")!r}, formats=["csv", "json"])
        """)
    process = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True)
    assert process.stdout.readline().strip() == "growing"
    process.send_signal(signal.SIGINT)
    out, _ = process.communicate(timeout=60)
    assert process.returncode == 0
    count, complete, stopped_by = out.split()
    assert complete == "False" and stopped_by == "SIGINT" and 1000 < int(count) < 10**8
    assert sum(1 for _ in open(tmp_path / "stopped.csv")) == int(count) + 1
    assert '"stopped_by": "SIGINT"' in (tmp_path / "stopped.json").read_text()


def _cpu_seconds(pid):
    """The processor time process `pid` has used (/proc's utime and stime)."""
    fields = open(f"/proc/{pid}/stat").read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def _interrupted(script, when):
    """Runs `script` in a Python of its own and sends it SIGINT once when(process) is true;
    returns its stdout and exit code."""
    process = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True)
    while process.poll() is None and not when(process):
        time.sleep(0.002)  # polling for the event, which decides nothing but when to look again
    process.send_signal(signal.SIGINT)
    out, _ = process.communicate(timeout=60)
    return out, process.returncode


def test_ctrl_c_while_the_links_are_made_returns_the_tree_without_them(tmp_path):
    # Growth alone is timed first: the signal comes well after it, while every pair of 30,000
    # particles within 100 spacings is looked at for links.
    def children_seconds():
        usage = resource.getrusage(resource.RUSAGE_CHILDREN)
        return usage.ru_utime + usage.ru_stime
    before = children_seconds()
    subprocess.run([sys.executable, "-c", "import dla3d; dla3d.ballistic(particles=30000)"], check=True)
    growth = children_seconds() - before
    script = textwrap.dedent("""
        import signal, dla3d
        signal.signal(signal.SIGINT, signal.default_int_handler)
        r = dla3d.ballistic(particles=30000, links="100,64")
        print(len(r), r.complete, r.stopped_by, len(r.links), flush=True)
        """)
    out, code = _interrupted(script, lambda p: _cpu_seconds(p.pid) > 1.5 * growth + 1.0)
    assert code == 0, out
    count, complete, stopped_by, links = out.split()
    assert (count, complete, stopped_by, links) == ("30001", "False", "SIGINT", "0")


def test_ctrl_c_while_files_are_written_raises_and_keeps_only_whole_ones(tmp_path):
    prefix = tmp_path / "part"
    script = textwrap.dedent(f"""
        import signal, dla3d
        signal.signal(signal.SIGINT, signal.default_int_handler)
        r = dla3d.grow(particles=100000, lod=4)
        try:
            r.write({str(prefix)!r}, formats=["csv", "glb"])
            print("written", flush=True)
        except KeyboardInterrupt:
            print("interrupted", flush=True)
        """)
    out, code = _interrupted(script, lambda p: os.path.exists(str(prefix) + ".csv"))
    assert code == 0 and out.strip() == "interrupted", out
    assert sum(1 for _ in open(str(prefix) + ".csv")) == 100002  # the header, the seed and each particle
    assert not os.path.exists(str(prefix) + "_lod4.glb")
    for name in os.listdir(tmp_path):
        assert not name.endswith(".tmp"), name
        if name.endswith(".glb"):
            data = open(tmp_path / name, "rb").read()
            assert int.from_bytes(data[8:12], "little") == len(data), name


# Random keyword sets, good values and bad: each grows a valid tree or raises one clear line,
# as the CLI's property test does for command lines (cli_property_test.cpp).
RANDOM_OPTIONS = {
    "grow": {"particles": [0, 1, 300, -3, "many", 10**13], "stickiness": [0.3, 1, 0, -1, 2],
             "dimensions": [2, 3, 4], "spawn": ["sphere", "disk", "box", "radial", "cube"],
             "drift": [(0, 0.2, 0), (1, 2), "up"], "seeds": [1, 2, 0], "rng_seed": [0, 7, -1],
             "radius": ["pipe", "taper", "boundary", "seed-distance", "fat"], "threads": [1, 2, 0, 300],
             "seed_at": [[(0, 0, 0), (10, 0, 0)], [(0, 0, 0), (0, 0, 0)], (1, 2, 3)], "index": ["grid", "kdtree", "x"],
             "tube_sides": [3, 8, 2, 65], "color_by": ["age", "depth", "mood"], "n": [200, -1],
             "uv_scale": [0, 2.5, 1e-9, -1, 1e10, "x"], "lod": [0, 2, 9, -1, 2**32 + 2],
             "tips_every": [1, 3, 0, 10**7, "x"], "leaf": [LEAF, "missing.glb", 3],
             "tips_exclude_paint": ["red", "mauve", 3],
             "links": [2, (3, 2), "1.5,4", 0, -1, (2, 0), (2, 1.5), "lattice", "x", (1, 2, 3)]},
    "colonize": {"venation": ["open", "closed", "shut", 1], "influence": [6, 2.5, -1],
                 "max_nodes": [10, 400, -1, 0], "attractors": [100, 0, -5], "kill_distance": [0.5, 2, -1, 0],
                 "noise": [(0.3, 5), (2, 2), -1], "dimensions": [2, 3, 5], "roots": [1, 3, 0, -2],
                 "rng_seed": [1, 2], "tropism": [(0, 1, 0), "down"], "influence": [5, 0, -1]},
    "drop": {"particles": [100, -1, 0], "dimensions": [2, 3], "zone": ["disk", "box", "ring"],
             "stickiness": [0.5, 1, 3], "rng_seed": [3, 4], "spacing": [1, 0, -2]},
    "ballistic": {"particles": [100, -1, 0], "dimensions": [2, 3, 7], "stickiness": [0.5, 1.5],
                  "rng_seed": [5], "spacing": [0.5, -1]},
    "eden": {"sites": [100, 0, -2], "lattice": ["square4", "square8", "hex", "cubic6", "tri"],
             "mode": ["perimeter", "site", "growth", "x"], "dimensions": [2, 3], "rng_seed": [9],
             "mask_threshold": [0.5, 2], "links": ["lattice", 1.5, "grid"]},
}


def test_leaves_go_in_the_glb_one_node_a_tip(tmp_path):
    import pathlib
    result = dla3d.grow(particles=600, rng_seed=2, leaf=pathlib.Path(LEAF), tips_every=2)
    result.write(str(tmp_path / "tree"), formats=["glb", "tips"])
    glb = (tmp_path / "tree.glb").read_bytes()
    length = int.from_bytes(glb[12:16], "little")
    gltf = json.loads(glb[20:20 + length])
    tips = (tmp_path / "tree_tips.ply").read_bytes()
    count = int(tips[tips.index(b"element vertex ") + 15:].split(b"\n")[0])
    assert count > 10
    assert len(gltf["nodes"]) == 2 + count and gltf["nodes"][1]["name"] == "leaves"
    assert all(node["mesh"] == 1 for node in gltf["nodes"][2:])
    # Result.instances(): the same points, in the same order.
    points = result.instances()
    assert len(points.positions) == count and points.positions.shape == points.directions.shape == (count, 3)
    placed = np.array([node["translation"] for node in gltf["nodes"][2:]])
    assert np.allclose(placed, points.positions, atol=1e-4)
    assert [node["name"] for node in gltf["nodes"][2:]] == [f"leaf {p}" for p in points.particle]
    assert np.allclose(np.linalg.norm(points.directions, axis=1), 1) and (points.scale > 0).all()


def test_random_keyword_sets_grow_or_refuse_in_one_line():
    import random
    rng = random.Random(int(os.environ.get("DLA_PROPERTY_SEED", "2026")))
    grown_count = refused = 0
    for _ in range(int(os.environ.get("DLA_PROPERTY_RUNS", "200"))):
        model = rng.choice(sorted(RANDOM_OPTIONS))
        table = RANDOM_OPTIONS[model]
        options = {key: rng.choice(table[key]) for key in rng.sample(sorted(table), rng.randint(0, 4))}
        try:
            result = getattr(dla3d, model)(**options)
        except (ValueError, OSError) as error:
            text = str(error)
            assert text and "\n" not in text and len(text) < 400, (model, options, text)
            refused += 1
            continue
        expect_tree(result, model, options)
        grown_count += 1
    assert grown_count > 20 and refused > 20, (grown_count, refused)


def test_solid_is_the_clis_closed_mesh(cli, tmp_path):
    result = dla3d.grow(particles=500, rng_seed=4, radius="pipe")
    solid = result.solid()
    vertices, faces = solid
    assert solid.vertices is vertices and solid.faces is faces
    assert vertices.dtype == np.float32 and faces.dtype == np.uint32 and faces.max() < len(vertices)
    assert solid.particle.shape == (len(vertices),)
    # Closed and oriented: every directed edge once, with its opposite.
    edges = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]).astype(np.int64)
    keys = edges[:, 0] * len(vertices) + edges[:, 1]
    assert len(np.unique(keys)) == len(keys)
    assert np.isin(edges[:, 1] * len(vertices) + edges[:, 0], keys).all()
    a, b, c = (vertices[faces[:, k]].astype(np.float64) for k in range(3))
    volume = np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0
    m = solid.measures
    assert m["shells"] == 1 and m["units"] == "scene"
    assert volume == pytest.approx(m["volume"], rel=1e-6)
    # The CLI's STL holds the same triangles.
    cli(*result.command.split()[1:], "-q", "--formats", "stl,json", "-o", str(tmp_path / "s"))
    with open(tmp_path / "s.stl", "rb") as stl:
        stl.seek(80)
        assert int(np.frombuffer(stl.read(4), np.uint32)[0]) == len(faces)
    # Printed: the longest side, in millimetres.
    printed = result.solid(print_size=50, min_wall=1.0)
    size = printed.vertices.max(axis=0) - printed.vertices.min(axis=0)
    assert size.max() == pytest.approx(50, rel=1e-5) and printed.measures["thinnest_wall"] >= 1.0
    with pytest.raises(ValueError, match="voxel"):
        result.solid(solid_voxel=-1)
    with pytest.raises(ValueError, match="bogus is not an option of solid"):
        result.solid(bogus=1)
    with pytest.raises(ValueError, match=r"solid_voxel=0.01 spacings would take about .* \(solid_memory\); solid_voxel=.* fits"):
        result.solid(solid_voxel=0.01, solid_memory=5)
