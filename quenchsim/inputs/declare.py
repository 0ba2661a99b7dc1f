"""Declared input tables: frozen dataclasses whose fields carry their unit, default, limits and meaning, and the one
converter between a TOML table and such a dataclass.

A table of an input file is declared once::

    @dataclass(frozen=True, kw_only=True)
    class Air(Table):
        \"\"\"[air]: cooling in air after the quench.\"\"\"

        temperature_C: float = quantity(25.0, unit="C", ge=-50.0, le=200.0, doc="air temperature")
        time_s: float = quantity(20000.0, unit="s", ge=0.0, doc="longest time in air")

:func:`from_table` turns a table read from a file into it, checking every key (unknown keys are errors, with the
closest known name), every type and every limit, and names the offending key with its table path; the class's
:meth:`Table.check` holds the rules that tie fields together. The limits and :meth:`Table.check` run again on a copy
made with :func:`dataclasses.replace`, so a value changed in code is checked like one read from a file.
:func:`to_table` writes the table back as it was given (the numbers in the form written, defaults only where the
declaration says the resolved inputs record them), so a case's resolved inputs and their digest do not depend on how
the case was built. :func:`key_rows` lists the declared keys for the generated references (docs/reference/).

Field annotations the converter understands: ``float``, ``int``, ``bool``, ``str``, ``Literal[...]``, tuples
(``tuple[float, ...]``, ``tuple[float, float]``), a nested :class:`Table` (a sub-table), ``tuple[SomeTable, ...]``
(an array of tables), ``Mapping[str, X]`` (a table of named entries of one kind), ``Mapping[str, Any]`` or ``Any``
(kept as given, checked elsewhere), ``X | None`` (optional), and unions of those (the first that fits).
"""

from __future__ import annotations

import dataclasses
import math
import types
import typing
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any, ClassVar, Literal, TypeVar, Union, get_args, get_origin

from quenchsim.errors import InputError, did_you_mean

REQUIRED: Any = dataclasses.MISSING
CONVERTERS: dict[Any, Callable[[Any, str], Any]] = {}
"""Conversions of value types a kind of file defines itself (a steel's property forms, :mod:`quenchsim.inputs.steel`):
annotation -> function(value as read, key path) returning the value or raising :class:`InputError`."""
TYPE_NAMES: dict[Any, str] = {}
"""What a value of such a type looks like, for messages and references ("a property: value, table, ...")."""
"""The default of a key that has none (the file must give it)."""

T = TypeVar("T", bound="Table")

PRIOR_KEYS = ("range", "range_factor")
"""The keys of a data file's ``{ value, range | range_factor, source }`` entry besides ``value`` and ``source``: the
prior of an uncertain value (quenchsim.calibration.inputs)."""


@dataclass(frozen=True)
class Spec:
    """What a declared key means: its ``doc``, ``unit``, limits, the choices of a string, the ``source`` of its
    default, whether the resolved inputs record its default (``written``), whether a data file may give the number as
    ``{ value, range, source }`` (``sourced``), the file's key when it is not the field's name (``key``) and a text
    saying what is allowed when the type alone does not (``allowed``)."""

    doc: str = ""
    unit: str = ""
    ge: float | None = None
    gt: float | None = None
    le: float | None = None
    lt: float | None = None
    choices: tuple[str, ...] | None = None
    source: str = ""
    written: bool = False
    sourced: bool = False
    key: str | None = None
    allowed: str = ""
    shown: str = ""
    """The default as the references show it, when its value does not say it (a property's 0)."""

    def limits_text(self) -> str:
        """``> 0``, ``0-1``, ``>= -50 and <= 200``: the limits for the references and the messages."""
        parts = []
        for op, bound in ((">=", self.ge), (">", self.gt), ("<=", self.le), ("<", self.lt)):
            if bound is not None:
                parts.append(f"{op} {bound:g}")
        return " and ".join(parts)


SPEC = "quenchsim.input"
"""The field-metadata key of a declared key's :class:`Spec`."""
RESOLVED = "quenchsim.resolved"
"""The field-metadata key of a field that is not a key of the file (:func:`resolved`)."""


def resolved(default: Any = None, *, init: bool = True) -> Any:
    """A field of a declared table that its file does not give: a value the reader passes in (``init``, e.g. the
    case's condition) or one the table resolves itself (``init=False``, set by :meth:`Table.check`, e.g. the case's
    loaded steel). Not compared, not written back."""
    return field(default=default, init=init, compare=False, repr=False, metadata={RESOLVED: True})


