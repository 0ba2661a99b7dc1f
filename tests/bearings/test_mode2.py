"""Mode II crack toolkit: printed fits, specimen checks, penny-crack SIF, Hertz subsurface stresses against closed
forms, critical crack size scaling, CLI and bad input."""

import json
import math

import numpy as np
import pytest

from quenchsim.bearings import mode2
from quenchsim.cli import main
from quenchsim.errors import InputError


def test_printed_fits_and_specimen_sif():
    # the reference notes' values of the printed polynomials
    assert mode2.F_II(np.array([0.0, 0.2, 0.5])) == pytest.approx([2.130, 0.927, 0.639], abs=6e-4)
    assert mode2.F_I(np.array([0.1, 0.3, 0.6])) == pytest.approx([0.805, 0.816, 1.425], abs=6e-4)
    a, W, t, P, M = 6e-3, 20e-3, 5e-3, 20e3, 30.0
    s = mode2.specimen_state(a, W, t, P, M)
    assert s.delta_K_II == pytest.approx(mode2.F_II(0.3) * P / (W * t) * math.sqrt(a), rel=1e-12)
    assert s.K_I_static == pytest.approx(mode2.F_I(0.3) * 6 * M / (t * W * W) * math.sqrt(a), rel=1e-12)
    assert s.K_I_parasitic == pytest.approx(0.08 * s.delta_K_II, rel=1e-12)   # 0.8 at K_II = 10
    assert s.above_threshold and not s.in_mode_II_range and s.opening_separates_faces   # 11.6 MPa sqrt(m): > 10
    low = mode2.specimen_state(a, W, t, 4e3, M)
    assert low.in_mode_II_range is False and low.above_threshold is False            # 2.3 < 3 MPa sqrt(m)
    with pytest.raises(InputError, match="crack_length_m"):
        mode2.specimen_state(0.03, W, t, P, M)


def test_penny_crack_factors():
    nu = 0.3
    assert mode2.penny_K_II_max(1.0, 1.0, nu) == pytest.approx(4.0 / (math.sqrt(math.pi) * 1.7), rel=1e-12)
    assert mode2.penny_K_III_max(1.0, 1.0, nu) == pytest.approx(0.7 * mode2.penny_K_II_max(1.0, 1.0, nu))
    d = mode2.penny_critical_diameter_m(3e6, 500e6, nu)
    assert mode2.penny_K_II_max(500e6, d / 2, nu) == pytest.approx(3e6, rel=1e-12)


def test_line_contact_stresses_closed_forms():
    x = np.linspace(-3.0, 3.0, 6001)
    st = mode2.line_contact_stresses(x, 0.5, 1.0, 1.0)
    i = int(np.argmax(np.abs(st.tau_zx_Pa)))
    assert abs(st.tau_zx_Pa[i]) == pytest.approx(0.25, abs=1e-6) and abs(x[i]) == pytest.approx(0.866, abs=1e-3)
    assert st.sigma_z_Pa[i] == pytest.approx(-0.433, abs=1e-3)
    assert st.tau_zx_Pa == pytest.approx(-st.tau_zx_Pa[::-1], abs=1e-12)
    z = np.array([0.2, 0.7, 1.5])
    axis = [mode2.line_contact_stresses(np.array([0.0]), zz, 1.0, 1.0).sigma_z_Pa[0] for zz in z]
    assert axis == pytest.approx(-1.0 / np.sqrt(1.0 + z * z), rel=1e-12)   # Johnson eq. 4.47


def test_elliptical_quadrature_closed_forms_and_limits():
    z = np.array([0.3, 1.0])
    axis = [mode2.elliptical_contact_stresses(np.array([0.0]), zz, 1.0, 1.0, 1.0).sigma_z_Pa[0] for zz in z]
    assert axis == pytest.approx(-1.0 / (1.0 + z * z), rel=1e-9)          # circular contact, Johnson eq. 3.44
    x = np.linspace(-2.0, 2.0, 41)
    line = mode2.line_contact_stresses(x, 0.5, 1.0, 1.0)
    long = mode2.elliptical_contact_stresses(x, 0.5, 1.0, 20.0, 1.0)
    assert np.abs(long.tau_zx_Pa - line.tau_zx_Pa).max() < 2e-3
    assert np.abs(long.sigma_z_Pa - line.sigma_z_Pa).max() < 2e-3


