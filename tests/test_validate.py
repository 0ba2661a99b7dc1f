"""`quenchsim validate`: targets as data, one runner, pages from metrics + targets, exit 1 on a missed target."""

from __future__ import annotations

import json
import subprocess
import sys
import textwrap

import pytest

from quenchsim import validation as v
from quenchsim.errors import InputError

STUDY = '''
TITLE = "A toy study"
SLOW = False
CALLS = []

def run(workdir):
    CALLS.append(1)
    (workdir / "toy.png").write_bytes(b"png")
    return {"ratio": 0.7, "table": {"a": 2.0}, "page_note": "computed"}

def page(metrics):
    return f"Body with ratio {metrics['ratio']:.2f}."
'''
TARGETS = '''
[[targets]]
metric = "ratio"
value = 0.75
tolerance = 0.08
source = "a published ratio"

[[targets]]
metric = "table.a"
value = 1.0
rel_tolerance = 0.1
source = "a measured value"
status = "open"
reason = "known to be missed: model too simple"

[[targets]]
metric = "table.a"
value = 2.1
status = "reference"
source = "another author's value"
'''


@pytest.fixture()
def root(tmp_path):
    folder = tmp_path / "validation" / "toy" / "one"
    folder.mkdir(parents=True)
    (folder / "study.py").write_text(textwrap.dedent(STUDY))
    (folder / "targets.toml").write_text(textwrap.dedent(TARGETS))
    v.study_module.cache_clear()
    return tmp_path / "validation"


def test_targets_are_checked_met_open_reference(root):
    (study,) = v.discover(root)
    assert study.key == "toy/one" and study.title() == "A toy study" and not study.slow()
    verdicts = v.evaluate(study.targets, {"ratio": 0.7, "table": {"a": 2.0}})
    assert [x.state for x in verdicts] == ["met", "open", "reference"]
    assert [x.state for x in v.evaluate(study.targets, {"ratio": 0.9, "table": {"a": 1.05}})] == \
        ["missed", "open, met", "reference"]
    assert v.evaluate(study.targets, {})[0].state == "absent"


def test_run_writes_page_metrics_and_plots_and_reuses_the_cache(root, tmp_path, monkeypatch):
    monkeypatch.setattr(v, "VALIDATION_ROOT", root)
    (study,) = v.discover(root)
    reports, runs = tmp_path / "reports", tmp_path / "runs"
    first = v.run_study(study, reports, runs)
    assert first.status == "ran", first.error
    page = (reports / "toy_one.md").read_text()
    assert page.startswith("# A toy study") and "Body with ratio 0.70." in page
    assert "| ratio | 0.7 | 0.75 +- 0.08 | met |" in page and "open (known miss)" in page and "model too simple" in page
    assert (reports / "toy.png").read_bytes() == b"png"
    record = json.loads((reports / "toy_one.json").read_text())
    assert record["metrics"]["ratio"] == 0.7 and record["fingerprint"] == v.study_fingerprint(study)
    assert v.run_study(study, reports, runs).status == "cached" and len(study.module.CALLS) == 1
    (study.folder / "data.toml").write_text("x = 1\n")  # an input of the study changed
    assert v.run_study(study, reports, runs).status == "ran" and len(study.module.CALLS) == 2
    # one open target: reported apart from the real misses, a failure only with strict
    assert v.exit_code([first]) == 0 and v.exit_code([first], strict=True) == 1
    lines = v.summary_lines([first])
    assert lines[0] == "OPEN (known misses):" and "MISSED:" not in lines


def test_check_evaluates_cached_metrics_and_counts_a_missing_study(root, tmp_path):
    (study,) = v.discover(root)
    reports = tmp_path / "reports"
    assert v.check_study(study, reports).status == "not run"
    assert v.exit_code([v.check_study(study, reports)]) == 1
    reports.mkdir()
    (reports / "toy_one.json").write_text(json.dumps({"fingerprint": "old", "metrics": {"ratio": 0.9, "table": {"a": 1.0}}}))
    r = v.check_study(study, reports)
    assert r.stale and [x.state for x in r.verdicts] == ["missed", "open, met", "reference"]
    assert any(line.startswith("MISSED:") for line in v.summary_lines([r]))


@pytest.mark.parametrize("text, field", [
    ('[[targets]]\nmetric = "x"\nvalue = 1.0\ntolerance = 0.1\n', "source"),
    ('[[targets]]\nmetric = "x"\nvalue = 1.0\nsource = "s"\n', "targets[0]"),
    ('[[targets]]\nmetric = "x"\nvalue = 1.0\ntolerance = 0.1\nsource = "s"\nstatus = "open"\n', "reason"),
    ('[[targets]]\nmetric = "x"\nmin = 1.0\nsource = "s"\ncolour = "red"\n', "unknown keys"),
    ('[[targets]]\nmetric = "x"\nvalue = 1.0\ntolerance = 0.1\nrel_tolerance = 0.1\nsource = "s"\n', "targets[0]"),
])
def test_a_bad_targets_file_is_a_one_line_error(tmp_path, text, field):
    path = tmp_path / "targets.toml"
    path.write_text(text)
    with pytest.raises(InputError, match=field.replace("[", r"\[")):
        v.load_targets(path)


def test_select_and_the_cli_reject_an_unknown_study(root, tmp_path):
    studies = v.discover(root)
    assert v.select(studies, ["toy"]) == studies and v.select(studies, ["one"]) == studies
    with pytest.raises(InputError, match="--only"):
        v.select(studies, ["nonsense"])
    res = subprocess.run([sys.executable, "-m", "quenchsim.cli", "validate", "--reports", str(tmp_path / "r"),
                          "--only", "nonsense"], capture_output=True, text=True, timeout=120)
    assert res.returncode == 2 and "--only" in res.stderr and "bearings/hertz" in res.stderr


def test_cached_run_is_reused_only_with_the_same_inputs_and_code(tmp_path, monkeypatch):
    """A finished quench run is reused; a changed case or a changed code fingerprint reruns it."""
    from quenchsim.case import case_from_dict
    from tests.test_sweep import small_case

    calls = []

    def fake_run(case, out, progress=True):
        calls.append(case.quench.time_s)
        out.mkdir(parents=True, exist_ok=True)
        (out / "case.toml").write_text(v._toml(case))
        (out / "summary.json").write_text('{"status": "ok"}')

    monkeypatch.setattr("quenchsim.pipeline.run", fake_run)
    case = case_from_dict(small_case(), None, {})
    v.cached_run(case, tmp_path / "r")
    v.cached_run(case, tmp_path / "r")
    assert len(calls) == 1
    v.cached_run(case_from_dict(small_case(), None, {"quench.time_s": 21.0}), tmp_path / "r")
    assert len(calls) == 2
    monkeypatch.setattr(v, "code_fingerprint", lambda: "another version")
    v.cached_run(case_from_dict(small_case(), None, {"quench.time_s": 21.0}), tmp_path / "r")
    assert len(calls) == 3


@pytest.mark.parametrize("args", [["--check"], ["--fast"], []], ids=["check", "fast", "run"])
def test_validate_without_studies_refuses_in_one_line(tmp_path, monkeypatch, capsys, args):
    """Installed from the wheel there is no validation/: `--check` printed "0 met, 0 missed, 0 open" and exited 0,
    `--fast` and a plain run crashed writing reports/index.json (issue 36)."""
    from quenchsim.cli import main

    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(v, "discover", lambda *a, **k: [])
    assert main(["validate", *args]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "holds no studies" in err[0]
    assert not any(tmp_path.iterdir())
