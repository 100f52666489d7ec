#!/usr/bin/env python3
"""Relative L2 difference of the .npy dumps of two `huygens run --dump` folders (tests/mpi/near_dumps.cmake).

compare_npy.py A B --limit 1e-6 [--also C [--also-limit 1e-6]]: every .npy of B must exist in A with the
same shape and ||A - B|| / ||B|| <= limit (exit 1 otherwise; --limit 0: the same bits); with --also,
||A - C|| / ||C|| is printed, and asserted <= the --also-limit when one is given.
"""
import argparse
import array
import ast
import math
import os
import struct
import sys


def load_npy(path):
    """(shape, values) of a little-endian float32 C-order .npy file (the format huygens dumps), stdlib only."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:6] != b"\x93NUMPY":
        raise ValueError(path + ": not an .npy file")
    major = data[6]
    if major == 1:
        hlen, start = struct.unpack("<H", data[8:10])[0], 10
    else:
        hlen, start = struct.unpack("<I", data[8:12])[0], 12
    header = ast.literal_eval(data[start:start + hlen].decode("latin1"))
    if header["descr"] != "<f4" or header["fortran_order"]:
        raise ValueError(path + ": expected little-endian float32 in C order, got " + str(header))
    values = array.array("f")
    values.frombytes(data[start + hlen:])
    return tuple(header["shape"]), values


def rel_l2(a, b):
    num = math.fsum((float(x) - float(y)) ** 2 for x, y in zip(a, b))
    den = math.fsum(float(y) ** 2 for y in b)
    return math.sqrt(num / den) if den > 0 else math.sqrt(num)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("a")
    ap.add_argument("b")
    ap.add_argument("--limit", type=float, required=True)
    ap.add_argument("--also")
    ap.add_argument("--also-limit", type=float)
    args = ap.parse_args()
    names = sorted(f for f in os.listdir(args.b) if f.endswith(".npy"))
    if not names:
        print("no .npy dumps in " + args.b)
        return 1
    worst, worst_also, bad = 0.0, 0.0, []
    for f in names:
        sa, a = load_npy(os.path.join(args.a, f))
        sb, b = load_npy(os.path.join(args.b, f))
        if sa != sb or not all(math.isfinite(x) for x in a):
            bad.append(f + " (shape or non-finite)")
            continue
        e = rel_l2(a, b)
        worst = max(worst, e)
        if e > args.limit:
            bad.append("%s (%.3e)" % (f, e))
        if args.also:
            e = rel_l2(a, load_npy(os.path.join(args.also, f))[1])
            worst_also = max(worst_also, e)
            if args.also_limit is not None and not e <= args.also_limit:
                bad.append("%s against %s (%.3e)" % (f, args.also, e))
    print("%d dumps: worst relative L2 %.3e (limit %g)%s" % (
        len(names), worst, args.limit,
        "; against %s %.3e (%s)" % (args.also, worst_also, "not asserted" if args.also_limit is None else
                                    "limit %g" % args.also_limit) if args.also else ""))
    if bad:
        print("over the limit: " + ", ".join(bad))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
