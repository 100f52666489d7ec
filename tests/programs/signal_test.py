#!/usr/bin/env python3
"""Every program stops cleanly on SIGINT and SIGTERM (docs/robustness.md, "Signals"): exit 130 or
143, a line that says what was stopped, no partial file; a second signal ends a program at once.

    signal_test.py --viz PATH --bench PATH --caustics-bench PATH
    signal_test.py --cli PATH --mpirun "mpirun [flags] -np"      (huygens run on 2 MPI ranks)

Each case starts the real program, waits until it is at work (a line on its output, or a time),
sends the signal and checks the exit code, the message and the files. No timing is asserted: a
loaded machine only makes the waits longer.
"""
import argparse
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time

FAILURES = []


def check(ok, what):
    print(("ok      " if ok else "FAILED  ") + what)
    if not ok:
        FAILURES.append(what)


def start(cmd, folder):
    out = open(os.path.join(folder, "out.txt"), "w")
    return subprocess.Popen(cmd, stdout=out, stderr=subprocess.STDOUT, cwd=folder), out


def wait_for(folder, text, seconds=300):
    """Waits until the program's output holds `text` (True) or `seconds` pass (False)."""
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        with open(os.path.join(folder, "out.txt")) as f:
            if text in f.read():
                return True
        time.sleep(0.1)
    return False


def finish(p, out, folder, seconds=300):
    try:
        code = p.wait(timeout=seconds)
    except subprocess.TimeoutExpired:
        p.kill()
        code = p.wait()
    out.close()
    with open(os.path.join(folder, "out.txt")) as f:
        return code, f.read()


def leftovers(folder):
    return [n for n in os.listdir(folder) if n.endswith(".tmp")]


def case_folder(root, name):
    d = os.path.join(root, name)
    os.makedirs(d)
    return d


def viz_headless(viz, root, sig, code):
    d = case_folder(root, f"viz_headless_{sig.name}")
    p, out = start([viz, "ring", "--headless", "--frames", "1000000", "--screenshot", "shot.png"], d)
    time.sleep(3.0)  # the handler is installed before the scene is read; any point of the run will do
    p.send_signal(sig)
    rc, text = finish(p, out, d)
    name = f"huygens-viz --headless, {sig.name}"
    check(rc == code, f"{name}: exit {rc}, expected {code}")
    check(f"stopped by {sig.name}" in text and "no image written" in text, f"{name}: says it stopped ({text[-200:]!r})")
    check(not os.path.exists(os.path.join(d, "shot.png")) and not leftovers(d), f"{name}: no image, no temporary")


def viz_window(viz, root):
    d = case_folder(root, "viz_window")
    if not shutil.which("xvfb-run"):
        check(False, "huygens-viz window: xvfb-run is not installed (apt-get install xvfb)")
        return
    script = f"'{viz}' ring > viz.txt 2>&1 & p=$!; sleep 6; kill -TERM $p; wait $p; echo \"rc=$?\" >> viz.txt"
    subprocess.run(["xvfb-run", "-a", "-s", "-screen 0 640x480x24", "sh", "-c", script], cwd=d, timeout=600)
    with open(os.path.join(d, "viz.txt")) as f:
        text = f.read()
    check("rc=143" in text, f"huygens-viz window, SIGTERM: exit 143 ({text[-300:]!r})")
    check("stopped by SIGTERM: the window closed" in text, "huygens-viz window, SIGTERM: says it stopped")


def bench(path, root, sig, code):
    d = case_folder(root, f"bench_{sig.name}")
    p, out = start([path, "accuracy", "--quick", "--csv", "bench.csv"], d)
    at_work = wait_for(d, "== accuracy:")  # the first table is out: stop during the next
    p.send_signal(sig)
    rc, text = finish(p, out, d)
    name = f"huygens-bench, {sig.name}"
    check(at_work, f"{name}: printed its first table")
    check(rc == code, f"{name}: exit {rc}, expected {code}")
    check(f"stopped by {sig.name}" in text and "complete table(s)" in text, f"{name}: says it stopped")
    check("== run time per section ==" in text, f"{name}: prints its section times")
    csv_path = os.path.join(d, "bench.csv")
    first = open(csv_path).readline() if os.path.exists(csv_path) else ""
    check(first.startswith(f"# stopped by {sig.name}"), f"{name}: the CSV's first line says it stopped ({first!r})")
    check(not leftovers(d), f"{name}: no temporary")


