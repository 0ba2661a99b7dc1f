"""A study's fingerprint covers the code and data it depends on, so an edit elsewhere leaves it fresh."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from quenchsim import validation as v
from quenchsim.dependencies import code_closure
from tests.test_validate import root  # noqa: F401 -- the toy study's folder (a fixture)

ROOT = Path(v.__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def checkout(tmp_path_factory):
    """A copy of the package, validation/, cases/ and materials/ to edit."""
    copy = tmp_path_factory.mktemp("checkout")
    for name in ("quenchsim", "validation", "cases", "materials"):
        shutil.copytree(ROOT / name, copy / name, ignore=shutil.ignore_patterns("__pycache__", "*.pyc"))
    return copy


def fingerprints(checkout_root: Path) -> dict[str, str]:
    return {s.key: v.study_fingerprint(s, checkout_root) for s in v.discover(checkout_root / "validation")}


def edit(path: Path, old: str, new: str) -> None:
    text = path.read_text()
    assert old in text
    path.write_text(text.replace(old, new, 1))


def test_a_progress_bar_edit_leaves_every_study_fresh_and_a_bath_edit_only_the_bearings(checkout):
    before = fingerprints(checkout)
    assert len(before) > 20 and len(set(before.values())) == len(before)
    edit(checkout / "quenchsim" / "progress" / "__init__.py", '"{desc}: {percentage:3.0f}%', '"{desc} - {percentage:3.0f}%')
    assert fingerprints(checkout) == before
    edit(checkout / "quenchsim" / "progress" / "forecasts.py", '"""', '"""Edited. ')   # a submodule: an observer too
    assert fingerprints(checkout) == before

    # wording, comments and type hints cannot change a result: the bath's docstring, a comment and an annotation
    edit(checkout / "quenchsim" / "bath" / "htc.py", '"""', '"""Edited. ')
    edit(checkout / "quenchsim" / "bath" / "config.py", "\n", "\n# a comment\n")
    edit(checkout / "quenchsim" / "bath" / "config.py", "def load_constants(name: str,", "def load_constants(name: object,")
    assert fingerprints(checkout) == before
    edit(checkout / "quenchsim" / "inputs" / "bath.py", "MAX_ROTATION_RPM = 600.0", "MAX_ROTATION_RPM = 601.0")
    after = fingerprints(checkout)
    bearings = [k for k in before if k.startswith("bearings/")]
    quench = ["quench/ring_a", "quench/ring_b", "quench/convergence", "quench/peer_race", "bath/model",
              "design/ring_a", "calibration/ring_a", "speed/quench_chain"]
    assert len(bearings) > 5
    assert [k for k in bearings if after[k] != before[k]] == []
    assert [k for k in quench if after[k] == before[k]] == []
    assert after["quench/thermal_verification"] == before["quench/thermal_verification"]  # no bath there


def test_a_case_or_material_edit_stales_the_studies_that_read_it(checkout):
    before = fingerprints(checkout)
    edit(checkout / "cases" / "srb_outer_ring.toml", "\n", "\n# edited\n")
    after = fingerprints(checkout)
    assert after["quench/ring_b"] != before["quench/ring_b"]
    assert after["quench/ring_a"] == before["quench/ring_a"] and after["bearings/hertz"] == before["bearings/hertz"]
    edit(checkout / "materials" / "SUJ3.toml", "\n", "\n# edited\n")
    again = fingerprints(checkout)
    assert again["quench/ring_a"] != after["quench/ring_a"] and again["bearings/hertz"] == after["bearings/hertz"]


def test_the_inputs_name_the_files_used(checkout):
    studies = {s.key: s for s in v.discover(checkout / "validation")}
    ring_b = v.study_inputs(studies["quench/ring_b"], checkout)
    assert "quenchsim/pipeline.py" in ring_b.code and not any(c.startswith("quenchsim/progress") for c in ring_b.code)
    assert "quenchsim/validation.py::cached_run" in ring_b.code and "quenchsim/validation.py" not in ring_b.code
    assert {"cases/srb_outer_ring.toml", "materials/SUJ3.toml", "validation/quench/ring_a/study.py"} <= set(ring_b.data)
    hertz = v.study_inputs(studies["bearings/hertz"], checkout)
    assert "quenchsim/bearings/hertz.py" in hertz.code and "quenchsim/pipeline.py" not in hertz.code
    assert not any(d.startswith(("materials/", "cases/")) for d in hertz.data)


def test_the_closure_follows_what_runs(tmp_path):
    """Whole modules for named imports (function bodies included), module level only for parent packages,
    nothing under TYPE_CHECKING, module names in strings, relative imports; observers left out."""
    pkg = tmp_path / "quenchsim"
    files = {
        "__init__.py": "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from quenchsim import typed\n"
                       "def load():\n    from quenchsim import lazy\n",
        "typed.py": "", "lazy.py": "", "progress.py": "", "table.py": "", "leaf.py": "", "other.py": "",
        "sub/__init__.py": "from .leaf import x\n",
        "sub/leaf.py": "x = 1\ndef f():\n    from quenchsim import table\n    from quenchsim import progress\n",
        "sub/cli.py": 'COMMANDS = {"a": "quenchsim.other"}\n',
    }
    for name, text in files.items():
        (pkg / name).parent.mkdir(parents=True, exist_ok=True)
        (pkg / name).write_text(text)
    closure = code_closure(["import quenchsim.sub.cli\n"], tmp_path)
    assert sorted(closure.modules) == ["quenchsim", "quenchsim.other", "quenchsim.sub", "quenchsim.sub.cli",
                                       "quenchsim.sub.leaf", "quenchsim.table"]
    assert sorted(code_closure(["from quenchsim import load\n"], tmp_path).modules) == ["quenchsim", "quenchsim.lazy"]


@pytest.fixture()
def toy(root):  # noqa: F811 -- `root` is the imported fixture, requested by name
    (study,) = v.discover(root)
    return study


def test_a_record_without_its_inputs_is_stale_never_fresh(toy, tmp_path):
    reports = tmp_path / "reports"
    assert v.run_study(toy, reports, tmp_path / "runs").status == "ran"
    record = json.loads((reports / "toy_one.json").read_text())
    assert record["inputs"]["data"] == ["validation/toy/one/study.py", "validation/toy/one/targets.toml"]
    assert not v.check_study(toy, reports).stale
    del record["inputs"]  # as written before the inputs were recorded, with the same fingerprint
    (reports / "toy_one.json").write_text(json.dumps(record))
    assert v.check_study(toy, reports).stale
    assert v.run_study(toy, reports, tmp_path / "runs").status == "ran"


def test_check_fails_on_a_regression_and_reports_an_open_miss(toy, tmp_path, capsys, monkeypatch):
    from quenchsim.cli import main

    reports = tmp_path / "reports"
    reports.mkdir()
    monkeypatch.setattr(v, "discover", lambda folder=v.VALIDATION_ROOT: [toy])

    def check(metrics: dict, *extra: str) -> int:
        (reports / "toy_one.json").write_text(json.dumps({"fingerprint": "x", "metrics": metrics}))
        return main(["validate", "--check", "--reports", str(reports), *extra])

    assert check({"ratio": 0.7, "table": {"a": 2.0}}) == 0  # the open miss is reported, not a failure
    out = capsys.readouterr().out
    assert "OPEN (known misses):" in out and "model too simple" in out and "1 met, 0 missed, 1 open" in out
    assert check({"ratio": 0.7, "table": {"a": 2.0}}, "--strict") == 1
    assert check({"ratio": 0.9, "table": {"a": 2.0}}) == 1  # a target that is not declared open is missed
    assert "MISSED:" in capsys.readouterr().out


def test_behaviour_bytes_ignore_wording_and_type_hints_but_not_code(tmp_path):
    from quenchsim.behaviour import behaviour_bytes

    def of(text: str) -> bytes:
        path = tmp_path / f"m{abs(hash(text))}.py"
        path.write_text(text)
        return behaviour_bytes(path)

    base = of('"""Doc."""\ndef f(x: float) -> float:\n    """Twice."""\n    y: float = 2.0\n    return y * x\n')
    assert of('# note\ndef f(x: "np.ndarray") -> object:\n    y: int = 2.0  # was float\n    return y * x\n') == base
    assert of('def f(x):\n    y = 2.0\n    return y * x\n') != base            # an annotated local became a plain one
    assert of('def f(x: float) -> float:\n    y: float = 2.0\n    return x * y\n') != base   # operand order
    assert of('def f(x: float) -> float:\n    y: float = 3.0\n    return y * x\n') != base
    # a class's annotations are fields (dataclasses) or not (ClassVar): they count
    cls = of("class A:\n    x: int = 1\n")
    assert of("class A:\n    x: ClassVar[int] = 1\n") != cls
    (tmp_path / "m.toml").write_text("a = 1  # a comment in data counts\n")
    assert behaviour_bytes(tmp_path / "m.toml") == b"a = 1  # a comment in data counts\n"


def test_a_cached_run_counts_by_the_code_a_run_executes(checkout):
    """The run cache's fingerprint (sweep.case_hash) covers the run's import closure and the data: an edit of the
    calibration's statistics leaves it (and every cached run) valid, an edit of the bath's code does not; the whole
    package's fingerprint moves with both."""
    from quenchsim.fingerprint import _fingerprint

    def both() -> tuple[str, str]:
        _fingerprint.cache_clear()
        args = ((), checkout / "materials")
        return (_fingerprint(*args, runs_only=True, package=checkout / "quenchsim"),
                _fingerprint(*args, runs_only=False, package=checkout / "quenchsim"))

    run0, code0 = both()
    edit(checkout / "quenchsim" / "calibration" / "conflicts.py", "LOCAL_STARTS = 4", "LOCAL_STARTS = 5")
    run1, code1 = both()
    assert run1 == run0 and code1 != code0
    edit(checkout / "quenchsim" / "inputs" / "bath.py", "MAX_ROTATION_RPM = 601.0", "MAX_ROTATION_RPM = 602.0")
    run2, code2 = both()
    assert run2 != run1 and code2 != code1
    edit(checkout / "materials" / "baths" / "jet_bath.toml", "value = 0.3,", "value = 0.31,")
    assert both()[0] != run2
