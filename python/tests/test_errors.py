"""Errors as Python exceptions carrying what the CLI prints: the JSON path, the stage and step, the memory figures."""
import json

import pytest

import huygens
from conftest import small_ring


def test_scene_error_is_a_value_error_with_the_json_path():
    s = small_ring()
    s["grid"]["margin"] = 100  # more than half of n = 128
    with pytest.raises(huygens.SceneError) as e:
        huygens.Simulation(s)
    assert isinstance(e.value, ValueError)
    assert e.value.path == "$.grid.margin" and str(e.value).startswith("$.grid.margin: ")


def test_scene_error_of_an_unknown_key_and_an_old_key():
    s = small_ring()
    s["time"]["dt"] = 0.1
    with pytest.raises(huygens.SceneError) as e:
        huygens.Simulation(s)
    assert e.value.path == "$.time.dt" and "dt_s" in str(e.value)


def test_scene_error_of_a_file(tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text('{"solver": "huygens", "grid": {"n": 64,, }}')
    with pytest.raises(huygens.SceneError) as e:
        huygens.Simulation(str(bad))
    assert "bad.json" in str(e.value)
    with pytest.raises(huygens.SceneError) as e:
        huygens.Simulation("no_such_scene")
    assert e.value.path == "$" and "no shipped scene" in str(e.value)


def test_scene_must_be_a_path_a_name_or_a_dict():
    with pytest.raises(TypeError):
        huygens.Simulation(42)


def test_run_stopped_names_the_stage_and_step(ring):
    ring.step(4)
    with pytest.raises(huygens.RunStopped) as e:
        ring.drop(7.5, 7.5, radius_m=1.0, depth_m=3e38)  # a spectrum past float's range
    assert isinstance(e.value, RuntimeError)
    assert e.value.stage == "drops" and e.value.step == 4 and e.value.time_s == pytest.approx(ring.time_s)
    assert "non-finite value produced by stage 'drops' at step 4" in str(e.value)
    with pytest.raises(huygens.RunStopped):  # it does not step on from a non-finite state
        ring.step()
    assert ring.step_count == 4
    ring.reset()
    assert ring.step(2) == 2


def test_memory_refused_carries_the_figures(monkeypatch):
    monkeypatch.setenv("HUYGENS_MAX_MEMORY_GIB", "0.001")  # 1.05e6 bytes
    with pytest.raises(huygens.MemoryRefused) as e:
        huygens.Simulation("ring")
    err = e.value
    assert isinstance(err, MemoryError)
    assert err.available_bytes <= 0.001 * 2**30 < err.needed_bytes
    assert err.needed_bytes == sum(p["bytes"] for p in err.parts)
    assert err.key == "$.grid.n" and "needs" in str(err) and "available" in str(err)


def test_memory_estimate_as_the_dry_run():
    one = huygens.memory_estimate("ocean")
    four = huygens.memory_estimate("ocean", ranks=4)
    assert one["solver"] == "huygens" and one["grid"] == "512 x 512" and one["ranks"] == 1
    assert 0 < four["total_bytes"] < one["total_bytes"] and one["fits"]
    sph = huygens.memory_estimate("sph_dam_break", ranks=8)
    assert sph["ranks"] == 1 and not sph["distributed"]
    with pytest.raises(ValueError):
        huygens.memory_estimate("dam_break", ranks=1000)
    with pytest.raises(huygens.SceneError):
        huygens.memory_estimate({"solver": "huygens"})
    big = huygens.memory_estimate(huygens.scene("ring") | {"grid": {"n": 32768, "length_m": 15.0, "margin": 64}})
    assert big["total_bytes"] > 2**30  # sized, not allocated


def test_validate_returns_the_rows():
    rows = huygens.validate("fft")
    assert rows and all(r["case"] == "fft" for r in rows)
    assert set(rows[0]) == {"case", "quantity", "measured", "expected", "error", "tolerance", "passed", "judged"}
    assert all(r["passed"] for r in rows if r["judged"])
    json.dumps(rows)  # plain Python values
    names = [c["name"] for c in huygens.validation_cases()]
    assert "cauchy_poisson" in names and "sph_dam_break" in names
    with pytest.raises(ValueError):
        huygens.validate(["no_such_case"])
