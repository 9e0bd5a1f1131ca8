#!/usr/bin/env python3
"""Refuse a relative file path read inside a doctest.

Edition 2024 merges all doctests into one binary compiled in a temporary
directory; `include_str!("../x")` inside a doc comment is then resolved from
that directory, the merged build fails, and rustdoc quietly falls back to
compiling every doctest on its own (several times slower). A doctest names a
file from the crate root instead:
`include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/analysis/..."))`.

Run: python3 .ci/doctest_paths.py [ROOT] (stdlib only; .ci/run runs it).
Prints one line per offending doc comment line and exits 1 if there is one.
"""

import os
import re
import sys

DOC = re.compile(r"^\s*//[/!]")
READ = re.compile(r'include_(?:str|bytes)!\(\s*"')


def offending(root):
    """(path, line number, text) of each doc comment line that reads a file by a literal path."""
    found = []
    for base, _dirs, files in os.walk(os.path.join(root, "src")):
        for name in sorted(files):
            if not name.endswith(".rs"):
                continue
            path = os.path.join(base, name)
            with open(path, encoding="utf-8") as f:
                for number, line in enumerate(f, 1):
                    if DOC.match(line) and READ.search(line):
                        found.append((os.path.relpath(path, root), number, line.strip()))
    return found


def main(argv):
    root = argv[1] if len(argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    bad = offending(root)
    for path, number, text in bad:
        print(f"{path}:{number}: a doctest reads a file by a literal path (use concat!(env!(\"CARGO_MANIFEST_DIR\"), ...)): {text}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
