#!/usr/bin/python3
"""Side by side: old and new huygens-bench CSV files of the same sections (compare_bench.sh).

For every table both builds print (matched by its title, decimals masked) and every row both print (matched by
its leading label cells: the cells before the first non-integer number), prints each timing or
ratio column (TIMING below: ms, ratios, GB/s, MLUPS, steps/s, wall s) as the median over the rounds
of the old value, of the new one, and new / old. A ratio column (step/raw and the like) compares
the work around the FFTs in each build; a time column compares the builds directly.
Example:
    scripts/compare_bench.py --old old-1.csv old-2.csv --new new-1.csv new-2.csv
"""
import argparse
import csv
import io
import re
import statistics
import sys

# timing and ratio columns of the sections (ms, step/raw, GB/s, MLUPS, steps/s, wall s ...)
TIMING = re.compile(r"\bms\b|\bratio\b|raw|/ copy|GB/s|MLUPS|steps/s|per CPU-s|per core|speed-up|run time|wall s|"
                    r"time/sim", re.IGNORECASE)
NOT_TIMING = re.compile(r"transforms|error|reps|%$", re.IGNORECASE)  # counts, accuracy, shares of a step


def read_blocks(path):
    """{title: (header, rows)} from a huygens-bench CSV file."""
    blocks, title, lines = {}, None, []

    def flush():
        rows = [r for r in csv.reader(io.StringIO("".join(lines))) if r]
        if title is not None and rows:
            blocks[title] = (rows[0], rows[1:])

    with open(path, newline="") as f:
        for line in f:
            if line.startswith("# "):
                flush()
                # measured values in a title (a verdict's numbers) would keep the runs apart
                title, lines = re.sub(r"[0-9]+\.[0-9]+(e[-+]?[0-9]+)?", "#", line[2:].strip()), []
            elif line.strip():
                lines.append(line)
    flush()
    return blocks


def number(s):
    """The cell's value ("105 %" reads 105), or None."""
    try:
        return float(s.strip().removesuffix("%"))
    except ValueError:
        return None


def row_key(row):
    """The leading label cells: up to the first cell holding a non-integer number."""
    key = []
    for cell in row:
        v = number(cell)
        if v is not None and not re.fullmatch(r"[0-9]+", cell.strip()):
            break
        key.append(cell.strip())
    return tuple(key)


def collect(paths):
    """{(title, key, column): [value per file]}, and the titles and columns in first-seen order."""
    values, order = {}, []
    for path in paths:
        for title, (header, rows) in read_blocks(path).items():
            for row in rows:
                key = row_key(row)
                for col, cell in zip(header[len(key):], row[len(key):]):
                    v = number(cell)
                    if v is None or not TIMING.search(col) or NOT_TIMING.search(col):
                        continue
                    k = (title, key, col)
                    if k not in values:
                        order.append(k)
                    values.setdefault(k, []).append(v)
    return values, order


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--old", nargs="+", required=True)
    ap.add_argument("--new", nargs="+", required=True)
    a = ap.parse_args()
    old, order = collect(a.old)
    new, _ = collect(a.new)
    # grouped by table, in the order the tables first appear
    titles = list(dict.fromkeys(k[0] for k in order))
    order.sort(key=lambda k: titles.index(k[0]))
    last_title = None
    print("== side by side: median over the rounds (old = %d runs, new = %d runs); new / old < 1: new is faster"
          " (for a time) or has less overhead (for a step/raw ratio)" % (len(a.old), len(a.new)))
    for k in order:
        if k not in new:
            continue
        title, key, col = k
        if title != last_title:
            print("\n# " + title)
            print("%-50s %-28s %12s %12s %9s" % ("row", "column", "old", "new", "new/old"))
            last_title = title
        o, n = statistics.median(old[k]), statistics.median(new[k])
        ratio = "%9.3f" % (n / o) if o else "        -"
        print("%-50s %-28s %12.4g %12.4g %s" % (" ".join(key)[:50], col[:28], o, n, ratio))
    only_old = sorted({k[0] for k in old} - {k[0] for k in new})
    if only_old:
        print("\ntables only the old build prints: " + "; ".join(only_old))
    return 0


if __name__ == "__main__":
    sys.exit(main())
