"""The steel data files: sources present, printed reference values, standard composition ranges."""

from __future__ import annotations

import numpy as np
import pytest

from quenchsim.materials import PHASES, load_material, thermal_properties
from quenchsim.metallurgy import load_kinetics

STEELS = ("SUJ2", "SUJ3", "100Cr6_furlan")
# JIS G4805 ranges (wt %), docs/reference/quench_cases.md
JIS = {"SUJ2": {"C": (0.95, 1.10), "Si": (0.15, 0.35), "Mn": (0.0, 0.50), "Cr": (1.30, 1.60)},
       "SUJ3": {"C": (0.95, 1.10), "Si": (0.40, 0.70), "Mn": (0.90, 1.15), "Cr": (0.90, 1.20)}}


@pytest.mark.parametrize("name", STEELS)
def test_every_data_table_has_a_source(name):
    m = load_material(name)
    assert m["composition"]["source"] and m["austenitisation"]["source"] and m["kinetics"]["source"]
    for section in ("thermal", "latent_heat"):
        for key, spec in m[section].items():
            assert isinstance(spec, dict) and spec.get("source"), f"{name}.{section}.{key} has no source"
    for sub in ("pearlite", "bainite", "martensite"):
        if sub in m["kinetics"]:
            assert m["kinetics"][sub]["source"]
    for phase in PHASES:
        assert m["hardness"][phase]["source"]


@pytest.mark.parametrize("name", STEELS)
def test_thermal_tables_parse_and_are_physical(name):
    """Within each phase's own range: austenite 20-900 C, ferritic products up to 700 C (below Ae1),
    latent heats of bainite and martensite up to 600 C (above the bainite start)."""
    tp = thermal_properties(load_material(name))
    for phase in PHASES:
        T = np.linspace(20.0, 900.0 if phase == "austenite" else 700.0, 45)
        X = {p: np.full_like(T, 1.0 if p == phase else 0.0) for p in PHASES}
        k = tp.conductivity_W_mK(T, X)
        c = tp.specific_heat_J_kgK(T, X)
        assert np.all((k > 10.0) & (k < 60.0)) and np.all((c > 300.0) & (c < 1000.0))
    T = np.linspace(20.0, 600.0, 30)
    for phase in ("bainite", "martensite"):
        L = tp.latent_heat_J_kg[phase](T)
        assert np.all((L > 5e4) & (L < 2.5e5))


def test_suj3_printed_reference_values():
    tp = thermal_properties(load_material("SUJ3"))
    np.testing.assert_allclose(tp.conductivity_W_mK(np.array([30.0, 300.0, 450.0, 600.0, 800.0])),
                               [25.2, 31.5, 31.5, 31.5, 25.2])
    assert tp.specific_heat_J_kgK(np.array([500.0]))[0] == 419.0
    assert tp.density_kg_m3(np.array([20.0]))[0] == 7850.0


@pytest.mark.parametrize("name", ["SUJ2", "SUJ3"])
def test_compositions_inside_jis_ranges(name):
    comp = load_material(name)["composition"]
    for el, (lo, hi) in JIS[name].items():
        assert lo <= comp[el] <= hi, (name, el)


def test_peer_100cr6_numbers_as_published():
    m = load_material("100Cr6_furlan")
    tp = thermal_properties(m)
    X = {p: np.array([1.0 if p == "martensite" else 0.0]) for p in PHASES}
    T = np.array([500.0])
    assert tp.specific_heat_J_kgK(T, X)[0] == pytest.approx(336.51 + 0.4875 * 500 - 6.16e-4 * 500**2 + 1.62e-6 * 500**3)
    assert tp.conductivity_W_mK(T, X)[0] == pytest.approx(39.3 + 0.024 * 500 - 6.43e-5 * 500**2)
    # latent heats as published per volume: 640 MJ/m3 (A->M), 1560 - 1.5 T MJ/m3 (A->B)
    assert tp.latent_heat_J_kg["martensite"](T)[0] * 7850 == pytest.approx(640e6, rel=1e-4)
    assert tp.latent_heat_J_kg["bainite"](T)[0] * 7850 == pytest.approx((1560 - 1.5 * 500) * 1e6, rel=1e-4)
    kin = load_kinetics(m, 850.0)
    assert set(kin.reactions) == {"bainite"}
    assert kin.reactions["bainite"].T_upper_C == pytest.approx(681.51 - 29618 * 0.01)
