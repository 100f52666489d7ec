#!/usr/bin/env python3
"""Dumps that survive a crash (docs/robustness.md, "Durable dumps"): every file meta.json lists is
complete and readable after

  1. SIGKILL at random points of a dumping `huygens run` (a crash of the process: 100 kills by
     default), and
  2. a simulated power cut (where the test can: root, and ext4 on a loop device): the run is frozen
     (SIGSTOP) at a random point, the loop device's backing file is copied, which is what the disk
     holds at that instant (the file system's unwritten page cache is not in it), and the copy is
     mounted (its journal replayed) and checked. The file system is mounted so that it does not
     rescue files written without fsync (data=writeback, noauto_da_alloc, a journal commit every
     second); a control run with --no-fsync must lose a listed file there at least once, which
     shows that the check can fail.

    dump_crash_test.py --cli build/cli/huygens [--kills 100] [--cuts 6] [--seed S]

Exit 0: passed (part 2 is skipped, with the reason, where it cannot run); 1: a listed file was
incomplete, or the control lost nothing (the check could not have failed).
"""
import argparse
import json
import math
import os
import random
import shutil
import signal
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "mpi"))
from compare_npy import load_npy  # noqa: E402  (the stdlib .npy reader the MPI tests use)

SCENES = [("ring", 1), ("dam_break", 1)]  # (shipped scene, --dump-every): 1 and 5 fields per dump


def listed_problems(folder):
    """The files meta.json lists that are missing, short, long or unreadable: a header that is not
    a float32 .npy's, or data that are not exactly the header's shape ([] when all are whole). A
    missing meta.json lists nothing; an unreadable one is itself a problem."""
    meta_path = os.path.join(folder, "meta.json")
    if not os.path.exists(meta_path):
        return []
    try:
        with open(meta_path) as f:
            meta = json.load(f)
    except (OSError, ValueError) as e:
        return [f"meta.json unreadable ({os.path.getsize(meta_path)} bytes): {e}"]
    problems = []
    for dump in meta["dumps"]:
        for name in dump["files"]:
            path = os.path.join(folder, name)
            try:
                shape, values = load_npy(path)
                if len(values) != math.prod(shape):
                    raise ValueError(f"{len(values)} values, the header's shape {shape} says {math.prod(shape)}")
            except (OSError, ValueError) as e:
                problems.append(f"{name}: {e}")
    return problems


def start_run(cli, scene, every, folder, extra=()):
    cmd = [cli, "run", scene, "--steps", "1000000000", "--dump", folder, "--dump-every", str(every),
           "--fast-plans", "--overwrite", *extra]
    return subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def kill_test(cli, work, kills, rng):
    """Part 1: SIGKILL at random points; returns the number of kills with a problem."""
    failed = listed_total = 0
    for k in range(kills):
        scene, every = SCENES[k % len(SCENES)]
        folder = os.path.join(work, "kill", scene)
        os.makedirs(folder, exist_ok=True)
        delay = rng.uniform(0.0, 0.6)
        p = start_run(cli, scene, every, folder)
        time.sleep(delay)
        p.send_signal(signal.SIGKILL)
        p.wait()
        problems = listed_problems(folder)
        if os.path.exists(os.path.join(folder, "meta.json")):
            with open(os.path.join(folder, "meta.json")) as f:
                listed_total += sum(len(d["files"]) for d in json.load(f)["dumps"])
        if problems:
            failed += 1
            print(f"kill {k} ({scene}, after {delay:.3f} s): {problems[:3]}")
    print(f"part 1: {kills} SIGKILLs at random points, {listed_total} listed files checked, "
          f"{failed} kill(s) left an incomplete listed file")
    return failed


def run_quiet(*cmd):
    return subprocess.run(cmd, capture_output=True, text=True)


