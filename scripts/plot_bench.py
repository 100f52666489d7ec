#!/usr/bin/python3
"""Plot run time against error from huygens-bench --csv output.

Reads the CSV written by `huygens-bench --csv FILE` (blocks of `# section: title` followed by a
header line and rows) and writes one PNG per run-time-against-error table (the kinds in SPECS:
the Huygens core and its baselines, the displayed-frame interpolation, the LBM Stoker sweep, the
SPH dam-break sweep): error against time, log-log, one marker style per method or series, the
Pareto front (points no other point beats in both time and error) drawn as a step line with the
optimal points ringed.

Uses Debian's python3-matplotlib and python3-numpy (scripts/install-deps.sh installs them).
Example:
    build/benchmarks/huygens-bench accuracy --csv bench.csv
    scripts/plot_bench.py bench.csv --out docs/plots
"""
import argparse
import csv
import io
import math
import os
import re
import sys
import textwrap

# (time column, [(error column, series label or None = the "method" column)], x label, y label,
#  column that names each point): one entry per kind of run-time-against-error table; a column
#  name ending in "*" matches the first header that starts with the rest (the SPH front error's
#  header names its time range, which --quick shortens)
SPECS = [
    ("time/sim s", [("error", None)], "wall time per simulated second (s)", "max error / amplitude", "n"),
    ("ms/displayed frame", [("cubic rms err / rms h", "cubic Hermite (eta, eta_dot)"),
                            ("linear rms err / rms h", "linear (eta only)")],
     "ms per displayed frame", "rms error / rms height", "D"),
    ("run time s", [("L1 rel. error", "LBM")], "run time (s)", "L1 relative error", "cells"),
    ("wall s", [("mean front error % (T <= *", "mean front error"), ("max front error %", "max front error")],
     "wall time (s)", "surge front error against Martin & Moyce (%)", "particles across a"),
]

def read_blocks(path):
    """Returns [(title, header, rows)] from a huygens-bench CSV file; each title ends with the
    run's machine line (its `# machine: ...` comment), so every plot says where it ran."""
    blocks, title, lines, machine = [], None, [], ""

    def flush():
        if title is not None and lines:
            rows = list(csv.reader(io.StringIO("".join(lines))))
            rows = [r for r in rows if r]
            if rows:
                blocks.append((title + ("\n" + machine if machine else ""), rows[0], rows[1:]))

    with open(path, newline="") as f:
        for line in f:
            if line.startswith("# machine: "):
                machine = line[2:].strip()
            elif line.startswith("# "):
                flush()
                title, lines = line[2:].strip(), []
            elif line.strip():
                lines.append(line)
    flush()
    return blocks


def number(s):
    try:
        v = float(s)
    except ValueError:
        return math.nan
    return v if math.isfinite(v) and v > 0 else math.nan


def pareto(points):
    """Indices of the points no other point beats in both coordinates (finite points only)."""
    idx = []
    for i, (t, e) in enumerate(points):
        if math.isnan(t) or math.isnan(e):
            continue
        dominated = any(
            j != i and not math.isnan(t2) and not math.isnan(e2) and t2 <= t and e2 <= e and (t2 < t or e2 < e)
            for j, (t2, e2) in enumerate(points))
        if not dominated:
            idx.append(i)
    return sorted(idx, key=lambda i: points[i][0])


def slug(title):
    s = re.sub(r"\(.*", "", title.split("\n")[0]).strip().lower()
    return re.sub(r"[^a-z0-9]+", "_", s).strip("_")[:80] or "table"


def plot_block(plt, title, header, rows, out_dir):
    col = {name: i for i, name in enumerate(header)}
    for name in header:
        for sp in SPECS:
            for e, _ in sp[1]:
                if e.endswith("*") and name.startswith(e[:-1]) and e not in col:
                    col[e] = col[name]
    spec = next((sp for sp in SPECS if sp[0] in col and all(e in col for e, _ in sp[1])), None)
    if spec is None:
        return None
    tname, series, xlabel, ylabel, label_col = spec
    tcol, mcol, ncol = col[tname], col.get("method"), col.get(label_col)
    # every plotted point: (time, error, series label, point label)
    pts = []
    for ename, label in series:
        for r in rows:
            pts.append((number(r[tcol]), number(r[col[ename]]), label or (r[mcol] if mcol is not None else "rows"),
                        r[ncol] if ncol is not None else ""))
    points = [(t, e) for t, e, _, _ in pts]
    if not any(not math.isnan(t) and not math.isnan(e) for t, e in points):
        return None
    fig, ax = plt.subplots(figsize=(8, 5.5), dpi=110)
    methods = []
    for p in pts:
        if p[2] not in methods:
            methods.append(p[2])
    markers = ["o", "s", "^", "D", "v", "P", "X", "*"]
    for k, m in enumerate(methods):
        sel = [p for p in pts if p[2] == m and not math.isnan(p[0]) and not math.isnan(p[1])]
        if not sel:
            continue
        ax.scatter([p[0] for p in sel], [p[1] for p in sel], marker=markers[k % len(markers)], s=36, label=m,
                   zorder=3)
        for t, e, _, name in sel:
            if name:
                ax.annotate(name, (t, e), textcoords="offset points", xytext=(4, 3), fontsize=6, color="0.35")
    front = pareto(points)
    if front:
        fx = [points[i][0] for i in front]
        fy = [points[i][1] for i in front]
        ax.step(fx, fy, where="post", color="k", lw=1.0, ls="--", label="Pareto front", zorder=2)
        ax.scatter(fx, fy, s=130, facecolors="none", edgecolors="k", lw=1.0, zorder=4)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title("\n".join(textwrap.fill(part, 110) for part in title.split("\n")), fontsize=7)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    path = os.path.join(out_dir, slug(title) + ".png")
    fig.savefig(path)
    plt.close(fig)
    return path

def main(argv=None):
    ap = argparse.ArgumentParser(description="Plot error against time per simulated second (log-log, Pareto front "
                                 "marked) from the CSV of `huygens-bench --csv FILE`.")
    ap.add_argument("csv", help="CSV file written by huygens-bench --csv")
    ap.add_argument("--out", default="bench-plots", help="folder for the PNG files (default: bench-plots)")
    args = ap.parse_args(argv)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    os.makedirs(args.out, exist_ok=True)
    written = []
    for title, header, rows in read_blocks(args.csv):
        p = plot_block(plt, title, header, rows, args.out)
        if p:
            written.append(p)
    for p in written:
        print(p)
    if not written:
        print("plot_bench.py: no run-time-against-error table in " + args.csv, file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
