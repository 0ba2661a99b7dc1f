"""Hot-austenite flow laws (dev/austenite_flow.py, the maintainers' tool that computes the steels' austenite yield
rows) against their printed forms, and the shipped austenite yield rows against the data file they are computed
from."""

from __future__ import annotations

import importlib.util
import math
import sys
from pathlib import Path

import numpy as np
import pytest

from quenchsim.materials import load_material

_TOOL = Path(__file__).resolve().parents[1] / "dev" / "austenite_flow.py"
_spec = importlib.util.spec_from_file_location("dev_austenite_flow", _TOOL)
_flow = importlib.util.module_from_spec(_spec)
sys.modules[_spec.name] = _flow   # its dataclasses look their module up
_spec.loader.exec_module(_flow)
R_J_molK, austenite_yield_table, kozlowski_III_stress_MPa = (_flow.R_J_molK, _flow.austenite_yield_table,
                                                            _flow.kozlowski_III_stress_MPa)
load_data, zener_hollomon_peak_stress_MPa = _flow.load_data, _flow.zener_hollomon_peak_stress_MPa

HUO = dict(A_1_s=1.0e18, alpha_1_MPa=0.0083, n=5.78, Q_J_mol=481363.0)


@pytest.mark.parametrize("T_C, rate", [(950.0, 0.01), (1100.0, 1.0), (850.0, 1e-3), (1200.0, 10.0)])
def test_zener_hollomon_inverse_returns_the_printed_law(T_C, rate):
    """The stress it returns, put back into HUO2013's printed law 1e18 sinh(0.0083 s)^5.78 exp(-481363/RT),
    gives the strain rate it was asked for."""
    s = zener_hollomon_peak_stress_MPa(T_C, rate, **HUO)
    back = 1.0e18 * math.sinh(0.0083 * s) ** 5.78 * math.exp(-481363.0 / (R_J_molK * (T_C + 273.15)))
    assert back == pytest.approx(rate, rel=1e-9)


def test_zener_hollomon_power_law_limit():
    """At low Z the sinh law is the power law rate = A (alpha s)^n exp(-Q/RT): s = (Z/A)^(1/n) / alpha."""
    T_C, rate = 1200.0, 1e-9
    z = rate * math.exp(HUO["Q_J_mol"] / (R_J_molK * (T_C + 273.15)))
    closed = (z / HUO["A_1_s"]) ** (1.0 / HUO["n"]) / HUO["alpha_1_MPa"]
    assert zener_hollomon_peak_stress_MPa(T_C, rate, **HUO) == pytest.approx(closed, rel=1e-3)


def test_kozlowski_returns_the_rate_it_was_given():
    """Model III inverted: the stress at (strain, rate) put back into rate = f_C (s - f1 e^f2)^f3 exp(-Q/T)."""
    T_C, eps, rate, C = 1000.0, 0.01, 1e-3, 0.4
    s = kozlowski_III_stress_MPa(T_C, eps, rate, C)
    T = T_C + 273.15
    f1, f2, f3 = 130.5 - 5.128e-3 * T, -0.6289 + 1.114e-3 * T, 8.132 - 1.54e-3 * T
    fc = 46550 + 71400 * C + 12000 * C ** 2
    assert fc * (s - f1 * eps ** f2) ** f3 * math.exp(-44465.0 / T) == pytest.approx(rate, rel=1e-9)


def test_kozlowski_softens_with_temperature_and_carbon_and_hardens_with_rate():
    base = kozlowski_III_stress_MPa(850.0, 0.002, 1e-3, 0.65)
    assert kozlowski_III_stress_MPa(900.0, 0.002, 1e-3, 0.65) < base
    assert kozlowski_III_stress_MPa(850.0, 0.002, 1e-3, 1.0) < base      # f_C grows with carbon
    assert kozlowski_III_stress_MPa(850.0, 0.002, 1e-2, 0.65) > base
    assert kozlowski_III_stress_MPa(850.0, 0.01, 1e-3, 0.65) > base      # strain hardening


def test_yield_table_is_hot_austenite_of_tens_of_MPa():
    """The point of the data: at 800-850 C and quench rates hot austenite holds a few tens of MPa, not the
    178 MPa of the former TRIP back-derivation."""
    table = austenite_yield_table(load_data())
    hot = dict(zip(table.T_C, np.array(table.yield_Pa) / 1e6))
    assert 20.0 < hot[850.0] < 100.0 and 20.0 < hot[800.0] < 100.0
    assert np.all(np.diff(table.yield_Pa) < 0.0)                          # softens monotonically with T
    assert table.range_factor >= 2.0


@pytest.mark.parametrize("steel", ["SUJ3", "SUJ2"])
def test_shipped_austenite_row_is_the_data_files_table(steel):
    """materials/<steel>.mechanics.toml's austenite yield row equals the table computed from
    materials/data/austenite_flow.toml (so neither can drift), covering 20-900 C."""
    row = load_material(steel)["mechanics"]["plastic"]["yield_Pa"]["per_phase"]["austenite"]
    table = austenite_yield_table(load_data())
    assert row["T_C"] == pytest.approx(table.T_C)
    assert row["value"] == pytest.approx(table.yield_Pa, rel=2e-3)
    assert row["range_factor"] == pytest.approx(table.range_factor)
    assert row["T_C"][0] <= 20.0 and row["T_C"][-1] >= 900.0
    assert "Greenwood" not in row["source"].split("Replaces")[0]


@pytest.mark.parametrize("steel", ["SUJ2", "SUJ3"])
def test_the_metastable_factor_scales_only_the_assumed_part_of_the_austenite_row(steel):
    """[plastic] metastable_austenite_yield_factor: nominal 1 in the shipped steels; a factor f multiplies the
    yield points below 750 C (the assumed, metastable part) and leaves the hot-test points, in the parsed model."""
    import copy

    from quenchsim.calibration.inputs import free_input
    from quenchsim.mechanics.model import METASTABLE_KEY, load_mechanics

    material = load_material(steel)
    entry = material["mechanics"]["plastic"][METASTABLE_KEY]
    assert entry["value"] == 1.0 and entry["below_T_C"] == 750.0
    assert free_input(f"material.{steel}.mechanics.plastic.{METASTABLE_KEY}").factor_bounds == pytest.approx((1 / 3, 3.0))
    row = material["mechanics"]["plastic"]["yield_Pa"]["per_phase"]["austenite"]
    T = np.array(row["T_C"])
    nominal = load_mechanics(material).yield_Pa.for_phase("austenite")(T)
    changed = copy.deepcopy(material)
    changed["mechanics"]["plastic"][METASTABLE_KEY]["value"] = 2.5
    scaled = load_mechanics(changed).yield_Pa.for_phase("austenite")(T)
    np.testing.assert_allclose(scaled, np.where(T < 750.0, 2.5, 1.0) * nominal, rtol=1e-12)
    np.testing.assert_allclose(nominal, row["value"], rtol=1e-12)
