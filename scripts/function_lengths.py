#!/usr/bin/env python3
"""Lists C++ function bodies longer than a limit (default 80 lines).

Usage: scripts/function_lengths.py [--max N] [PATH...]   (default PATH: core validation; scripts/test.sh also checks viz cli benchmarks)
A body is a brace block opened after a parameter list `(...)` (with optional qualifiers,
trailing return type or constructor initialisers) at namespace or class scope; lambdas and
nested blocks count toward their enclosing function. Length = closing line - opening line + 1
of the function's head through its closing brace. Exits 1 when a function is over the limit.
"""
import argparse
import pathlib
import re
import sys

CONTROL = re.compile(r"\b(if|for|while|switch|catch|do|else)\s*$")
CONTAINER = re.compile(r"\b(namespace|class|struct|union|enum)\b[^()]*$")


def strip(text):
    """Blanks comments, string and character literals, keeping line breaks."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i)); i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j])); i = j
        elif text.startswith('R"', i):
            m = re.match(r'R"([^(]*)\(', text[i:])
            end = text.find(")" + m.group(1) + '"', i) + len(m.group(1)) + 2
            out.append(re.sub(r"[^\n]", " ", text[i:end])); i = end
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(" " * (j + 1 - i)); i = j + 1
        else:
            out.append(c); i += 1
    return "".join(out)


def functions(path):
    text = strip(path.read_text(errors="replace"))
    # a stack of scopes: (kind, start line, name)
    stack, head_start, results = [], 0, []
    line = 1
    for i, c in enumerate(text):
        if c == "\n":
            line += 1
        if c not in "{};":
            continue
        head = text[head_start:i]
        if c == "{":
            in_function = any(k == "function" for k, _, _ in stack)
            h = head.strip()
            is_function = (not in_function and not CONTAINER.search(h) and ")" in h
                           and not CONTROL.search(h.split("(")[0].strip()) and not h.endswith("="))
            if is_function:
                name = re.findall(r"([~\w:<>]+)\s*\(", h)
                first = line - head.rstrip().count("\n") + len(head) - len(head.lstrip()) and \
                    line - text[head_start:i].lstrip().count("\n")
                stack.append(("function", first, name[0] if name else "?"))
            else:
                stack.append(("block", line, ""))
        elif c == "}" and stack:
            kind, start, name = stack.pop()
            if kind == "function":
                results.append((line - start + 1, name, start))
        head_start = i + 1
    return results


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--max", type=int, default=80)
    ap.add_argument("paths", nargs="*", default=["core", "validation"])
    args = ap.parse_args()
    over = []
    for root in args.paths:
        p = pathlib.Path(root)
        files = [p] if p.is_file() else sorted(list(p.rglob("*.cpp")) + list(p.rglob("*.hpp")))
        for f in files:
            for length, name, start in functions(f):
                if length > args.max:
                    over.append((length, f"{f}:{start}", name))
    for length, where, name in sorted(over, reverse=True):
        print(f"{length:5d}  {where:55s} {name}")
    print(f"{len(over)} functions over {args.max} lines")
    return 1 if over else 0


if __name__ == "__main__":
    sys.exit(main())
