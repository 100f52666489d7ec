#!/usr/bin/env python3
"""Counts the floating-point arithmetic of the SPH neighbour loops in the object code.

usage: simd_report.py OBJECT_OR_ARCHIVE [--min-bits 128|256|512] [--objdump objdump]

Disassembles the object (or static library, e.g. libhuygens_core.a) with objdump and, for the
functions of the SPH density and force passes (SphSystem::compute_density / compute_forces and
their OpenMP bodies, the range sums sph_poly6_range / sph_force_range / sph_wall_range and the
DFSPH sums sph_dfsph_boundary_range / sph_dfsph_list_*, kept out of line), counts the single-precision arithmetic instructions (add, sub, mul, fused
multiply-add, min, max) by register width: scalar (ss), 128-bit (xmm ps), 256-bit (ymm ps), 512-bit (zmm ps); and
the innermost loops (a backward jump and its target) holding six or more of them, each by the
widest register its arithmetic uses.

With --min-bits B every range-sum function must hold a loop whose arithmetic is packed at B bits
or more: the vectorised neighbour loop (beside it the compiler keeps scalar and narrower copies
for a remainder, which ranges padded to 8 floats never run at 256 bits). The force loop
compiled for AVX2 before issue 19 held scalar loops only. Exit 1 when the check fails, 77 when
the object holds none of the functions or cannot be disassembled (CTest: skipped).
"""
import argparse
import re
import subprocess
import sys

DFSPH = r"|sph_dfsph_(boundary_range|list_(flags|factors|divergence|kick|viscous))\("
HOT = re.compile(r"SphSystem::compute_(density|forces)\(|sph_(poly6|force)_range<|sph_(wall|contact)_range\(" + DFSPH)
# the functions that hold a neighbour loop (not the DFSPH kick: its vector loop holds 4 such instructions, one add
# and three fused multiply-adds, below the 6 that make a loop here; it is listed)
LOOP = re.compile(r"sph_(poly6|force)_range<|sph_(wall|contact)_range\(" + DFSPH.replace("|kick", ""))
ARITH = re.compile(r"^v?(add|sub|mul|min|max|f[n]?m(add|sub)(132|213|231))(ss|ps)$")
WIDTH = {"xmm": 128, "ymm": 256, "zmm": 512}


def disassemble(path, objdump):
    try:
        out = subprocess.run([objdump, "-d", "-C", "--no-show-raw-insn", path], capture_output=True, text=True)
    except FileNotFoundError:
        print("simd_report: no", objdump)
        sys.exit(77)
    if out.returncode != 0:
        sys.stderr.write(out.stderr)
        sys.exit(77)
    return out.stdout


def parse(text):
    """{function: [(address, mnemonic, operands)]} for the hot functions."""
    funcs, cur = {}, None
    for line in text.splitlines():
        head = re.match(r"^[0-9a-f]+ <(.*)>:$", line)
        if head:
            cur = funcs.setdefault(head.group(1), []) if HOT.search(head.group(1)) else None
            continue
        ins = re.match(r"^\s*([0-9a-f]+):\t(\S+)\s*(.*)$", line)
        if cur is not None and ins:
            cur.append((int(ins.group(1), 16), ins.group(2), ins.group(3)))
    return funcs


def width(mnemonic, operands):
    """0 for scalar single-precision arithmetic, 128/256/512 for packed, None otherwise."""
    if not ARITH.match(mnemonic):
        return None
    if mnemonic.endswith("ss"):
        return 0
    return max((WIDTH[r] for r in re.findall(r"%([xyz]mm)", operands)), default=128)


def loops(insns):
    """The innermost loops (a backward jump and its target, holding no other loop) with at least
    six single-precision arithmetic instructions, each as its widest width (0: scalar)."""
    spans = []
    for addr, mn, ops in insns:
        tgt = re.match(r"^([0-9a-f]+) <", ops)
        if mn.startswith("j") and tgt and int(tgt.group(1), 16) <= addr:
            spans.append((int(tgt.group(1), 16), addr))
    inner = [s for s in spans if not any(o != s and s[0] <= o[0] and o[1] <= s[1] for o in spans)]
    out = []
    for lo, hi in inner:
        ws = [w for a, mn, ops in insns if lo <= a <= hi for w in [width(mn, ops)] if w is not None]
        if len(ws) >= 6:
            out.append(max(ws))
    return out


def count(funcs):
    """{function: {"scalar": n, 128: n, 256: n, 512: n, "loops": [width...]}}."""
    res = {}
    for name, insns in funcs.items():
        c = {"scalar": 0, 128: 0, 256: 0, 512: 0, "loops": loops(insns)}
        for _, mn, ops in insns:
            w = width(mn, ops)
            if w is not None:
                c["scalar" if w == 0 else w] += 1
        res[name] = c
    return res


def short(name):
    name = re.sub(r"\(.*\)", "()", name, count=1)
    return name.replace("huygens::", "")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("object")
    ap.add_argument("--min-bits", type=int, choices=(128, 256, 512))
    ap.add_argument("--objdump", default="objdump")
    args = ap.parse_args()
    funcs = count(parse(disassemble(args.object, args.objdump)))
    if not funcs:
        print("simd_report: no SPH density or force function in", args.object)
        return 77
    print(f"{'scalar':>7} {'xmm ps':>7} {'ymm ps':>7} {'zmm ps':>7}  {'loops: scalar/128/256/512':>26}  function")
    failed = []
    for name, c in sorted(funcs.items()):
        nl = {w: c["loops"].count(w) for w in (0, 128, 256, 512)}
        lp = "/".join(str(nl[w]) for w in (0, 128, 256, 512))
        print(f"{c['scalar']:7d} {c[128]:7d} {c[256]:7d} {c[512]:7d}  {lp:>26}  {short(name)}")
        if args.min_bits and LOOP.search(name) and max(c["loops"], default=0) < args.min_bits:
            failed.append(short(name))
    print("(single-precision add/sub/mul/fma/min/max; loops: innermost loops with >= 6 of them, by widest register)")
    if failed:
        print(f"simd_report: loops not vectorised at {args.min_bits} bits or more: " + "; ".join(failed))
        return 1
    if args.min_bits:
        print(f"simd_report: the SPH density and force loops are vectorised at >= {args.min_bits} bits")
    return 0


if __name__ == "__main__":
    sys.exit(main())
