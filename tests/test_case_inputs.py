"""Bad inputs give one-line errors that name the field (case files, geometry, HTC tables, probes)."""

import copy
import re
import tomllib
from pathlib import Path

import numpy as np
import pytest

from quenchsim.case import case_from_dict, load_case
from quenchsim.cli import main
from quenchsim.errors import InputError
from quenchsim.geometry import general_profile, mesh_profile, rectangular_ring, spherical_outer_ring
from quenchsim.thermal import parse_htc_table

CASE_A = Path(__file__).parents[1] / "cases" / "crb_outer_ring.toml"


def raw_case() -> dict:
    return tomllib.loads(CASE_A.read_text())


def test_reference_case_loads_every_condition():
    for cond in ("1", "2", "3"):
        case = load_case(CASE_A, cond)
        assert case.condition == cond
        assert case.get("geometry.inner_diameter_mm") == 218.3
    assert [p["name"] for p in load_case(CASE_A, "1").get("probes")] == ["P1", "P2", "P3", "P4", "P5"]


def test_condition_overrides_are_merged_over_the_base():
    raw = raw_case()
    c1, c2 = case_from_dict(raw, "1"), case_from_dict(raw, "2")
    assert c2.get("quench.bath.od_jet_speed_mm_s") == 2 * c1.get("quench.bath.od_jet_speed_mm_s")
    assert c1.get("quench.time_s") == c2.get("quench.time_s") == raw["quench"]["time_s"]


@pytest.mark.parametrize("condition, message", [("9", "--condition = '9'"), (None, "--condition = None")])
def test_missing_or_unknown_condition(condition, message):
    with pytest.raises(InputError, match=message.replace("(", r"\(")):
        case_from_dict(raw_case(), condition)


def test_unknown_material_names_the_field():
    raw = raw_case()
    raw["material"] = "UNOBTAINIUM"
    with pytest.raises(InputError, match="material = 'UNOBTAINIUM': unknown"):
        case_from_dict(raw, "1")


@pytest.mark.parametrize("kw, field", [
    (dict(inner_diameter_m=0.31, outer_diameter_m=0.301, width_m=0.173), "geometry.outer_diameter_mm"),
    (dict(inner_diameter_m=0.2183, outer_diameter_m=0.301, width_m=-0.01), "geometry.width_mm"),
    (dict(inner_diameter_m=0.2183, outer_diameter_m=0.301, width_m=0.173, chamfer_m=0.03), "geometry.chamfer_mm"),
])
def test_impossible_rectangular_geometry(kw, field):
    with pytest.raises(InputError, match=field):
        rectangular_ring(**kw)


def test_impossible_spherical_ring():
    with pytest.raises(InputError, match="geometry.outer_diameter_mm"):
        spherical_outer_ring(0.427, 0.420, 0.1185)


def test_general_profile_must_close_and_arcs_must_be_circular():
    spec = {"start_mm": [100, 0], "segments": [{"to_mm": [120, 0], "name": "bottom"},
                                                {"to_mm": [120, 30], "name": "od"},
                                                {"to_mm": [100, 31], "name": "top"}]}
    with pytest.raises(InputError, match="must close"):
        general_profile(spec)
    spec["segments"][2]["to_mm"] = [100, 30]
    spec["segments"].append({"to_mm": [100, 0], "name": "bore", "center_mm": [0, 10]})
    with pytest.raises(InputError, match="equidistant"):
        general_profile(spec)


def test_general_profile_with_arc_meshes_and_names_every_segment():
    spec = {"start_mm": [100, 0], "segments": [{"to_mm": [130, 0], "name": "bottom"},
                                                {"to_mm": [130, 40], "name": "od"},
                                                {"to_mm": [100, 40], "name": "top"},
                                                {"to_mm": [100, 0], "name": "raceway", "center_mm": [40, 20]}]}
    section = mesh_profile(general_profile(spec), 0.004, 0.002, 0.004)
    assert set(section.boundaries) == {"bottom", "od", "top", "raceway"}
    # the arc bulges outward from the section (centre at r = 40 mm): area > the 30 x 40 rectangle
    assert section.profile.area_m2() < 30e-3 * 40e-3
    assert section.mesh.boundary_facets().size == sum(len(f) for f in section.boundaries.values())


