"""Every numeric option of `quenchsim bearings VERB` outside its physical range: a one-line error naming the
option, the value and the allowed range, exit code 2, before any work (no output file, no traceback)."""

import pytest

from quenchsim.bearings.commands import VERBS
from quenchsim.cli import main

GREASE = ["grease-life", "--grease", "urea", "--base-oil", "mineral", "--bearing", "6204", "--speed", "1000",
          "--temperature", "100", "--load-ratio", "0.03"]
KINEMATICS = ["kinematics", "--bearing", "6204", "--inner-rpm", "1800"]
EXPLICIT = ["kinematics", "--pitch-diameter-mm", "40", "--ball-diameter-mm", "8", "--balls", "9", "--inner-rpm", "1800"]
POINT = ["hertz", "point", "--load", "500", "--rx1-mm", "4", "--ry1-mm", "4", "--rx2-mm", "12.8", "--ry2-mm", "-4.1"]
LINE = ["hertz", "line", "--load", "500", "--length-mm", "20", "--r1-mm", "5", "--r2-mm", "89"]
RACE = ["hertz", "ball-race", "--bearing", "6204", "--inner-groove-ratio", "0.515", "--outer-groove-ratio", "0.525"]
STATIC = ["gas-journal", "static", "--bearing-number", "1", "--eccentricity", "0.5"]
ORBIT = ["gas-journal", "orbit", "--bearing-number", "1", "--load", "0.1", "--mass", "1"]
STABILITY = ["gas-journal", "stability", "--bearing-number", "1"]
BIG_END = ["big-end", "cases/big_end_two_stroke.toml"]
FREE_RUN = ["free-run", "no_such_pulses.csv"]
LINEAR = ["gas-journal", "linear", "--bearing-number", "1", "--eccentricity", "0.4"]
DOJ = ["doj", "--case", "3"]


def with_option(base, option, value):
    argv = list(base)
    if option in argv:
        argv[argv.index(option) + 1] = value
    else:
        argv += [option, value]
    return argv


@pytest.mark.parametrize("base, option, value, allowed", [
    (GREASE, "--temperature", "1000", "in [-60, 250] C"),
    (GREASE, "--temperature", "-273", "in [-60, 250] C"),
    (GREASE, "--speed", "-1000", "in (0, 1e+06] rpm"),
    (GREASE, "--speed", "0", "in (0, 1e+06] rpm"),
    (GREASE, "--load-ratio", "1.5", "in [0, 1)"),
    (GREASE, "--weibull-slope", "-1", "in (0, 100]"),
    (GREASE[:5] + ["--dm", "-30"] + GREASE[7:], "--dm", "-30", "in (0, 10000] mm"),
    (KINEMATICS, "--inner-rpm", "1e12", "in [-1e+06, 1e+06] rpm"),
    (KINEMATICS, "--outer-rpm", "nan", "in [-1e+06, 1e+06] rpm"),
    (KINEMATICS, "--measured-cage-rpm", "inf", "in [-1e+06, 1e+06] rpm"),
    (KINEMATICS, "--contact-angle-deg", "90", "in [0, 90) deg"),
    (EXPLICIT, "--ball-diameter-mm", "0", "in (0, 10000] mm"),
    (EXPLICIT, "--pitch-diameter-mm", "-40", "in (0, 10000] mm"),
    (EXPLICIT, "--balls", "0", "an integer in [1, 1000]"),
    (EXPLICIT, "--ball-diameter-mm", "48", "must be < --pitch-diameter-mm = 40 mm"),
    (EXPLICIT, "--balls", "30", "must fit on the pitch circle"),
    (POINT, "--load", "-5", ">= 0 N"),
    (POINT, "--rx1-mm", "0", "other than 0"),
    (POINT, "--E1-GPa", "0", "in (0, 1500] GPa"),
    (POINT, "--nu2", "0.7", "in (-1, 0.5]"),
    (LINE, "--length-mm", "0", "in (0, 10000] mm"),
    (RACE, "--inner-groove-ratio", "0.4", "in (0.5, 10]"),
    (STATIC, "--eccentricity", "1", "in [0, 1)"),
    (STATIC, "--eccentricity", "-0.1", "in [0, 1)"),
    (STATIC, "--bearing-number", "-1", "in [0, 1e+06]"),
    (STATIC, "--ld", "0", "in (0, 20]"),
    (STATIC, "--level", "0", "an integer in [1, 10]"),
    (STATIC, "--sor-omega", "2", "in (0, 2)"),
    (STATIC + ["--grooves", "12"], "--groove-angle", "95", "in (0, 90) deg"),
    (STATIC + ["--grooves", "12"], "--groove-width-ratio", "1", "in (0, 1)"),
    (STATIC, "--grooves", "0", "an integer in [1, 1000]"),
    (ORBIT, "--mass", "-1", "> 0"),
    (ORBIT, "--duration", "0", "in (0, 1e+06]"),
    (STABILITY, "--start-eccentricity", "1", "in (0, 1)"),
    (STABILITY, "--mass-range", "0", "> 0"),
    (STABILITY, "--max-iterations", "0", "an integer in [1, 10000]"),
    (LINEAR, "--whirl-ratio", "0", "in (0, 10]"),
    (DOJ, "--angle-deg", "30", "in [0, 25] deg"),
    (DOJ, "--window-clearance-mm", "-0.5", "in [-0.1, 1] mm"),
    (BIG_END, "--revolutions", "-1", "in (0, 1e+06]"),
    (BIG_END, "--clearance-set", "0", "an integer in [1, 1000]"),
    (FREE_RUN, "--inertia", "-1", "in (0, 1e+06] kg m^2"),
    (FREE_RUN + ["--inertia", "1"], "--alpha-percent", "100", "in (0, 100) %"),
    (FREE_RUN + ["--inertia", "1"], "--clock-hz", "0", "in (0, 1e+12] Hz"),
])
def test_an_option_outside_its_physical_range_is_one_line_before_any_work(base, option, value, allowed, capsys,
                                                                          tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "cases").symlink_to(__import__("pathlib").Path(__file__).resolve().parents[2] / "cases")
    argv = with_option(base, option, value)
    if option == "--mass-range":
        argv = argv[:-1] + ["0", "5"]
    assert main(["bearings", *argv, "--json"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"quenchsim: error: {option} = "), err
    assert allowed in err[0], err[0]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cases"]      # nothing written


def test_every_verb_declares_the_ranges_of_its_numeric_options():
    import argparse
    import importlib

    for verb, module_name in VERBS.items():
        module = importlib.import_module(module_name)
        parser = argparse.ArgumentParser()
        module.configure(parser)
        numeric = {a.dest for a in parser._actions if a.type in (int, float)}
        assert numeric <= set(getattr(module, "RANGES", {})), (verb, numeric - set(getattr(module, "RANGES", {})))