def quantity(default: Any = REQUIRED, *, doc: str = "", unit: str = "", ge: float | None = None,
             gt: float | None = None, le: float | None = None, lt: float | None = None,
             choices: tuple[str, ...] | None = None, source: str = "", written: bool = False, sourced: bool = False,
             key: str | None = None, allowed: str = "", shown: str = "") -> Any:
    """A declared key of an input table (a dataclass field with a :class:`Spec`); ``default`` :data:`REQUIRED` when
    the file must give it. A mutable default (a dict or list) is copied per instance."""
    spec = Spec(doc=doc, unit=unit, ge=ge, gt=gt, le=le, lt=lt, choices=choices, source=source, written=written,
                sourced=sourced, key=key, allowed=allowed, shown=shown)
    if isinstance(default, (dict, list)):
        value = default
        return field(default_factory=lambda: type(value)(value), metadata={SPEC: spec})
    return field(default=default, metadata={SPEC: spec})


@dataclass(frozen=True, kw_only=True)
class Table:
    """Base of a declared input table. ``_given`` holds the keys the input gave, as given (the numbers in the form
    written), for :func:`to_table`; it is not part of the value (equality, repr)."""

    _given: Mapping[str, Any] = field(default_factory=dict, repr=False, compare=False, kw_only=True)

    OTHER_KEYS: ClassVar[tuple[str, ...]] = ()
    """Keys the table accepts besides its fields and ignores (older names read by :meth:`check`, provenance)."""
    UNKNOWN: ClassVar[str] = "unknown key"
    """How an unknown key is called in the message (a table of tables: "unknown table or key")."""

    def __post_init__(self) -> None:
        for f in declared_fields(type(self)):
            value = getattr(self, f.name)
            normal = _normalised(value, f.type)
            if normal is not value:
                object.__setattr__(self, f.name, normal)
            _check_limits(spec_of(f), key_of(f), normal)
        self.check()

    def check(self) -> None:
        """Rules that tie the table's keys together; raise :class:`InputError` naming the key (relative to the
        table). Runs on every construction, :func:`dataclasses.replace` included."""

    @classmethod
    def check_keys_given(cls, table: Mapping[str, Any]) -> None:
        """Rules on which keys a table read from a file may give together, checked before its values are read (so
        that the message names the rule, not a value the rule makes irrelevant)."""


@dataclass(frozen=True, kw_only=True)
class DataFile(Table):
    """Base of a data file's top level (a quenchant, a bath layout, ...): its name, one line and its source."""

    name: str = quantity("", doc="the file's name (default: the file stem)")
    description: str = quantity("", doc="one line")
    source: str = quantity("", doc="where the data come from")


def spec_of(f: dataclasses.Field[Any]) -> Spec:
    spec = f.metadata.get(SPEC)
    return spec if isinstance(spec, Spec) else Spec()


def declared_fields(cls: type[Table]) -> list[dataclasses.Field[Any]]:
    """The declared keys of ``cls`` (its init fields but ``_given``), with their annotations resolved."""
    hints = _hints(cls)
    out = []
    for f in dataclasses.fields(cls):
        if f.name == "_given" or not f.init or f.metadata.get(RESOLVED):
            continue
        f.type = hints[f.name]
        out.append(f)
    return out


_HINTS: dict[type, dict[str, Any]] = {}


def _hints(cls: type) -> dict[str, Any]:
    if cls not in _HINTS:
        _HINTS[cls] = typing.get_type_hints(cls)
    return _HINTS[cls]


def key_of(f: dataclasses.Field[Any]) -> str:
    """The file's key of a declared field."""
    return spec_of(f).key or f.name


