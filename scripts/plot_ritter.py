#!/usr/bin/env python3
"""Depth and velocity profiles of Ritter's dry-bed dam break (the lbm_ritter_long set-up) against
the exact solution, written to docs/lbm_ritter.png (docs/lbm.md, "The front of a dam break onto a
dry bed").

Runs `huygens run` on a scene of the validation's channel: 200 m of one row (periodic in y,
walls at both ends), h0 = 1 m left of the dam at a third of the length, dry beyond, CFL 0.5 on
the front speed 2 sqrt(g h0), tau 0.55, until the rarefaction head is 6.7 m from the upstream wall
(the front 120 m beyond the dam); with --rows N, N rows between free-slip sides. Reads the last
h_ and u_ dumps. Needs numpy and matplotlib (/usr/bin/python3).
Example: python3 scripts/plot_ritter.py --huygens build/cli/huygens --cells 1024 2048
"""
import argparse
import json
import math
import pathlib
import subprocess
import tempfile

import numpy as np

G = 9.81


def exact(x, t, h0):
    c0 = math.sqrt(G * h0)
    s = 2 * c0 - x / t
    fan = (x > -c0 * t) & (x < 2 * c0 * t)
    h = np.where(x <= -c0 * t, h0, np.where(fan, s * s / (9 * G), 0.0))
    return h, np.where(fan, 2 * (c0 + x / t) / 3, 0.0)


def run(huygens, cells, rows, h0, tau, work):
    """Runs the channel; returns cell centres (m from the dam), depth, velocity (row means) and t."""
    length, dx = 200.0, 200.0 / cells
    c0 = math.sqrt(G * h0)
    x0 = (cells // 3) * dx
    dt = 0.5 * dx / (2 * c0)
    steps = round(0.9 * x0 / c0 / dt)
    sides = "slip" if rows > 1 else "periodic"
    scene = {"solver": "lbm", "lbm": {
        "grid": {"cols": cells, "rows": rows, "cell_m": dx},
        "time": {"dt_s": dt},
        "water": {"gravity_mps2": G, "tau": tau},
        "initial": {"dam": {"x_m": x0, "left_depth_m": h0, "right_depth_m": 0.0}},
        "boundaries": {"left": "wall", "right": "wall", "bottom": sides, "top": sides}}}
    d = pathlib.Path(work) / f"ritter_{cells}_{rows}"
    d.mkdir()
    (d / "scene.json").write_text(json.dumps(scene))
    subprocess.run([huygens, "run", str(d / "scene.json"), "--steps", str(steps), "--dump", str(d / "out"),
                    "--dump-every", str(steps)], check=True, stdout=subprocess.DEVNULL)
    h = np.load(d / "out" / f"h_{steps:06d}.npy").mean(axis=0)
    u = np.load(d / "out" / f"u_{steps:06d}.npy")[..., 0].mean(axis=0)
    return (np.arange(cells) + 0.5) * dx - x0, h, u, steps * dt


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--huygens", default="build/cli/huygens")
    p.add_argument("--cells", type=int, nargs="+", default=[1024, 2048])
    p.add_argument("--rows", type=int, default=1)
    p.add_argument("--depth", type=float, default=1.0)
    p.add_argument("--tau", type=float, default=0.55)
    p.add_argument("--out", default="docs/lbm_ritter.png")
    a = p.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(3, 1, figsize=(8, 9), sharex=True)
    with tempfile.TemporaryDirectory() as work:
        for cells in a.cells:
            x, h, u, t = run(a.huygens, cells, a.rows, a.depth, a.tau, work)
            he, _ = exact(x, t, a.depth)
            lab = f"{cells} cells"
            ax[0].plot(x, h / a.depth, lw=1, label=lab)
            ax[1].plot(x, u / math.sqrt(G * a.depth), lw=1, label=lab)
            m = he > 0.01 * a.depth
            ax[2].plot(x[m], (h[m] - he[m]) / he[m], lw=1, label=lab)
    xe = np.linspace(x[0], x[-1], 4000)
    he, ue = exact(xe, t, a.depth)
    ax[0].plot(xe, he / a.depth, "k--", lw=0.8, label="Ritter (exact)")
    ax[1].plot(xe, ue / math.sqrt(G * a.depth), "k--", lw=0.8, label="Ritter (exact)")
    for level in (0.1, 0.01):
        ax[0].axhline(level, color="0.7", lw=0.5)
    ax[0].set_yscale("log")
    ax[0].set_ylim(1e-3, 1.5)
    ax[0].set_ylabel("h / h0")
    ax[1].set_ylabel("u / sqrt(g h0)")
    ax[2].set_ylabel("(h - h_exact) / h_exact")
    ax[2].axhspan(-0.05, 0.05, color="0.9")
    ax[2].set_ylim(-0.2, 0.2)
    ax[2].set_xlabel("x from the dam (m)")
    side = f"{a.rows} rows, free-slip sides" if a.rows > 1 else "one row"
    ax[0].set_title(f"Ritter, 200 m, {side}, h0 = {a.depth:g} m, tau = {a.tau:g}, t = {t:.2f} s")
    for k in ax:
        k.legend(fontsize=8)
        k.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(a.out, dpi=90)
    print("wrote", a.out)


if __name__ == "__main__":
    main()
