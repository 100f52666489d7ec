#!/usr/bin/env python3
"""Deterministic scene mutations run through the real program (docs/robustness.md, "Scene and
npy validation").

Every shipped scene is mutated in seeded ways (numbers set to 0, -1, 1e-300, 1e300, 1e400 as text,
a 400-digit literal, NaN/Infinity as text and as strings; values of the wrong type; keys deleted
or added; the file truncated; nested garbage; huge grid sizes), each mutant is written to a
temporary folder and run as `huygens run MUTANT --steps 2 --fast-plans`. Each run must end with
exit code 0 (a valid scene), 2 (refused scene), 3 (stopped on a non-finite value or a dry cell)
or 4 (refused for memory), within the time limit; a non-zero exit must print a message on
stderr starting with "huygens:". A signal (abort, segmentation fault), exit code 1 (an uncaught
failure), a time-out or a silent refusal fails the test and is listed.

Each run has an address-space limit (--memory-gib, default 4; 0 for none, under AddressSanitizer):
a mutant asking for gigabytes must be refused (exit 2 or 4) or fail its allocation with exit 4,
not fill the machine.

usage: scene_mutation_test.py --cli PATH/huygens --scenes SCENES_DIR [--per-scene N] [--seed S]
       [--jobs J] [--timeout SECONDS] [--memory-gib G]
"""
import argparse
import concurrent.futures
import copy
import json
import os
import random
import resource
import subprocess
import sys
import tempfile

ALLOWED_CODES = {0, 2, 3, 4}

# Replacements of a number, as JSON text (some are not valid JSON on purpose: the parser must
# refuse them with exit 2, not abort).
NUMBER_TEXTS = ["0", "-1", "1", "1e-300", "1e300", "-1e300", "1e400", "-1e400", "7" * 400, "1e19",
                "18446744073709551616", "9223372036854775807", "-9223372036854775809", "0.5", "-0.0",
                "2.5e-8", "NaN", "Infinity", "-Infinity", "nan", "1e", "--1", "0x10"]
# Replacements of any value by a value of another type (valid JSON).
WRONG_TYPES = ['"x"', '"1.0"', '""', "null", "true", "false", "[]", "[1, 2, 3]", "{}", '{"a": 1}',
               '"NaN"', '"Infinity"', '[1e308, -1e308, 0]']
# Grid sizes a real machine cannot hold or that are at a parser's limit.
HUGE_SIZES = ["16384", "16385", "65536", "1048576", "2147483647", "2147483648", "1e9", "4294967296"]
SIZE_KEYS = {"n", "rows", "cols", "margin", "display_per_step"}


def leaves(value, path=()):
    """Every (path, value) of a JSON document; containers too, after their children."""
    if isinstance(value, dict):
        for k, v in value.items():
            yield from leaves(v, path + (k,))
    elif isinstance(value, list):
        for i, v in enumerate(value):
            yield from leaves(v, path + (i,))
    if path:
        yield path, value


def placeholder_dump(doc, path, text):
    """The document as JSON text with the value at `path` replaced by raw `text`."""
    marker = "__HUYGENS_MUTANT__"
    d = copy.deepcopy(doc)
    target = d
    for p in path[:-1]:
        target = target[p]
    target[path[-1]] = marker
    return json.dumps(d, indent=1).replace('"' + marker + '"', text, 1)


def mutate(doc, text, rng):
    """One mutation of a scene: (description, mutant text)."""
    all_leaves = list(leaves(doc))
    numbers = [(p, v) for p, v in all_leaves if isinstance(v, (int, float)) and not isinstance(v, bool)]
    kind = rng.choice(["number", "number", "number", "type", "type", "delete", "add", "truncate",
                       "nested", "size"])
    if kind == "number" and numbers:
        path, _ = rng.choice(numbers)
        t = rng.choice(NUMBER_TEXTS)
        return "number %s = %s" % (fmt_path(path), t[:24]), placeholder_dump(doc, path, t)
    if kind in ("number", "type"):
        path, _ = rng.choice(all_leaves)
        t = rng.choice(WRONG_TYPES)
        return "type %s = %s" % (fmt_path(path), t), placeholder_dump(doc, path, t)
    if kind == "delete":
        path, _ = rng.choice(all_leaves)
        d = copy.deepcopy(doc)
        target = d
        for p in path[:-1]:
            target = target[p]
        del target[path[-1]]
        return "delete %s" % fmt_path(path), json.dumps(d)
    if kind == "add":
        objects = [p for p, v in all_leaves if isinstance(v, dict)] + [()]
        path = rng.choice(objects)
        d = copy.deepcopy(doc)
        target = d
        for p in path:
            target = target[p]
        target["unknown_key_%d" % rng.randrange(100)] = 1
        return "add key under %s" % fmt_path(path), json.dumps(d)
    if kind == "truncate":
        cut = rng.randrange(len(text))
        return "truncate at byte %d" % cut, text[:cut]
    if kind == "nested":
        path, _ = rng.choice(all_leaves)
        depth = rng.choice([10, 1000, 100000])
        t = rng.choice(["[" * depth + "]" * depth, '{"a":' * depth + "1" + "}" * depth])
        return "nested depth %d at %s" % (depth, fmt_path(path)), placeholder_dump(doc, path, t)
    sizes = [(p, v) for p, v in numbers if p and p[-1] in SIZE_KEYS]
    if not sizes:
        return mutate(doc, text, rng)
    path, _ = rng.choice(sizes)
    t = rng.choice(HUGE_SIZES)
    return "size %s = %s" % (fmt_path(path), t), placeholder_dump(doc, path, t)


