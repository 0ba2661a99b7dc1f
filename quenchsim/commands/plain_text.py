"""A bearing verb's result (one JSON-serialisable dict) as plain text, for `quenchsim bearings VERB` without --json."""

from __future__ import annotations


def plain_lines(value: object, indent: str = "") -> list[str]:
    """A bearing verb's result as text, one ``key: value`` line per entry: tables nested by indent, a list of tables
    as one ``- key value, ...`` line per item, numbers to 6 significant digits."""
    if isinstance(value, dict):
        lines: list[str] = []
        for key, item in value.items():
            if isinstance(item, dict) or (isinstance(item, list) and any(isinstance(x, dict) for x in item)):
                lines += [f"{indent}{key}:", *plain_lines(item, indent + "  ")]
            else:
                lines.append(f"{indent}{key}: {_plain_value(item)}")
        return lines
    if isinstance(value, list):
        return [f"{indent}- " + (", ".join(f"{k} {_plain_value(v)}" for k, v in item.items()) if isinstance(item, dict)
                                else _plain_value(item)) for item in value]
    return [f"{indent}{_plain_value(value)}"]


def _plain_value(value: object) -> str:
    if isinstance(value, bool) or value is None:
        return str(value).lower() if value is not None else "-"
    if isinstance(value, float):
        return format(value, ".6g")
    if isinstance(value, (list, tuple)):
        return ", ".join(_plain_value(v) for v in value)
    if isinstance(value, dict):
        return "; ".join(f"{k} {_plain_value(v)}" for k, v in value.items())
    return str(value)
