"""The user's data folders (issue 36: "a locally fitted oil in ./materials/quenchants is not found by name"): the
fitters write into ./materials by default, `quenchsim run` finds what they wrote by name, a user's file shadows a
shipped one of the same name as quenchsim.materials documents, the validation studies see the shipped data only,
and nothing is ever written into the shipped folder. ~30 s."""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

from quenchsim import fingerprint, materials
from quenchsim.cli import main
from quenchsim.errors import InputError
from quenchsim.fingerprint import code_fingerprint
from quenchsim.materials import data_folders, find_data_file, load_material, shipped_data_only

ROOT = Path(__file__).resolve().parents[1]
SHIPPED = ROOT / "materials"
CURVE = ROOT / "docs" / "guide" / "first_hour_probe_curve.csv"
TTT_DATA = ROOT / "docs" / "guide" / "first_hour_ttt.toml"


def shipped_digest() -> str:
    """SHA-1 over every file of the shipped materials folder (names and bytes)."""
    digest = hashlib.sha1()
    for path in sorted(SHIPPED.rglob("*")):
        if path.is_file():
            digest.update(path.relative_to(SHIPPED).as_posix().encode())
            digest.update(path.read_bytes())
    return digest.hexdigest()


def _cli(cwd: Path, *args: str, env: dict[str, str] | None = None) -> subprocess.CompletedProcess:
    environ = {**os.environ, "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]),
               **(env or {})}
    environ.pop(materials.DATA_ENV, None) if env is None else None
    return subprocess.run([sys.executable, "-m", "quenchsim.cli", *args], cwd=cwd, env=environ, capture_output=True,
                          text=True, timeout=600)


def _user_copy(folder: Path, name: str, description: str) -> Path:
    """A copy of shipped SUJ2 called ``name`` in ``folder`` with its own description."""
    folder.mkdir(parents=True, exist_ok=True)
    text = (SHIPPED / "SUJ2.toml").read_text()
    data = tomllib.loads(text)
    path = folder / f"{name}.toml"
    path.write_text(text.replace(f'description = {json.dumps(data["description"])}',
                                 f'description = {json.dumps(description)}'))
    assert tomllib.loads(path.read_text())["description"] == description
    return path