def bench_twice(path, root):
    d = case_folder(root, "bench_twice")
    p, out = start([path, "accuracy", "--quick"], d)
    wait_for(d, "== accuracy:")
    p.send_signal(signal.SIGINT)
    time.sleep(0.2)
    p.send_signal(signal.SIGINT)
    rc, _ = finish(p, out, d)
    check(rc == -signal.SIGINT, f"huygens-bench, two SIGINTs: the second ended it by the signal (got {rc})")


def caustics_bench(path, root, sig, code):
    d = case_folder(root, f"caustics_{sig.name}")
    p, out = start([path, "--csv", "c.csv"], d)  # the full run: a minute or more
    at_work = wait_for(d, "GL:")
    time.sleep(1.0)
    p.send_signal(sig)
    rc, text = finish(p, out, d)
    name = f"huygens-caustics-bench, {sig.name}"
    check(at_work, f"{name}: started")
    check(rc == code, f"{name}: exit {rc}, expected {code}")
    check(f"stopped by {sig.name}" in text, f"{name}: says it stopped ({text[-200:]!r})")
    csv_path = os.path.join(d, "c.csv")
    first = open(csv_path).readline() if os.path.exists(csv_path) else ""
    check(first.startswith(f"# stopped by {sig.name}"), f"{name}: the CSV's first line says it stopped")
    check(not leftovers(d), f"{name}: no temporary")


def rank_pids(mpirun_pid):
    r = subprocess.run(["pgrep", "-P", str(mpirun_pid)], capture_output=True, text=True)
    return [int(x) for x in r.stdout.split()]


def mpi_run(cli, mpirun, root, signal_ranks):
    """huygens run on 2 ranks, SIGTERM to the ranks (what mpirun passes on: exit 143) or to mpirun
    itself (Open MPI 4.1's mpirun then exits 1 after the ranks stopped cleanly; README)."""
    d = case_folder(root, "mpi_ranks" if signal_ranks else "mpi_mpirun")
    cmd = mpirun.split() + ["2", cli, "run", "ring", "--steps", "1000000000", "--dump", "out", "--dump-every",
                            "20", "--fast-plans"]
    p, out = start(cmd, d)
    end = time.monotonic() + 300
    while time.monotonic() < end and not os.path.exists(os.path.join(d, "out", "meta.json")):
        time.sleep(0.1)
    time.sleep(1.0)
    for pid in rank_pids(p.pid) if signal_ranks else [p.pid]:
        os.kill(pid, signal.SIGTERM)
    rc, text = finish(p, out, d)
    name = "mpirun -np 2 huygens run, SIGTERM to " + ("the ranks" if signal_ranks else "mpirun")
    check(rc == 143 if signal_ranks else rc in (1, 143), f"{name}: exit {rc}")
    meta = open(os.path.join(d, "out", "meta.json")).read() if os.path.exists(os.path.join(d, "out", "meta.json")) else ""
    check('"signal": "SIGTERM"' in meta, f"{name}: meta.json records the stop ({text[-300:]!r})")
    check(not leftovers(os.path.join(d, "out")), f"{name}: no temporary")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--viz")
    ap.add_argument("--bench")
    ap.add_argument("--caustics-bench")
    ap.add_argument("--cli")
    ap.add_argument("--mpirun", help='the launcher and its flags up to the count, e.g. "mpirun -np"')
    a = ap.parse_args()
    root = tempfile.mkdtemp(prefix="huygens-signals-")
    try:
        if a.mpirun:
            mpi_run(os.path.abspath(a.cli), a.mpirun, root, True)
            mpi_run(os.path.abspath(a.cli), a.mpirun, root, False)
            return report()
        a.viz, a.bench, a.caustics_bench = (os.path.abspath(x) for x in (a.viz, a.bench, a.caustics_bench))
        viz_headless(a.viz, root, signal.SIGTERM, 143)
        viz_headless(a.viz, root, signal.SIGINT, 130)
        viz_window(a.viz, root)
        bench(a.bench, root, signal.SIGINT, 130)
        bench(a.bench, root, signal.SIGTERM, 143)
        bench_twice(a.bench, root)
        caustics_bench(a.caustics_bench, root, signal.SIGTERM, 143)
    finally:
        shutil.rmtree(root, ignore_errors=True)
    return report()


def report():
    print(f"signal_test: {len(FAILURES)} failed")
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