def loop_mount_possible(work):
    if os.geteuid() != 0 or not shutil.which("mkfs.ext4") or not shutil.which("mount"):
        return "needs root with mkfs.ext4 and mount"
    img, mnt = os.path.join(work, "probe.img"), os.path.join(work, "probe")
    os.makedirs(mnt, exist_ok=True)
    run_quiet("truncate", "-s", "16M", img)
    if run_quiet("mkfs.ext4", "-q", "-F", img).returncode != 0:
        return "mkfs.ext4 failed"
    r = run_quiet("mount", "-o", "loop", img, mnt)
    if r.returncode != 0:
        return "a loop device cannot be mounted here: " + r.stderr.strip()
    run_quiet("umount", mnt)
    return ""


def one_cut(cli, work, scene, every, extra, rng):
    """One simulated power cut; returns the problems the copy of the disk shows."""
    img, mnt, snap, smnt = (os.path.join(work, n) for n in ("disk.img", "mnt", "snap.img", "smnt"))
    for d in (mnt, smnt):
        os.makedirs(d, exist_ok=True)
    run_quiet("truncate", "-s", "512M", img)
    run_quiet("mkfs.ext4", "-q", "-F", img)
    r = run_quiet("mount", "-o", "loop,data=writeback,noauto_da_alloc,commit=1", img, mnt)
    if r.returncode != 0:
        raise RuntimeError("mount failed: " + r.stderr)
    try:
        p = start_run(cli, scene, every, os.path.join(mnt, "out"), extra)
        time.sleep(rng.uniform(1.5, 3.0))
        p.send_signal(signal.SIGSTOP)  # the instant of the cut: nothing more reaches the disk
        shutil.copyfile(img, snap)
        p.send_signal(signal.SIGKILL)
        p.wait()
    finally:
        run_quiet("umount", mnt)
    r = run_quiet("mount", "-o", "loop", snap, smnt)  # replays the copy's journal, as a reboot would
    if r.returncode != 0:
        raise RuntimeError("mounting the copy failed: " + r.stderr)
    try:
        return listed_problems(os.path.join(smnt, "out"))
    finally:
        run_quiet("umount", smnt)
        os.remove(snap)
        os.remove(img)


def power_cut_test(cli, work, cuts, rng):
    """Part 2: returns (failed cuts with fsync, control cuts that lost a file, controls run)."""
    failed = 0
    for k in range(cuts):
        scene, every = SCENES[k % len(SCENES)]
        problems = one_cut(cli, work, scene, 4 * every, (), rng)
        if problems:
            failed += 1
            print(f"power cut {k} ({scene}): {problems[:3]}")
    controls = max(2, cuts // 2)
    lost = sum(1 for k in range(controls) if one_cut(cli, work, SCENES[k % 2][0], 4, ("--no-fsync",), rng))
    print(f"part 2: {cuts} simulated power cuts, {failed} left an incomplete listed file; control without "
          f"fsync: {lost} of {controls} cuts lost a listed file")
    return failed, lost, controls


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cli", required=True)
    ap.add_argument("--kills", type=int, default=100)
    ap.add_argument("--cuts", type=int, default=6)
    ap.add_argument("--seed", type=int, default=None)
    a = ap.parse_args()
    seed = a.seed if a.seed is not None else int(time.time())
    print(f"seed {seed} (--seed {seed} repeats these points)")
    rng = random.Random(seed)
    work = tempfile.mkdtemp(prefix="huygens-crash-")
    try:
        bad = kill_test(a.cli, work, a.kills, rng)
        why = loop_mount_possible(work) if a.cuts > 0 else "--cuts 0"
        if why:
            print(f"part 2 skipped: {why}")
        else:
            failed, lost, controls = power_cut_test(a.cli, work, a.cuts, rng)
            bad += failed
            with open("/proc/sys/vm/dirty_expire_centisecs") as f:
                lagging = int(f.read()) >= 500  # data reach the disk 5 s or more after the metadata
            if lagging and lost == 0:
                print(f"the control lost nothing in {controls} cuts: this check could not have failed")
                bad += 1
    finally:
        shutil.rmtree(work, ignore_errors=True)
    print(f"dump_crash_test: {'passed' if bad == 0 else 'FAILED'}")
    return 0 if bad == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
