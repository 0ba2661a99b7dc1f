"""`quenchsim material fit` / `quenchsim ttt` / `cct --overlay` from the command line, and the Jominy bar."""

from __future__ import annotations

import json
import subprocess
import sys
import tomllib
from pathlib import Path

import numpy as np
import pytest
import tomli_w

from quenchsim.fitting import kinetics as fk
from quenchsim.fitting.diagram_data import load_diagram_data
from quenchsim.fitting.jominy import air_h_W_m2K, cooling_histories, load_bar
from quenchsim.materials import load_material
from quenchsim.metallurgy import hv_to_hrc, load_kinetics

ROOT = Path(__file__).resolve().parents[1]


def _cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "quenchsim.cli", *args], cwd=ROOT, capture_output=True, text=True,
                          timeout=600)


def _ttt_file(tmp_path: Path, **changes) -> Path:
    kin = load_kinetics(load_material("SUJ2"), 850.0)
    bainite = kin.reactions["bainite"]
    T = np.array([300.0, 350.0, 400.0])
    entry = {"phase": "bainite", "T_C": T.tolist(), "t_start_s": bainite.isothermal_time_s(0.01, T).tolist(),
             "t_finish_s": bainite.isothermal_time_s(0.99, T).tolist(), "time_uncertainty_factor": 1.2,
             "source": "SUJ2 model times", "kind": "read", **changes}
    spec = {"T_ref_C": 350, "free": ["tau_ref_s"], "T_upper_C": {"value": bainite.T_upper_C, "source": "SUJ2"}}
    for k in ("undercooling_exponent", "Q_J_mol"):
        spec[k] = {"value": bainite.params[k], "source": "SUJ2 file"}
    for k in ("n_nodes_T_C", "n_nodes"):  # SUJ2's bainite n(T) is piecewise linear
        spec[k] = {"value": bainite.params[k].tolist(), "source": "SUJ2 file"}
    spec["tau_ref_s"] = {"value": 10.0, "source": "start"}
    path = tmp_path / "bainite_ttt.toml"
    path.write_text(tomli_w.dumps({"name": "t", "material": "SUJ2", "T_aust_C": 850, "source": "test", "ttt": [entry],
                                   "fit": {"bainite": spec}}))
    return path


def test_material_fit_cli_writes_file_and_prints_residuals(tmp_path):
    out = tmp_path / "materials" / "MY_STEEL.toml"
    r = _cli("material", "fit", str(_ttt_file(tmp_path)), "--out", str(out), "--plots", str(tmp_path / "plots"))
    assert r.returncode == 0, r.stderr
    assert "bainite start time" in r.stdout and "tau_ref_s" in r.stdout
    written = tomllib.loads(out.read_text())   # the user's steel, named after the file, not the base "SUJ2"
    assert written["name"] == "MY_STEEL" and "SUJ2" in written["description"] and "bainite_ttt.toml" in written["description"]
    assert "note: no MY_STEEL.mechanics.toml beside it" in r.stdout
    fitted = tomllib.loads(out.read_text())["kinetics"]["bainite"]["tau_ref_s"]["value"]
    shipped = load_material("SUJ2")["kinetics"]["bainite"]["tau_ref_s"]["value"]
    assert fitted == pytest.approx(shipped, rel=1e-3)   # the SUJ2 model's own times give back its tau_ref
    assert (tmp_path / "plots" / "MY_STEEL_cct.png").stat().st_size > 1000
    assert (tmp_path / "plots" / "MY_STEEL_ttt.png").stat().st_size > 1000


def test_material_fit_cli_bad_data_exit_2(tmp_path):
    r = _cli("material", "fit", str(_ttt_file(tmp_path, phase="sorbite")), "--out", str(tmp_path / "x.toml"))
    assert r.returncode == 2
    assert r.stderr.strip().count("\n") == 0 and "bainite_ttt.toml: ttt[0].phase = 'sorbite': unknown phase name" in r.stderr


def test_ttt_cli_json_matches_the_kinetics(tmp_path):
    r = _cli("ttt", "SUJ2", "--T-aust", "850", "--temperatures", "300", "400", "--json", "--png", str(tmp_path / "t.png"))
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    bainite = load_kinetics(load_material("SUJ2"), 850.0).reactions["bainite"]
    assert out["bainite_start_s"] == pytest.approx(bainite.isothermal_time_s(0.01, np.array([300.0, 400.0])).tolist())
    assert (tmp_path / "t.png").stat().st_size > 1000
    r = _cli("cct", "SUJ2", "--T-aust", "850", "--rates", "10", "--png", str(tmp_path / "c.png"), "--overlay")
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "c.png").stat().st_size > 1000


