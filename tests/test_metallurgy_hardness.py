"""Hardness per phase (Maynier), rule of mixtures, HV -> HRC (ASTM E140), and bad kinetics inputs."""

from __future__ import annotations

import copy

import numpy as np
import pytest

from quenchsim.errors import InputError
from quenchsim.materials import load_material
from quenchsim.metallurgy import PhaseState, hardness_HV, hrc_to_hv, hv_to_hrc, initial_state, load_kinetics
from quenchsim.metallurgy.hardness import phase_hardness_HV


def _state(kin, fractions: dict[str, float], rate_C_s: float) -> PhaseState:
    s = initial_state((1,), kin)
    return PhaseState(fractions={p: np.array([fractions.get(p, 0.0)]) for p in s.fractions}, additivity=s.additivity,
                      T_min_C=s.T_min_C, cooling_rate_700_C_s=np.array([rate_C_s]))


def test_maynier_per_phase_closed_form_and_mixture():
    kin = load_kinetics(load_material("SUJ2"), 845.0)
    d, b = kin.dissolved, kin.composition
    logv = np.log10(20.0 * 3600.0)
    hv_m = 127 + 949 * d["C"] + 27 * d["Si"] + 11 * d["Mn"] + 16 * d["Cr"] + 21 * logv
    hv_b = min(-323 + 185 * b["C"] + 330 * b["Si"] + 153 * b["Mn"] + 144 * b["Cr"]
               + (89 + 53 * b["C"] - 55 * b["Si"] - 22 * b["Mn"] - 20 * b["Cr"]) * logv, 645.0)  # bulk, capped
    hv_p = 42 + 223 * b["C"] + 53 * b["Si"] + 30 * b["Mn"] + 7 * b["Cr"] + (10 - 19 * b["Si"] + 8 * b["Cr"]) * logv
    assert phase_hardness_HV(kin, "martensite", np.array([20.0]))[0] == pytest.approx(hv_m, rel=1e-12)
    assert phase_hardness_HV(kin, "bainite", np.array([20.0]))[0] == pytest.approx(hv_b, rel=1e-12)
    assert phase_hardness_HV(kin, "pearlite", np.array([20.0]))[0] == pytest.approx(hv_p, rel=1e-12)
    X = {"martensite": 0.6, "bainite": 0.1, "pearlite": 0.2, "austenite": 0.1}
    mixed = hardness_HV(_state(kin, X, 20.0), kin)[0]
    assert mixed == pytest.approx(0.6 * hv_m + 0.1 * hv_b + 0.2 * hv_p + 0.1 * 300.0, rel=1e-12)


def test_martensite_cap_applies_to_bulk_carbon():
    kin = load_kinetics(load_material("100Cr6_furlan"), 850.0)
    hv = phase_hardness_HV(kin, "martensite", np.array([1.0, 100.0]))
    np.testing.assert_allclose(hv, 900.0)  # Maynier with 1 %C would give ~1200 HV


def test_unknown_rate_uses_zero_log_term():
    kin = load_kinetics(load_material("SUJ3"), 845.0)
    np.testing.assert_allclose(phase_hardness_HV(kin, "pearlite", np.array([np.nan])),
                               phase_hardness_HV(kin, "pearlite", np.array([1.0 / 3600.0])))


def test_hv_to_hrc_table_points_interpolation_and_range():
    np.testing.assert_allclose(hv_to_hrc(np.array([940.0, 800.0, 653.0, 513.0, 238.0])), [68, 64, 58, 50, 20])
    assert hv_to_hrc(np.array([816.0]))[0] == pytest.approx(64.5)
    assert np.all(np.isnan(hv_to_hrc(np.array([200.0, 237.9, 941.0]))))
    hv = np.linspace(240.0, 935.0, 50)
    np.testing.assert_allclose(hrc_to_hv(hv_to_hrc(hv)), hv, rtol=1e-12)


def _broken(edit) -> dict:
    material = copy.deepcopy(load_material("SUJ3"))
    edit(material)
    return material


@pytest.mark.parametrize("edit, field", [
    (lambda m: m["kinetics"]["martensite"].pop("alpha_per_K"), "SUJ3.kinetics.martensite.alpha_per_K"),
    (lambda m: m["kinetics"]["martensite"].update(alpha_per_K=-0.01), "SUJ3.kinetics.martensite.alpha_per_K"),
    (lambda m: m["kinetics"]["martensite"].update(Ms_formula={"const": 561, "Xx": 3}), "SUJ3.kinetics.martensite.Ms_formula.Xx"),
    (lambda m: m["kinetics"]["pearlite"].update(model="avrami"), "SUJ3.kinetics.pearlite.model"),
    (lambda m: m["kinetics"]["pearlite"].pop("source"), "SUJ3.kinetics.pearlite.source"),
    (lambda m: m["kinetics"]["bainite"].update(n_per_K=0.05), "SUJ3.kinetics.bainite.n_per_K"),
    (lambda m: m["kinetics"]["pearlite"].update(Q_J_mol="high"), "SUJ3.kinetics.pearlite.Q_J_mol"),
    (lambda m: m["kinetics"]["bainite"].update(T_ref_C=500.0), "SUJ3.kinetics.bainite.T_ref_C"),
    (lambda m: m["kinetics"]["bainite"].update(n_nodes_T_C=[240, 440], n_nodes=[3, 2]), "SUJ3.kinetics.bainite.n"),
    (lambda m: [m["kinetics"]["bainite"].pop(k) for k in ("n", "n_per_K")]
     and m["kinetics"]["bainite"].update(n_nodes_T_C=[440, 240], n_nodes=[3, 2]), "SUJ3.kinetics.bainite.n_nodes_T_C"),
    (lambda m: [m["kinetics"]["bainite"].pop(k) for k in ("n", "n_per_K")]
     and m["kinetics"]["bainite"].update(n_nodes_T_C=[240, 440], n_nodes=[3, 0]), "SUJ3.kinetics.bainite.n_nodes"),
    (lambda m: m["kinetics"]["pearlite"].pop("tau_ref_s"), "SUJ3.kinetics.pearlite.tau_ref_s"),
    (lambda m: m.pop("kinetics"), "SUJ3.kinetics"),
    (lambda m: m["austenitisation"]["dissolved_wt"].update(C=[0.5, 1.5]), "SUJ3.austenitisation.dissolved_wt.C"),
    (lambda m: m["composition"].update(C=-1.0), "SUJ3.composition.C"),
    (lambda m: m["hardness"].pop("austenite"), "SUJ3.hardness.austenite"),
    (lambda m: m["hardness"]["martensite"].update(composition="matrix"), "SUJ3.hardness.martensite.composition"),
])
def test_bad_kinetics_fields_are_named(edit, field):
    with pytest.raises(InputError) as err:
        load_kinetics(_broken(edit), 845.0)
    assert err.value.field == field
    assert str(err.value).startswith(field)


def test_li1998_model_needs_a_grain_size():
    material = copy.deepcopy(load_material("SUJ3_li1998"))
    material["austenitisation"].pop("grain_size_ASTM")
    with pytest.raises(InputError) as err:
        load_kinetics(material, 845.0)
    assert err.value.field == "SUJ3_li1998.austenitisation.grain_size_ASTM"


def test_bad_austenitising_temperature_and_unknown_material():
    with pytest.raises(InputError) as err:
        load_kinetics(load_material("SUJ3"), 950.0)
    assert err.value.field == "T_aust_C"
    with pytest.raises(InputError) as err:
        load_material("SUJ99")
    assert err.value.field == "material"
