"""Shared set-up of the jellysim Python tests: a cheap scene (a coarse tank, no picture or VTK
files) and the CLI they compare with (JELLYSIM_BIN, set by CTest)."""
import os
import shutil
import subprocess

import pytest

import jellysim

# A coarse tank: seconds per simulated second; simulate runs it without pictures or VTK files.
CHEAP = {"tank.cells": [48, 96], "output.pictures": False, "output.vtk": False}


@pytest.fixture(scope="session")
def cheap_scene():
    return jellysim.load_scene(overrides=CHEAP)


@pytest.fixture(scope="session")
def jellysim_bin():
    path = os.environ.get("JELLYSIM_BIN") or shutil.which("jellysim")
    if not path:
        pytest.skip("JELLYSIM_BIN is not set (CTest sets it to the built CLI)")
    return path


def run_cli(*args, **kwargs):
    """Runs the CLI without the interpreter's LD_PRELOAD (the ASan runtime in a sanitizer build,
    which a program linked with its own runtime must not get twice)."""
    env = {k: v for k, v in os.environ.items() if k != "LD_PRELOAD"}
    return subprocess.run(list(args), env=env, **kwargs)
