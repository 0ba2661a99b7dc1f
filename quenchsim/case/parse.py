"""Reading a case file: its conditions merged, dotted overrides applied, every table read against its declaration
(:mod:`quenchsim.inputs.case`) and the whole checked (:class:`quenchsim.case.Case`) before any work starts."""

from __future__ import annotations

import copy
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from quenchsim.case.model import Case
from quenchsim.errors import InputError, require
from quenchsim.inputs.declare import check_keys, from_table
from quenchsim.inputs.reader import read_toml, reading


def deep_merge(base: Mapping[str, Any], override: Mapping[str, Any]) -> dict[str, Any]:
    """Recursively merge ``override`` into a copy of ``base`` (tables merge, other values replace)."""
    out = copy.deepcopy(dict(base))
    for key, value in override.items():
        if isinstance(value, Mapping) and isinstance(out.get(key), Mapping):
            out[key] = deep_merge(out[key], value)
        else:
            out[key] = copy.deepcopy(value)
    return out


def set_dotted(data: dict[str, Any], dotted: str, value: Any) -> None:
    """Set ``data["a"]["b"]["c"] = value`` for ``dotted = "a.b.c"`` (creating tables)."""
    keys = dotted.split(".")
    node = data
    for key in keys[:-1]:
        node = node.setdefault(key, {})
        if not isinstance(node, dict):
            raise InputError(dotted, value, f"'{key}' is not a table")
    node[keys[-1]] = value


def _unset_dotted(data: dict[str, Any], dotted: str) -> None:
    """Remove the key at ``dotted`` (if present), so that its default applies."""
    *tables, key = dotted.split(".")
    node: Any = data
    for name in tables:
        node = node.get(name) if isinstance(node, dict) else None
    if isinstance(node, dict):
        node.pop(key, None)


def load_case(path: str | Path, condition: str | None = None,
              overrides: Mapping[str, Any] | None = None) -> Case:
    """Load a case file, merge ``[conditions.<condition>]`` and dotted ``overrides``, check everything."""
    path = Path(path)
    raw = read_toml(path, "case")
    require(raw, "case", str(path), "the file is empty (no keys, no tables): is it the case file you meant, or was "
                                    "it cut short?")
    with reading(path):
        return case_from_dict(raw, condition, overrides, path=path)


def case_from_dict(raw: Mapping[str, Any], condition: str | None = None,
                   overrides: Mapping[str, Any] | None = None, path: Path | None = None) -> Case:
    """Build and check a case from a dict (as read from TOML); see :func:`load_case`. The key names of every
    condition are checked whichever condition runs; the values of the one that runs with the case."""
    conditions = raw.get("conditions", {})
    require(isinstance(conditions, Mapping), "conditions", conditions, "must be a table of [conditions.NAME] tables")
    for key, table in conditions.items():
        require(isinstance(table, Mapping), f"conditions.{key}", table, "must be a table")
        check_keys(Case, table, f"conditions.{key}")
    data = {k: v for k, v in raw.items() if k != "conditions"}
    if condition is not None:
        condition = str(condition)
        if not conditions:
            where = path.name if path is not None else "this case"
            raise InputError("--condition", condition, f"not in this case: {where} has no [conditions.NAME] tables at all "
                                                       "(is the file complete, not truncated?)")
        if condition not in conditions:
            raise InputError("--condition", condition, f"not in this case; available: {', '.join(sorted(conditions))}")
        data = deep_merge(data, conditions[condition])
    elif conditions:
        raise InputError("--condition", None, f"required; available: {', '.join(sorted(conditions))}")
    name = str(raw.get("name", path.stem if path else "case"))
    return build_case(data, name, condition, path, overrides)


def build_case(data: Mapping[str, Any], name: str, condition: str | None, path: Path | None,
               overrides: Mapping[str, Any] | None = None) -> Case:
    """The checked :class:`Case` of the merged table ``data`` (plus dotted ``overrides``; a value None removes a key
    so that its default applies)."""
    data = deep_merge(data, {})
    for dotted, value in (overrides or {}).items():
        require(dotted.split(".")[0] != "conditions", dotted, value, "sets the case as run, its condition merged: "
                "give the key without conditions.<name>. and choose the condition")
        if value is None:
            _unset_dotted(data, dotted)
        else:
            set_dotted(data, dotted, value)
    return from_table(Case, {**data, "name": name}, condition=condition, path=path)
