"""The package as a whole: its modules' imports, its version."""
import ast
import os
import subprocess

import luxtrace

PACKAGE = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "luxtrace")


def _imports(module):
    """The package's modules that ``module`` imports, at the top or inside a function."""
    with open(os.path.join(PACKAGE, module + ".py")) as f:
        tree = ast.parse(f.read())
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.level == 1:
            if node.module:
                out.add(node.module.split(".")[0])
            else:
                out.update(a.name for a in node.names)
    return out


def test_no_module_imports_itself_through_others():
    modules = [f[:-3] for f in os.listdir(PACKAGE) if f.endswith(".py") and f != "__init__.py"]
    graph = {m: _imports(m) & set(modules) for m in modules}

    def reachable(start):
        seen, todo = set(), list(graph[start])
        while todo:
            m = todo.pop()
            if m not in seen:
                seen.add(m)
                todo.extend(graph[m])
        return seen

    cycles = sorted(m for m in modules if m in reachable(m))
    assert cycles == [], f"modules in an import cycle: {cycles}"


def test_version_is_the_binarys(binary):
    """One version number (CMakeLists.txt's project()) for both; the binary adds the commit
    it was built from (``luxtrace 0.4.0+gabc1234``)."""
    out = subprocess.run([binary, "--version"], capture_output=True, text=True, check=True).stdout.split()
    assert out[0] == "luxtrace"
    assert luxtrace.__version__ == out[1].split("+")[0]