# -- reading ---------------------------------------------------------------------------------------------------------
def from_table(cls: type[T], table: Any, where: str = "", /, **derived: Any) -> T:
    """The declared table ``cls`` from ``table`` (as read from TOML) at table path ``where`` (``"quench.bath"``;
    ``""`` for a file's top level). Unknown keys, missing required keys, wrong types and values outside the limits
    are :class:`InputError` naming ``where.key``. ``derived``: values of fields the file does not give (``init``
    fields the caller resolves, e.g. a loaded steel)."""
    if not isinstance(table, Mapping):
        raise InputError(where or "file", table, "must be a table")
    fields = declared_fields(cls)
    keys = {key_of(f): f for f in fields if f.name not in derived}
    allowed = (*keys, *cls.OTHER_KEYS)
    for key in table:
        if key not in allowed:
            raise InputError(_join(where, key), table[key], f"{cls.UNKNOWN}; [{where or 'top level'}] takes "
                                                             f"{', '.join(allowed)}{did_you_mean(key, allowed)}")
    try:
        cls.check_keys_given(table)
    except InputError as exc:
        raise _located(exc, where) from None
    values: dict[str, Any] = dict(derived)
    given: dict[str, Any] = {}
    for key, f in keys.items():
        spec = spec_of(f)
        if key in table:
            given[f.name] = table[key]
            values[f.name] = convert(table[key], f.type, _join(where, key), spec)
        elif f.default is dataclasses.MISSING and f.default_factory is dataclasses.MISSING:
            if not _optional(f.type):
                raise InputError(_join(where, key), None, f"is required{_about(spec)}")
            values[f.name] = None
        else:
            default = _default(f)
            if isinstance(default, Table):   # a default sub-table: with the defaults its declaration writes
                default = from_table(type(default), {}, _join(where, key))
                values[f.name] = default
            if spec.written:
                given[f.name] = default
    for key in cls.OTHER_KEYS:
        if key in table:
            given[key] = table[key]
    try:
        return cls(**values, _given=given)
    except InputError as exc:
        raise _located(exc, where) from None


def check_keys(cls: type[Table], table: Any, where: str) -> None:
    """Only the key names of ``table`` against the declaration ``cls``, sub-tables included (a condition's tables,
    whose values are checked when that condition runs): an unknown key is an :class:`InputError` naming it."""
    if not isinstance(table, Mapping):
        raise InputError(where, table, "must be a table")
    fields = {key_of(f): f for f in declared_fields(cls)}
    allowed = (*fields, *cls.OTHER_KEYS)
    for key, value in table.items():
        if key not in allowed:
            raise InputError(_join(where, key), value, f"{cls.UNKNOWN}; [{where}] takes "
                                                       f"{', '.join(allowed)}{did_you_mean(key, allowed)}")
        if key in fields:
            _check_sub_keys(fields[key].type, value, _join(where, key))


def _check_sub_keys(tp: Any, value: Any, where: str) -> None:
    members = [a for a in get_args(tp) if a is not type(None)] if _is_union(tp) else [tp]
    for member in members:
        if isinstance(member, type) and issubclass(member, Table) and isinstance(value, Mapping):
            check_keys(member, value, where)
        elif get_origin(member) in (Mapping, dict, typing.Mapping) and isinstance(value, Mapping):
            sub = get_args(member)[1]
            if isinstance(sub, type) and issubclass(sub, Table):
                for name, entry in value.items():
                    if isinstance(entry, Mapping):
                        check_keys(sub, entry, _join(where, name))
        elif get_origin(member) is tuple and isinstance(value, list):
            sub = get_args(member)[0]
            if isinstance(sub, type) and issubclass(sub, Table):
                for i, entry in enumerate(value):
                    if isinstance(entry, Mapping):
                        check_keys(sub, entry, _join(where, i))


def _about(spec: Spec) -> str:
    return f" ({spec.doc})" if spec.doc else ""


def _join(where: str, key: str | int) -> str:
    if isinstance(key, int):
        return f"{where}[{key}]"
    return f"{where}.{key}" if where and key else where or key


def _located(exc: InputError, where: str) -> InputError:
    """``exc`` with its key placed in table ``where`` (a rule of :meth:`Table.check` names keys relative to it)."""
    if not where:
        return exc
    return InputError(_join(where, exc.field), exc.value, exc.allowed, exc.file)


def _optional(tp: Any) -> bool:
    return type(None) in get_args(tp) if _is_union(tp) else tp is type(None)


def _is_union(tp: Any) -> bool:
    return get_origin(tp) in (Union, types.UnionType)


