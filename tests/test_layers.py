"""The layering of the installed package, read from its modules' source (AST, nothing imported but the packages).

Stages and what each may import (README "Layout"): ``core`` no stage; ``nlp`` core;
``scheduler`` nlp and core; ``scene`` scheduler, nlp and core; ``motiondb`` core; ``synthesis`` core; ``output`` (the writers
and pictures) core; the API (``text2anim`` itself, folder ``api/``) anything but the command
line; ``cli`` anything. Every module counts, in every subpackage of every stage, and every
import, at module level or inside a function, and under ``if TYPE_CHECKING`` too. No module
imports another module's ``_private`` names, and no two modules import each other in a cycle.
"""
from __future__ import annotations

import ast
import importlib.util
from dataclasses import dataclass
from pathlib import Path

ROOT = "text2anim"
STAGES = ("core", "output", "nlp", "scheduler", "scene", "motiondb", "synthesis", "cli")
#: The stages each stage may import (its own included); "api" is the ``text2anim`` package itself.
MAY_IMPORT = {
    "core": {"core"},
    "output": {"output", "core"},
    "nlp": {"nlp", "core"},
    "scheduler": {"scheduler", "nlp", "core"},
    "scene": {"scene", "scheduler", "nlp", "core"},
    "motiondb": {"motiondb", "core"},
    "synthesis": {"synthesis", "core"},
    "api": {"api", "core", "nlp", "scheduler", "scene", "motiondb", "synthesis", "output"},
    "cli": {"cli", "api", "core", "nlp", "scheduler", "scene", "motiondb", "synthesis", "output"},
}

@dataclass(frozen=True)
class Import:
    """One import statement's target: ``module`` (a module of the package) and the ``name`` taken from it."""

    importer: str
    module: str
    name: str | None
    line: int


@dataclass
class Graph:
    """The package's modules (name -> source file) and every import between them."""

    modules: dict[str, Path]
    imports: list[Import]

    def edges(self) -> dict[str, set[str]]:
        out: dict[str, set[str]] = {m: set() for m in self.modules}
        for imp in self.imports:
            if imp.module != imp.importer:
                out[imp.importer].add(imp.module)
        return out


def _package_folder(package: str) -> Path | None:
    """The folder of an installed package, ``None`` when it is not installed."""
    spec = importlib.util.find_spec(package)
    if spec is None or not spec.submodule_search_locations:
        return None
    return Path(list(spec.submodule_search_locations)[0])


def installed_stages() -> tuple[str, ...]:
    """The stages, each asserted installed."""
    missing = [s for s in STAGES if _package_folder(f"{ROOT}.{s}") is None]
    assert not missing, f"stages not installed: {missing}"
    return STAGES


def installed_modules() -> dict[str, Path]:
    """Every module of the installed package, in every subpackage of every stage: dotted name -> file."""
    modules: dict[str, Path] = {}
    for package in (ROOT, *(f"{ROOT}.{s}" for s in installed_stages())):
        folder = _package_folder(package)
        assert folder is not None, f"{package} is not installed"
        for path in sorted(folder.rglob("*.py")):
            parts = [package, *path.relative_to(folder).with_suffix("").parts]
            if parts[-1] == "__init__":
                parts.pop()
            modules[".".join(parts)] = path
    return modules


