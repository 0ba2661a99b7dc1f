"""CCT / TTT / Jominy data files: what they hold, and one-line errors naming the file, the point and the rule."""

from __future__ import annotations

import numpy as np
import pytest
import tomli_w

from quenchsim.errors import InputError
from quenchsim.fitting.diagram_data import load_diagram_data

BASE = {"name": "test", "material": "SUJ2", "T_aust_C": 850, "source": "test"}
CCT = {"cooling_rate_C_s": 5.0, "start_C": {"pearlite": 650.0}, "finish_C": {"pearlite": 600.0},
       "temperature_uncertainty_K": 10.0, "source": "catalogue p. 3", "kind": "read"}
TTT = {"phase": "bainite", "T_C": [300.0, 350.0], "t_start_s": [48.0, 13.0], "t_finish_s": [361.0, 134.0],
       "time_uncertainty_factor": 1.15, "source": "atlas", "kind": "read"}
JOMINY = {"distance_mm": [1.5, 10.0], "hardness_HRC": [65.0, 50.0], "hardness_uncertainty_HV": 30.0,
          "source": "mill certificate", "kind": "printed"}


def _load(tmp_path, **entries):
    path = tmp_path / "steel_data.toml"
    path.write_text(tomli_w.dumps({**BASE, **entries}))
    return load_diagram_data(path)


def test_good_file_is_read(tmp_path):
    newton = {"t8_5_s": 30.0, "fractions": {"pearlite": 0.2, "martensite": 0.7}, "fraction_uncertainty": 0.05,
              "hardness_HV": 700.0, "hardness_uncertainty_HV": 30.0, "source": "catalogue", "kind": "printed"}
    data = _load(tmp_path, cct=[CCT, newton], ttt=[TTT], jominy=[JOMINY])
    assert len(data.cct) == 2 and len(data.ttt) == 2 and len(data.jominy) == 2
    linear, curve = data.cct[0].curve, data.cct[1].curve
    assert linear.temperature_C(np.array([10.0]))[0] == pytest.approx(800.0)
    # Newtonian curve labelled by t8/5: 800 -> 500 C takes exactly 30 s
    t800, t500 = (curve.theta_s * np.log((850.0 - 20.0) / (T - 20.0)) for T in (800.0, 500.0))
    assert t500 - t800 == pytest.approx(30.0) and curve.t8_5_s() == pytest.approx(30.0)
    assert data.jominy[0].hardness_HV > data.jominy[1].hardness_HV > 500.0
    assert data.ttt[1].source == "atlas" and data.ttt[1].kind == "read"


@pytest.mark.parametrize("entries, match", [
    ({"cct": [{**CCT, "finish_C": {"pearlite": 660.0}}]}, r"steel_data\.toml: cct\[0\] \(5 C/s\)\.finish_C\.pearlite = 660\.0: finish before start"),
    ({"ttt": [{**TTT, "t_finish_s": [361.0, 10.0]}]}, r"steel_data\.toml: ttt\[0\] point 1 \(T_C = 350\)\.t_finish_s = 10\.0: finish before start"),
    ({"cct": [{**CCT, "cooling_rate_C_s": -2.0}]}, r"steel_data\.toml: cct\[0\]\.cooling_rate_C_s = -2\.0: a cooling curve must cool"),
    ({"cct": [{**CCT, "T_end_C": 900.0}]}, r"steel_data\.toml: cct\[0\]\.T_end_C = 900\.0: a cooling curve must cool"),
    ({"cct": [{**CCT, "hardness_HV": 1200.0, "hardness_uncertainty_HV": 20.0}]}, r"cct\[0\] \(5 C/s\)\.hardness = 1200\.0: hardness must lie within 100-1000 HV"),
    ({"jominy": [{**JOMINY, "hardness_HRC": [65.0, 10.0]}]}, r"jominy\[0\]\.hardness_HRC\[1\] = 10\.0: HRC must lie within 20-68"),
    ({"jominy": [{**JOMINY, "distance_mm": [1.5, 120.0]}]}, r"jominy\[0\] point 1 \(distance_mm = 120\)\.distance_mm = 120\.0: Jominy distance beyond the bar"),
    ({"cct": [{**CCT, "start_C": {"perlite": 650.0}}]}, r"cct\[0\] \(5 C/s\)\.start_C\.perlite = 650\.0: unknown phase name"),
    ({"ttt": [{**TTT, "phase": "troostite"}]}, r"ttt\[0\]\.phase = 'troostite': unknown phase name"),
    ({"cct": [{**CCT, "kind": "guessed"}]}, r"cct\[0\]\.kind = 'guessed': must be one of \('printed', 'read'\)"),
    ({"cct": [{**CCT, "source": ""}]}, r"cct\[0\]\.source = '': is required"),
])
def test_bad_data_one_line_error(tmp_path, entries, match):
    with pytest.raises(InputError, match=match) as err:
        _load(tmp_path, **entries)
    assert "\n" not in str(err.value)


def test_fit_table_checks(tmp_path):
    fit = {"pearlite": {"T_ref_C": 650, "free": ["tau_ref_s", "Q"], "T_upper_C": {"value": 724, "source": "s"}}}
    with pytest.raises(InputError, match=r"fit\.pearlite\.tau_ref_s = None: is required"):
        _load(tmp_path, cct=[CCT], fit=fit)
    values = {k: {"value": v, "source": "s"} for k, v in
              (("tau_ref_s", 1.0), ("undercooling_exponent", 3.0), ("Q_J_mol", 1e5), ("n", 2.0))}
    with pytest.raises(InputError, match=r"fit\.pearlite\.free = \['tau_ref_s', 'Q'\]: must list parameters among"):
        _load(tmp_path, cct=[CCT], fit={"pearlite": {**fit["pearlite"], **values}})
    fixed_without_source = {**fit["pearlite"], **values, "free": [], "n": 2.0}
    with pytest.raises(InputError, match=r"fit\.pearlite\.n = 2\.0: a parameter the fit holds fixed needs"):
        _load(tmp_path, cct=[CCT], fit={"pearlite": fixed_without_source})
