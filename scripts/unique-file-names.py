#!/usr/bin/env python3
"""Fails when a file base name occurs in more than one module (docs/architecture.md: unique file names).

    python3 scripts/unique-file-names.py

A module's files are src/<module>/ and include/jellysim/<module>/ (subfolders included); a base name is
the file name without its extension, so src/fluid/flow_mirror.cpp and include/jellysim/fluid/flow_mirror.hpp
are one module's pair, while the same base name in src/fluid/ and src/elastic/ is a repeat. The CTest
test CodeHealth.UniqueFileNames runs the check.
"""
import collections
import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent


def modules_by_base_name(root):
    """For every base name in a module folder, the set of modules that hold it."""
    found = collections.defaultdict(set)
    for top in (root / 'src', root / 'include' / 'jellysim'):
        for path in top.glob('*/**/*'):
            if path.is_file():
                module = path.relative_to(top).parts[0]
                found[path.name.split('.')[0]].add(module)
    return found


def main():
    repeats = {name: sorted(mods) for name, mods in modules_by_base_name(ROOT).items() if len(mods) > 1}
    for name, mods in sorted(repeats.items()):
        print(f'{name}: in modules {", ".join(mods)} (name each for what it holds in its module)')
    return 1 if repeats else 0


if __name__ == '__main__':
    sys.exit(main())
