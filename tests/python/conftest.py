# pytest fixtures for the Python module's tests (tests/python/CMakeLists.txt runs them with
# PYTHONPATH=build/python and GLINT=build/app/glint, in a cold environment as every test).
import os
import subprocess
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import meshes  # noqa: E402


@pytest.fixture(scope="session")
def glint_exe():
    exe = os.environ.get("GLINT")
    if not exe or not os.path.exists(exe):
        pytest.fail("GLINT must name the glint command (ctest sets it)")
    return os.path.abspath(exe)


@pytest.fixture(scope="session")
def run(glint_exe):
    """Runs the glint command; returns the CompletedProcess (text)."""
    def run_glint(*args, check=True, **kwargs):
        result = subprocess.run([glint_exe, *map(str, args)], capture_output=True, text=True, **kwargs)
        if check and result.returncode != 0:
            raise AssertionError(f"glint {' '.join(map(str, args))}: exit {result.returncode}: {result.stderr}")
        return result
    return run_glint


@pytest.fixture(scope="session")
def pair(tmp_path_factory):
    """A low/high sphere pair as OBJ files: (low.obj, high.obj)."""
    folder = tmp_path_factory.mktemp("pair")
    low, high = folder / "sphere_low.obj", folder / "sphere_high.obj"
    meshes.write_obj(low, *meshes.sphere(24, 12))
    meshes.write_obj(high, *meshes.sphere(96, 48, bumps=0.03))
    return low, high