@pytest.mark.parametrize("table, field, allowed", [
    ({"T_C": [0, 400, 300], "h_W_m2K": [1, 2, 3], "ambient_C": 60}, "quench.htc_table.T_C", "strictly increasing"),
    ({"T_C": [0, 400, 800], "h_W_m2K": [1, -2, 3], "ambient_C": 60}, "quench.htc_table.h_W_m2K", ">= 0"),
    ({"T_C": [0, 400], "h_W_m2K": [1, 2, 3], "ambient_C": 60}, "quench.htc_table.h_W_m2K", "as long as"),
    ({"T_C": [0, 400], "h_W_m2K": [1, 2]}, "quench.htc_table.ambient_C", "must be a number"),
])
def test_bad_htc_tables(table, field, allowed):
    with pytest.raises(InputError, match=rf"{field} = .*{allowed}"):
        parse_htc_table(table, np.array(["bore", "od"]))


def test_htc_table_per_segment_overrides_and_unknown_segment():
    seg = np.array(["bore", "od", "od"])
    htc = parse_htc_table({"T_C": [0, 1000], "h_W_m2K": [100, 100], "ambient_C": 60,
                           "segments": {"od": {"T_C": [0, 1000], "h_W_m2K": [0, 1000]}}}, seg)
    assert np.allclose(htc(np.array([500.0, 500.0, 250.0]), 0.0), [100, 500, 250])
    assert np.allclose(htc.ambient_C, 60)
    with pytest.raises(InputError, match="quench.htc_table.segments.odd"):
        parse_htc_table({"T_C": [0, 1], "h_W_m2K": [1, 1], "ambient_C": 1, "segments": {"odd": {"T_C": [0, 1], "h_W_m2K": [1, 1]}}}, seg)


def test_htc_versus_time_table():
    htc = parse_htc_table({"time_s": [0, 10], "h_W_m2K": [1000, 0], "ambient_C": 20}, np.array(["od"]))
    assert np.allclose(htc(np.array([800.0]), 5.0), 500.0)


