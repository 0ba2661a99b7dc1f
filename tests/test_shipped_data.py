"""The data quenchsim ships (issue 36): its cases found by name, from a checkout and from a wheel's layout, listed and
copied by `quenchsim cases`; its materials never overwritten by the fitters; a fitted steel named as the user's;
a steel without mechanics data refused for a mechanics run instead of silently skipping the mechanics."""

from __future__ import annotations

import shutil
import tomllib
from pathlib import Path

import pytest

import quenchsim.shipped as shipped
from quenchsim.case import load_case
from quenchsim.cli import main
from quenchsim.commands.run import summary_table
from quenchsim.quench_setup import require_mechanics_data
from quenchsim.errors import InputError
from quenchsim.fitting.kinetics import _identity

ROOT = Path(__file__).resolve().parents[1]
SHIPPED_CASES = sorted(p.stem for p in (ROOT / "cases").glob("*.toml"))


def _one_line_error(capsys) -> str:
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and err.startswith("quenchsim: error: "), err
    return err


# --- the shipped cases, by name ---------------------------------------------------------------------------------

def test_cases_lists_every_shipped_case_with_description_and_conditions(capsys):
    assert main(["cases"]) == 0
    *lines, examples = capsys.readouterr().out.splitlines()
    assert [ln.split()[0] for ln in lines] == SHIPPED_CASES
    assert examples.startswith("example files (quenchsim cases copy NAME): ") and "first_hour_ttt.toml" in examples
    ring_a = next(ln for ln in lines if ln.startswith("crb_outer_ring "))
    assert "Cylindrical-roller-bearing outer ring (case A)" in ring_a and "[conditions: 1, 2, 3]" in ring_a


def test_cases_copy_writes_the_file_and_never_overwrites_without_force(tmp_path, capsys):
    target = tmp_path / "mine" / "crb_outer_ring.toml"
    assert main(["cases", "copy", "crb_outer_ring", str(tmp_path / "mine")]) == 0
    assert target.read_text() == (ROOT / "cases" / "crb_outer_ring.toml").read_text()
    target.write_text("# my edits\n")
    assert main(["cases", "copy", "crb_outer_ring", str(tmp_path / "mine")]) == 2
    err = _one_line_error(capsys)
    assert "DIR = " in err and "already holds crb_outer_ring.toml" in err and "--force" in err
    assert target.read_text() == "# my edits\n"   # untouched
    assert main(["cases", "copy", "crb_outer_ring", str(tmp_path / "mine"), "--force"]) == 0
    assert target.read_text() == (ROOT / "cases" / "crb_outer_ring.toml").read_text()


