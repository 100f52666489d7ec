"""Ctrl-C: run() and step() stop at a step boundary and raise KeyboardInterrupt; one thread at a time."""
import math
import os
import signal
import subprocess
import textwrap
import threading
import time

import numpy as np
import pytest

import huygens
from conftest import PYTHON, python_env, small_ring

CHILD = textwrap.dedent(
    """
    import math, sys
    import numpy as np
    import huygens
    s = huygens.scene("ring"); s["grid"]["n"] = 128; s["grid"]["margin"] = 16
    sim = huygens.Simulation(s, fast_plans=True)
    dt = sim.meta["dt"]
    print("ready", flush=True)
    if sys.argv[1] == "uncaught":
        sim.run(until_s=math.inf)
    try:
        sim.run(until_s=math.inf)
    except KeyboardInterrupt:
        n = sim.step_count
        assert n > 0 and abs(sim.time_s - n * dt) < 1e-9 * sim.time_s, (n, sim.time_s)
        assert np.isfinite(sim.field("eta")).all()
        assert sim.step(3) == 3 and sim.step_count == n + 3   # it goes on from the boundary
        print("interrupted at step", n, flush=True)
        sys.exit(0)
    sys.exit(5)
    """
)


def run_child(mode):
    p = subprocess.Popen([PYTHON, "-c", CHILD, mode], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         env=python_env())
    assert p.stdout.readline().strip() == "ready"
    time.sleep(0.5)  # stepping by now
    p.send_signal(signal.SIGINT)
    out, err = p.communicate(timeout=120)
    return p.returncode, out, err


def test_sigint_stops_run_at_a_step_boundary():
    rc, out, err = run_child("caught")
    assert rc == 0, err
    assert out.startswith("interrupted at step ")


def test_uncaught_sigint_ends_python_as_ctrl_c_does():
    rc, out, err = run_child("uncaught")
    assert rc == -signal.SIGINT, (rc, err)  # Python re-raises SIGINT after an uncaught KeyboardInterrupt
    assert "KeyboardInterrupt" in err


def test_a_second_thread_is_refused_while_one_steps_and_ctrl_c_stops_it():
    sim = huygens.Simulation(small_ring(), fast_plans=True)
    seen = []

    def other_thread():
        time.sleep(0.3)
        try:
            sim.field("eta")
        except RuntimeError as e:
            seen.append(str(e))
        os.kill(os.getpid(), signal.SIGINT)

    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        t = threading.Thread(target=other_thread)
        t.start()
        with pytest.raises(KeyboardInterrupt):
            sim.run(until_s=math.inf)
        t.join()
    finally:
        signal.signal(signal.SIGINT, previous)
    assert seen and "in use by another thread" in seen[0]
    n = sim.step_count
    assert n > 0 and sim.step(1) == 1 and np.isfinite(sim.field("eta")).all()


def test_a_signal_handler_reads_the_state_between_steps_but_changes_nothing():
    sim = huygens.Simulation(small_ring(), fast_plans=True)
    seen = {}

    def handler(signum, frame):
        seen["step"], seen["time"] = sim.step_count, sim.time_s  # the state is whole between two steps
        try:
            sim.drop(7.5, 7.5)
        except RuntimeError as e:
            seen["drop"] = str(e)
        raise KeyboardInterrupt

    previous = signal.signal(signal.SIGINT, handler)
    try:
        timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
        timer.start()
        with pytest.raises(KeyboardInterrupt):
            sim.run(until_s=math.inf)
        timer.join()
    finally:
        signal.signal(signal.SIGINT, previous)
    assert seen["step"] == sim.step_count > 0 and seen["time"] == sim.time_s
    assert "one call at a time" in seen["drop"]