def test_cli_bad_input_exits_2_with_one_line(tmp_path, capsys):
    raw = CASE_A.read_text().replace("inner_diameter_mm = 218.3", "inner_diameter_mm = 318.3")
    bad = tmp_path / "bad.toml"
    bad.write_text(raw)
    assert main(["run", str(bad), "--condition", "1", "--out", str(tmp_path / "o"), "--quiet"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "geometry.outer_diameter_mm = 301.0" in err[0]


def test_probe_outside_section_is_rejected(tmp_path, capsys):
    raw = CASE_A.read_text().replace("r_mm = 129.825", "r_mm = 160.0")
    bad = tmp_path / "bad.toml"
    bad.write_text(raw)
    assert main(["run", str(bad), "--condition", "1", "--out", str(tmp_path / "o"), "--quiet"]) == 2
    assert "probes[0] = 'P1 at (160, 86.5) mm': lies outside the section" in capsys.readouterr().err


def test_negative_numbers_in_case_fields():
    raw = copy.deepcopy(raw_case())
    raw["quench"]["time_s"] = -5
    with pytest.raises(InputError, match="quench.time_s = -5: must be > 0"):
        case_from_dict(raw, "1")


@pytest.mark.parametrize("override, message", [
    ({"geometry.width_mm": float("inf")}, "geometry.width_mm = inf: must be a finite number"),
    ({"geometry.inner_diameter_mm": -1.0}, "geometry.inner_diameter_mm = -1.0: must be >= 0"),  # 0: a solid section
    ({"quench.bath.od_jet_speed_mm_s": 1e9}, "quench.bath.od_jet_speed_mm_s = 1000000000.0: must be <= 50000"),
    ({"quench.bath.rotation_rpm": 1e5}, "quench.bath.rotation_rpm = 100000.0: must be <= 600"),
    ({"quench.bath.oil_temperature_C": 900.0}, "quench.bath.oil_temperature_C = 900.0: must be below the boiling"),
    ({"mesh.size_mmm": 4.0}, "mesh.size_mmm = 4.0: unknown key"),
    ({"quench.tme_s": 4.0}, "quench.tme_s = 4.0: unknown key"),
    ({"colling": 1}, "colling = 1: unknown table or key"),
    ({"time.dt_min_s": 500.0}, "time.dt_min_s = 500.0: must not exceed time.dt_max_s"),
    ({"air.emissivity": 1.5}, "air.emissivity = 1.5: must be <= 1"),
    ({"mechanics.plastisity": False}, "mechanics.plastisity = False: unknown key; [mechanics] takes plasticity"),
    ({"mechanics.plasticity": "yes"}, "mechanics.plasticity = 'yes': must be true or false"),
    ({"mechanics.newton_rtol": 5}, "mechanics.newton_rtol = 5: must be <= 0.01"),
    ({"quench.bath.od_jet_sped_mm_s": 8000}, "quench.bath.od_jet_sped_mm_s = 8000: unknown key; [quench.bath] takes"),
    ({"quench.bath.layout": None, "quench.bath.nozzles": {"od_a": {"diameter_mm": 10.0, "cont": 12}}},
     "quench.bath.nozzles.od_a.cont = 12: unknown key; [quench.bath.nozzles.od_a] takes side, diameter_mm"),
    ({"quench.htc_model": "table", "quench.htc_table": {"T_C": [0.0, 1000.0], "h_W_m2K": [500.0, 500.0]},
      "quench.bath.od_jet_sped_mm_s": 8000}, "quench.bath.od_jet_sped_mm_s = 8000: unknown key"),
    ({"conditions.1.quench.bath.od_jet_speed_mm_s": 8000}, "conditions.1.quench.bath.od_jet_speed_mm_s = 8000: sets "
                                                           "the case as run"),
    # one austenitising temperature: a second name in [mechanics] was silently replaced by the process's
    ({"mechanics.austenitizing_T_C": 900.0}, "mechanics.austenitizing_T_C = 900.0: is not a mechanics option: a case "
                                             "has one austenitising temperature, process.austenitising_temperature_C"),
])
def test_absurd_inputs_are_one_line_errors_before_any_work(override, message):
    with pytest.raises(InputError, match=re.escape(message)):
        load_case(CASE_A, "1", override)


def test_quench_medium_hotter_than_the_austenitising_temperature_is_an_error():
    raw = raw_case()
    raw["quench"] = {"time_s": 100.0, "htc_model": "table",
                     "htc_table": {"T_C": [0.0, 1000.0], "h_W_m2K": [500.0, 500.0], "ambient_C": 900.0}}
    with pytest.raises(InputError, match="quench.htc_table.ambient_C = 900.0: the quench medium must be colder"):
        case_from_dict(raw, "1")


def test_a_failed_check_writes_nothing_and_an_unwritable_out_is_one_line(tmp_path, capsys):
    out = tmp_path / "o"
    assert main(["run", str(CASE_A), "--condition", "1", "--set", "geometry.width_mm=-1", "--out", str(out),
                 "--quiet"]) == 2
    assert not out.exists()
    blocker = tmp_path / "a_file"
    blocker.write_text("")
    assert main(["run", str(CASE_A), "--condition", "1", "--out", str(blocker / "run"), "--quiet"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 2 and "out = " in err[1] and "cannot be written" in err[1]


@pytest.mark.parametrize("sets, message", [
    (["quench.bath.od_jet_speed_mm_s=1e9"], "quench.bath.od_jet_speed_mm_s = 1000000000.0: must be <= 50000"),
    (['quench.htc_model="table"', "quench.htc_table={T_C=[0.0, 1000.0], h_W_m2K=[500.0, 500.0], ambient_C=900.0}"],
     "quench.htc_table.ambient_C = 900.0: the quench medium must be colder"),
    (["geometry.width_mm=inf"], "geometry.width_mm = inf: must be a finite number"),
    (["quench.bath.oil_temperature_C=900"], "quench.bath.oil_temperature_C = 900.0: must be below the boiling"),
    (["air.emissivity=1.5"], "air.emissivity = 1.5: must be <= 1"),
    (["output.checkpoint_minutes=-1"], "output.checkpoint_minutes = -1: must be >= 0"),
    (["quench.bath.od_jet_sped_mm_s=8000"], "quench.bath.od_jet_sped_mm_s = 8000: unknown key; [quench.bath] takes"),
    (['mechanics.plasticity="yes"'], "mechanics.plasticity = 'yes': must be true or false"),
    (["mechanics.newton_rtol=5"], "mechanics.newton_rtol = 5: must be <= 0.01"),
])
def test_each_absurd_input_from_the_command_line_is_one_line_and_writes_nothing(tmp_path, capsys, sets, message):
    """The absurd inputs of issue 20 through `quenchsim run`: exit 2, one line naming the field, the value and what
    is allowed, and no output folder (the checks run before anything is written or meshed)."""
    out = tmp_path / "run"
    argv = ["run", str(CASE_A), "--condition", "1", "--out", str(out), "--quiet"]
    assert main(argv + [arg for value in sets for arg in ("--set", value)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and message in err[0], err
    assert not out.exists()


@pytest.mark.parametrize("table, message", [
    ("[conditions.9.quench.bath]\nod_jet_sped_mm_s = 8000.0\n",
     "conditions.9.quench.bath.od_jet_sped_mm_s = 8000.0: unknown key; [conditions.9.quench.bath] takes quenchant"),
    ("[conditions.9.quench.bath.nozzles.od_a]\ncont = 12\n",
     "conditions.9.quench.bath.nozzles.od_a.cont = 12: unknown key; [conditions.9.quench.bath.nozzles.od_a] takes"),
    ("[conditions.9.quench]\ntme_s = 5.0\n", "conditions.9.quench.tme_s = 5.0: unknown key; [conditions.9.quench]"),
    ("[conditions.9.mechanics]\nplastisity = false\n", "conditions.9.mechanics.plastisity = False: unknown key"),
    ("[conditions.9.colling]\nx = 1\n", "conditions.9.colling = {'x': 1}: unknown table or key; [conditions.9]"),
])
def test_a_typo_in_any_condition_is_one_line_and_writes_nothing(tmp_path, capsys, table, message):
    """A misspelt key in any condition's tables (the bath's and its nozzle rows included) is refused when the case
    loads, whichever condition is run."""
    bad = tmp_path / "bad.toml"
    bad.write_text(CASE_A.read_text() + "\n" + table)
    out = tmp_path / "run"
    assert main(["run", str(bad), "--condition", "1", "--out", str(out), "--quiet"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and message in err[0], err
    assert not out.exists()


def test_derived_cases_are_checked_again():
    case = load_case(CASE_A, "1")
    finer = case.refined(mesh=0.5, step=0.5)
    assert finer.mesh.size_mm == 0.5 * case.mesh.size_mm and finer.time.max_dT_K == 0.5 * case.time.max_dT_K
    assert case.mesh.size_mm == 5.0    # the original is unchanged (frozen)
    with pytest.raises(InputError, match="mesh.size_mm = -5.0"):
        case.with_overrides({"mesh.size_mm": -5.0})
    assert case.with_overrides({"air.until_max_C": None}).air.until_max_C == 40.0   # None: back to the default


def test_mesh_picture_colours_each_named_segment_once_with_its_legend_entry():
    from quenchsim.commands.mesh import segments_figure
    from quenchsim.geometry.profile import MM

    case = load_case(CASE_A, "1")
    section = mesh_profile(case.profile, 10 * MM, 3 * MM, 10 * MM)
    ax = segments_figure(section).axes[0]
    lines = [c for c in ax.collections if c.get_label() in section.boundaries]
    assert sorted(c.get_label() for c in lines) == sorted(section.boundaries)
    colours = [tuple(np.round(c.get_colors()[0], 6)) for c in lines]
    assert len(set(colours)) == len(colours)
    from matplotlib.colors import to_rgba

    legend = {t.get_text(): tuple(np.round(to_rgba(h.get_color()), 6))
              for t, h in zip(ax.get_legend().get_texts(), ax.get_legend().legend_handles)}
    assert legend == {c.get_label(): col for c, col in zip(lines, colours)}
