#!/usr/bin/env python3
"""Checks the rule of a module's surface: a header is public only when another module needs it.

A module src/M keeps its interface in include/binpick/M/*.hpp and everything else beside its
sources in src/M/src. A public header is needed when a file of another module under src/ includes
it, or when a needed public header of its own module includes it (it must compile there too).
Tests and benchmarks do not count: they reach private headers through binpick::M_internals, which
no module may link.

Usage: check-module-surfaces.py SOURCE_ROOT   (exit 1 and one line per finding when the rule is broken)
"""
import pathlib
import re
import sys

INCLUDE = re.compile(r'#include\s+"(binpick/([a-z_]+)/[A-Za-z0-9_]+\.hpp)"')
QUOTED_INCLUDE = re.compile(r'#include\s+"([^"]+)"')


def module_of(path, src):
    return path.relative_to(src).parts[0]


def included_headers(path):
    return INCLUDE.findall(path.read_text(errors="replace"))


def public_headers(src):
    """binpick/M/x.hpp -> (module, path) for every module's include directory."""
    headers = {}
    for path in sorted(src.glob("*/include/binpick/*/*.hpp")):
        headers[str(path.relative_to(path.parents[2]))] = (module_of(path, src), path)
    return headers


def needed_headers(src, headers):
    needed = set()
    for path in src.rglob("*"):
        if path.suffix not in (".cpp", ".hpp"):
            continue
        for name, module in included_headers(path):
            if name in headers and module != module_of(path, src):
                needed.add(name)
    grew = True
    while grew:  # what a needed header includes of its own module is needed too
        grew = False
        for name in list(needed):
            for inner, _ in included_headers(headers[name][1]):
                if inner in headers and inner not in needed:
                    needed.add(inner)
                    grew = True
    return needed


def findings(root):
    src = root / "src"
    headers = public_headers(src)
    needed = needed_headers(src, headers)
    for name, (module, path) in sorted(headers.items()):
        if name not in needed:
            yield f"{name}: public, but no other module includes it; move it beside the sources in src/{module}/src"
        for included in QUOTED_INCLUDE.findall(path.read_text(errors="replace")):
            if not included.startswith("binpick/"):
                yield f"{name}: a public header includes the private header \"{included}\""
    for cmake in sorted(src.glob("*/CMakeLists.txt")):
        if "_internals" in cmake.read_text():
            yield f"{cmake.relative_to(root)}: a module links another module's internals"


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    problems = list(findings(pathlib.Path(sys.argv[1])))
    for problem in problems:
        print(problem)
    if problems:
        sys.exit(1)
    print("module surfaces: every public header is needed by another module")


if __name__ == "__main__":
    main()
