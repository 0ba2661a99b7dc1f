"""The quenchsim code and data a piece of Python depends on, found statically (no import is executed).

:func:`code_closure` follows the ``import quenchsim...`` statements of some sources through the package:

* a module imported by name (``import quenchsim.a.b``, ``from quenchsim.a import b``, ``from . import x``) is
  followed with all its imports, those inside functions included (conservative: a function may be called);
* a package that is only the parent of an imported module contributes its module-level imports (what runs when
  the submodule is imported), not the imports inside its functions, nor those under ``if TYPE_CHECKING:``;
* a string constant naming a module (``"quenchsim.commands.run"`` in the CLI's table, ``-m quenchsim.cli``) counts
  as an import of it: the CLI imports its commands by name -- except in the modules of :data:`NAMES_ONLY`, whose
  module names are the subjects of their analysis, not code they run;
* the modules of :data:`BY_NAME` are followed per imported name, so a study that takes ``cached_run`` from the
  validation runner depends on the quench pipeline and one that takes ``study_targets`` does not;
* the modules of :data:`OBSERVERS` are left out.

:func:`package_data` adds the data files that travel with the modules (``data/`` folders and non-Python files
beside them) and says whether the closure reads the ``materials/`` folder. Third-party packages are not covered.
"""

from __future__ import annotations

import ast
import functools
import re
from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path

PACKAGE = "quenchsim"
OBSERVERS = frozenset({"quenchsim.progress"})
"""Modules that only display a run (the progress bar and its time-left estimate): the run calls them, but nothing
they return reaches a result, so an edit there cannot move a number. A package's submodules are observers too."""


def _observer(module: str) -> bool:
    """Whether ``module`` is one of the :data:`OBSERVERS` or a submodule of one."""
    return any(module == o or module.startswith(f"{o}.") for o in OBSERVERS)
NAMES_ONLY = frozenset({"quenchsim.dependencies", "quenchsim.fingerprint"})
"""Modules whose module-naming strings (this module's special cases, the run fingerprint's run modules) are not
imports."""
BY_NAME = frozenset({"quenchsim.validation"})
"""Modules followed per imported name: the studies' runner, whose helpers pull in very different code."""
MATERIALS_READERS = ("quenchsim.materials",)
"""Modules (and their submodules) that read the ``materials/`` folder; a module that names the folder in a string
constant (``"materials"``) reads it too."""
PROSE_SUFFIXES = (".md",)
"""Files in data folders that only describe the data (README.md, SOURCES.md): never read by the code."""
_MODULE_NAME = re.compile(rf"^{PACKAGE}(\.[A-Za-z_]\w*)+$")


@dataclass(frozen=True)
class _Import:
    """``import module`` (``names`` empty) or ``from module import names``."""

    module: str
    names: tuple[str, ...] = ()


@dataclass(frozen=True)
class _Definition:
    """A top-level name of a :data:`BY_NAME` module: its source, the top-level names it uses, its imports."""

    source: str
    uses: frozenset[str]
    imports: tuple[_Import, ...]
    is_import: bool = False


@dataclass(frozen=True)
class _Analysis:
    """What one source file imports: at module level (run at import), anywhere, and per top-level name."""

    module_level: tuple[_Import, ...]
    anywhere: tuple[_Import, ...]
    definitions: dict[str, _Definition] = field(hash=False)
    names_materials: bool


