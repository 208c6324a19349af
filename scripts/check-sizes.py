#!/usr/bin/env python3
"""Fails when a library function or source file is too long.

A function is counted from the first line of its signature to the closing
brace at the signature's indentation (the shape clang-format gives every
function of the library, members included); a file by its lines. Usage: check-sizes.py ROOT [--max-function N] [--max-file N] [--list K]
"""
import argparse
import os
import re
import sys

LIBRARY = ["symbolic", "codegen", "print", "figure", "exercises", "names",
           "numeric", "expr", "cli", "adapters"]
SUFFIXES = (".cpp", ".hpp", ".h", ".cc")


def sources(root):
    for folder in LIBRARY:
        for base, _, files in os.walk(os.path.join(root, folder)):
            for name in sorted(files):
                if name.endswith(SUFFIXES):
                    yield os.path.join(base, name)


CONTROL = re.compile(r"^(if|for|while|switch|else|do|catch|try|return|namespace|struct|class|"
                     r"enum|union|extern|case|default)\b|^template\s*<.*>\s*(class|struct)\b")


def statement_start(lines, index):
    """The first line of the statement whose last line is lines[index]."""
    while index > 0:
        before = re.sub(r"//.*$", "", lines[index - 1]).strip()
        if (not before or before.endswith((";", "{", "}", ":")) or before.startswith(("//", "#"))
                or before.endswith("*/")):
            break
        index -= 1
    return index


def functions(lines):
    """Yields (name, first line, length) of each function body, members and
    functions in namespaces alike: from the line that opens the body to the
    closing brace at the indentation of the signature."""
    for index, line in enumerate(lines):
        code = re.sub(r"//.*$", "", line).rstrip()
        if not code.endswith("{"):
            continue
        first = statement_start(lines, index)
        head = " ".join(part.strip() for part in lines[first:index + 1])
        if "(" not in head or CONTROL.search(head) or re.search(r"(=|\]|return)\s*\(?\s*\[", head):
            continue
        if re.search(r"=\s*\{$", head) or head.startswith(("}", ")", "[", ".")):
            continue
        indent = re.match(r"\s*", lines[first]).group(0)
        closing = re.compile("^" + re.escape(indent) + r"\}[;,)]*\s*$")
        for end in range(index + 1, len(lines)):
            if closing.match(lines[end]):
                break
        else:
            continue
        match = re.search(r"([A-Za-z_~][\w:~<>=!+\-*/\[\]]*)\s*\(", head)
        name = match.group(1) if match else head
        yield name, first + 1, end - first + 1


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("root")
    parser.add_argument("--max-function", type=int, default=120)
    parser.add_argument("--max-file", type=int, default=1100)
    parser.add_argument("--list", type=int, default=0)
    args = parser.parse_args()
    found = []
    files = []
    for path in sources(args.root):
        with open(path, encoding="utf-8") as handle:
            lines = handle.read().split("\n")
        if lines and lines[-1] == "":
            lines.pop()
        relative = os.path.relpath(path, args.root)
        files.append((len(lines), relative))
        for name, start, length in functions(lines):
            found.append((length, f"{relative}:{start}", name))
    found.sort(reverse=True)
    files.sort(reverse=True)
    if args.list:
        print("longest functions:")
        for length, where, name in found[:args.list]:
            print(f"  {length:5d}  {where}  {name}")
        print("longest files:")
        for length, where in files[:args.list]:
            print(f"  {length:5d}  {where}")
    failures = [f"function {name} at {where} has {length} lines (limit {args.max_function})"
                for length, where, name in found if length > args.max_function]
    failures += [f"file {where} has {length} lines (limit {args.max_file})"
                 for length, where in files if length > args.max_file]
    for failure in failures:
        print(failure, file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
