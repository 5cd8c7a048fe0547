"""The Blender add-on (blender/dla3d_blender) in Debian's headless Blender: skipped, by name,
without Blender. Its zip is checked without Blender."""

import importlib.util
import os
import shutil
import subprocess
import tomllib
import zipfile

import numpy as np
import pytest

HERE = os.path.dirname(__file__)
ZIP = os.environ.get("DLA3D_BLENDER_ZIP", "")
NO_BLENDER = shutil.which("blender") is None


def test_the_zip_holds_one_folder_of_python_and_a_manifest():
    with zipfile.ZipFile(ZIP) as z:
        names = z.namelist()
        manifest = tomllib.loads(z.read("dla3d_blender/blender_manifest.toml").decode())
    assert all(name.startswith("dla3d_blender/") for name in names), names
    assert "dla3d_blender/__init__.py" in names
    assert not [n for n in names if n.endswith((".so", ".pyd", ".pyc", ".dll", ".dylib"))], names
    for key in ("schema_version", "id", "version", "name", "tagline", "maintainer", "type", "blender_version_min",
                "license"):
        assert key in manifest, key
    assert manifest["type"] == "add-on" and manifest["id"] == "dla3d_blender"
    assert manifest["blender_version_min"] == "4.2.0"
    assert manifest["permissions"]["files"]


def addon_core():
    """The add-on's Blender-free part, imported from the source tree."""
    spec = importlib.util.spec_from_file_location(
        "dla3d_blender_core", os.path.join(HERE, "..", "..", "blender", "dla3d_blender", "core.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_an_untouched_panel_passes_no_option():
    # Each option at the value the panel starts with (numbers held in single precision, as
    # Blender's properties hold them) adds no word: dla3d's own defaults apply.
    core = addon_core()
    description = core.read_description(os.environ["DLA3D"])
    for model in description["models"]:
        for option in core.panel_options(model):
            if option["type"] == core.MESH_FILE:
                continue
            if option["kind"] == "flag":
                value = "default" if core.flag_default(option) is None else core.flag_default(option)
            elif option["kind"] in ("integer", "real") and core.number_default(option) is not None:
                value = core.number_default(option)
                value = float(np.float32(value)) if option["kind"] == "real" else value
            else:
                value = "" if option["kind"] in ("integer", "real") else option["default"]
            assert core.option_words(option, value) == [], (model["name"], option["name"], value)
    grow = next(m for m in description["models"] if m["name"] == "grow")
    assert core.main_mesh_option(grow)["name"] == "--stl"
    breakdown = next(m for m in description["models"] if m["name"] == "breakdown")
    assert core.main_mesh_option(breakdown)["name"] == "--stl"  # not the target electrode


def test_a_run_streams_what_the_csv_holds(tmp_path):
    core = addon_core()
    grow = next(m for m in core.read_description(os.environ["DLA3D"])["models"] if m["name"] == "grow")
    run = core.Run(os.environ["DLA3D"], grow, ["--particles=3000", "--rng-seed=3"], str(tmp_path))
    assert run.wait(120) == 0 and run.error() is None
    positions, parents = run.snapshot()
    columns = core.read_csv(run.prefix + ".csv")
    assert len(positions) == len(columns["x"]) == 3001
    assert np.array_equal(positions, np.column_stack([columns["x"], columns["y"], columns["z"]]).astype(np.float32))
    assert np.array_equal(parents, columns["parent"])
    bad = core.Run(os.environ["DLA3D"], grow, ["--particles=-4"], str(tmp_path / "bad"))
    assert bad.wait(60) != 0
    assert "--particles" in bad.error() and "\n" not in bad.error()
    with pytest.raises(core.Missing, match="not an executable file"):
        core.find_dla3d("/nonexistent/dla3d")


def run_in_blender(tmp_path, *extra):
    bust = tmp_path / "bust.stl"
    subprocess.run([os.environ["DLA3D"], "convert", os.environ["DLA_BUST_OFF"], str(bust)], check=True)
    env = dict(os.environ, BLENDER_USER_SCRIPTS=str(tmp_path / "scripts"), BLENDER_USER_CONFIG=str(tmp_path / "config"))
    env.pop("PYTHONPATH", None)  # nothing of dla3d's on Blender's path
    done = subprocess.run(["blender", "-b", "--factory-startup", "--python-exit-code", "1", "--python",
                           os.path.join(HERE, "blender_addon_check.py"), "--", ZIP, os.environ["DLA3D"], str(bust),
                           str(tmp_path), *extra], capture_output=True, text=True, timeout=1200, env=env)
    assert done.returncode == 0, done.stdout[-4000:] + done.stderr[-3000:]
    assert "dla3d add-on: every check passed" in done.stdout
    print("\n".join(line for line in done.stdout.splitlines() if line.startswith("dla3d add-on:")))


@pytest.mark.skipif(NO_BLENDER, reason="Blender is not installed (the README's clients step)")
def test_the_addon_grows_live_in_the_bust_and_animates(tmp_path):
    run_in_blender(tmp_path)


@pytest.mark.skipif(NO_BLENDER, reason="Blender is not installed (the README's clients step)")
def test_the_addon_renders_growth_in_cycles(tmp_path):
    run_in_blender(tmp_path, str(tmp_path / "growth.png"))
    assert (tmp_path / "growth.png").stat().st_size > 10000


INSTALLED = "/usr/local/lib/python3.11/dist-packages/dla3d"


@pytest.mark.skipif(NO_BLENDER or not os.path.isdir(INSTALLED),
                    reason="Blender or the installed module (the README's setup: cmake --install) is missing")
def test_blenders_python_imports_the_installed_module():
    # No path added: Debian's Blender runs Debian's Python, whose dist-packages hold the module.
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    done = subprocess.run(["blender", "-b", "--factory-startup", "--python-exit-code", "1", "--python-expr",
                           "import dla3d; r = dla3d.grow(particles=500); print('grown', len(r), dla3d.__file__)"],
                          capture_output=True, text=True, timeout=300, env=env)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    assert f"grown 501 {INSTALLED}/__init__.py" in done.stdout
