"""What a fingerprint hashes of a file (:func:`behaviour_bytes`): a Python module by what it computes -- its syntax
tree without comments, docstrings and function annotations, in a text that does not depend on the Python version --
so that an edit of wording or type hints leaves every cached run and validation study as it was."""

from __future__ import annotations

import ast
import functools
from pathlib import Path


def _without_docstring(body: list[ast.stmt]) -> list[ast.stmt]:
    first = body[0] if body else None
    is_doc = (isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant)
              and isinstance(first.value.value, str))
    return body[1:] if is_doc else body


def _behaviour_tree(tree: ast.Module) -> ast.Module:
    """``tree`` without docstrings and without the annotations of function arguments, returns and local
    variables (class-level annotations stay: a dataclass's fields and ``ClassVar`` depend on them)."""
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
            node.body = _without_docstring(node.body) or [ast.Pass()]
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            node.returns = None
            args = node.args
            for arg in [*args.posonlyargs, *args.args, *args.kwonlyargs, args.vararg, args.kwarg]:
                if arg is not None:
                    arg.annotation = None
            for inner in ast.walk(ast.Module(body=node.body, type_ignores=[])):
                if isinstance(inner, ast.AnnAssign):
                    inner.annotation = ast.Name("_", ast.Load())
    return tree


def _dump(node: object) -> str:
    """A version-stable text of an AST: fields that are None or empty are left out (Python 3.12 added
    ``type_params = []`` to every definition, 3.13 changed ``ast.dump``'s defaults)."""
    if isinstance(node, ast.AST):
        fields = ",".join(f"{k}={_dump(v)}" for k, v in ast.iter_fields(node) if v is not None and v != [])
        return f"{type(node).__name__}({fields})"
    if isinstance(node, list):
        return "[" + ",".join(_dump(v) for v in node) + "]"
    return repr(node)


@functools.lru_cache(maxsize=2048)
def _behaviour_of(path: str, mtime_ns: int, size: int) -> bytes:
    text = Path(path).read_bytes()
    try:
        tree = ast.parse(text)
    except (SyntaxError, ValueError):
        return text
    return _dump(_behaviour_tree(tree)).encode()


def behaviour_bytes(path: Path) -> bytes:
    """What a fingerprint hashes of a file: for a Python module its syntax tree without comments, docstrings and
    function annotations -- edits that cannot change what the code computes (wording, type hints) leave a
    fingerprint as it was; for any other file (or one that does not parse) its bytes."""
    path = Path(path)
    if path.suffix != ".py":
        return path.read_bytes()
    stat = path.stat()
    return _behaviour_of(str(path.resolve()), stat.st_mtime_ns, stat.st_size)
