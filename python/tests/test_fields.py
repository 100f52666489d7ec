"""Fields as NumPy arrays: zero-copy read-only views of the solver's buffers, their lifetime, copies."""
import gc

import numpy as np
import pytest

import huygens
from conftest import small_ring, small_sph


def data_pointer(a):
    return a.__array_interface__["data"][0]


@pytest.mark.parametrize("scene,names", [(small_ring, ["eta"]), (small_sph, ["pos", "vel", "density", "pressure", "eta"]),
                                         ("dam_break", ["h", "u", "eta"])])
def test_every_field_is_a_view_of_the_solvers_buffer(scene, names):
    sim = huygens.Simulation(scene() if callable(scene) else scene, fast_plans=True)
    sim.step(2)
    assert sim.fields == names
    for name in names:
        a = sim.field(name)
        assert a.dtype == np.float32 and a.flags.c_contiguous
        assert data_pointer(a) == sim._field_address(name), name  # no copy
        assert a.base is not None and not a.flags.owndata
        assert not a.flags.writeable
        with pytest.raises(ValueError):
            a[(0,) * a.ndim] = 1.0
        assert data_pointer(sim.field(name)) == data_pointer(a)  # the same buffer every call


def test_a_view_shows_the_next_state_and_a_copy_keeps_this_one(ring):
    view = ring.field("eta")
    kept = ring.field("eta", copy=True)
    assert data_pointer(kept) != data_pointer(view) and kept.flags.writeable and kept.flags.owndata
    ring.step(10)
    assert not np.array_equal(view, kept)  # Huygens writes the next height into the same buffer
    assert np.array_equal(view, ring.field("eta"))
    kept[0, 0] = 1.0  # a copy is the user's


def test_an_array_keeps_the_solver_alive_after_the_simulation_is_gone():
    sim = huygens.Simulation(small_ring(), fast_plans=True)
    sim.step(5)
    view = sim.field("eta")
    expected = view.copy()
    del sim
    gc.collect()
    other = huygens.Simulation(small_ring(), fast_plans=True)  # would reuse freed memory
    other.step(7)
    junk = [np.full(view.shape, 7.0, np.float32) for _ in range(8)]
    assert np.array_equal(view, expected) and np.isfinite(view).all()
    del junk


def test_an_array_of_the_solver_before_reset_stays_readable(ring):
    ring.step(8)
    old = ring.field("eta")
    expected = old.copy()
    ring.reset()
    ring.step(3)
    assert np.array_equal(old, expected)
    assert data_pointer(ring.field("eta")) != data_pointer(old)  # the new solver's own buffer


def test_unknown_field_names_the_fields(ring):
    with pytest.raises(KeyError) as e:
        ring.field("h")
    assert "eta" in str(e.value)
