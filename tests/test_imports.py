"""The import structure of ``src/thermocomp``: no cycle, and the core never reaches the shell.

Every module is parsed with :mod:`ast` (nothing is imported), so the test sees
module-level and function-level imports alike; only imports under
``if TYPE_CHECKING:`` are left out (they never run).  A package's ``__init__``
is a module of its own: ``from ..models import ARX`` depends on
``thermocomp.models`` (the ``__init__``), ``from . import cv`` on
``thermocomp.diagnose.cv``.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src"
ROOT = "thermocomp"

# The core: pure computations a CNC deployment or a notebook can import without the shell.
CORE = ("models", "select", "denoise", "metrics", "stats", "iso10791", "frame", "compensator",
        "evaluation", "diagnose", "deploy", "model_selection", "files", "jsonsafe", "errors",
        "plots", "volumetric", "monitor", "io", "paths")
# What the core must never import, even through another module.
SHELL = (f"{ROOT}.stages", f"{ROOT}.cli", f"{ROOT}.callbacks", f"{ROOT}.tracking",
         "hydra", "omegaconf")

# Known violations in files being rewritten on another branch (issue 11: side inputs and
# streaming).  Each entry is an import edge "importer -> imported" that is tolerated until that
# work lands; the lead empties this set.  An entry that no longer exists fails the test below.
PENDING: set[str] = set()


def _module_name(path: Path) -> str:
    parts = path.relative_to(SRC).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _runtime_nodes(tree: ast.AST):
    """Every node except the bodies of ``if TYPE_CHECKING:`` blocks."""
    stack = [tree]
    while stack:
        node = stack.pop()
        yield node
        for child in ast.iter_child_nodes(node):
            if isinstance(child, ast.If) and "TYPE_CHECKING" in ast.unparse(child.test):
                stack.extend(child.orelse)
            else:
                stack.append(child)


def _imports(name: str, path: Path, modules: set[str]) -> set[str]:
    """Names this module imports: modules of the package where they resolve, else top-level names."""
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    out = set()
    for node in _runtime_nodes(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            out.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.rsplit(".", node.level - 1)[0] if node.level > 1 else package
                base = f"{base}.{node.module}" if node.module else base
            else:
                base = node.module
            for alias in node.names:
                sub = f"{base}.{alias.name}"
                out.add(sub if sub in modules else base)
    return out


def _graph() -> dict[str, set[str]]:
    files = {_module_name(p): p for p in sorted((SRC / ROOT).rglob("*.py"))}
    modules = set(files)
    return {name: _imports(name, path, modules) for name, path in files.items()}


GRAPH = _graph()


def _edges(graph=None, pending=None) -> dict[str, set[str]]:
    """The graph (``GRAPH``) without the ``pending`` edges (``PENDING``)."""
    graph, pending = GRAPH if graph is None else graph, PENDING if pending is None else pending
    return {m: {d for d in deps if f"{m} -> {d}" not in pending} for m, deps in graph.items()}


def _stale(pending, graph) -> list[str]:
    """The ``pending`` edges the code no longer has."""
    return sorted(e for e in pending if e.split(" -> ")[1] not in graph.get(e.split(" -> ")[0], ()))


def _cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """One cycle per strongly connected component of more than one module (Tarjan)."""
    index, low, on_stack, stack, found = {}, {}, set(), [], []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph.get(v, ())):
            if w not in graph:
                continue
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = set()
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.add(w)
                if w == v:
                    break
            if len(component) > 1 or v in graph.get(v, ()):
                found.append(_cycle_through(v, component, graph))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return found


def _cycle_through(start: str, component: set[str], graph) -> list[str]:
    """A shortest path start -> ... -> start inside one component (breadth first)."""
    previous, frontier = {}, [start]
    while frontier:
        nxt = []
        for v in frontier:
            for w in sorted(graph[v] & component):
                if w == start:
                    path = [v]
                    while path[-1] != start:
                        path.append(previous[path[-1]])
                    return [start, *reversed(path[:-1]), start] if v != start else [start, start]
                if w not in previous:
                    previous[w] = v
                    nxt.append(w)
        frontier = nxt
    raise AssertionError("not a cycle")  # pragma: no cover


def _reaches(start: str, graph, forbidden) -> list[list[str]]:
    """Shortest import chains from ``start`` to any name under ``forbidden``."""
    def bad(name):
        return any(name == f or name.startswith(f + ".") for f in forbidden)

    previous, frontier, chains = {start: None}, [start], []
    while frontier:
        nxt = []
        for v in frontier:
            for w in sorted(graph.get(v, ())):
                if w in previous:
                    continue
                previous[w] = v
                if bad(w):
                    chain = [w]
                    while previous[chain[-1]] is not None:
                        chain.append(previous[chain[-1]])
                    chains.append(chain[::-1])
                elif w in graph:
                    nxt.append(w)
        frontier = nxt
    return chains


def _in(name: str, packages) -> bool:
    return any(name == f"{ROOT}.{p}" or name.startswith(f"{ROOT}.{p}.") for p in packages)


def test_the_parser_sees_function_level_and_relative_imports():
    # callbacks imports tracking only inside its methods; compare is a stage module
    assert f"{ROOT}.tracking" in GRAPH[f"{ROOT}.callbacks"]
    assert f"{ROOT}.diagnose.cv" in GRAPH[f"{ROOT}.diagnose.diagnosis"]
    assert f"{ROOT}.models" in GRAPH  # a package's __init__ is a module
    assert _cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c", "a"]]
    assert _reaches("a", {"a": {"b"}, "b": {"hydra.utils"}}, ("hydra",)) == [["a", "b", "hydra.utils"]]


def test_pending_entries_are_still_real():
    # the mechanism on a graph with one pending edge still there and one gone (PENDING may be empty)
    graph = {"a": {"b", "c"}, "b": set()}
    assert _edges(graph, {"a -> b"}) == {"a": {"c"}, "b": set()}
    assert _stale({"a -> b", "b -> a"}, graph) == ["b -> a"]
    stale = _stale(PENDING, GRAPH)
    assert not stale, f"these PENDING edges are gone, remove them from tests/test_imports.py: {stale}"


def test_no_import_cycle():
    cycles = _cycles(_edges())
    assert not cycles, "import cycles in src/thermocomp:\n" + "\n".join(
        "  " + " -> ".join(c) for c in cycles)


def _unit(module: str) -> str:
    """The package a module belongs to: the root's subpackage or root module it lies in."""
    return ".".join(module.split(".")[:2])


