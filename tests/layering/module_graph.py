"""The declared module graph, as tests/layering/CMakeLists.txt writes it from the jellysim_module() calls of
src/CMakeLists.txt (the one place the graph is declared): one line per module, its name then the modules it
declares. Shared by check_includes.py and probe_include_trees.py."""
import pathlib


def read_graph(path):
    """{module: [declared dependencies]} from the generated graph file."""
    graph = {}
    for line in pathlib.Path(path).read_text().splitlines():
        words = line.split()
        if words:
            graph[words[0]] = words[1:]
    return graph


def closure(graph, module):
    """The module and every module it reaches through its declared dependencies."""
    seen, todo = set(), list(graph[module])
    while todo:
        d = todo.pop()
        if d not in seen:
            seen.add(d)
            todo.extend(graph.get(d, []))
    return seen | {module}