def _is_type_checking(node: ast.AST) -> bool:
    test = node.test if isinstance(node, ast.If) else None
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or \
        (isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING")


def _absolute(node: ast.ImportFrom, package: str) -> str:
    if not node.level:
        return node.module or ""
    parts = package.split(".")
    base = parts[:len(parts) - node.level + 1]
    return ".".join(base + ([node.module] if node.module else []))


def _imports_in(nodes: Iterable[ast.AST], package: str, into_functions: bool, names: bool = True) -> list[_Import]:
    """The quenchsim imports (and, with ``names``, module-naming string constants) under ``nodes``, skipping
    ``if TYPE_CHECKING:`` bodies and, unless ``into_functions``, function bodies."""
    found: list[_Import] = []
    stack = list(nodes)
    while stack:
        node = stack.pop()
        if isinstance(node, ast.If) and _is_type_checking(node):
            stack.extend(node.orelse)
            continue
        if not into_functions and isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
            continue
        if isinstance(node, ast.Import):
            found += [_Import(a.name) for a in node.names if a.name.split(".")[0] == PACKAGE]
        elif isinstance(node, ast.ImportFrom):
            module = _absolute(node, package)
            if module.split(".")[0] == PACKAGE:
                found.append(_Import(module, tuple(a.name for a in node.names)))
        elif names and isinstance(node, ast.Constant) and isinstance(node.value, str) and _MODULE_NAME.match(node.value):
            found.append(_Import(node.value))
        stack.extend(ast.iter_child_nodes(node))
    return found


def _bound_names(node: ast.stmt) -> list[str]:
    if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
        return [node.name]
    if isinstance(node, (ast.Assign, ast.AnnAssign)):
        targets = node.targets if isinstance(node, ast.Assign) else [node.target]
        return [n.id for t in targets for n in ast.walk(t) if isinstance(n, ast.Name)]
    if isinstance(node, ast.Import):
        return [(a.asname or a.name).split(".")[0] for a in node.names]
    return []


def _definitions(tree: ast.Module, text: str, package: str) -> dict[str, _Definition]:
    lines = text.splitlines()
    out = {}
    for node in tree.body:
        first = min([node.lineno, *(d.lineno for d in getattr(node, "decorator_list", []))])
        source = "\n".join(lines[first - 1:node.end_lineno])
        uses = frozenset(n.id for n in ast.walk(node) if isinstance(n, ast.Name))
        imports = tuple(_imports_in([node], package, into_functions=True))
        if isinstance(node, ast.ImportFrom):  # each bound name takes only its own import
            for alias in node.names:
                own = tuple(_Import(i.module, (alias.name,)) for i in imports)
                out[alias.asname or alias.name] = _Definition(source, uses, own, is_import=True)
            continue
        for name in _bound_names(node):
            out[name] = _Definition(source, uses, imports, is_import=isinstance(node, ast.Import))
    return out


@functools.lru_cache(maxsize=4096)
def _analyse(module: str, is_package: bool, text: str) -> _Analysis:
    tree = ast.parse(text)
    package = module if is_package else module.rpartition(".")[0]
    strings = {n.value for n in ast.walk(tree) if isinstance(n, ast.Constant) and isinstance(n.value, str)}
    names = module not in NAMES_ONLY
    return _Analysis(tuple(_imports_in(tree.body, package, into_functions=False, names=names)),
                     tuple(_imports_in(tree.body, package, into_functions=True, names=names)),
                     _definitions(tree, text, package) if module in BY_NAME else {},
                     "materials" in strings)


@dataclass
class Closure:
    """The modules a set of sources depends on: ``modules`` (followed whole or as parents, by path relative to
    the root) and ``parts`` (``path::name`` -> source of the definitions taken from a :data:`BY_NAME` module)."""

    root: Path
    modules: dict[str, Path] = field(default_factory=dict)
    parts: dict[str, str] = field(default_factory=dict)
    reads_materials: bool = False
    _whole: set[str] = field(default_factory=set)
    _parents: set[str] = field(default_factory=set)
    _names: set[tuple[str, str]] = field(default_factory=set)

    def path(self, module: str) -> Path | None:
        """The file of ``module`` under the root, None when it is not a module there."""
        base = self.root.joinpath(*module.split("."))
        for candidate in (base.with_suffix(".py"), base / "__init__.py"):
            if candidate.is_file():
                return candidate
        return None

    def _analysis(self, module: str) -> _Analysis | None:
        path = self.path(module)
        return None if path is None else _analyse(module, path.name == "__init__.py", path.read_text())

    def _keep(self, module: str) -> bool:
        """Record ``module``'s file; False when it is an observer or not a module of the root."""
        path = self.path(module)
        if _observer(module) or path is None:
            return False
        self.modules[module] = path
        return True

    def add_imports(self, imports: Iterable[_Import]) -> None:
        for imp in imports:
            if _observer(imp.module):
                continue
            submodules = [f"{imp.module}.{n}" for n in imp.names if self.path(f"{imp.module}.{n}") is not None]
            for sub in submodules:
                self.add_whole(sub)
            names = [n for n in imp.names if f"{imp.module}.{n}" not in submodules]
            if imp.module in BY_NAME and names and "*" not in names:
                self.add_names(imp.module, names)
            elif names or not imp.names:
                self.add_whole(imp.module)

    def _add_parents(self, module: str) -> None:
        parts = module.split(".")
        for i in range(1, len(parts)):
            parent = ".".join(parts[:i])
            if parent in self._parents or parent in self._whole:
                continue
            self._parents.add(parent)
            if self._keep(parent):
                analysis = self._analysis(parent)
                assert analysis is not None
                self.add_imports(analysis.module_level)

    def add_whole(self, module: str) -> None:
        """``module`` with every import it makes (function bodies included) and its parent packages."""
        if module in self._whole or not self._keep(module):
            return
        self._whole.add(module)
        self._add_parents(module)
        analysis = self._analysis(module)
        assert analysis is not None
        self.reads_materials |= analysis.names_materials or module.startswith(MATERIALS_READERS)
        self.add_imports(analysis.anywhere)

    def add_names(self, module: str, names: Iterable[str]) -> None:
        """The top-level ``names`` of a :data:`BY_NAME` module, with the names and imports they use."""
        analysis = self._analysis(module)
        path = self.path(module)
        if analysis is None or path is None:
            return
        self._add_parents(module)
        todo = list(names)
        while todo:
            name = todo.pop()
            if (module, name) in self._names:
                continue
            self._names.add((module, name))
            definition = analysis.definitions.get(name)
            if definition is None:  # not a top-level name: take the whole module
                self.add_whole(module)
                continue
            if not definition.is_import:  # an import is covered by the module it brings in
                self.parts[f"{self.relative(path)}::{name}"] = definition.source
            todo += [n for n in definition.uses if n in analysis.definitions]
            self.add_imports(definition.imports)

    def relative(self, path: Path) -> str:
        return path.relative_to(self.root).as_posix()


def code_closure(sources: Iterable[str], root: Path) -> Closure:
    """The closure of the quenchsim imports of ``sources`` (Python texts outside the package, such as a study's
    files) over the package under ``root`` (the folder that holds ``quenchsim/``)."""
    closure = Closure(Path(root))
    for text in sources:
        closure.add_imports(_imports_in(ast.parse(text).body, "", into_functions=True))
    return closure


def package_data(closure: Closure) -> list[Path]:
    """The non-Python files that travel with the closure's modules: those beside each module and in a ``data/``
    folder there, for the module's folder and every package folder above it."""
    folders: set[Path] = set()
    top = closure.root / PACKAGE
    for path in closure.modules.values():
        folder = path.parent
        while folder.is_relative_to(top):
            folders.add(folder)
            folder = folder.parent
    files = set()
    for folder in folders:
        files |= {p for p in folder.iterdir() if p.is_file() and p.suffix not in (".py", ".pyc", *PROSE_SUFFIXES)}
        if (folder / "data").is_dir():
            files |= set(data_files(folder / "data"))
    return sorted(files)


def data_files(folder: Path) -> list[Path]:
    """Every file under ``folder`` but caches and prose (:data:`PROSE_SUFFIXES`)."""
    return sorted(p for p in Path(folder).rglob("*") if p.is_file() and "__pycache__" not in p.parts
                  and p.suffix not in (".pyc", *PROSE_SUFFIXES))


def named_files(texts: Iterable[str], folder: Path) -> list[Path]:
    """The files of ``folder`` whose names appear in ``texts`` or in the text of a file so found (a sweep file
    names its base case)."""
    candidates = {p.name: p for p in Path(folder).glob("*") if p.is_file()}
    found: dict[str, Path] = {}
    todo = list(texts)
    while todo:
        text = todo.pop()
        for name, path in candidates.items():
            if name not in found and name in text:
                found[name] = path
                todo.append(path.read_text(errors="replace"))
    return sorted(found.values())
