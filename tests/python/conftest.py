"""The Python tests run from ctest (tests/CMakeLists.txt), which puts the build's module first
on PYTHONPATH and names dla3d's binary in DLA3D."""

import os
import subprocess

import pytest


@pytest.fixture(scope="session")
def cli():
    """Runs dla3d with `words`; returns the completed process."""
    binary = os.environ.get("DLA3D", "dla3d")

    def run(*words, check=True):
        done = subprocess.run([binary, *words], capture_output=True, text=True, timeout=300)
        if check and done.returncode != 0:
            raise AssertionError(f"dla3d {' '.join(words)} failed: {done.stderr}")
        return done
    return run


@pytest.fixture
def sphere_mesh():
    """A closed octahedron-subdivided sphere of radius 10: (V, 3) vertices, (F, 3) faces."""
    import numpy as np
    vertices = [np.array(v, float) for v in [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]]
    faces = [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)]
    for _ in range(3):
        middle = {}

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in middle:
                p = vertices[a] + vertices[b]
                vertices.append(p / np.linalg.norm(p))
                middle[key] = len(vertices) - 1
            return middle[key]
        faces = [t for a, b, c in faces
                 for t in ((a, mid(a, b), mid(c, a)), (b, mid(b, c), mid(a, b)), (c, mid(c, a), mid(b, c)),
                           (mid(a, b), mid(b, c), mid(c, a)))]
    return 10.0 * np.array(vertices), np.array(faces, dtype=np.int64)
