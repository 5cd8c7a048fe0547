"""The Blender add-on in Debian's headless Blender: skipped, by name, without Blender."""

import os
import shutil
import subprocess

import pytest

HERE = os.path.dirname(__file__)
ADDON = os.path.join(HERE, "..", "..", "python", "dla3d_blender.py")


@pytest.mark.skipif(shutil.which("blender") is None, reason="Blender is not installed (the README's clients step)")
def test_the_addon_grows_curves_in_the_selected_mesh(tmp_path):
    env = dict(os.environ, BLENDER_USER_SCRIPTS=str(tmp_path / "scripts"), BLENDER_USER_CONFIG=str(tmp_path / "config"))
    module_path = os.environ["PYTHONPATH"].split(os.pathsep)[0]
    done = subprocess.run(["blender", "-b", "--factory-startup", "--python-exit-code", "1", "--python",
                           os.path.join(HERE, "blender_addon_check.py"), "--", ADDON, module_path],
                          capture_output=True, text=True, timeout=600, env=env)
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    assert "dla3d add-on:" in done.stdout


INSTALLED = "/usr/local/lib/python3.11/dist-packages/dla3d"


@pytest.mark.skipif(shutil.which("blender") is None or not os.path.isdir(INSTALLED),
                    reason="Blender or the installed module (the README's setup: cmake --install) is missing")
def test_blenders_python_imports_the_installed_module():
    # No path added: Debian's Blender runs Debian's Python, whose dist-packages hold the module.
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    done = subprocess.run(["blender", "-b", "--factory-startup", "--python-exit-code", "1", "--python-expr",
                           "import dla3d; r = dla3d.grow(particles=500); print('grown', len(r), dla3d.__file__)"],
                          capture_output=True, text=True, timeout=300, env=env)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    assert f"grown 501 {INSTALLED}/__init__.py" in done.stdout