def stage(module: str) -> str:
    """The stage a module belongs to (``api`` for the ``text2anim`` package's own modules)."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 and parts[1] in STAGES else "api"


def _known(name: str, modules: dict[str, Path]) -> str:
    """The longest prefix of ``name`` that is a module of the package."""
    parts = name.split(".")
    while parts and ".".join(parts) not in modules:
        parts.pop()
    return ".".join(parts)


def _imports_of(module: str, path: Path, modules: dict[str, Path]) -> list[Import]:
    tree = ast.parse(path.read_text(encoding="utf-8"), str(path))
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.split(".")[0] == ROOT:
                    out.append(Import(module, _known(alias.name, modules), None, node.lineno))
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - node.level + 1]
                source = ".".join(base + ([node.module] if node.module else []))
            else:
                source = node.module or ""
            if source.split(".")[0] != ROOT:
                continue
            for alias in node.names:
                sub = f"{source}.{alias.name}"
                if sub in modules:
                    out.append(Import(module, sub, None, node.lineno))
                else:
                    out.append(Import(module, _known(source, modules), alias.name, node.lineno))
    return out


def _private_attributes(module: str, path: Path, modules: dict[str, Path]) -> list[str]:
    """``alias._name`` uses where ``alias`` is another module of the package bound by an import."""
    tree = ast.parse(path.read_text(encoding="utf-8"), str(path))
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    aliases: dict[str, str] = {}
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            base = package.split(".")[: len(package.split(".")) - node.level + 1] if node.level else []
            source = ".".join(base + ([node.module] if node.module else []))
            for alias in node.names:
                if f"{source}.{alias.name}" in modules:
                    aliases[alias.asname or alias.name] = f"{source}.{alias.name}"
        elif isinstance(node, ast.Import):
            for alias in node.names:
                if alias.asname and alias.name in modules:
                    aliases[alias.asname] = alias.name
    out = []
    for node in ast.walk(tree):
        if (isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id in aliases
                and _is_private(node.attr) and aliases[node.value.id] != module):
            out.append(f"{aliases[node.value.id]}.{node.attr}")
    return out


def _is_private(name: str) -> bool:
    return name.startswith("_") and not name.startswith("__")


def module_graph() -> Graph:
    modules = installed_modules()
    imports = [imp for m, p in sorted(modules.items()) for imp in _imports_of(m, p, modules)]
    return Graph(modules, imports)


def layer_violations(graph: Graph) -> set[tuple[str, str, str]]:
    """``("layer", importer, imported)`` for each import of a stage its stage may not import."""
    return {("layer", i.importer, i.module) for i in graph.imports
            if stage(i.module) not in MAY_IMPORT[stage(i.importer)]}


def private_imports(graph: Graph) -> set[tuple[str, str, str]]:
    """``("private", importer, module.name)`` for each ``_name`` taken from another module."""
    found = {("private", i.importer, f"{i.module}.{i.name}") for i in graph.imports
             if i.name and _is_private(i.name) and i.module != i.importer}
    for m, path in graph.modules.items():
        found |= {("private", m, used) for used in _private_attributes(m, path, graph.modules)}
    return found


def cycles(graph: Graph) -> set[tuple[str, ...]]:
    """``("cycle", *modules)``: strongly connected groups of two or more modules (Tarjan), sorted."""
    edges = graph.edges()
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: set[tuple[str, ...]] = set()

    def visit(v: str) -> None:  # recursion depth is bounded by the module count (~150)
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(edges[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            group = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                group.append(w)
                if w == v:
                    break
            if len(group) > 1:
                found.add(("cycle", *sorted(group)))

    for v in sorted(edges):
        if v not in index:
            visit(v)
    return found


def violations(graph: Graph) -> set[tuple[str, ...]]:
    return layer_violations(graph) | private_imports(graph) | cycles(graph)


# ------------------------------------------------------------------- the tests
def test_the_checker_sees_the_whole_installed_package():
    graph = module_graph()
    assert {stage(m) for m in graph.modules} == {"api", *installed_stages()}
    for module in ("text2anim", "text2anim.pipeline", "text2anim.core.motion", "text2anim.output.viewer",
                   "text2anim.motiondb.library.reach", "text2anim.cli.main", "text2anim.cli.batch.cluster",
                   "text2anim.scheduler.postures"):
        assert module in graph.modules
    edges = graph.edges()
    assert "text2anim.pipeline" in edges["text2anim.cli.cmd_compare"]  # an import inside a function
    assert "text2anim.scheduler.types" in edges["text2anim.scheduler.plan"]  # a relative import
    assert "text2anim.cli.batch.lines" in edges["text2anim.cli.batch.runner"]  # `from . import lines`


def test_the_checker_walks_every_subpackage_of_every_stage():
    """Every ``.py`` file under each installed package's folder, however deep, is a module the checks read."""
    graph = module_graph()
    files = set(graph.modules.values())
    for package in (ROOT, *(f"{ROOT}.{s}" for s in installed_stages())):
        folder = _package_folder(package)
        assert folder is not None
        assert set(folder.rglob("*.py")) <= files, package


def test_the_checker_finds_each_kind_of_violation(tmp_path):
    """A made-up core module with every kind of fault, checked by the same functions as the package."""
    modules = installed_modules()
    bad = tmp_path / "bad.py"
    bad.write_text(
        "from text2anim.core import motion as m\n"
        "from . import skeleton\n"
        "def f():\n"
        "    from text2anim.cli import main\n"          # a later stage, inside a function
        "    from .contacts import _private_helper\n"   # a private name
        "    return m._cache, skeleton\n",              # a private attribute of another module
        encoding="utf-8")
    modules["text2anim.core.bad"] = bad
    imports = [imp for m, p in modules.items() for imp in _imports_of(m, p, modules)]
    # and a cycle: core.motion "imports" core.bad
    imports.append(Import("text2anim.core.motion", "text2anim.core.bad", None, 1))
    found = violations(Graph(modules, imports))
    assert ("layer", "text2anim.core.bad", "text2anim.cli.main") in found
    assert ("private", "text2anim.core.bad", "text2anim.core.contacts._private_helper") in found
    assert ("private", "text2anim.core.bad", "text2anim.core.motion._cache") in found
    assert any(v[0] == "cycle" and {"text2anim.core.bad", "text2anim.core.motion"} <= set(v) for v in found)


def test_no_stage_imports_a_later_stage_or_private_names_and_no_cycles():
    found = sorted(violations(module_graph()))
    assert not found, "layering violations:\n" + "\n".join(map(str, found))


def test_no_two_modules_of_the_package_import_each_other():
    """Within a stage too: a cycle (``a`` imports ``b``, which imports ``a``, even inside a function) is found
    in any subpackage."""
    found = sorted(cycles(module_graph()))
    assert not found, "import cycles:\n" + "\n".join(map(str, found))
