"""huygens.Simulation: scenes from a name, a path or a dict; stepping; the state it reports."""
import math

import numpy as np
import pytest

import huygens
from conftest import small_kelvin, small_ring, small_sph


def test_scene_from_a_shipped_name_a_path_and_a_dict(scenes_dir):
    by_name = huygens.Simulation("ring", fast_plans=True)
    by_path = huygens.Simulation(scenes_dir / "ring.json", fast_plans=True)
    by_dict = huygens.Simulation(huygens.scene("ring"), fast_plans=True)
    assert by_name.scene == "built-in ring.json"
    assert by_path.scene.endswith("ring.json") and by_dict.scene == "<dict>"
    for s in (by_name, by_path, by_dict):
        assert s.solver == "huygens" and s.fields == ["eta"] and s.field("eta").shape == (384, 384)
    assert np.array_equal(by_name.field("eta"), by_dict.field("eta"))


def test_scenes_lists_the_shipped_scenes():
    names = huygens.scenes()
    assert {"ring", "ocean", "kelvin", "sph_dam_break", "dam_break"} <= set(names)
    assert all(not n.endswith(".json") for n in names)
    assert huygens.scene("ocean")["solver"] == "huygens"


def test_step_and_run_advance_time(ring):
    dt = ring.meta["dt"]
    assert ring.step(5) == 5 and ring.step_count == 5
    assert ring.time_s == pytest.approx(5 * dt, rel=1e-12)
    assert ring.step() == 1 and ring.step(0) == 0
    taken = ring.run(until_s=0.5)
    assert ring.time_s == pytest.approx(0.5, rel=1e-9) and taken == 30 - 6
    assert ring.run(until_s=0.2) == 0  # already past it


def test_run_rejects_nan_and_step_negative(ring):
    with pytest.raises(ValueError):
        ring.run(until_s=math.nan)
    with pytest.raises(ValueError):
        ring.step(-1)


def test_reset_starts_again(ring):
    start = ring.field("eta", copy=True)
    ring.step(10)
    ring.reset()
    assert ring.step_count == 0 and ring.time_s == 0.0
    assert np.array_equal(ring.field("eta"), start)


def test_same_steps_same_field_as_a_second_simulation():
    a, b = huygens.Simulation(small_ring(), fast_plans=True), huygens.Simulation(small_ring(), fast_plans=True)
    a.step(20)
    b.run(until_s=a.time_s)
    assert b.step_count == 20 and np.array_equal(a.field("eta"), b.field("eta"))


def test_meta_stats_memory_repr(ring):
    ring.step(3)
    assert ring.meta["solver"] == "huygens" and ring.meta["n"] == 128
    stages = {s["stage"]: s for s in ring.stats()}
    assert "propagate" in stages or len(stages) > 0
    assert all(s["calls"] >= 0 and s["total_ms"] >= 0 for s in stages.values())
    m = ring.memory
    assert m["total_bytes"] > 0 and m["available_bytes"] > 0 and m["parts"][0]["key"].startswith("$")
    assert "step 3" in repr(ring) and repr(ring).startswith("<huygens.Simulation")


def test_sph_and_lbm_fields():
    sph = huygens.Simulation(small_sph())
    assert sph.solver == "sph" and sph.fields == ["pos", "vel", "density", "pressure", "eta"]
    pos = sph.field("pos")
    assert pos.ndim == 2 and pos.shape[1] == 3 and pos.shape[0] == sph.meta["particles"]
    sph.run(until_s=0.01)
    assert sph.time_s >= 0.01 and np.isfinite(sph.field("pos")).all()
    lbm = huygens.Simulation("dam_break")
    assert lbm.fields == ["h", "u", "eta"]
    assert lbm.field("h").shape == (200, 200) and lbm.field("u").shape == (200, 200, 2)
    lbm.step(5)
    assert float(lbm.field("h").max()) == pytest.approx(10.0, abs=0.5)


def test_commands_drop_steer_toggle(ring):
    before = ring.field("eta", copy=True)
    ring.drop(x_m=4.0, y_m=4.0, radius_m=0.1, depth_m=0.02)
    ring.step()
    assert not np.array_equal(ring.field("eta"), before)
    with pytest.raises(huygens.CommandRefused) as e:
        ring.drop(x_m=-1.0, y_m=4.0)
    assert e.value.command == "drop" and "drop(x_m=-1" in str(e.value) and isinstance(e.value, ValueError)
    with pytest.raises(huygens.CommandRefused):
        ring.steer_ship(0, 5.0, 5.0)
    ring.toggle("stokes", True)
    ring.step()
    with pytest.raises(huygens.CommandRefused):
        ring.toggle("no_such_feature")
    with pytest.raises(huygens.CommandRefused):
        ring.set_param("gravity_z", -9.81)


def test_steer_ship_turns_the_hull():
    sim = huygens.Simulation(small_kelvin(), fast_plans=True)
    sim.step(10)
    (pose,) = sim.ship_poses()
    assert pose["heading_rad"] == pytest.approx(0.0, abs=1e-6) and pose["speed_mps"] > 1.0
    sim.steer_ship(0, x_m=pose["x_m"], y_m=pose["y_m"] + 4.0, vx_mps=0.0, vy_mps=1.2)
    sim.step(20)
    (turned,) = sim.ship_poses()
    assert turned["y_m"] > pose["y_m"] + 0.1 and turned["heading_rad"] > 0.2
    with pytest.raises(huygens.CommandRefused):
        sim.steer_ship(3, 1.0, 1.0)


def test_sph_gravity_param():
    sim = huygens.Simulation(small_sph())
    sim.set_param("gravity_x", 2.0)
    sim.drop(0.02, 0.007, radius_m=0.01, depth_m=0.005)
    sim.step(2)
    with pytest.raises(huygens.CommandRefused):
        sim.set_param("viscosity", 1.0)
