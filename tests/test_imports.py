"""The import structure of ``src/thermocomp``: layers you can see, no upward import, no cycle.

The layers are the root package's folders (``base``, ``core``, ``apps``, ``shell``), lowest
first in the root's ``__layers__``; a module imports only its own layer and those below.  A
package (a layer's subpackage or module: ``core.io``, ``apps.deploy``) forms no cycle with
another even where the modules do not.  Every module is parsed with :mod:`ast` (nothing is
imported), so the test sees module-level and function-level imports alike; only imports under
``if TYPE_CHECKING:`` are left out (they never run).  A package's ``__init__`` is a module of its
own: ``from ..models import ARX`` depends on ``thermocomp.core.models`` (the ``__init__``),
``from . import cv`` on ``thermocomp.apps.diagnose.cv``.

A command's start-up (the console command, a stage's module, what their import runs: functions'
bodies left out, the packages above an imported module in) loads none of :data:`LOADED_ON_USE`.
"""

from __future__ import annotations

import ast
import functools
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src"
ROOT = "thermocomp"

PACKAGE = SRC / ROOT
# Hydra's config belongs to the top layer (the shell): the layers below never load it.
CONFIG_LIBRARIES = ("hydra", "omegaconf")
MAX_ROOT_MODULES = 6


def _layers() -> tuple[str, ...]:
    """``__layers__`` of the root ``__init__``: the layer folders, lowest first."""
    tree = ast.parse((PACKAGE / "__init__.py").read_text())
    return next(ast.literal_eval(node.value) for node in tree.body if isinstance(node, ast.Assign)
                and any(getattr(t, "id", None) == "__layers__" for t in node.targets))


LAYERS = _layers()


def _module_name(path: Path) -> str:
    parts = path.relative_to(SRC).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _runtime_nodes(tree: ast.AST, import_time: bool = False):
    """Every node except the bodies of ``if TYPE_CHECKING:`` blocks (``import_time``: and of
    functions, which the module's import does not run; a class body it does)."""
    stack = [tree]
    while stack:
        node = stack.pop()
        yield node
        for child in ast.iter_child_nodes(node):
            if isinstance(child, ast.If) and "TYPE_CHECKING" in ast.unparse(child.test):
                stack.extend(child.orelse)
            elif import_time and isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef)):
                stack.extend([*child.decorator_list, child.args])    # these run at import
            elif not (import_time and isinstance(child, ast.Lambda)):
                stack.append(child)


def _imports(name: str, path: Path, modules: set[str], import_time: bool = False,
             tree: ast.AST | None = None) -> set[str]:
    """Names this module imports: modules of the package where they resolve, else top-level names
    (``import_time``: only those its import itself runs, not those inside its functions)."""
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    out = set()
    for node in _runtime_nodes(tree or ast.parse(path.read_text(), str(path)), import_time):
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
    """Each module's imports: parsed by the first test that asks (1.1 s of CPU), not at
    collection, which every xdist worker does and one of them for nothing."""
    return _graphs()[0]


def _import_time_graph() -> dict[str, set[str]]:
    """What importing each module runs: its imports outside functions, and the packages above
    each of ours it imports (``from ..machine.record import x`` runs ``apps/machine/__init__``)."""
    return _graphs()[1]


@functools.cache
def _graphs() -> tuple[dict[str, set[str]], dict[str, set[str]]]:
    """:func:`_graph` and :func:`_import_time_graph` from one parse of each file (no tree kept:
    held, the trees made the collector's every pass over them cost 3 s of CPU more)."""
    files = {_module_name(p): p for p in sorted((SRC / ROOT).rglob("*.py"))}
    modules = set(files)
    graph, import_time = {}, {}
    for name, path in files.items():
        tree = ast.parse(path.read_text(), str(path))
        graph[name] = _imports(name, path, modules, tree=tree)
        deps = _imports(name, path, modules, import_time=True, tree=tree)
        import_time[name] = deps | {p for d in deps if d in modules for p in _packages_above(d)} - {name}
    return graph, import_time


