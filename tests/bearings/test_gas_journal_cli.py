"""CLI of the gas journal bearing module: JSON keys, bad input -> exit 2."""

import json

import pytest

from quenchsim.cli import main


def _run(capsys, *argv):
    code = main(["bearings", "gas-journal", *argv, "--json"])
    out = capsys.readouterr()
    return code, out


def test_static_json(capsys):
    code, out = _run(capsys, "static", "--bearing-number", "3", "--eccentricity", "0.6", "--level", "4")
    assert code == 0
    data = json.loads(out.out)
    assert set(data) >= {"load", "attitude_deg", "grid", "iterations", "residual", "wall_time_s"}
    assert data["grid"] == [81, 17]
    assert data["load"] == pytest.approx(0.720, rel=0.02)
    assert data["residual"] <= 1e-5


def test_static_grooved_direct_matches_multigrid(capsys):
    args = ["static", "--bearing-number", "10", "--eccentricity", "0.5", "--grooves", "5", "--level", "3"]
    _, mg = _run(capsys, *args)
    _, direct = _run(capsys, *args, "--method", "direct")
    assert json.loads(mg.out)["load"] == pytest.approx(json.loads(direct.out)["load"], rel=1e-4)
    assert json.loads(mg.out)["groove_width_length_ratio_on_grid"] == [0.5, 0.5]


def test_bench_json(capsys):
    code, out = _run(capsys, "bench", "--levels", "2", "3", "--bearing-number", "1", "100", "--budget", "2")
    assert code == 0
    rows = json.loads(out.out)["results"]
    assert len(rows) == 2 * 2 * 4
    for row in rows:
        assert set(row) >= {"method", "level", "bearing_number", "nodes", "iterations", "wall_time_s"}
        assert row["converged"] or row["extrapolated"]
    assert {r["nodes"] for r in rows} == {21 * 5, 41 * 9}


@pytest.mark.parametrize(
    "argv",
    [
        ["static", "--bearing-number", "3", "--eccentricity", "1.0"],
        ["static", "--bearing-number", "-1", "--eccentricity", "0.5"],
        ["static", "--bearing-number", "3", "--eccentricity", "0.5", "--grooves", "5", "--groove-width-ratio", "0"],
        ["static", "--bearing-number", "3", "--eccentricity", "0.5", "--grooves", "5", "--groove-length-ratio", "1.2"],
        ["static", "--bearing-number", "3", "4", "--eccentricity", "0.5"],
        ["static", "--bearing-number", "3"],
        ["orbit", "--bearing-number", "3", "--load", "0.7"],
        ["orbit", "--bearing-number", "3", "--load", "0.7", "--mass-parameter", "-1"],
        ["stability", "--bearing-number", "-2"],
        ["stability", "--bearing-number", "1", "--mass-range", "5", "1"],
        ["stability", "--bearing-number", "1", "--max-iterations", "1", "--by", "orbit"],
        ["stability", "--bearing-number", "1", "--max-time-s", "0"],
        ["stability", "--bearing-number", "1", "--by", "linear", "--load", "0.2"],
        ["stability", "--bearing-number", "1", "--by", "linear", "--grooves", "20", "--grooved", "rotor",
         "--eccentricity", "0.3"],
        ["stability", "--bearing-number", "1", "--grid-tol", "0"],
        ["stability", "--bearing-number", "1", "--max-level", "11"],
        ["stability", "--bearing-number", "0", "--eccentricity", "0.4"],
        ["orbit", "--bearing-number", "3", "--load", "0.7", "--mass", "0.1", "--max-time-s", "0"],
    ],
)
def test_bad_input_exit_2(capsys, argv):
    code, out = _run(capsys, *argv)
    assert code == 2
    assert out.err.startswith("quenchsim: error:") and out.err.count("\n") == 1


def test_orbit_json_and_csv(capsys, tmp_path):
    csv = tmp_path / "orbit.csv"
    code, out = _run(capsys, "orbit", "--bearing-number", "3", "--load", "0.72", "--mass-parameter", "0.5",
                     "--level", "2", "--duration", "20", "--orbit-csv", str(csv))
    assert code == 0
    data = json.loads(out.out)
    assert set(data) >= {"eccentricity", "attitude_deg", "stable", "orbit_csv"}
    assert data["orbit_csv"] == str(csv)
    lines = csv.read_text().splitlines()
    assert lines[0] == "T,e_x,e_y,F_x,F_y" and len(lines) > 10
    assert 0.0 < data["eccentricity"] < 1.0


def _strict_json(text):
    """json.loads that refuses NaN / Infinity (not JSON)."""
    return json.loads(text, parse_constant=lambda name: pytest.fail(f"{name} in JSON output"))


A1 = ["--grooves", "20", "--groove-angle", "30", "--groove-depth", "1.1", "--groove-width-ratio", "0.5",
      "--groove-length-ratio", "0.5", "--grooved", "rotor"]