def test_critical_crack_scales_as_p_to_minus_two_and_is_bounded_by_the_contact_shape():
    a = mode2.critical_crack(2.5e9, "line")
    b = mode2.critical_crack(5.0e9, "line")
    assert a.critical_diameter_m / b.critical_diameter_m == pytest.approx(4.0, rel=1e-12)
    assert a.shear_range_factor == pytest.approx(0.209, abs=1e-3)          # reference notes' DERIVED 0.209
    c = mode2.critical_crack(2.5e9, "ellipse", 1.0)
    assert c.shear_range_factor == pytest.approx(0.154, abs=1e-3)          # and 0.154 for a circle
    assert a.critical_diameter_m < mode2.critical_crack(2.5e9, "ellipse", 2.0).critical_diameter_m < c.critical_diameter_m
    with pytest.raises(InputError, match="ellipticity"):
        mode2.critical_crack(2.5e9, "ellipse", 0.5)


def test_inclusion_over_critical_is_the_area_equivalent_crack():
    # a penny crack of diameter 2a has area pi a^2 (Murakami's sqrt(area) = sqrt(pi) a): an inclusion of that
    # area is exactly critical; the ratio is linear in the inclusion size and inverse in the critical diameter
    assert mode2.inclusion_over_critical(math.sqrt(math.pi) * 4e-6, 8e-6) == pytest.approx(1.0, rel=1e-14)
    assert mode2.inclusion_over_critical(16e-6, 8e-6) == pytest.approx(2.0 / (math.sqrt(math.pi) / 2.0), rel=1e-14)
    with pytest.raises(InputError, match="sqrt_area_m"):
        mode2.inclusion_over_critical(0.0, 8e-6)


def test_cli_inclusions_against_the_critical_crack(capsys):
    assert main(["bearings", "mode2", "rcf", "--p-max-GPa", "6", "--shape", "circle", "--inclusion-sqrt-area-um",
                 "16", "24", "--json"]) == 0
    crack = json.loads(capsys.readouterr().out)["cracks"][0]
    expected = [s / (math.sqrt(math.pi) / 2.0 * crack["critical_diameter_um"]) for s in (16.0, 24.0)]
    assert crack["inclusion_over_critical"] == pytest.approx(expected, rel=1e-12)
    assert min(crack["inclusion_over_critical"]) > 1.0   # the paper's measured inclusions exceed the critical size


def test_cli(capsys):
    assert main(["bearings", "mode2", "rcf", "--p-max-GPa", "2.5", "6", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert [round(c["critical_diameter_um"], 1) for c in out["cracks"]] == [37.4, 6.5]
    assert main(["bearings", "mode2", "specimen", "--crack-mm", "6", "--width-mm", "20", "--thickness-mm", "5",
                 "--shear-load-range-kN", "10", "--opening-moment-Nm", "30", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["in_mode_II_range"] is True and out["parasitic_below_K_Ith"] is True


@pytest.mark.parametrize("argv, option, allowed", [
    (["rcf", "--p-max-GPa", "-1"], "--p-max-GPa", "in (0, 20] GPa"),
    (["rcf", "--p-max-GPa", "2", "--shape", "ellipse", "--ellipticity", "0.5"], "--ellipticity", "in [1, 20]"),
    (["rcf", "--p-max-GPa", "2", "--shape", "ellipse"], "--ellipticity", "required with --shape ellipse"),
    (["rcf", "--p-max-GPa", "2", "--inclusion-sqrt-area-um", "0"], "--inclusion-sqrt-area-um", "in (0, 10000] um"),
    (["specimen", "--crack-mm", "30", "--width-mm", "20", "--thickness-mm", "5", "--shear-load-range-kN", "1"],
     "--crack-mm", "must be below --width-mm"),
    (["specimen", "--width-mm", "20", "--thickness-mm", "5", "--shear-load-range-kN", "1"], "--crack-mm", "required"),
])
def test_cli_bad_input_is_one_line(argv, option, allowed, capsys):
    assert main(["bearings", "mode2", *argv, "--json"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"quenchsim: error: {option} = ") and allowed in err[0], err
