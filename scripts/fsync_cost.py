#!/usr/bin/env python3
"""The cost of durable dumps: `huygens run` with a dump every step, flushed to the disk (the
default: fsync of each file and of the folder before meta.json lists it) and with --no-fsync,
alternated in one run of this script so both see the same machine and load (docs/robustness.md,
"Durable dumps").

    python3 scripts/fsync_cost.py [--cli build/cli/huygens] [--dir DIR] [--repeats 3]

DIR (default: a new folder under the system's temporary folder) decides the file system measured:
the cost is the disk's flush latency, so it differs between an SSD, a network disk and tmpfs.
"""
import argparse
import json
import os
import platform
import shutil
import subprocess
import tempfile
import time

CASES = [  # (scene, steps): one field per dump (ring), five fields per dump (dam_break, LBM)
    ("ring", 100),
    ("dam_break", 100),
]


def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown CPU"


def file_system(path):
    out = subprocess.run(["df", "-T", path], capture_output=True, text=True).stdout.splitlines()
    return out[-1].split()[1] if len(out) > 1 else "?"


def one_run(cli, scene, steps, folder, fsync):
    shutil.rmtree(folder, ignore_errors=True)
    cmd = [cli, "run", scene, "--steps", str(steps), "--dump", folder, "--dump-every", "1", "--fast-plans"]
    if not fsync:
        cmd.append("--no-fsync")
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    wall = time.perf_counter() - t0
    with open(os.path.join(folder, "meta.json")) as f:
        meta = json.load(f)
    size = sum(os.path.getsize(os.path.join(folder, n)) for n in os.listdir(folder))
    return wall, len(meta["dumps"]), size


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cli", default="build/cli/huygens")
    ap.add_argument("--dir", default=None, help="where the dumps go (its file system is measured)")
    ap.add_argument("--repeats", type=int, default=3)
    a = ap.parse_args()
    root = a.dir or tempfile.mkdtemp(prefix="huygens-fsync-")
    os.makedirs(root, exist_ok=True)
    print(f"machine: {cpu_model()}, {os.cpu_count()} cores, load {os.getloadavg()[0]:.2f}; "
          f"dumps on {file_system(root)}")
    rows = []
    for scene, steps in CASES:
        best = {True: None, False: None}
        for _ in range(a.repeats):  # alternated; the fastest of each kind counts
            for fsync in (True, False):
                r = one_run(a.cli, scene, steps, os.path.join(root, scene), fsync)
                if best[fsync] is None or r[0] < best[fsync][0]:
                    best[fsync] = r
        on, off = best[True], best[False]
        rows.append((scene, on[1], on[2] / on[1] / 1024, on[1] / on[0], off[1] / off[0], on[0] / off[0]))
    shutil.rmtree(root, ignore_errors=True) if a.dir is None else None
    head = ("scene", "dumps", "KiB/dump", "dumps/s fsync", "dumps/s --no-fsync", "run time ratio")
    print("  ".join(f"{h:>18}" for h in head))
    for r in rows:
        print(f"{r[0]:>18}  {r[1]:>18d}  {r[2]:>18.0f}  {r[3]:>18.1f}  {r[4]:>18.1f}  {r[5]:>18.2f}")
    print("(a dump every step, the solver's steps included in both; fastest of "
          f"{a.repeats} alternated runs each)")


if __name__ == "__main__":
    main()