def _describe(tp: Any) -> str:
    """What a value of annotation ``tp`` looks like, for messages and references."""
    if tp is float:
        return "a number"
    if tp is int:
        return "an integer"
    if tp is bool:
        return "true or false"
    if tp is str:
        return "a string"
    if tp is Any:
        return "any value"
    if tp in TYPE_NAMES:
        return TYPE_NAMES[tp]
    if isinstance(tp, type) and issubclass(tp, Table):
        return "a table"
    origin, args = get_origin(tp), get_args(tp)
    if origin is Literal:
        return repr(args[0]) if len(args) == 1 else "one of " + ", ".join(repr(a) for a in args)
    if _is_union(tp):
        return " or ".join(dict.fromkeys(_describe(a) for a in args if a is not type(None)))
    if origin is tuple:
        if len(args) == 2 and args[1] is Ellipsis:
            if isinstance(args[0], type) and issubclass(args[0], Table):
                return "an array of tables"
            return f"a list of {_plural(args[0])}"
        return f"a list of {len(args)} {_plural(args[0])}"
    if origin in (Mapping, dict, typing.Mapping):
        return "a table" if args[1] is Any else f"a table of {_plural(args[1])}"
    return str(tp)


def _plural(tp: Any) -> str:
    text = _describe(tp)
    for article in ("a ", "an "):
        if text.startswith(article):
            text = text[len(article):]
    return {"number": "numbers", "integer": "integers", "string": "strings", "table": "tables"}.get(text, text)


def convert(value: Any, tp: Any, where: str, spec: Spec = Spec()) -> Any:
    """``value`` (as read from TOML) as annotation ``tp``, checked; errors name ``where``."""
    if spec.sourced and isinstance(value, Mapping) and _scalar(tp):
        value = _sourced_value(value, where)
    if tp is Any:
        return value
    if tp in CONVERTERS:
        return CONVERTERS[tp](value, where)
    if _is_union(tp):
        members = [a for a in get_args(tp) if a is not type(None)]
        kinds = _kinds(members)
        if kinds is not None and isinstance(value, Mapping):
            key, by_kind = kinds
            default = next((k for k, m in by_kind.items() if _field(m, key).default is not dataclasses.MISSING), None)
            kind = value.get(key, default)
            if kind not in by_kind:
                raise InputError(_join(where, key), kind, f"must be one of {', '.join(map(repr, by_kind))}"
                                 f"{did_you_mean(kind, by_kind) if isinstance(kind, str) else ''}")
            return from_table(by_kind[kind], value, where)
        first: InputError | None = None
        for member in members:
            try:
                return convert(value, member, where, dataclasses.replace(spec, sourced=False))
            except InputError as exc:
                first = first or exc
        if len(members) == 1 and first is not None:
            raise first
        raise InputError(where, value, spec.allowed or f"must be {_describe(tp)}")
    if tp is float:
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise InputError(where, value, spec.allowed or "must be a finite number")
        _check_limits(spec, where, value)
        return float(value)
    if tp is int:
        if isinstance(value, float) and value.is_integer():
            value = int(value)
        if isinstance(value, bool) or not isinstance(value, int):
            raise InputError(where, value, spec.allowed or "must be an integer")
        _check_limits(spec, where, value)
        return value
    if tp is bool:
        if not isinstance(value, bool):
            raise InputError(where, value, spec.allowed or "must be true or false")
        return value
    if tp is str:
        if not isinstance(value, str):
            raise InputError(where, value, spec.allowed or "must be a string")
        if spec.choices is not None and value not in spec.choices:
            raise InputError(where, value, spec.allowed or f"must be one of {', '.join(spec.choices)}"
                             f"{did_you_mean(value, spec.choices)}")
        return value
    if isinstance(tp, type) and issubclass(tp, Table):
        if not isinstance(value, Mapping):
            raise InputError(where, value, spec.allowed or f"must be a table{_about(spec)}")
        return from_table(tp, value, where)
    origin, args = get_origin(tp), get_args(tp)
    if origin is Literal:
        if value not in args or isinstance(value, bool) != isinstance(args[0], bool):
            raise InputError(where, value, spec.allowed or f"must be {_describe(tp)}"
                             f"{did_you_mean(value, args) if isinstance(value, str) else ''}")
        return value
    if origin is tuple:
        if not isinstance(value, (list, tuple)):
            raise InputError(where, value, spec.allowed or f"must be {_describe(tp)}")
        if len(args) == 2 and args[1] is Ellipsis:
            return tuple(convert(v, args[0], _join(where, i)) for i, v in enumerate(value))
        if len(value) != len(args):
            raise InputError(where, value, spec.allowed or f"must be {_describe(tp)}")
        return tuple(convert(v, a, _join(where, i)) for i, (v, a) in enumerate(zip(value, args)))
    if origin in (Mapping, dict, typing.Mapping):
        if not isinstance(value, Mapping):
            raise InputError(where, value, spec.allowed or f"must be {_describe(tp)}")
        if args and args[1] is Any:
            return dict(value)
        return {str(k): convert(v, args[1], _join(where, str(k)), dataclasses.replace(spec, choices=None))
                for k, v in value.items()}
    raise TypeError(f"quenchsim.inputs: no conversion for the annotation {tp!r} ({where})")


