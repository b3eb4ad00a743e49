#!/usr/bin/env python3
"""Every include of a jellysim module's header from a module's sources and public headers names a module it
declares in src/CMakeLists.txt (directly or through its dependencies): the layering of docs/architecture.md,
checked for every edge of the declared graph (the build enforces it by staged include trees; this lists any
edge at once, with the file and line).
Usage: check_includes.py SOURCE_DIR"""
import pathlib, re, sys

root = pathlib.Path(sys.argv[1])
declared = {}
cmake = re.sub(r"#[^\n]*", "", (root / "src/CMakeLists.txt").read_text())
for name, arguments in re.findall(r"^\s*jellysim_module\((\w+)([^)]*)\)", cmake, re.M):
    words = arguments.split()
    deps = words[words.index("DEPS") + 1:] if "DEPS" in words else []
    ends = [k for k, w in enumerate(deps) if w in ("PUBLIC_LIBS", "PRIVATE_LIBS", "EXTRA_SOURCES")]
    declared[name] = deps[:ends[0]] if ends else deps

def closure(module):
    seen, todo = set(), list(declared[module])
    while todo:
        d = todo.pop()
        if d not in seen:
            seen.add(d)
            todo.extend(declared.get(d, []))
    return seen | {module}

problems, edges = [], 0
for module in sorted(declared):
    allowed = closure(module)
    files = list((root / "src" / module).glob("*.[ch]pp")) + list((root / "include/jellysim" / module).glob("*.hpp"))
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
