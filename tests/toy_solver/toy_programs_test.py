#!/usr/bin/env python3
"""The programs with the test-only toy solver registered (tests/toy_solver/): huygens run, --dry-run,
validate, huygens-bench's solvers section and the viewer's headless frame all take a toy scene with
no edit outside the toy's folder and its registration."""
import argparse
import json
import os
import shutil
import struct
import subprocess
import sys
import zlib


def run(cmd, expect=0):
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=240)
    if p.returncode != expect:
        sys.exit(f"FAIL: {' '.join(cmd)} -> {p.returncode} (expected {expect})\n{p.stdout}\n{p.stderr}")
    return p.stdout + p.stderr


def require(cond, what, out=""):
    if not cond:
        sys.exit(f"FAIL: {what}\n{out}")
    print(f"ok: {what}")


def png_rows(path):
    """The PNG's width, height and distinct RGB colours of its first IDAT's decoded bytes."""
    data = open(path, "rb").read()
    require(data[:8] == b"\x89PNG\r\n\x1a\n", f"{path} is a PNG")
    w, h = struct.unpack(">II", data[16:24])
    i, idat = 8, b""
    while i < len(data):
        n = struct.unpack(">I", data[i:i + 4])[0]
        if data[i + 4:i + 8] == b"IDAT":
            idat += data[i + 8:i + 8 + n]
        i += 12 + n
    raw = zlib.decompress(idat)
    return w, h, len(set(raw))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cli", required=True)
    ap.add_argument("--bench")
    ap.add_argument("--viz")
    ap.add_argument("--scene", required=True)
    ap.add_argument("--tmp", required=True)
    a = ap.parse_args()
    shutil.rmtree(a.tmp, ignore_errors=True)
    os.makedirs(a.tmp)
    out = os.path.join(a.tmp, "run")
    text = run([a.cli, "run", a.scene, "--steps", "40", "--dump", out, "--dump-every", "10"])
    meta = json.load(open(os.path.join(out, "meta.json")))
    etas = sorted(f for f in os.listdir(out) if f.startswith("eta_") and f.endswith(".npy"))
    require(len(etas) == 5, f"huygens run wrote 5 eta dumps ({etas})", text)
    require(os.path.getsize(os.path.join(out, etas[-1])) >= 64 * 64 * 4, "a dump holds the 64 x 64 field")
    text = run([a.cli, "run", a.scene, "--dry-run"])
    require("solver toy" in text and "toy runs on one process" in text, "huygens run --dry-run sizes the toy", text)
    text = run([a.cli, "validate", "--list"])
    require("toy_standing_wave" in text, "huygens validate --list lists the toy's case", text)
    text = run([a.cli, "validate", "toy_standing_wave"])
    require("FAIL" not in text and "toy_standing_wave" in text, "huygens validate toy_standing_wave passes", text)
    bad = os.path.join(a.tmp, "bad.json")
    json.dump({"solver": "toy", "toy": {"n": 64, "dt_s": 1.0}}, open(bad, "w"))
    text = run([a.cli, "run", bad, "--steps", "1"], expect=2)
    require("$.toy.dt_s" in text, "a bad toy scene exits 2 naming $.toy.dt_s", text)
    if a.bench:
        text = run([a.bench, "solvers:toy", "--quick", "--threads", "1"])
        rows = [l for l in text.splitlines() if l.split()[:1] == ["toy"]]
        require(len(rows) == 1 and "leapfrog" in rows[0], "huygens-bench solvers:toy times the toy", text)
    if a.viz:
        png = os.path.join(a.tmp, "toy.png")
        text = run([a.viz, a.scene, "--headless", "--frames", "3", "--screenshot", png])
        w, h, colours = png_rows(png)
        require(w > 0 and h > 0 and colours > 16, f"huygens-viz drew the toy's wave ({w} x {h}, {colours} byte values)")
    print("toy solver: every program ran it")


if __name__ == "__main__":
    main()
