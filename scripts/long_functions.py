#!/usr/bin/env python3
"""Lists the longest C++ functions (lines from the opening to the closing brace).

Usage: scripts/long_functions.py [--limit N] [--top K] DIR...
A brace counter, not a parser: it skips comments, strings and character literals and
takes a brace block as a function body when the text before it ends in ')' (plus
qualifiers such as const, override, noexcept, a trailing return type or an initializer
list) at namespace or class level. Lambdas and local classes count toward the function
that holds them. Exits 1 when a function is longer than --limit (default: no limit).
"""
import argparse
import pathlib
import re
import sys

CONTROL = re.compile(r"\b(if|for|while|switch|catch|do|else|try)\s*(\(|$)")
SCOPE = re.compile(r"\b(namespace|class|struct|union|enum)\b[^()]*$")


def strip(text):
    """The text with comments, strings and character literals blanked (newlines kept)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append("\n" * text.count("\n", i, j))
            i = j
        elif text.startswith('R"', i):
            m = re.match(r'R"([^(]*)\(', text[i:])
            end = text.find(")" + (m.group(1) if m else "") + '"', i)
            end = n if end < 0 else end + len(m.group(1) if m else "") + 2
            out.append('""' + "\n" * text.count("\n", i, end))
            i = end
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(c + c)
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def functions(path):
    text = strip(path.read_text(errors="replace"))
    stack = []  # per open brace: (kind, start line, name)
    head_start = 0
    line = 1
    for i, c in enumerate(text):
        if c == "\n":
            line += 1
        elif c in ";":
            head_start = i + 1
        elif c == "{":
            head = " ".join(text[head_start:i].split())
            inside_function = any(kind == "function" for kind, _, _ in stack)
            kind = "block"
            if not inside_function:
                if SCOPE.search(head) or head.endswith("=") or head.startswith("extern"):
                    kind = "scope"
                elif ")" in head and not CONTROL.search(head.split(")")[0]):
                    kind = "function"
            name = re.sub(r"\s*\(.*", "", head).split(" ")[-1] if kind == "function" else ""
            stack.append((kind, line, name))
            head_start = i + 1
        elif c == "}":
            if stack:
                kind, start, name = stack.pop()
                if kind == "function":
                    yield name, start, line - start + 1
            head_start = i + 1


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--limit", type=int, default=0)
    parser.add_argument("--top", type=int, default=15)
    parser.add_argument("dirs", nargs="+")
    args = parser.parse_args()
    found = []
    for folder in args.dirs:
        for path in sorted(pathlib.Path(folder).rglob("*")):
            if path.suffix in (".cpp", ".hpp", ".h", ".cc"):
                for name, start, length in functions(path):
                    found.append((length, f"{path}:{start}", name))
    found.sort(reverse=True)
    for length, where, name in found[: args.top]:
        print(f"{length:5d}  {where}  {name}")
    over = [f for f in found if args.limit and f[0] > args.limit]
    if over:
        print(f"{len(over)} function(s) over {args.limit} lines", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
