"""Plausibility of the CCT / TTT data a user brings to `quenchsim material fit` (issue 36, item 2): a unit slip -- a
time in ms or minutes, a rate in C/min, a temperature in K or F -- or a contradiction is a one-line error naming the
file, the point, its value and what is allowed, exit code 2, before any file is written."""

from __future__ import annotations

import pytest
import tomli_w

from quenchsim.cli import main
from test_fitting_data import BASE, CCT, TTT

NEWTON = {"fractions": {"pearlite": 0.3}, "fraction_uncertainty": 0.05, "source": "catalogue", "kind": "read"}


@pytest.mark.parametrize("entries, field, allowed", [
    ({"T_aust_C": 1123.15 + 273.15}, "T_aust_C = 1396.3", "within 700-1200 C"),           # in K
    ({"T_aust_C": 1562}, "T_aust_C = 1562", "within 700-1200 C"),                          # in F
    ({"cct": [{**CCT, "cooling_rate_C_s": 3000.0}]}, "cct[0].cooling_rate_C_s = 3000.0", "within 0.001-1000 C/s"),
    ({"cct": [{**CCT, "cooling_rate_C_s": 1e-4}]}, "cct[0].cooling_rate_C_s = 0.0001", "within 0.001-1000 C/s"),
    ({"cct": [{**NEWTON, "t8_5_s": 3e5}]}, "cct[0].t8_5_s = 300000.0",
     "within 0.1-100000 s"),
    ({"cct": [{**NEWTON, "lambda": 0.0005}]}, "cct[0].lambda = 0.0005",
     "within 0.001-1000"),
    ({"cct": [{**CCT, "T_start_C": 950.0}]}, "cct[0].T_start_C = 950.0", "at or below the austenitising temperature"),
    ({"cct": [{**CCT, "T_end_C": -300.0}]}, "cct[0].T_end_C = -300.0", "must be >= -200 C"),
    ({"cct": [{**CCT, "fractions": {"pearlite": 0.0}, "fraction_uncertainty": 0.02}]},
     "cct[0] (5 C/s).fractions.pearlite = 0.0", "contradicts the pearlite line"),
    ({"ttt": [{**TTT, "T_C": [300.0, 900.0]}]}, "ttt[0] point 1 (T_C = 900).T_C = 900.0", "austenitising temperature"),
    ({"ttt": [{**TTT, "T_C": [300.0, 623.15 - 1000]}]}, "ttt[0] point 1 (T_C = -376.85).T_C", "-200 C"),
    ({"ttt": [{**TTT, "t_start_s": [48.0, 1e6], "t_finish_s": [361.0, 2e6]}]},
     "ttt[0] point 1 (T_C = 350).t_start_s = 1000000.0", "within 0.01-100000 s"),
    ({"ttt": [{**TTT, "t_start_s": [0.001, 13.0]}]}, "ttt[0] point 0 (T_C = 300).t_start_s = 0.001",
     "within 0.01-100000 s"),
    ({"ttt": [{**TTT, "t_finish_s": [361.0, 5e6]}]}, "ttt[0] point 1 (T_C = 350).t_finish_s = 5000000.0",
     "<= 1e+06 s"),
])
def test_implausible_data_is_refused_before_the_fit_writes(tmp_path, capsys, entries, field, allowed):
    data = tmp_path / "steel_data.toml"
    data.write_text(tomli_w.dumps({**BASE, "cct": [CCT], **entries}))
    out = tmp_path / "materials" / "MINE.toml"
    assert main(["material", "fit", str(data), "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith(f"quenchsim: error: steel_data.toml: {field}"), err
    assert "\n" not in err and allowed in err
    assert not out.exists() and not out.parent.exists()
