"""Handling and part inputs (issue 17 items 3-4): transfer in air, immersion speed, support, non-transforming
materials, material paths relative to the case file, solid sections and chamfers."""

import shutil
import tomllib
from pathlib import Path

import numpy as np
import pytest

from quenchsim.case import case_from_dict, load_case
from quenchsim.errors import InputError
from quenchsim.geometry import rectangular_ring
from quenchsim.pipeline import run
from quenchsim.thermal import ImmersionHTC

ROOT = Path(__file__).parents[1]
CYLINDER = ROOT / "cases" / "solid_cylinder_still_oil.toml"
STEEL = ROOT / "validation" / "quenchants" / "probe_fit" / "specimen_steel.toml"


def raw() -> dict:
    return tomllib.loads(CYLINDER.read_text())


def test_material_path_is_taken_from_the_case_files_folder(tmp_path, monkeypatch):
    folder = tmp_path / "job"
    folder.mkdir()
    shutil.copy(STEEL, folder / "my_steel.toml")
    data = raw()
    data["material"] = "my_steel.toml"
    (folder / "case.toml").write_text(CYLINDER.read_text().replace(
        'material = "../validation/quenchants/probe_fit/specimen_steel.toml"', 'material = "my_steel.toml"'))
    monkeypatch.chdir(tmp_path)                    # not the case's folder
    case = load_case(folder / "case.toml")
    assert Path(case.material) == (folder / "my_steel.toml").resolve()
    assert case.get("material") == case.material   # the run's case.toml records the resolved path
    with pytest.raises(InputError, match=r"^material = 'missing.toml': no such file"):
        case_from_dict({**data, "material": "missing.toml"}, path=folder / "case.toml")


def test_shipped_example_loads_with_its_relative_material_path():
    case = load_case(CYLINDER)
    assert Path(case.material) == STEEL.resolve()
    assert case.transfer.time_s == 5.0 and case.quench.immersion_speed_mm_s == 100.0
    assert case.quench.bath.support == "hanging" and case.quench.bath.agitation == "still"


@pytest.mark.parametrize("override, message", [
    ({"quench.immersion_speed_mm_s": 0.0}, "quench.immersion_speed_mm_s = 0.0: must be > 0"),
    ({"quench.immersion_speed_mm_s": -50.0}, "quench.immersion_speed_mm_s = -50.0: must be > 0"),
    ({"transfer.time_s": -1.0}, "transfer.time_s = -1.0: must be >= 0"),
    ({"transfer.emissivity": 0.0}, "transfer.emissivity = 0.0: must be > 0"),
    ({"transfer.speed": 1.0}, "transfer.speed = 1.0: unknown key"),
    ({"quench.bath.agitation": "flow", "quench.bath.agitation_m_s": -0.2},
     "quench.bath.agitation_m_s = -0.2: must be >= 0"),
    ({"quench.bath.quenchant": "castor_oil"}, "quench.bath.quenchant = 'castor_oil': unknown"),
    # it said "less than half the wall (12.5 mm)", quoting the whole wall (issue 36)
    ({"geometry.chamfer_mm": 7.0}, "geometry.chamfer_mm = 7.0: must be >= 0 and less than 6.25 mm, half the smaller "
                                   "of the wall (12.5 mm) and the width (100 mm)"),
    # `--mesh-size 1000` ran the whole quench, then failed in the traverses with a traceback (issue 36)
    ({"mesh.size_mm": 1000.0}, "mesh.size_mm = 1000.0: must be > 0 and at most 100 mm, the larger extent of the "
                               "section (radial 12.5 mm, axial 100 mm)"),
    ({"mesh.surface_size_mm": 101.0}, "mesh.surface_size_mm = 101.0: must be > 0 and at most 100 mm"),
])
def test_bad_handling_inputs_are_one_line_errors(override, message):
    with pytest.raises(InputError) as err:
        case_from_dict(raw(), overrides=override, path=CYLINDER)
    assert str(err.value).startswith(message)
    assert "\n" not in str(err.value)


def test_zero_second_air_and_transfer_stages_are_allowed():
    case = case_from_dict(raw(), overrides={"air.time_s": 0.0, "transfer.time_s": 0.0}, path=CYLINDER)
    assert case.air.time_s == 0.0 and case.transfer.time_s == 0.0