def test_an_unknown_case_name_lists_the_shipped_ones_before_any_work(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(["cases", "copy", "crb_outer", str(tmp_path)]) == 2
    err = _one_line_error(capsys)
    assert "NAME = 'crb_outer'" in err and "crb_outer_ring, " in err and "srb_outer_ring" in err
    assert main(["run", "crb_outer", "--condition", "1", "--out", str(tmp_path / "run"), "--quiet"]) == 2
    err = _one_line_error(capsys)
    assert "case = 'crb_outer': no such file and no shipped case of that name" in err and "crb_outer_ring" in err
    assert not (tmp_path / "run").exists()


def test_a_bare_name_is_a_shipped_case_and_a_path_stays_a_path(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert shipped.resolve_case("crb_outer_ring") == ROOT / "cases" / "crb_outer_ring.toml"
    case = load_case(shipped.resolve_case("crb_outer_ring"), "1")
    assert case.name == "crb_outer_ring" and case.material == "SUJ3"
    assert shipped.resolve_case("my/crb_outer_ring") == Path("my/crb_outer_ring")
    assert shipped.resolve_case("my_ring.toml") == Path("my_ring.toml")
    with pytest.raises(InputError, match="give its name, crb_outer_ring"):   # not here, but shipped (issue 47)
        shipped.resolve_case("crb_outer_ring.toml")
    (tmp_path / "crb_outer_ring").write_text("")   # an existing file of that name is the user's
    assert shipped.resolve_case("crb_outer_ring") == Path("crb_outer_ring")


def test_a_wheel_finds_its_cases_inside_the_package(tmp_path, monkeypatch):
    """An installed wheel has no cases/ beside the package: setup.py copies them to quenchsim/_data/cases."""
    assert "cases" in (ROOT / "setup.py").read_text().split("DATA_FOLDERS = ")[1].splitlines()[0]
    package = tmp_path / "site-packages" / "quenchsim"
    (package / "_data" / "cases").mkdir(parents=True)
    shutil.copyfile(ROOT / "cases" / "srb_outer_ring.toml", package / "_data" / "cases" / "srb_outer_ring.toml")
    monkeypatch.setattr(shipped, "PACKAGE", package)
    assert [c.name for c in shipped.shipped_cases()] == ["srb_outer_ring"]
    assert shipped.resolve_case("srb_outer_ring") == package / "_data" / "cases" / "srb_outer_ring.toml"
    assert shipped.shipped_cases()[0].conditions == ("4", "5", "6")


# --- the fitters never overwrite shipped data, and name what they write after the user ---------------------------

def test_material_fit_refuses_a_shipped_steel_before_reading_its_data(tmp_path, capsys):
    before = (ROOT / "materials" / "SUJ2.toml").read_bytes()
    assert main(["material", "fit", str(tmp_path / "no_data_yet.toml"), "--out", str(ROOT / "materials" / "SUJ2.toml")]) == 2
    err = _one_line_error(capsys)
    assert "--out = " in err and "materials/SUJ2.toml" in err and "never overwritten" in err
    assert (ROOT / "materials" / "SUJ2.toml").read_bytes() == before


def test_quenchant_fit_refuses_a_shipped_oil_before_reading_the_curve(tmp_path, capsys):
    shipped_oil = ROOT / "materials" / "quenchants" / "astm_d6200_fast_oil.toml"
    before = shipped_oil.read_bytes()
    assert main(["quenchant", "fit", str(tmp_path / "no_curve.csv"), "--out", str(shipped_oil)]) == 2
    err = _one_line_error(capsys)
    assert "materials/quenchants/astm_d6200_fast_oil.toml" in err and "never overwritten" in err
    assert shipped_oil.read_bytes() == before


def test_a_fitted_steel_carries_the_users_name_not_the_base_steels(tmp_path):
    out = tmp_path / "MY_STEEL.toml"
    out.write_text(_identity((ROOT / "materials" / "SUJ2.toml").read_text(), "MY_STEEL",
                             "MY_STEEL: kinetics fitted to my data"))
    mine, base = tomllib.loads(out.read_text()), tomllib.loads((ROOT / "materials" / "SUJ2.toml").read_text())
    assert mine["name"] == "MY_STEEL" and mine["description"] == "MY_STEEL: kinetics fitted to my data"
    assert {k: v for k, v in mine.items() if k not in ("name", "description")} == \
        {k: v for k, v in base.items() if k not in ("name", "description")}


# --- a steel without mechanics data is never run as if its dimensions were computed ------------------------------

def _user_steel_case(tmp_path: Path, with_mechanics: bool) -> Path:
    steel = tmp_path / "steels" / "MY_STEEL.toml"
    steel.parent.mkdir(parents=True)
    shutil.copyfile(ROOT / "materials" / "SUJ3.toml", steel)
    if with_mechanics:
        shutil.copyfile(ROOT / "materials" / "SUJ3.mechanics.toml", steel.with_name("MY_STEEL.mechanics.toml"))
    text = (ROOT / "cases" / "crb_outer_ring.toml").read_text().replace('material = "SUJ3"',
                                                                       'material = "steels/MY_STEEL.toml"')
    case = tmp_path / "ring.toml"
    case.write_text(text)
    return case


def test_a_steel_without_mechanics_is_refused_with_the_file_and_the_way_out(tmp_path, capsys):
    case = _user_steel_case(tmp_path, with_mechanics=False)
    out = tmp_path / "run"
    assert main(["run", str(case), "--condition", "1", "--out", str(out), "--quiet"]) == 2
    err = _one_line_error(capsys)
    assert "MY_STEEL.mechanics.toml" in err and "--set mechanics.enabled=false" in err
    assert not out.exists()
    with pytest.raises(InputError, match="has no mechanics data"):
        require_mechanics_data(load_case(case, "1"))
    require_mechanics_data(load_case(case, "1", {"mechanics.enabled": False}))   # the user's choice: passes
    require_mechanics_data(load_case(_user_steel_case(tmp_path / "b", with_mechanics=True), "1"))


def test_the_api_refuses_a_steel_without_mechanics_before_writing_anything(tmp_path):
    """The check is the run's own (where it loads the material), so ``quenchsim.run`` refuses as the CLI does."""
    import quenchsim as qs

    case = load_case(_user_steel_case(tmp_path, with_mechanics=False), "1")
    with pytest.raises(InputError, match="has no mechanics data"):
        qs.run(case, tmp_path / "run", progress=False)
    assert not (tmp_path / "run").exists()


def test_the_terminal_says_when_no_dimensions_were_computed():
    summary = {"case": "ring", "condition": "1", "status": "ok", "end_state": {"at_room_temperature": True},
               "solver": {"steps": 10, "wall_time_s": 1.0}, "probes": {}}
    table = summary_table(summary, Path("runs/x"))
    assert "no mechanics in this run: no dimensions" in table
    summary["dimensions_mm"] = {"before": {"id": 1.0}, "after": {"id": 1.1}, "change": {"id": 0.1}}
    assert "no mechanics" not in summary_table(summary, Path("runs/x"))