@pytest.fixture
def project(tmp_path, monkeypatch) -> Path:
    """An empty project folder as the current directory, no QUENCHSIM_DATA."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv(materials.DATA_ENV, raising=False)
    monkeypatch.delenv(materials.SHIPPED_ONLY_ENV, raising=False)
    return tmp_path


def test_the_search_order_is_data_env_then_current_folder_then_shipped(project, monkeypatch):
    assert data_folders() == [project / "materials", SHIPPED]
    _user_copy(project / "materials", "SUJ2", "mine in ./materials")
    assert load_material("SUJ2")["description"] == "mine in ./materials"   # the user's file shadows the shipped one
    _user_copy(project / "env_data", "SUJ2", "mine in QUENCHSIM_DATA")
    monkeypatch.setenv(materials.DATA_ENV, str(project / "env_data"))
    assert load_material("SUJ2")["description"] == "mine in QUENCHSIM_DATA"
    _user_copy(project / "flag_data", "SUJ2", "mine in --data")
    materials.use_data_folders([project / "flag_data"])
    assert data_folders()[:3] == [(project / "flag_data").resolve(), project / "env_data", project / "materials"]
    assert load_material("SUJ2")["description"] == "mine in --data"
    with shipped_data_only():   # what the validation studies see
        assert data_folders() == [SHIPPED]
        assert load_material("SUJ2")["description"] == tomllib.loads((SHIPPED / "SUJ2.toml").read_text())["description"]
    assert load_material("SUJ2")["description"] == "mine in --data"


def test_a_steels_mechanics_file_is_the_one_beside_the_file_found(project):
    _user_copy(project / "materials", "SUJ3", "mine")
    assert "mechanics" not in load_material("SUJ3")      # not the shipped SUJ3.mechanics.toml
    shutil.copyfile(SHIPPED / "SUJ3.mechanics.toml", project / "materials" / "SUJ3.mechanics.toml")
    assert "mechanics" in load_material("SUJ3")


def test_an_unknown_name_lists_the_folders_searched(project):
    with pytest.raises(InputError) as err:
        find_data_file("no_such_oil", "quenchants", "quench.bath.quenchant")
    text = str(err.value)
    assert str(project / "materials" / "quenchants") in text and str(SHIPPED / "quenchants") in text
    assert "astm_d6200_fast_oil" in text and "\n" not in text


def test_a_missing_data_folder_is_refused(project, capsys):
    assert main(["cct", "SUJ2", "--data", str(project / "nowhere")]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("quenchsim: error: --data") and "nowhere" in err and "\n" not in err


def test_a_user_folder_changes_the_run_fingerprint_but_not_the_studies(project):
    with shipped_data_only():
        shipped_only = code_fingerprint()
    plain = code_fingerprint()
    assert plain == shipped_only     # an empty ./materials: nothing of the user's
    _user_copy(project / "materials", "SUJ2", "mine")
    fingerprint._fingerprint.cache_clear()   # computed once per process and search path
    assert code_fingerprint() != shipped_only
    with shipped_data_only():
        assert code_fingerprint() == shipped_only
        shipped_runs = fingerprint.run_fingerprint()
    assert fingerprint.run_fingerprint() != shipped_runs   # the run cache's fingerprint reads the user's data too


def test_the_fitters_refuse_a_new_file_in_the_shipped_folder(tmp_path, capsys):
    target = SHIPPED / "quenchants" / "my_new_oil.toml"
    assert main(["quenchant", "fit", str(CURVE), "--out", str(target), "--fast"]) == 2
    err = capsys.readouterr().err.strip()
    assert "--out" in err and "materials/quenchants/my_new_oil.toml" in err and "\n" not in err
    assert not target.exists()
    target = SHIPPED / "MY_NEW_STEEL.toml"
    assert main(["material", "fit", str(TTT_DATA), "--out", str(target)]) == 2
    assert "materials/MY_NEW_STEEL.toml" in capsys.readouterr().err and not target.exists()


@pytest.fixture(scope="module")
def fitted_project(tmp_path_factory) -> dict:
    """A project folder where an oil and a steel are fitted with the fitters' default --out, then a short run of a
    cylinder case that names both (mechanics off: the fitted steel has no mechanics file)."""
    folder = tmp_path_factory.mktemp("project")
    before = shipped_digest()
    shutil.copyfile(CURVE, folder / "my_oil.csv")
    shutil.copyfile(TTT_DATA, folder / "MY_STEEL.toml")
    case = (ROOT / "cases" / "solid_cylinder_still_oil.toml").read_text()
    case = case.replace('material = "../validation/quenchants/probe_fit/specimen_steel.toml"', 'material = "MY_STEEL"')
    case = case.replace('quenchant = "astm_d6200_fast_oil"', 'quenchant = "my_oil"')
    (folder / "cylinder.toml").write_text(case)
    steps = [("quenchant", "fit", "my_oil.csv", "--fast"), ("material", "fit", "MY_STEEL.toml"),
             ("run", "cylinder.toml", "--mesh-size", "6", "--set", "quench.time_s=30", "--out", "runs/mine",
              "--quiet", "--json")]
    results = [_cli(folder, *step) for step in steps]
    return {"folder": folder, "results": results, "shipped_before": before, "shipped_after": shipped_digest()}


def test_fitted_oil_and_steel_are_written_into_the_projects_materials(fitted_project):
    for r in fitted_project["results"]:
        assert r.returncode == 0, r.stderr[-2000:]
    folder = fitted_project["folder"]
    oil = tomllib.loads((folder / "materials" / "quenchants" / "my_oil.toml").read_text())
    steel = tomllib.loads((folder / "materials" / "MY_STEEL.toml").read_text())
    assert oil["name"] == "my_oil" and steel["name"] == "MY_STEEL" and "SUJ2" in steel["description"]


def test_a_run_finds_the_fitted_oil_and_steel_by_name(fitted_project):
    run = fitted_project["results"][-1]
    assert run.returncode == 0, run.stderr[-2000:]
    summary = json.loads((fitted_project["folder"] / "runs" / "mine" / "summary.json").read_text())
    case = tomllib.loads((fitted_project["folder"] / "runs" / "mine" / "case.toml").read_text())
    assert case["material"] == "MY_STEEL" and case["quench"]["bath"]["quenchant"] == "my_oil"
    assert summary["hardness"]["core_HRC"] > 20.0   # the fitted steel's kinetics ran


def test_the_user_folder_never_modifies_the_shipped_materials(fitted_project):
    assert fitted_project["shipped_after"] == fitted_project["shipped_before"]
    assert not (SHIPPED / "MY_STEEL.toml").exists() and not (SHIPPED / "quenchants" / "my_oil.toml").exists()


def test_a_users_steel_named_like_its_shipped_base_is_described_as_the_users(project):
    """`material fit` of data based on SUJ2 into ./materials/SUJ2.toml writes the user's SUJ2 (found first by name in
    the user's runs), described as fitted, not with the shipped SUJ2's description."""
    shutil.copyfile(TTT_DATA, project / "SUJ2.toml")
    assert main(["material", "fit", "SUJ2.toml", "--json"]) == 0
    mine = tomllib.loads((project / "materials" / "SUJ2.toml").read_text())
    assert mine["name"] == "SUJ2" and mine["description"].startswith("SUJ2: kinetics fitted by `quenchsim material fit")
    assert load_material("SUJ2")["description"] == mine["description"]
