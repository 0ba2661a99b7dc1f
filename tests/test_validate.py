"""`quenchsim validate`: every report module run, nothing skipped silently, reports/ replaced only when all worked."""

from __future__ import annotations

import json
import subprocess
import sys
import textwrap

import pytest

from quenchsim.commands.validate import REPORT_MODULES, regenerate
from quenchsim.errors import InputError

GOOD = '''
from pathlib import Path

def write(reports_dir: Path) -> list[Path]:
    page = reports_dir / "good.md"
    page.write_text("# A good page\\n\\n![plot](good.png)\\n")
    (reports_dir / "good.png").write_bytes(b"png")
    return [page]
'''
BAD = '''
def write(reports_dir):
    (reports_dir / "half.md").write_text("# half")
    raise RuntimeError("model diverged")
'''

CACHED = '''
from pathlib import Path

def write(reports_dir: Path) -> list[Path]:
    page, cache = reports_dir / "cached.md", reports_dir / "cached.json"
    page.write_text("# Uses a cache\\n")
    if not cache.is_file():
        cache.write_text("{}")
    return [page, cache]
'''


@pytest.fixture()
def package(tmp_path, monkeypatch):
    pkg = tmp_path / "fakereports"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    (pkg / "good.py").write_text(textwrap.dedent(GOOD))
    (pkg / "bad.py").write_text(textwrap.dedent(BAD))
    (pkg / "nowrite.py").write_text("X = 1\n")
    (pkg / "cached.py").write_text(textwrap.dedent(CACHED))
    monkeypatch.syspath_prepend(str(tmp_path))
    return "fakereports"


def test_full_run_replaces_the_folder_and_indexes_every_module(tmp_path, package):
    reports = tmp_path / "reports"
    reports.mkdir()
    (reports / "stale.md").write_text("# from an old run")
    results, stage = regenerate(reports, modules=("good", "absent"), package=package, echo=False)
    assert stage is None
    assert {r.name: r.status for r in results} == {"good": "ok", "absent": "missing"}
    assert sorted(p.name for p in reports.iterdir()) == ["README.md", "good.md", "good.png", "index.json"]
    readme = (reports / "README.md").read_text()
    assert "[A good page](good.md)" in readme and "fakereports.absent" in readme and "missing" in readme
    index = json.loads((reports / "index.json").read_text())
    assert index[0]["files"] == ["good.md", "good.png"]        # a file written but not returned is listed too
    assert not list(tmp_path.glob(".reports-new-*"))


def test_a_returned_file_left_unchanged_is_still_indexed_with_a_relative_reports_dir(tmp_path, package, monkeypatch):
    monkeypatch.chdir(tmp_path)
    for _ in range(2):  # the second run finds its cache and does not rewrite it
        results, _ = regenerate("reports", only=["cached"], modules=("cached",), package=package, echo=False)
        assert results[0].files == ["cached.json", "cached.md"]


def test_a_failing_module_leaves_the_committed_folder_untouched(tmp_path, package):
    reports = tmp_path / "reports"
    reports.mkdir()
    (reports / "committed.md").write_text("# committed")
    results, stage = regenerate(reports, modules=("good", "bad", "nowrite"), package=package, echo=False)
    status = {r.name: r.status for r in results}
    assert status == {"good": "ok", "bad": "failed", "nowrite": "failed"}
    assert "model diverged" in next(r.error for r in results if r.name == "bad")
    assert [p.name for p in reports.iterdir()] == ["committed.md"]
    assert stage is not None and (stage / "good.md").is_file() and "model diverged" in (stage / "README.md").read_text()


def test_only_rewrites_the_named_module_and_keeps_the_rest(tmp_path, package):
    reports = tmp_path / "reports"
    regenerate(reports, modules=("good", "absent"), package=package, echo=False)
    (reports / "good.md").write_text("# edited by hand")
    (reports / "other.md").write_text("# another module's page")
    results, _ = regenerate(reports, only=["good"], modules=("good", "absent"), package=package, echo=False)
    assert [r.status for r in results] == ["ok"]
    assert (reports / "good.md").read_text().startswith("# A good page")
    assert (reports / "other.md").is_file()
    readme = (reports / "README.md").read_text()
    assert "fakereports.absent" in readme and "[A good page](good.md)" in readme
    with pytest.raises(InputError, match="--only"):
        regenerate(reports, only=["nonsense"], modules=("good",), package=package, echo=False)


def test_the_cli_lists_the_known_modules_and_rejects_an_unknown_one(tmp_path):
    assert {"validation", "bench", "cct", "sweep_bench"} <= set(REPORT_MODULES)
    res = subprocess.run([sys.executable, "-m", "quenchsim.cli", "validate", "--reports", str(tmp_path / "r"),
                          "--only", "nonsense"], capture_output=True, text=True, timeout=120)
    assert res.returncode == 2 and "--only" in res.stderr and "sweep_bench" in res.stderr


def test_cached_run_is_reused_only_with_the_same_inputs_and_code(tmp_path, monkeypatch):
    """A finished validation run is reused; a changed case or a changed code fingerprint reruns it."""
    from quenchsim.case import case_from_dict
    from quenchsim.report import validation
    from tests.test_sweep import small_case

    calls = []

    def fake_run(case, out, progress=True):
        calls.append(case.data["quench"]["time_s"])
        out.mkdir(parents=True, exist_ok=True)
        (out / "case.toml").write_text(validation._toml(case))
        (out / "summary.json").write_text('{"status": "ok"}')

    monkeypatch.setattr("quenchsim.simulation.run_case", fake_run)
    case = case_from_dict(small_case(), None, {})
    validation.cached_run(case, tmp_path / "r")
    validation.cached_run(case, tmp_path / "r")
    assert len(calls) == 1
    validation.cached_run(case_from_dict(small_case(), None, {"quench.time_s": 21.0}), tmp_path / "r")
    assert len(calls) == 2
    monkeypatch.setattr(validation, "code_fingerprint", lambda: "another version")
    validation.cached_run(case_from_dict(small_case(), None, {"quench.time_s": 21.0}), tmp_path / "r")
    assert len(calls) == 3
