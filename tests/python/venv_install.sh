#!/usr/bin/env bash
# The pip install of docs/python.md in a fresh venv: `pip install --no-build-isolation ./python`
# builds the module for the venv's Python and installs it there, downloading nothing; the venv
# then grows what dla3d grows. Arguments: SOURCE_DIR WORK_DIR DLA3D
set -euo pipefail
source_dir=$1 work=$2 dla3d=$3
rm -rf "$work"
mkdir -p "$work"
/usr/bin/python3 -m venv --system-site-packages "$work/venv"
CMAKE_BUILD_PARALLEL_LEVEL=2 "$work/venv/bin/python" -m pip install --no-build-isolation --no-index \
  --disable-pip-version-check "$source_dir/python"
cd "$work"
# The venv's own copy, not /usr/local's or the build tree's.
env -u PYTHONPATH "$work/venv/bin/python" - "$dla3d" <<'PY'
import os, subprocess, sys
import dla3d
here = os.path.dirname(dla3d.__file__)
assert here.startswith(sys.prefix), f"dla3d imported from {here}, not the venv {sys.prefix}"
assert os.path.exists(os.path.join(here, "ensemble.py"))
result = dla3d.grow(particles=2000, rng_seed=3)
result.write("venv", formats=["csv"])
subprocess.run([sys.argv[1], "-n", "2000", "--rng-seed", "3", "-q", "--formats", "csv", "-o", "cli"], check=True)
assert open("venv.csv", "rb").read() == open("cli.csv", "rb").read(), "the venv's module grows another structure"
print("venv install: dla3d from", here, "grows the CLI's structure")
PY