def test_jominy_bar_cools_from_the_quenched_end():
    """Cooling time from T_aust to 700 C grows monotonically with the distance from the quenched end; air alone
    (far end of a 100 mm bar, radiation + convection) is two orders slower than the quenched end."""
    material = load_material("SUJ2")
    kin = load_kinetics(material, 850.0)
    d = np.array([1.5, 5.0, 10.0, 20.0, 40.0, 80.0])
    t, T = cooling_histories(material, kin, d, end_time_s=300.0)
    t700 = np.array([np.interp(-700.0, -T[:, j], t) for j in range(d.size)])
    assert np.all(np.diff(t700) > 0.0)
    assert t700[-1] / t700[0] > 30.0
    bar = load_bar()
    h800 = air_h_W_m2K(bar, np.array([800.0]))[0]
    # 10 + 0.3 sigma (T^2 + Ta^2)(T + Ta) at 1073.15 K against 293.15 K: 10 + 28.76 W/m2K
    assert h800 == pytest.approx(10.0 + 0.3 * 5.670374e-8 * (1073.15**2 + 293.15**2) * (1073.15 + 293.15), rel=1e-12)
    assert h800 == pytest.approx(38.76, abs=0.01)


@pytest.mark.slow
def test_jominy_fit_recovers_pearlite_time_scale(tmp_path):
    """Jominy hardness generated by the SUJ2 model on the bar is fitted back to its pearlite tau_ref within 2 %."""
    material = load_material("SUJ2")
    kin = load_kinetics(material, 850.0)
    d = np.array([5.0, 8.0, 10.0, 12.0, 15.0, 20.0])
    hist = cooling_histories(material, kin, d)
    _, hv = fk.run_histories(kin, *hist)
    pearlite = kin.reactions["pearlite"]
    spec = {"T_ref_C": pearlite.params["T_ref_C"], "free": ["tau_ref_s"],
            "T_upper_C": {"value": pearlite.T_upper_C, "source": "SUJ2"}, "tau_ref_s": {"value": 30.0, "source": "start"}}
    for k in ("undercooling_exponent", "Q_J_mol", "n"):
        spec[k] = {"value": pearlite.params[k], "source": "SUJ2"}
    jom = {"distance_mm": d.tolist(), "hardness_HV": hv.tolist(), "hardness_uncertainty_HV": 20.0, "source": "model",
           "kind": "printed"}
    path = tmp_path / "jominy.toml"
    path.write_text(tomli_w.dumps({"name": "j", "material": "SUJ2", "T_aust_C": 850, "source": "t", "jominy": [jom],
                                   "fit": {"pearlite": spec}}))
    data = load_diagram_data(path)
    result = fk.fit_kinetics(data, fk.jominy_histories(data))
    assert result.parameters["pearlite"]["tau_ref_s"] == pytest.approx(pearlite.params["tau_ref_s"], rel=0.02)
    assert np.all(np.isfinite(hv_to_hrc(hv[:2])))


def test_material_fit_regenerating_a_steel_in_place_keeps_its_name(tmp_path):
    """A maintainer's re-fit writes over the base steel itself: its curated name and description stay."""
    base = tmp_path / "SUJ2.toml"
    base.write_bytes((Path(__file__).resolve().parents[1] / "materials" / "SUJ2.toml").read_bytes())
    data = _ttt_file(tmp_path)
    spec = tomllib.loads(data.read_text())
    spec["material"] = str(base)
    data.write_text(tomli_w.dumps(spec))
    before = tomllib.loads(base.read_text())
    r = _cli("material", "fit", str(data), "--out", str(base))
    assert r.returncode == 0, r.stderr
    after = tomllib.loads(base.read_text())
    assert (after["name"], after["description"]) == (before["name"], before["description"])


def test_replace_shipped_lets_a_maintainer_past_the_shipped_file_check(tmp_path):
    shipped = Path(__file__).resolve().parents[1] / "materials" / "SUJ2.toml"
    before = shipped.read_bytes()
    r = _cli("material", "fit", str(tmp_path / "missing.toml"), "--out", str(shipped), "--replace-shipped")
    assert r.returncode == 2 and "never overwritten" not in r.stderr and "missing.toml" in r.stderr
    assert shipped.read_bytes() == before
    r = _cli("material", "fit", str(tmp_path / "missing.toml"), "--out", str(shipped))
    assert r.returncode == 2 and "never overwritten" in r.stderr and "--replace-shipped" in r.stderr