def _package_graph(graph: dict[str, set[str]]) -> dict[str, set[str]]:
    """Import edges between packages (``deploy`` -> ``monitor``), the root ``__init__`` left out."""
    units = {_unit(m) for m in graph if m != ROOT}
    out = {u: set() for u in units}
    for m, deps in graph.items():
        for d in deps:
            if m != ROOT and _unit(d) in units and _unit(d) != _unit(m):
                out[_unit(m)].add(_unit(d))
    return out


def test_no_package_level_cycle():
    # A module-level DAG can still tie two packages together (deploy.pyfunc -> monitor.adaptive
    # -> deploy.streaming): then neither can be understood, tested or shipped without the other.
    assert _package_graph({"r.a.x": {"r.b.y"}, "r.b.y": {"r.a.z"}, "r.a.z": set()}) == \
        {"r.a": {"r.b"}, "r.b": {"r.a"}}
    cycles = _cycles(_package_graph(_edges()))
    assert not cycles, "package-level import cycles in src/thermocomp:\n" + "\n".join(
        "  " + " -> ".join(c) for c in cycles)


@pytest.mark.parametrize("package", CORE)
def test_core_does_not_import_the_shell(package):
    graph = _edges()
    chains = [c for m in sorted(graph) if _in(m, [package]) for c in _reaches(m, graph, SHELL)]
    assert not chains, (f"core {package!r} reaches the shell (stages, cli, callbacks, tracking, "
                        f"hydra, omegaconf):\n" + "\n".join("  " + " -> ".join(c) for c in chains))


def _stage_modules() -> set[str]:
    """The modules of the ``module:function`` entries of ``STAGES`` in ``stages/__init__``."""
    tree = ast.parse((SRC / ROOT / "stages" / "__init__.py").read_text())
    table = next(ast.literal_eval(node.value) for node in tree.body if isinstance(node, ast.Assign)
                 and any(getattr(t, "id", None) == "STAGES" for t in node.targets))
    return {f"{ROOT}.stages.{entry.split(':')[0]}" for entry in table.values()}


def test_stages_do_not_import_each_other():
    # The stage modules are those ``stages/__init__`` registers (imported on use); common and
    # artifacts are the stages' shared helpers.  Stages meet at files, not at each other's functions.
    stages = _stage_modules()
    assert len(stages) >= 5 and stages <= set(GRAPH), stages
    graph = _edges()
    bad = sorted(f"{m} -> {d}" for m in stages for d in graph[m] if d in stages and d != m)
    assert not bad, "a stage imports another stage (move the shared code out of stages/):\n  " + \
        "\n  ".join(bad)


def test_deploy_never_loads_hydra():
    graph = _edges()
    chains = [c for m in sorted(graph) if _in(m, ["deploy"])
              for c in _reaches(m, graph, ("hydra", "omegaconf"))]
    assert not chains, "the deployed model would need Hydra:\n" + "\n".join(
        "  " + " -> ".join(c) for c in chains)