def _packages_above(module: str) -> list[str]:
    parts = module.split(".")
    return [".".join(parts[:i]) for i in range(1, len(parts))]


def _edges() -> dict[str, set[str]]:
    return {m: set(deps) for m, deps in _graph().items()}


def _layer(module: str) -> str | None:
    """The layer folder a module lies in (None: the root's own modules)."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 and parts[1] in LAYERS else None


def _upward(graph: dict[str, set[str]]) -> list[str]:
    """Edges from a layer to a higher one (``core.x -> shell.y``)."""
    rank = {layer: i for i, layer in enumerate(LAYERS)}
    return sorted(f"{m} -> {d}" for m, deps in graph.items() for d in deps
                  if _layer(m) and _layer(d) and rank[_layer(d)] > rank[_layer(m)])


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


def test_the_parser_sees_function_level_and_relative_imports():
    # callbacks imports tracking only inside its methods
    assert f"{ROOT}.shell.tracking" in _graph()[f"{ROOT}.shell.callbacks"]
    assert f"{ROOT}.apps.diagnose.cv" in _graph()[f"{ROOT}.apps.diagnose.diagnosis"]
    assert f"{ROOT}.core.models" in _graph()  # a package's __init__ is a module
    assert _cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c", "a"]]
    assert _reaches("a", {"a": {"b"}, "b": {"hydra.utils"}}, ("hydra",)) == [["a", "b", "hydra.utils"]]


def test_the_layers_are_the_folders_and_the_root_is_small():
    folders = {p.name for p in PACKAGE.iterdir() if (p / "__init__.py").is_file()}
    assert folders == set(LAYERS), f"folders {sorted(folders)} != __layers__ {LAYERS}"
    root_modules = sorted(p.name for p in PACKAGE.glob("*.py"))
    assert len(root_modules) <= MAX_ROOT_MODULES, f"the root holds {root_modules}: give them a layer"


def test_no_upward_import():
    planted = {f"{ROOT}.{LAYERS[0]}.x": {f"{ROOT}.{LAYERS[-1]}.y"}, f"{ROOT}.{LAYERS[-1]}.y": set()}
    assert _upward(planted) == [f"{ROOT}.{LAYERS[0]}.x -> {ROOT}.{LAYERS[-1]}.y"]
    bad = _upward(_edges())
    assert not bad, f"imports from a lower layer to a higher one ({' < '.join(LAYERS)}):\n  " + \
        "\n  ".join(bad)


def test_no_import_cycle():
    cycles = _cycles(_edges())
    assert not cycles, "import cycles in src/thermocomp:\n" + "\n".join(
        "  " + " -> ".join(c) for c in cycles)


def _unit(module: str) -> str:
    """The package a module belongs to: the subpackage or module of its layer it lies in."""
    return ".".join(module.split(".")[:3] if _layer(module) else module.split(".")[:2])


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
    core = f"{ROOT}.{LAYERS[1]}"
    assert _package_graph({f"{core}.a.x": {f"{core}.b"}, f"{core}.b": {f"{core}.a.z"},
                           f"{core}.a.z": set()}) == {f"{core}.a": {f"{core}.b"},
                                                      f"{core}.b": {f"{core}.a"}}
    cycles = _cycles(_package_graph(_edges()))
    assert not cycles, "package-level import cycles in src/thermocomp:\n" + "\n".join(
        "  " + " -> ".join(c) for c in cycles)


@pytest.mark.parametrize("layer", LAYERS[:-1])
def test_below_the_shell_nothing_loads_hydra(layer):
    graph = _edges()
    chains = [c for m in sorted(graph) if _layer(m) == layer
              for c in _reaches(m, graph, CONFIG_LIBRARIES)]
    assert not chains, f"{layer!r} reaches Hydra's config:\n" + "\n".join(
        "  " + " -> ".join(c) for c in chains)


def _stage_modules() -> set[str]:
    """The modules of the ``module:function`` entries of ``STAGES`` (the command table's)."""
    from thermocomp.shell.stages import STAGES

    return {f"{ROOT}.shell.stages.{entry.split(':')[0]}" for entry in STAGES.values()}


def test_stages_do_not_import_each_other():
    # The stage modules are those ``stages/__init__`` registers (imported on use); common and
    # artifacts are the stages' shared helpers.  Stages meet at files, not at each other's functions.
    stages = _stage_modules()
    assert len(stages) >= 5 and stages <= set(_graph()), stages
    graph = _edges()
    bad = sorted(f"{m} -> {d}" for m in stages for d in graph[m] if d in stages and d != m)
    assert not bad, "a stage imports another stage (move the shared code out of stages/):\n  " + \
        "\n  ".join(bad)


# Private helpers (``_name``) other modules import, by importer: debt, not to grow.  A helper
# two modules share is public where it is defined (``manifest.apply_split_overrides``,
# ``starts.utc_instant``, which ``read`` imported as private ones until session 53).
PRIVATE_IMPORTS_LEFT = {
    "apps.diagnose.figures": {"_arr", "_hour_ticks"},
    "core.io.manifest": {"_OTHER_DELIMITERS", "_first_line"},
    "core.io.read": {"_load_csv", "_load_parquet", "_ordered", "_values", "_check_periods",
                     "_error_ranges", "_keep_missing", "_repair_missing",
                     "_set_time_seconds", "_warn_error_ranges"},
    "core.io.roles": {"_roles"},
    "core.io.sniff": {"_OTHER_DELIMITERS"},
    "core.io.starts": {"_contract_names", "_first_text", "_timed"},
    "core.io.steps": {"_values"},
    "core.io.tables": {"_OTHER_DELIMITERS", "_first_line"},
    "core.io.values": {"_chunks", "_values"},
    "core.models.lstm": {"_Net", "_padded", "_torch_threads"},
    "shell.stages.calibrate": {"_check_writable"},
    "shell.stages.compare": {"_check_writable"},
    "shell.stages.diagnose": {"_split"},
    "shell.stages.simulate": {"_check_writable"},
    "shell.tracking": {"_split", "_is_locked"},
}


def _private_imports() -> dict[str, set[str]]:
    """``{module: the private names it imports from another}`` (``from .x import _y``)."""
    out: dict[str, set[str]] = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        for node in _runtime_nodes(ast.parse(path.read_text(), str(path))):
            ours = isinstance(node, ast.ImportFrom) and (
                node.level or (node.module or "").split(".")[0] == ROOT)   # not a library's
            if ours:
                names = {a.name for a in node.names if a.name.startswith("_")
                         and not a.name.startswith("__")}
                if names:
                    out.setdefault(_module_name(path).removeprefix(f"{ROOT}."), set()).update(names)
    return out


def test_private_helpers_are_imported_only_where_listed():
    # a new one: make it public where it is defined; one gone: take it off the list
    assert _private_imports() == PRIVATE_IMPORTS_LEFT


# Libraries a command loads only where it uses them (a local import, with a comment why): at
# import of the console command, of a stage's module and of what that imports, none.  Each costs
# every CLI process that does not use it: skfuzzy (select=cluster_grey, ati clustering=fuzzy),
# MLflow (a run tracked, only once there is one), matplotlib (a figure), torch (model=lstm), ...
LOADED_ON_USE = ("torch", "mlflow", "matplotlib", "skfuzzy", "PyEMD", "asyncua", "ray", "optuna",
                 "submitit", "blark", "onnx", "onnxruntime", "psycopg2", "dvc", "uvicorn")


def test_commands_load_optional_libraries_only_on_use():
    graph = _import_time_graph()
    # the parser sees a package's __init__ run by an import below it, and not a function's body
    assert f"{ROOT}.apps.machine" in graph[f"{ROOT}.shell.stages.twin"]
    assert "asyncua" not in graph[f"{ROOT}.shell.stages.twin"]      # inside twin()
    starts = sorted(_stage_modules() | {f"{ROOT}.__main__", f"{ROOT}.shell.cli"})
    chains = [c for m in starts for c in _reaches(m, graph, LOADED_ON_USE)]
    assert not chains, "a command's start-up imports a library it may not use:\n" + "\n".join(
        "  " + " -> ".join(c) for c in chains)
