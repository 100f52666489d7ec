"""Shared set-up of the package's tests: small scenes (a few ms a step) built from shipped ones."""
import pathlib
import sys

import pytest

import huygens

ROOT = pathlib.Path(__file__).resolve().parents[2]


def small_ring(n=128, margin=16):
    """The shipped ring at n cells (15 m pool, a Gaussian hump at the centre)."""
    s = huygens.scene("ring")
    s["grid"]["n"] = n
    s["grid"]["margin"] = margin
    return s


def small_kelvin():
    """The shipped Kelvin scene on a 128^2 grid of 0.1 m: one hull moving along +x."""
    s = huygens.scene("kelvin")
    s["grid"] = {"n": 128, "length_m": 12.8, "margin": 16}
    s["ships"][0]["path"] = [{"t_s": 0.0, "x_m": 3.0, "y_m": 6.4}, {"t_s": 5.0, "x_m": 9.3, "y_m": 6.4}]
    return s


def small_sph():
    """The shipped SPH dam break at half its resolution (8 particles across the column)."""
    s = huygens.scene("sph_dam_break")
    s["sph"]["spacing_m"] *= 2
    s["sph"]["surface"]["cell_m"] *= 2
    s["sph"]["container_m"][1] *= 2
    s["sph"]["fluid"][0]["max_m"][1] *= 2
    return s


@pytest.fixture
def ring():
    return huygens.Simulation(small_ring(), fast_plans=True)


@pytest.fixture
def scenes_dir():
    return ROOT / "scenes"


def python_env():
    """The environment of a child interpreter that imports the same package as this one."""
    import os

    env = dict(os.environ)
    env["PYTHONPATH"] = str(pathlib.Path(huygens.__file__).resolve().parents[1]) + os.pathsep + env.get("PYTHONPATH", "")
    return env


PYTHON = sys.executable
