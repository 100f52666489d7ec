#!/usr/bin/env python3
"""What stepping from Python costs over `huygens run`: the same scene, the same steps, timed in the
same run, alternated.

    python3 benchmarks/python_step_overhead.py [--build build] [--scene ocean] [--steps 300] [--repeats 5]

Each repeat runs, in a child process each and in an order that alternates (ABC, CBA, ...):
  cli        `huygens run SCENE --steps N --fast-plans`: the wall time it prints for its steps;
  step(N)    huygens.Simulation(SCENE, fast_plans=True).step(N): one call, N steps;
  N x step() the same with N calls of step() from a Python loop.
Every child gets the same environment (OpenMP threads: OMP_NUM_THREADS as set, or all cores; the
programs and the package both set GOMP_SPINCOUNT=3000 unless a wait policy is set). Two measures:
  wall  the steps' wall time each child prints (set-up, parsing and FFT plans, outside it);
  CPU   the child's CPU time (user + sys, getrusage) less that of the same child run with 0 steps
        (its start, import, parsing and plans): the steps' CPU time, which a loaded machine disturbs
        far less than the wall time (with OMP_NUM_THREADS=1 it is the work itself).
Prints the CPU, the build's ISA, the load, each repeat's times and the ratios of the medians to the
CLI's (the issue's target: <= 1.02). On a loaded machine both scatter by more than that from run to
run, so the script also measures the cost itself: the same three ways on a tiny scene (the ring on
a 16^2 grid, one OpenMP thread, --tiny-steps steps of a few microseconds each), whose per-step difference to the CLI
is what Python adds to every step (the GIL released and taken back, a signal check, and for N x
step() a call), printed as a fraction of the scene's own CLI step. Times nothing it asserts.
"""
import argparse
import json
import os
import pathlib
import re
import resource
import statistics
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[1]

CHILD = """
import sys, time
import huygens
scene, steps, mode = sys.argv[1], int(sys.argv[2]), sys.argv[3]
sim = huygens.Simulation(scene, fast_plans=True)
t0 = time.perf_counter()
if mode == "batch":
    sim.step(steps)
else:
    for _ in range(steps):
        sim.step()
wall = time.perf_counter() - t0
assert sim.step_count == steps
print(f"{wall:.6f}")
"""


