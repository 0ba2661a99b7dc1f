"""Every number of the shipped material files (steels, their mechanics, quenchants, lubricants, fit data) has a
source, and none is marked placeholder, assumed or [R] (issues 16, 17, 21)."""

import re
import tomllib
from pathlib import Path

import pytest

MATERIALS = Path(__file__).resolve().parents[1] / "materials"
FORBIDDEN = re.compile(r"placeholder|assumed|\[R\]", re.IGNORECASE)


def unsourced_numbers(table: dict, path: str = "", sourced: bool = False) -> list[str]:
    """Dotted keys of numbers (or number lists) with no ``source`` in their table or an enclosing one.
    Prior keys (range, range_factor) are covered by the source of their table; a ``<group>_source`` key (the
    lubricant files) sources its table too."""
    sourced = sourced or any(bool(str(v).strip()) for k, v in table.items() if k == "source" or k.endswith("_source"))
    out = []
    for key, value in table.items():
        where = f"{path}.{key}" if path else key
        if isinstance(value, dict):
            out += unsourced_numbers(value, where, sourced)
        elif isinstance(value, (int, float, list)) and not isinstance(value, bool) and not sourced:
            out.append(where)
    return out


@pytest.mark.parametrize("path", sorted(MATERIALS.rglob("*.toml")), ids=lambda p: str(p.relative_to(MATERIALS)))
def test_every_material_number_has_a_source(path):
    data = tomllib.loads(path.read_text())
    assert unsourced_numbers(data) == []
    hits = [line for line in path.read_text().splitlines() if FORBIDDEN.search(line)]
    assert hits == []


def test_the_scan_finds_an_unsourced_number():
    assert unsourced_numbers({"a": {"b": 1.0}, "c": {"source": "x", "d": [1, 2]}}) == ["a.b"]
