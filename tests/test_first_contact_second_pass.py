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