@pytest.mark.slow
def test_stability_json(capsys):
    code, out = _run(capsys, "stability", "--bearing-number", "1", *A1, "--by", "orbit", "--level", "3",
                     "--rel-tol", "0.1", "--max-time-s", "600")
    assert code == 0
    data = _strict_json(out.out)
    assert data["status"] == "bracketed" and data["method"] == "orbit"
    assert data["stable_below"] < data["critical_mass_parameter"] < data["unstable_above"]
    # the orbit grid's error from the linear ladder: level 3 lies ~25 % below the grid-converged threshold
    assert -0.30 < data["grid_error"]["relative_error_of_level"] < -0.20
    assert "grid error of level 3" in data["message"]


@pytest.mark.slow
def test_default_stability_of_rotor_a1_meets_the_papers_threshold(capsys):
    # the paper's orbit example: rotor A-1 at Lambda ~1 stable at Mbar 12, unstable at 13 (issue 49)
    code, out = _run(capsys, "stability", "--bearing-number", "1", *A1)
    assert code == 0
    data = _strict_json(out.out)
    assert data["method"] == "linear" and data["status"] == "converged"
    assert data["critical_mass_parameter"] == pytest.approx(12.5, rel=0.15)
    assert data["relative_grid_error"] <= 0.02
    assert "grid error of Richardson's estimate" in out.err.splitlines()[-1]


def test_default_stability_is_the_grid_converged_linear_threshold(capsys):
    # plain L/D 1 at eps 0.4, Lambda 1: levels 3, 4, 5 give Mbar 17.00, 17.10, 17.13 (second order)
    code, out = _run(capsys, "stability", "--bearing-number", "1", "--eccentricity", "0.4")
    assert code == 0
    data = _strict_json(out.out)
    assert data["method"] == "linear" and data["status"] == "converged"
    levels = [row["critical_mass_parameter"] for row in data["levels"]]
    assert [row["level"] for row in data["levels"]] == [3, 4, 5]
    assert levels[0] < levels[1] < levels[2] < data["critical_mass_parameter"]
    assert data["observed_order"] == pytest.approx(2.0, abs=0.3)
    ratio = (levels[1] - levels[0]) / (levels[2] - levels[1])
    assert data["critical_mass_parameter"] == pytest.approx(levels[2] + (levels[2] - levels[1]) / (ratio - 1))
    assert data["grid_error"] == pytest.approx(data["critical_mass_parameter"] - levels[2])
    assert [line.split(":")[0] for line in out.err.splitlines()[:3]] == [
        f"stability linear level {k}" for k in (3, 4, 5)]


def test_stability_linear_time_budget_says_what_the_next_level_needs(capsys):
    code, out = _run(capsys, "stability", "--bearing-number", "1", "--eccentricity", "0.4", "--max-time-s", "0.001")
    assert code == 0
    data = _strict_json(out.out)
    assert data["status"] == "time_budget" and [row["level"] for row in data["levels"]] == [3]
    assert data["critical_mass_parameter"] == data["levels"][0]["critical_mass_parameter"]
    assert data["next_level_seconds"] > 0.0
    assert f"level 4 needs ~{data['next_level_seconds']:.0f} s more" in data["message"]
    assert "grid error not estimated" in data["message"]


def test_stability_of_unloaded_plain_bearing_answers_unstable_in_range(capsys):
    code, out = _run(capsys, "stability", "--bearing-number", "1", "--level", "2", "--duration", "20",
                     "--mass-range", "0.5", "50", "--by", "orbit")
    assert code == 0
    data = _strict_json(out.out)
    assert data["status"] == "unstable_in_range" and data["mass_range"] == [0.5, 50.0]
    assert data["critical_mass_parameter"] is None and data["stable_below"] is None
    assert [t["mass_parameter"] for t in data["trials"]] == [50.0, 0.5]
    # progress on stderr: one bar per orbit naming the stage and the mass, then the message line
    assert "stability range end orbit 1 Mbar 50" in out.err and "orbit 2 Mbar 0.5" in out.err
    assert out.err.splitlines()[-1] == data["message"]
    assert data["message"].startswith("unstable for every mass in range")


def test_stability_time_budget(capsys):
    code, out = _run(capsys, "stability", "--bearing-number", "1", "--level", "2", "--duration", "20",
                     "--max-time-s", "0.05", "--by", "orbit")
    assert code == 0
    data = _strict_json(out.out)
    assert data["status"] == "time_budget" and data["orbits"] == 0
    assert "time budget of 0.05 s reached" in out.err.splitlines()[-1]
    # it says how much more it needs: the two range ends, the bracketing and the bisection to --rel-tol
    assert data["seconds_needed"] > 0.0 and "more orbits to a bracket within 5 %" in data["message"]
