#!/usr/bin/env python3
"""Lists C++ functions longer than a limit (default 120 lines, from the line of their opening
brace to the line of their closing brace), so that long functions are found before review.

Usage: function_length.py [--max N] [--check] PATH...   (folders are searched for .cc/.h/.inc)
With --check the exit status is 1 when any function is longer than the limit.

A heuristic, not a parser: comments, strings and character literals are blanked; a brace that
opens a body right after ')' (optionally followed by const, override, noexcept, final, or a
trailing return type / initialiser list) at namespace or class level starts a function; lambdas
and nested blocks count towards the function they are in."""

import argparse
import os
import re
import sys

SUFFIXES = (".cc", ".h", ".inc", ".cpp", ".hpp", ".cu", ".cuh")


def blank(text):
    """Comments, string and char literals replaced by spaces (newlines kept)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif text.startswith('R"', i):
            m = re.match(r'R"([^(]*)\(', text[i:])
            if not m:
                out.append(c)
                i += 1
                continue
            end = ")" + m.group(1) + '"'
            j = text.find(end, i + m.end())
            j = n if j < 0 else j + len(end)
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            j = min(n, j + 1)
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        else:
            out.append(c)
            i += 1
    return "".join(out)


SCOPE_WORDS = re.compile(r"\b(namespace|class|struct|union|enum)\b[^;{}()]*$")


def functions(path):
    text = blank(open(path, encoding="utf-8", errors="replace").read())
    stack = []  # per open brace: ("scope" | "function" | "block", start line, name)
    results = []
    line = 1
    last = 0  # index after the last ; { or }
    for i, c in enumerate(text):
        if c == "\n":
            line += 1
        elif c == "{":
            head = text[last:i]
            inside_function = any(kind == "function" for kind, _, _ in stack)
            kind = "block"
            name = ""
            if not inside_function:
                flat = " ".join(head.split())
                if SCOPE_WORDS.search(flat) or flat.endswith("=") or flat == "" or flat.endswith("extern \"C\""):
                    kind = "scope"
                elif ")" in flat:
                    kind = "function"
                    m = re.search(r"([~\w:<>]+)\s*\(", flat)
                    name = m.group(1) if m else flat[:40]
                else:
                    kind = "scope"
            stack.append((kind, line, name))
            last = i + 1
        elif c == "}":
            if stack:
                kind, start, name = stack.pop()
                if kind == "function":
                    results.append((name, start, line, line - start + 1))
            last = i + 1
        elif c == ";":
            last = i + 1
    return results


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--max", type=int, default=120)
    ap.add_argument("--check", action="store_true")
    ap.add_argument("paths", nargs="+")
    a = ap.parse_args()
    files = []
    for p in a.paths:
        if os.path.isdir(p):
            for root, _, names in os.walk(p):
                files += [os.path.join(root, f) for f in sorted(names) if f.endswith(SUFFIXES)]
        else:
            files.append(p)
    long_ones = []
    for f in sorted(files):
        for name, start, end, length in functions(f):
            if length > a.max:
                long_ones.append((length, f, start, name))
    for length, f, start, name in sorted(long_ones, reverse=True):
        print(f"{f}:{start}: {name}: {length} lines (limit {a.max})")
    if a.check and long_ones:
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