KIND_KEYS = ("type", "kind", "model", "form")
"""The keys that say which of several declared tables a table is (``[geometry] type = "profile"``, a reaction's
``model``, the free strain's ``form``)."""


def _kinds(members: list[Any]) -> tuple[str, dict[Any, type[Table]]] | None:
    """For a union of declared tables told apart by a ``type`` or ``kind`` key (each a ``Literal`` of one value):
    that key and the table of each value; else None."""
    if not members or not all(isinstance(m, type) and issubclass(m, Table) for m in members):
        return None
    for key in KIND_KEYS:
        fields = [_field(m, key) for m in members]
        if all(f is not None and get_origin(f.type) is Literal and len(get_args(f.type)) == 1 for f in fields):
            return key, {get_args(f.type)[0]: m for f, m in zip(fields, members)}
    return None


def _field(cls: type[Table], name: str) -> Any:
    return next((f for f in declared_fields(cls) if f.name == name), None)


def _scalar(tp: Any) -> bool:
    """Whether annotation ``tp`` is a single value (a number, string, list; optional or not), not a table."""
    members = [a for a in get_args(tp) if a is not type(None)] if _is_union(tp) else [tp]
    return all(m in (float, int, str, bool) or get_origin(m) in (tuple, Literal) for m in members)


def _sourced_value(entry: Mapping[str, Any], where: str) -> Any:
    """The number of a ``{ value, source, range | range_factor }`` entry, its prior checked."""
    if "value" not in entry:
        wrong = next((k for k in entry if k not in ("source", *PRIOR_KEYS)), None)
        if wrong is not None:
            raise InputError(_join(where, wrong), entry[wrong], "unknown key; an entry takes value, source, range, "
                                                                 f"range_factor{did_you_mean(wrong, ('value',))}")
        raise InputError(where, dict(entry), "needs a 'value' (and a 'source')")
    for key in entry:
        if key not in ("value", "source", *PRIOR_KEYS):
            raise InputError(_join(where, key), entry[key], "unknown key; an entry takes value, source, range, "
                                                             f"range_factor{did_you_mean(key, ('value', 'source'))}")
    check_prior(entry, where)
    return entry["value"]


def check_prior(entry: Mapping[str, Any], where: str) -> None:
    """A data file's prior on an entry: ``range = [lo, hi]`` (numbers, lo <= hi, holding a numeric ``value``) and
    ``range_factor = f`` (a number >= 1)."""
    if "range" in entry:
        rng = entry["range"]
        if not (isinstance(rng, (list, tuple)) and len(rng) == 2
                and all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in rng) and rng[0] <= rng[1]):
            raise InputError(_join(where, "range"), rng, "must be [lo, hi] numbers with lo <= hi")
        value = entry.get("value")
        if isinstance(value, (int, float)) and not isinstance(value, bool) and not rng[0] <= value <= rng[1]:
            raise InputError(_join(where, "value"), value, f"must lie in its range [{rng[0]}, {rng[1]}]")
    if "range_factor" in entry:
        factor = entry["range_factor"]
        if isinstance(factor, bool) or not isinstance(factor, (int, float)) or factor < 1.0:
            raise InputError(_join(where, "range_factor"), factor, "must be a number >= 1")


def _normalised(value: Any, tp: Any) -> Any:
    """A value set in code in the declared form: an integer for a float field as a float, a list as a tuple (so
    that a copy made with :func:`dataclasses.replace` computes as one read from a file)."""
    if isinstance(value, int) and not isinstance(value, bool) and (tp is float or (
            _is_union(tp) and float in get_args(tp) and int not in get_args(tp))):
        return float(value)
    if isinstance(value, list) and (get_origin(tp) is tuple or (
            _is_union(tp) and any(get_origin(a) is tuple for a in get_args(tp)))):
        return tuple(value)
    return value


def _check_limits(spec: Spec, name: str, value: Any) -> None:
    """Raise :class:`InputError` naming ``name`` when the number ``value`` lies outside ``spec``'s limits."""
    problem = _outside(spec, value)
    if problem:
        raise InputError(name, value, problem)