def test_transformation_flag_is_checked(tmp_path):
    bad = tmp_path / "steel.toml"
    bad.write_text(STEEL.read_text().replace('transformations = "none"', 'transformations = "never"'))
    with pytest.raises(InputError, match=r"transformations = 'never': must be one of austenite, none"):
        case_from_dict({**raw(), "material": str(bad)}, path=CYLINDER)
    mech = tmp_path / "steel2.toml"
    mech.write_text(STEEL.read_text() + "\n[mechanics]\nsource = \"x\"\n")
    with pytest.raises(InputError, match="thermal only"):
        case_from_dict({**raw(), "material": str(mech)}, path=CYLINDER)


def test_solid_section_takes_chamfers_on_its_od_corners_only():
    solid = rectangular_ring(0.0, 0.025, 0.1, chamfer_m=0.001)
    names = [s.name for s in solid.segments]
    assert names == ["bottom", "chamfer_od_bottom", "od", "chamfer_od_top", "top", "axis"]
    r0, r1, z0, z1 = solid.bounds()
    assert (r0, r1, z0, z1) == pytest.approx((0.0, 0.0125, 0.0, 0.1))
    # the area lost to two 45-deg chamfers of 1 mm legs: 2 x 0.5 mm^2
    plain = rectangular_ring(0.0, 0.025, 0.1)
    assert plain.area_m2() - solid.area_m2() == pytest.approx(1.0e-6, rel=1e-6)


def test_immersion_wets_the_part_bottom_first_and_keeps_the_air_flux_above_the_level():
    class Const:
        def __init__(self, h, ambient):
            self.h, self.ambient_C = h, np.full(3, ambient)

        def __call__(self, T, t):
            return np.full(np.shape(T), self.h)

    z = np.array([0.0, 0.05, 0.1])
    htc = ImmersionHTC(Const(1000.0, 60.0), Const(20.0, 25.0), z, 0.0, 0.1, start_s=5.0)
    T = np.full(3, 800.0)
    assert htc.wetted(5.0).tolist() == [True, False, False]
    assert htc.wetted(5.6).tolist() == [True, True, False]
    assert htc.wetted(6.0).tolist() == [True, True, True]
    h = htc(T, 5.6)
    assert h[:2].tolist() == [1000.0, 1000.0]
    # the point in air loses the air flux 20 (800 - 25) although the solver's ambient is the bath's 60 C
    assert h[2] * (800.0 - 60.0) == pytest.approx(20.0 * (800.0 - 25.0))


def test_non_transforming_cylinder_run_reports_no_hardness(tmp_path):
    """The shipped example, shortened: the summary records the handling and carries no hardness; the transfer
    stage cools the part slowly (air) before the oil does it fast."""
    case = load_case(CYLINDER).with_overrides({"quench.time_s": 30.0, "air.time_s": 0.0})
    result = run(case, tmp_path / "run", progress=False)
    s = result.summary
    assert "hardness" not in s and "phases_final" not in s
    assert s["notes"] == ['the material does not transform (transformations = "none"): no phases, no hardness']
    assert s["quench"]["support"] == "hanging" and s["quench"]["transfer_time_s"] == 5.0
    assert not (tmp_path / "run" / "hardness_traverse.csv").exists()
    t, surface = result.time_s, result.probe_T_C["near_surface"]
    at_transfer_end = float(np.interp(5.0, t, surface))
    assert 800.0 < at_transfer_end < 850.0                          # 5 s of air: some ten kelvin
    air_rate, oil_rate = (850.0 - at_transfer_end) / 5.0, (at_transfer_end - float(np.interp(10.0, t, surface))) / 5.0
    assert oil_rate > 5.0 * air_rate


def test_the_run_table_of_a_solid_steel_bar_shows_its_missing_bore_depth_as_a_dash(tmp_path):
    """A solid section's "bore" HRC58 depth is None in summary.json (its traverse starts on the axis); the
    terminal table printed it with a float format and `quenchsim run` of an SUJ2 round bar ended in a TypeError
    after every result was written."""
    from quenchsim.commands.run import summary_table

    summary = {"case": "SUJ2_round_bar_oil", "condition": "", "status": "ok",
               "solver": {"steps": 241, "wall_time_s": 12.0}, "end_state": {"at_room_temperature": True},
               "probes": {"centre": {"t_to_500C_s": None, "t_to_300C_s": 40.0, "t8_5_s": None}},
               "hardness": {"depth_mm": {"HRC58_bore_mid": None, "HRC58_od_mid": 9.999}, "core_HRC": 64.05}}
    table = summary_table(summary, tmp_path)
    assert "HRC58 depth at mid-width (mm): bore -, od 9.999; core 64.0 HRC" in table   # lengths: 3 decimals
