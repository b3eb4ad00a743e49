#!/usr/bin/env python3
"""Every include of a jellysim module's header from a module's sources, public headers and tests names a module it
declares in src/CMakeLists.txt (directly or through its dependencies): the layering of docs/architecture.md,
checked for every edge of the declared graph (the build enforces it by staged include trees; this lists any
edge at once, with the file and line).
Usage: check_includes.py SOURCE_DIR GRAPH_FILE (the declared graph: module_graph.py)"""
import pathlib, re, sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from module_graph import closure, read_graph  # noqa: E402

root = pathlib.Path(sys.argv[1])
declared = read_graph(sys.argv[2])

problems, edges = [], 0
for module in sorted(declared):
    allowed = closure(declared, module)
    files = [f for folder in (root / "src" / module, root / "include/jellysim" / module, root / "tests" / module)
             for f in folder.glob("*.[ch]pp")]
    for f in sorted(files):
        for number, text in enumerate(f.read_text().splitlines(), 1):
            m = re.match(r'\s*#\s*include\s+"jellysim/(\w+)/', text)
            if not m:
                continue
            edges += 1
            if m.group(1) not in allowed:
                problems.append(f"{f.relative_to(root)}:{number}: module '{module}' includes '{m.group(1)}', "
                                f"not among its declared dependencies {sorted(allowed - {module})}")
print(f"{len(declared)} modules, {edges} includes of module headers checked")
for p in problems:
    print(p)
sys.exit(1 if problems else 0)
