"""What a new user met on the second first-contact pass (issue 47): shipped examples that end where the guides say,
errors that point the right way and come before any work, lengths in fixed decimals, and the small ones."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from quenchsim.cli import main
from quenchsim.sweep import load_sweep, run_point

ROOT = Path(__file__).resolve().parents[1]
CASES = ROOT / "cases"


# -- 1. the sweep example ends ok ------------------------------------------------------------------------------

def test_the_sweep_examples_slowest_cooling_case_ends_at_room_temperature(tmp_path):
    """cases/sweep_nozzles.toml cut the air stage to 300 s: all six cases ended `hot` (up to 58 C). Its slowest
    cooling case (the weakest ID and OD jets) must now end `ok`, cooled to room temperature."""
    spec = load_sweep(CASES / "sweep_nozzles.toml")
    slowest = min(spec.points, key=lambda p: (p["quench.bath.od_jet_speed_mm_s"], p["quench.bath.id_jet_speed_mm_s"]))
    result = run_point(spec.raw_case, str(spec.case_path), spec.condition, spec.overrides(slowest),
                       str(tmp_path / "slowest"))
    assert result["error"] is None
    assert result["status"] == "ok" and result["summary"]["end_state"]["at_room_temperature"]


# -- 3. the austenitising temperature against the steel's table, at load -----------------------------------------

@pytest.mark.parametrize("T_aust", [1118.0, 1150.0, 1000.0, 700.0])
def test_an_austenitising_temperature_outside_the_steels_table_is_refused_before_anything_is_written(
        tmp_path, capsys, T_aust):
    """Inside the case limits (600-1200 C) but outside SUJ3's tabulated 815-880 C: 1118 and 1150 C crashed in the
    mechanics (Poisson's ratio 0.5025) after case.toml and mesh.msh were written; 1000 C was named right, but also
    after writing them."""
    out = tmp_path / "run"
    rc = main(["run", "crb_outer_ring", "--condition", "1", "--set", f"process.austenitising_temperature_C={T_aust}",
               "--out", str(out), "--quiet"])
    err = capsys.readouterr().err.strip()
    assert rc == 2 and len(err.splitlines()) == 1, err
    assert f"process.austenitising_temperature_C = {T_aust}" in err and "815-880 C" in err and "SUJ3" in err
    assert not out.exists()


# -- 6. messages that point the right way --------------------------------------------------------------------------

def _case_with(tmp_path: Path, old: str, new: str) -> Path:
    text = (CASES / "crb_outer_ring.toml").read_text()
    assert old in text
    path = tmp_path / "ring.toml"
    path.write_text(text.replace(old, new, 1))
    return path


def _one_line_error(capsys, argv: list[str]) -> str:
    rc = main(argv)
    err = capsys.readouterr().err.strip()
    assert rc == 2 and len(err.splitlines()) == 1, err
    return err


@pytest.mark.parametrize("old, typo, meant", [
    ("inner_diameter_mm = 218.3", "inner_diamter_mm = 218.3", "inner_diameter_mm"),   # a required key: was "is required"
    ("chamfer_mm = 2.0", "chamfr_mm = 2.0", "chamfer_mm"),                             # an optional one: was ignored
    ("time_s = 900.0", "tme_s = 900.0", "time_s"),                                     # [quench]
])
def test_a_misspelt_key_is_named_with_the_key_it_was_meant_to_be(tmp_path, capsys, old, typo, meant):
    case = _case_with(tmp_path, old, typo)
    err = _one_line_error(capsys, ["run", str(case), "--condition", "1", "--out", str(tmp_path / "run"), "--quiet"])
    assert f".{typo.split()[0]} = " in err and "unknown key" in err and f"did you mean {meant}?" in err
    assert "is required" not in err and not (tmp_path / "run").exists()


def test_an_empty_case_file_is_named_as_empty_not_as_a_missing_condition(tmp_path, capsys):
    empty = tmp_path / "empty.toml"
    empty.write_text("\n# nothing yet\n")
    err = _one_line_error(capsys, ["run", str(empty), "--condition", "1", "--out", str(tmp_path / "run")])
    assert "empty.toml" in err and "empty" in err.split(":", 1)[1] and "--condition" not in err


def test_a_truncated_case_file_is_named_as_such_not_as_a_missing_condition(tmp_path, capsys):
    """Cut at a line before its [conditions] tables, the file still parses: the error is about the file."""
    text = (CASES / "crb_outer_ring.toml").read_text()
    cut = tmp_path / "cut.toml"
    cut.write_text(text[:text.index("[[probes]]")])
    err = _one_line_error(capsys, ["run", str(cut), "--condition", "1", "--out", str(tmp_path / "run")])
    assert "cut.toml has no [conditions." in err and "truncated" in err


def test_a_misspelt_table_is_named_with_the_table_it_was_meant_to_be(tmp_path, capsys):
    case = _case_with(tmp_path, "[process]", "[proces]")
    err = _one_line_error(capsys, ["run", str(case), "--condition", "1", "--out", str(tmp_path / "run")])
    assert err.startswith("quenchsim: error: proces = ") and "did you mean process?" in err


def test_a_probe_curve_in_kelvin_is_refused_with_a_hint_to_give_degrees_c(tmp_path, capsys, monkeypatch):
    """The first-hour probe curve with its temperatures in K said only "never reaches 300 C"."""
    lines = [ln for ln in (ROOT / "docs" / "guide" / "first_hour_probe_curve.csv").read_text().splitlines()
             if not ln.startswith("#")]
    rows = [ln.split(",") for ln in lines[1:]]
    (tmp_path / "curve_K.csv").write_text(lines[0] + "\n" + "".join(f"{t},{float(T) + 273.15:.2f}\n" for t, T in rows))
    monkeypatch.chdir(tmp_path)
    err = _one_line_error(capsys, ["quenchant", "fit", "curve_K.csv", "--fast"])
    assert "never reaches 300 C" in err and "is it in K?" in err
    assert not (tmp_path / "materials").exists()