def child_cpu(command, env):
    """(stdout, CPU seconds of the child: user + sys)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    out = subprocess.run(command, env=env, check=True, capture_output=True, text=True).stdout
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return out, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def run_cli(cli, scene, steps, env):
    out, cpu = child_cpu([str(cli), "run", scene, "--steps", str(steps), "--fast-plans"], env)
    m = re.search(r"(\d+) steps to t = \S+ s in ([0-9.]+) s wall", out)
    if not m or int(m.group(1)) != steps:
        sys.exit(f"python_step_overhead: no wall time in huygens run's output:\n{out}")
    return float(m.group(2)), cpu


def run_python(pythonpath, scene, steps, mode, env):
    env = dict(env, PYTHONPATH=str(pythonpath) + os.pathsep + env.get("PYTHONPATH", ""))
    out, cpu = child_cpu([sys.executable, "-c", CHILD, scene, str(steps), mode], env)
    return float(out.strip().splitlines()[-1]), cpu


def tiny_overhead(args, cli, pythonpath, env, step_s):
    """What Python adds to a step, from a scene whose steps cost microseconds."""
    scene = {
        "solver": "huygens",
        "grid": {"n": 16, "length_m": 1.0, "margin": 2},
        "time": {"dt_s": 0.01},
        "initial": [{"type": "gaussian", "x_m": 0.5, "y_m": 0.5, "sigma_m": 0.1, "amplitude_m": 0.001}],
    }
    env = dict(env, OMP_NUM_THREADS="1")  # the binding's cost, not barrier waits of threads on a 16^2 grid
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "tiny.json")
        with open(path, "w") as f:
            json.dump(scene, f)
        n = args.tiny_steps
        ways = {
            "cli": lambda: run_cli(cli, path, n, env)[0],
            "step(N)": lambda: run_python(pythonpath, path, n, "batch", env)[0],
            "N x step()": lambda: run_python(pythonpath, path, n, "loop", env)[0],
        }
        per_step = {k: [] for k in ways}
        for r in range(args.repeats):
            for name in (list(ways) if r % 2 == 0 else list(ways)[::-1]):
                per_step[name].append(ways[name]() / n)
    base = statistics.median(per_step["cli"])
    print(f"tiny scene (16^2, {n} steps): cli {1e6 * base:.2f} us/step")
    for name in ("step(N)", "N x step()"):
        extra = statistics.median(per_step[name]) - base
        print(f"  {name:>10}: {1e6 * statistics.median(per_step[name]):.2f} us/step, {1e6 * extra:+.2f} us a step over "
              f"the cli = {100 * extra / step_s:+.3f} % of a {args.scene} step ({1e3 * step_s:.2f} ms in this run)")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=str(ROOT / "build"), help="the CMake build folder (cli/huygens, python/)")
    ap.add_argument("--scene", default="ocean")
    ap.add_argument("--steps", type=int, default=300)
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--tiny-steps", type=int, default=20000, help="steps of the tiny scene")
    args = ap.parse_args()
    build = pathlib.Path(args.build).resolve()
    cli, pythonpath = build / "cli" / "huygens", build / "python"
    env = dict(os.environ)
    if "OMP_WAIT_POLICY" not in env and "GOMP_SPINCOUNT" not in env:
        env["GOMP_SPINCOUNT"] = "3000"  # what both set for themselves: the same for all three
    info = subprocess.run([sys.executable, "-c", "import huygens; print(huygens.cpu_isa()); print(huygens.build_isa())"],
                          env=dict(env, PYTHONPATH=str(pythonpath)), check=True, capture_output=True, text=True)
    cpu, isa = info.stdout.strip().splitlines()
    print(f"CPU: {cpu}; build: {isa}; OMP_NUM_THREADS={env.get('OMP_NUM_THREADS', 'all')} of {os.cpu_count()} cores; "
          f"load {os.getloadavg()[0]:.2f} at the start; Python {sys.version.split()[0]}")
    print(f"scene {args.scene}, {args.steps} steps, {args.repeats} repeats (wall s of the steps alone)")
    runs = {
        "cli": lambda n: run_cli(cli, args.scene, n, env),
        "step(N)": lambda n: run_python(pythonpath, args.scene, n, "batch", env),
        "N x step()": lambda n: run_python(pythonpath, args.scene, n, "loop", env),
    }
    wall = {k: [] for k in runs}
    cpu = {k: [] for k in runs}
    order = list(runs)
    for r in range(args.repeats):
        for name in (order if r % 2 == 0 else order[::-1]):
            w, c = runs[name](args.steps)
            _, c0 = runs[name](0)
            wall[name].append(w)
            cpu[name].append(c - c0)
        print(f"  repeat {r + 1}: " + ", ".join(f"{k} {wall[k][-1]:.3f} s wall, {cpu[k][-1]:.3f} s CPU" for k in runs),
              flush=True)
    for label, times in (("wall", wall), ("CPU", cpu)):
        base = statistics.median(times["cli"])
        for name in runs:
            med = statistics.median(times[name])
            pairs = statistics.median(p / c for p, c in zip(times[name], times["cli"]))
            print(f"{label:>4} {name:>10}: median {med:.3f} s, {1e3 * med / args.steps:.3f} ms/step; ratio to cli "
                  f"{med / base:.4f} (median of the repeats' ratios {pairs:.4f})")
    tiny_overhead(args, cli, pythonpath, env, statistics.median(wall["cli"]) / args.steps)
    print(f"load {os.getloadavg()[0]:.2f} at the end")


if __name__ == "__main__":
    main()