def fmt_path(path):
    out = "$"
    for p in path:
        out += "[%d]" % p if isinstance(p, int) else "." + p
    return out


def limit_address_space(gib):
    """A preexec function: an address-space limit for the child, so that a mutant that allocates
    gigabytes fails at once (exit 4, out of memory) instead of filling the machine."""
    def apply():
        resource.setrlimit(resource.RLIMIT_AS, (gib << 30, gib << 30))
    return apply if gib > 0 else None


def run_one(cli, file, timeout, gib):
    """(exit code or signal as a negative number or 'timeout', stderr)."""
    env = dict(os.environ, OMP_NUM_THREADS="1", OMP_WAIT_POLICY="PASSIVE")
    try:
        r = subprocess.run([cli, "run", file, "--steps", "2", "--fast-plans"], stdout=subprocess.DEVNULL,
                           stderr=subprocess.PIPE, timeout=timeout, env=env, cwd=os.path.dirname(file),
                           preexec_fn=limit_address_space(gib))
    except subprocess.TimeoutExpired:
        return "timeout", ""
    return r.returncode, r.stderr.decode("utf-8", "replace")


def problem(code, err):
    """Why a run's outcome is wrong, or None."""
    if code == "timeout":
        return "time-out"
    if code < 0:
        return "killed by signal %d" % -code
    if code not in ALLOWED_CODES:
        return "exit code %d" % code
    if code != 0 and not err.strip():
        return "exit code %d without a message" % code
    if code != 0 and not err.lstrip().startswith("huygens:"):
        return "exit code %d, message not starting with 'huygens:'" % code
    return None


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cli", required=True)
    ap.add_argument("--scenes", required=True)
    ap.add_argument("--per-scene", type=int, default=int(os.environ.get("HUYGENS_MUTATIONS_PER_SCENE", "60")))
    ap.add_argument("--seed", type=int, default=16)
    ap.add_argument("--verbose", action="store_true", help="print every mutant's outcome and message")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--timeout", type=float, default=60)
    # 0: no limit, for sanitizer builds (AddressSanitizer reserves terabytes of address space)
    ap.add_argument("--memory-gib", type=int, default=4)
    args = ap.parse_args()
    args.cli = os.path.abspath(args.cli)
    scenes = sorted(f for f in os.listdir(args.scenes) if f.endswith(".json"))
    if not scenes:
        print("no scenes in %s" % args.scenes)
        return 1
    with tempfile.TemporaryDirectory(prefix="huygens_mutants_") as tmp:
        cases = []
        for name in scenes:
            text = open(os.path.join(args.scenes, name), encoding="utf-8").read()
            doc = json.loads(text)
            rng = random.Random("%d:%s" % (args.seed, name))  # one stream per scene: stable when scenes are added
            for i in range(args.per_scene):
                what, mutant = mutate(doc, text, rng)
                file = os.path.join(tmp, "%s.%03d.json" % (name[:-5], i))
                with open(file, "w", encoding="utf-8") as f:
                    f.write(mutant)
                cases.append((name, i, what, file))
        with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
            results = list(pool.map(lambda c: run_one(args.cli, c[3], args.timeout, args.memory_gib), cases))
    counts = {}
    failures = []
    for (name, i, what, _), (code, err) in zip(cases, results):
        counts[code] = counts.get(code, 0) + 1
        why = problem(code, err)
        if args.verbose:
            print("%s %d %s -> %s %s" % (name, i, what, code, err.strip().splitlines()[0][:200] if err.strip() else ""))
        if why:
            failures.append("%s mutant %d (%s): %s; stderr: %s" % (name, i, what, why, err.strip()[-300:]))
    print("%d mutants of %d scenes; outcomes: %s" % (len(cases), len(scenes),
                                                    ", ".join("%s: %d" % (k, v) for k, v in sorted(counts.items(), key=str))))
    for f in failures:
        print("FAIL " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