def _outside(spec: Spec, value: Any) -> str:
    """What is allowed, when the number ``value`` lies outside ``spec``'s limits; else ``""``."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return ""
    for ok, op, bound in ((spec.ge is None or value >= spec.ge, ">=", spec.ge),
                          (spec.gt is None or value > spec.gt, ">", spec.gt),
                          (spec.le is None or value <= spec.le, "<=", spec.le),
                          (spec.lt is None or value < spec.lt, "<", spec.lt)):
        if not ok:
            low = spec.ge if spec.ge is not None else spec.gt
            high = spec.le if spec.le is not None else spec.lt
            both = f" (range {low:g} to {high:g})" if low is not None and high is not None else ""
            return (f"must be {op} {bound:g}{' ' + spec.unit if spec.unit else ''}{both}"
                    f"{'; ' + spec.allowed if spec.allowed else ''}")
    return ""


# -- writing back ----------------------------------------------------------------------------------------------------
def to_table(obj: Table) -> dict[str, Any]:
    """``obj`` as the table it was read from: the keys given (numbers in the form written), the defaults the
    declaration records (``written``) and every key changed since (a copy made with :func:`dataclasses.replace`)."""
    out: dict[str, Any] = {}
    given = obj._given
    for f in declared_fields(type(obj)):
        value = getattr(obj, f.name)
        key = key_of(f)
        if f.name in given:
            out[key] = _as_given(value, given[f.name])
        elif value is not None and value != _default(f):
            out[key] = encode(value)
    for key in type(obj).OTHER_KEYS:
        if key in given:
            out[key] = given[key]
    return out


def _default(f: dataclasses.Field[Any]) -> Any:
    if f.default is not dataclasses.MISSING:
        return f.default
    if f.default_factory is not dataclasses.MISSING:
        return f.default_factory()
    return None


def _as_given(value: Any, given: Any) -> Any:
    """``value`` written as ``given`` was when it is the same value (an integer stays an integer), else encoded."""
    if isinstance(value, Table):
        return to_table(value)
    if isinstance(value, (tuple, list)) and isinstance(given, (list, tuple)) and len(value) == len(given):
        return [_as_given(v, g) for v, g in zip(value, given)]
    if isinstance(value, Mapping) and isinstance(given, Mapping) and set(value) == set(given):
        return {k: _as_given(value[k], given[k]) for k in given}
    if _same(value, given):
        return given
    return encode(value)


def _same(value: Any, given: Any) -> bool:
    if isinstance(given, bool) or isinstance(value, bool):
        return value is given
    if isinstance(given, (int, float)) and isinstance(value, (int, float)):
        return float(value) == float(given)
    if isinstance(given, Mapping) and isinstance(value, Mapping):
        return dict(value) == dict(given)
    return bool(value == given)


def encode(value: Any) -> Any:
    """A declared value as TOML data (tables as dicts, tuples as lists)."""
    if isinstance(value, Table):
        return to_table(value)
    if isinstance(value, (tuple, list)):
        return [encode(v) for v in value]
    if isinstance(value, Mapping):
        return {str(k): encode(v) for k, v in value.items()}
    return value


# -- references ------------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class KeyRow:
    """One declared key for a generated reference: its key, what it takes, unit, default, limits and meaning."""

    key: str
    takes: str
    unit: str
    default: str
    limits: str
    doc: str


def key_rows(cls: type[Table]) -> list[KeyRow]:
    """The declared keys of ``cls`` in declaration order (sub-tables and arrays of tables included as one row)."""
    rows = []
    for f in declared_fields(cls):
        spec = spec_of(f)
        default = _default(f)
        if spec.shown:
            shown = spec.shown
        elif f.default is dataclasses.MISSING and f.default_factory is dataclasses.MISSING:
            shown = "optional" if _optional(f.type) else "required"
        elif default is None or default == {} or default == ():
            shown = "optional"
        elif isinstance(default, Table):
            shown = "its defaults"
        elif default == "":
            shown = "none"
        else:
            shown = _shown(default)
        takes = _describe(f.type)
        if spec.choices:
            takes = "one of " + ", ".join(f'"{c}"' for c in spec.choices)
        rows.append(KeyRow(key_of(f), takes.replace("'", '"'), spec.unit, shown, spec.limits_text(), spec.doc))
    return rows


def _shown(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return f'"{value}"'
    if isinstance(value, float):
        return f"{value:g}"
    return str(value)
