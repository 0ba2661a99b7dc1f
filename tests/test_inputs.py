"""The input layer (quenchsim/inputs/): every kind of file read one way -- a typo or a bad value is one line naming
the file, the key, the value and what is allowed (exit 2 from the command line, before any work); a value changed by
a copy is checked like one read from a file; the key references are generated from the declarations."""

from __future__ import annotations

import dataclasses
import re
import shutil
from pathlib import Path

import pytest

from quenchsim.case import load_case
from quenchsim.cli import main
from quenchsim.errors import InputError
from quenchsim.inputs.declare import from_table, to_table
from quenchsim.inputs.references import REFERENCES

ROOT = Path(__file__).resolve().parents[1]
CASE_A = ROOT / "cases" / "crb_outer_ring.toml"


def test_the_key_references_are_generated_from_the_declarations_and_current():
    for name, write in REFERENCES.items():
        assert (ROOT / name).read_text() == write(), f"{name} is stale: python dev/write_references.py"


def _edited(tmp_path: Path, source: Path, old: str, new: str, name: str | None = None) -> Path:
    text = source.read_text()
    assert re.search(old, text, flags=re.M), old
    path = tmp_path / (name or source.name)
    path.write_text(re.sub(old, new, text, count=1, flags=re.M))
    return path


def _one_line(capsys: pytest.CaptureFixture[str], argv: list[str]) -> str:
    assert main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1, err
    return err[0]


@pytest.mark.parametrize("old, new, message", [
    (r"^time_s = 900\.0", "tme_s = 900.0", "quench.tme_s = 900.0: unknown key; [quench] takes time_s, htc_model, bath, "
                                            "htc_table, immersion_speed_mm_s; did you mean time_s?"),
    (r"^time_s = 900\.0", "time_s = -900.0", "quench.time_s = -900.0: must be > 0 s"),
    (r"^time_s = 900\.0", 'time_s = "long"', "quench.time_s = 'long': must be a finite number"),
    (r'^htc_model = "bath"', 'htc_model = "bth"', "quench.htc_model = 'bth': must be one of 'bath', 'table'; did "
                                                  "you mean bath?"),
])
def test_a_case_typo_or_bad_value_names_the_file_and_key_and_writes_nothing(tmp_path, capsys, old, new, message):
    case = _edited(tmp_path, CASE_A, old, new)
    out = tmp_path / "run"
    err = _one_line(capsys, ["run", str(case), "--condition", "1", "--out", str(out), "--quiet"])
    assert err == f"quenchsim: error: {case}: {message}"
    assert not out.exists()


def _data_folder(tmp_path: Path, subdir: str, source: Path, old: str, new: str) -> Path:
    folder = tmp_path / "data"
    (folder / subdir).mkdir(parents=True)
    _edited(folder / subdir, source, old, new)
    return folder


@pytest.mark.parametrize("source, old, new, message", [
    ("reference_nozzles.toml", r"^count = \{ value = 8,", "cont = { value = 8,",
     "nozzles.id.cont = {'value': 8, 'source': '[est] ID nozzles on a central manifold in the bore'}: unknown key"),
    ("reference_nozzles.toml", r"^diameter_mm = \{ value = 8\.0,", "diameter_mm = { value = -8.0,",
     "nozzles.id.diameter_mm.value = -8.0: must lie in its range [5.0, 12.0]"),
    ("jet_bath.toml", r"^corner_carryover = \{ value = 0\.3,", "corner_carryover = { value = 1.3,",
     "flow.corner_carryover.value = 1.3: must lie in its range [0.1, 0.6]"),
    ("jet_bath.toml", r"^od = \{ value = 1\.0,", "od = { valu = 1.0,", "htc_factor.od.valu = 1.0: unknown key"),
])
def test_a_bath_layout_or_constants_typo_names_its_file(tmp_path, capsys, monkeypatch, source, old, new, message):
    monkeypatch.setenv("QUENCHSIM_DATA", "")   # --data puts its folder on this process's search path
    folder = _data_folder(tmp_path, "baths", ROOT / "materials" / "baths" / source, old, new)
    err = _one_line(capsys, ["run", str(CASE_A), "--condition", "1", "--data", str(folder),
                             "--out", str(tmp_path / "run"), "--quiet"])
    assert err.startswith(f"quenchsim: error: {folder / 'baths' / source}: {message}"), err


def test_a_copy_with_a_changed_value_is_checked_like_a_file():
    case = load_case(CASE_A, "1")
    longer = dataclasses.replace(case, quench=dataclasses.replace(case.quench, time_s=900.0))
    assert longer.quench.time_s == 900.0 and case.quench.time_s == 900.0
    longer = dataclasses.replace(case, quench=dataclasses.replace(case.quench, time_s=1200.0))
    assert longer.quench.time_s == 1200.0 and case.quench.time_s == 900.0
    assert longer.resolved() == case.with_overrides({"quench.time_s": 1200.0}).resolved()
    with pytest.raises(InputError, match=r"^time_s = -1\.0: must be > 0 s$"):
        dataclasses.replace(case.quench, time_s=-1.0)
    with pytest.raises(InputError, match=r"^until_max_C = 10\.0: must be >= 25"):
        dataclasses.replace(case, air=dataclasses.replace(case.air, until_max_C=10.0))
    with pytest.raises(InputError, match=r"^mesh\.size_mm = 400\.0: must be > 0 and at most 173 mm"):
        dataclasses.replace(case, mesh=dataclasses.replace(case.mesh, size_mm=400.0))


def test_a_case_reads_back_as_written_so_its_digest_does_not_depend_on_how_it_was_built(tmp_path):
    """The resolved inputs keep the numbers in the form written (an integer stays one): a case written to case.toml
    and read again is the same case, with the same case_sha256."""
    import tomli_w

    case = load_case(CASE_A, "1", {"quench.time_s": 600, "temper.temperature_C": 180, "temper.time_s": 7200})
    assert case.resolved()["quench"]["time_s"] == 600 and isinstance(case.resolved()["quench"]["time_s"], int)
    assert case.quench.time_s == 600.0 and isinstance(case.quench.time_s, float)
    written = tmp_path / "case.toml"
    written.write_text(tomli_w.dumps({k: v for k, v in case.resolved().items() if k != "condition"}))
    again = load_case(written)
    assert again.digest() != case.digest()   # the condition is part of what ran
    assert {**again.resolved(), "condition": "1"} == case.resolved()
    shutil.copy(written, tmp_path / "copy.toml")
    assert load_case(tmp_path / "copy.toml").resolved() == {**again.resolved(), "name": again.name}


def test_a_table_reads_back_to_what_it_was_given():
    from quenchsim.inputs.case import Air

    air = from_table(Air, {"until_max_C": 45, "htc_model": "natural"}, "air")
    assert air.until_max_C == 45.0 and to_table(air)["until_max_C"] == 45
    assert to_table(air) == {"temperature_C": 25.0, "until_max_C": 45, "time_s": 20000.0, "htc_model": "natural",
                             "emissivity": 0.8}
    assert to_table(dataclasses.replace(air, until_max_C=50.0))["until_max_C"] == 50.0


def test_each_input_module_imports_first():
    """Every module of the input layer imports on its own, first in a fresh interpreter (the steel's declarations
    read the property forms of quenchsim.materials, whose loader reads the steel's declarations: no import cycle)."""
    import subprocess
    import sys

    modules = sorted(p.stem for p in (ROOT / "quenchsim" / "inputs").glob("*.py") if p.stem != "__init__")
    code = "import importlib, sys; [importlib.import_module(m) for m in sys.argv[1:]]"
    for module in modules:
        done = subprocess.run([sys.executable, "-c", code, f"quenchsim.inputs.{module}"], capture_output=True,
                              text=True, cwd=ROOT)
        assert done.returncode == 0, (module, done.stderr[-500:])


# -- a typo or a bad value in every kind of file: one line naming the file, the key, the value, what is allowed ------
def _copy(tmp_path: Path, source: Path, old: str, new: str, name: str | None = None) -> Path:
    """``source`` copied to ``tmp_path`` with its first line matching ``old`` replaced by ``new``."""
    return _edited(tmp_path, source, old, new, name)


def _steel_case(tmp_path: Path) -> Path:
    """Ring A's case file, its material the copy of SUJ3 in ``tmp_path`` (with its mechanics file)."""
    case = tmp_path / "ring.toml"
    case.write_text(CASE_A.read_text().replace('material = "SUJ3"', 'material = "SUJ3.toml"'))
    assert 'material = "SUJ3.toml"' in case.read_text()
    return case


STEEL = ROOT / "materials" / "SUJ3.toml"
MECHANICS = ROOT / "materials" / "SUJ3.mechanics.toml"
OIL = ROOT / "materials" / "quenchants" / "reference_quench_oil.toml"


@pytest.mark.parametrize("source, old, new, message", [
    (STEEL, r"^alpha_per_K = 0\.01104", "alpha_per_K = -0.011",
     "kinetics.martensite.alpha_per_K = -0.011: must be > 0 1/K"),
    (STEEL, r"^Cr = 1\.05", "Crr = 1.05", "composition.Crr = 1.05: unknown key; [composition] takes source, C, Si"),
    (MECHANICS, r"^law = \"desalos\"", 'law = "desalo"', "trip.law = 'desalo': must be one of 'desalos', 'leblond'; "
                                                         "did you mean desalos?"),
    (MECHANICS, r"^phase = \"pearlite\"", 'phse = "pearlite"', "annealed.phse = 'pearlite': unknown key"),
])
def test_a_steel_or_mechanics_file_typo_names_its_file(tmp_path, capsys, source, old, new, message):
    for original in (STEEL, MECHANICS):
        (tmp_path / original.name).write_text(original.read_text())
    bad = _copy(tmp_path, source, old, new)
    err = _one_line(capsys, ["run", str(_steel_case(tmp_path)), "--condition", "1", "--out", str(tmp_path / "run"),
                             "--quiet"])
    assert err.startswith(f"quenchsim: error: {bad}: {message}"), err
    assert not (tmp_path / "run").exists()


@pytest.mark.parametrize("old, new, message", [
    (r"^density_kg_m3 = \{ value = 860\.0,", "density_kg_m3 = { value = -860.0,",
     "liquid.density_kg_m3 = -860.0: must be > 0 kg/m3"),
    (r"^zuber_K = \{", "zuber = {", "boiling.zuber = {"),
])
def test_a_quenchant_typo_names_its_file(tmp_path, capsys, monkeypatch, old, new, message):
    monkeypatch.setenv("QUENCHSIM_DATA", "")   # --data puts its folder on this process's search path
    folder = _data_folder(tmp_path, "quenchants", OIL, old, new)
    err = _one_line(capsys, ["run", str(CASE_A), "--condition", "1", "--data", str(folder),
                             "--out", str(tmp_path / "run"), "--quiet"])
    assert err.startswith(f"quenchsim: error: {folder / 'quenchants' / OIL.name}: {message}"), err


def test_a_sweep_design_or_calibration_file_typo_names_its_file(tmp_path, capsys):
    (tmp_path / "ring.toml").write_text(CASE_A.read_text())
    sweep = tmp_path / "s.toml"
    sweep.write_text('[sweep]\ncase = "ring.toml"\ncondtion = "1"\n[grid]\n"quench.time_s" = [600.0]\n')
    err = _one_line(capsys, ["sweep", str(sweep), "--out", str(tmp_path / "runs"), "--quiet"])
    assert err.startswith(f"quenchsim: error: {sweep}: sweep.condtion = '1': unknown key; [sweep] takes case, "
                          "condition, name; did you mean condition?"), err
    study = tmp_path / "d.toml"
    study.write_text('[study]\ncase = "ring.toml"\ncondition = "1"\ntrials = 0\n[variables]\n'
                     '"quench.time_s" = [600.0, 900.0]\n[objectives]\n"hardness.core_HRC" = "max"\n')
    err = _one_line(capsys, ["optimise", str(study), "--out", str(tmp_path / "opt"), "--quiet"])
    assert err.startswith(f"quenchsim: error: {study}: study.trials = 0: must be >= 1"), err
    cal = _copy(tmp_path, ROOT / "docs" / "guide" / "calibrate_example" / "ring.cal.toml", r"^uncertainty_K = 2\.0",
                "uncertainty_K = -2.0", "ring.cal.toml")
    err = _one_line(capsys, ["calibrate", str(cal), "--out", str(tmp_path / "cal"), "--quiet"])
    assert err.startswith(f"quenchsim: error: {cal}: measurements[0].uncertainty_K = -2.0: must be > 0 K"), err


def test_a_targets_file_typo_names_its_file(tmp_path):
    from quenchsim.validation import load_targets

    bad = _copy(tmp_path, ROOT / "validation" / "quench" / "ring_a" / "targets.toml", r"^role = ", "rol = ",
                "targets.toml")
    with pytest.raises(InputError) as err:
        load_targets(bad)
    assert re.match(rf"^{re.escape(str(bad))}: targets\[\d+\]\.rol = '.*': unknown keys; \[targets\[\d+\]\] takes "
                    r"metric, source", str(err.value)), str(err.value)


@pytest.mark.parametrize("verb, source, old, new, message", [
    ("big-end", "big_end_rig.toml", r"^cage_kg = ", "cage_mass_kg = ", "masses.cage_mass_kg = 0.00386: unknown key"),
    ("big-end", "big_end_rig.toml", r"^roller_kg = 0\.405e-3", "roller_kg = -0.405e-3",
     "masses.roller_kg = -0.000405: must be > 0 kg"),
    ("runout", "runout_hdd_first_order.toml", r"^balls = ", "ballz = ", "bearing.ballz = "),
])
def test_a_bearing_case_typo_names_its_file(tmp_path, capsys, verb, source, old, new, message):
    bad = _copy(tmp_path, ROOT / "cases" / source, old, new)
    err = _one_line(capsys, ["bearings", verb, str(bad), "--json"])
    assert err.startswith(f"quenchsim: error: {bad}: {message}"), err


def test_every_shipped_data_file_and_example_loads_through_the_reader():
    """Every TOML file shipped (cases/, materials/) and every example of the guides (docs/guide/) read by its kind's
    loader: nothing is left unread, and none fails."""
    from quenchsim.bath.config import read_baths_file
    from quenchsim.bearings.big_end.case import load_case as load_big_end
    from quenchsim.bearings.big_end.lubricant import load_oil as load_lubricant
    from quenchsim.bearings.runout.case import load_case as load_runout
    from quenchsim.calibration.spec import load_calibration
    from quenchsim.fitting.diagram_data import load_diagram_data
    from quenchsim.fitting.jominy import load_bar
    from quenchsim.inputs.bath import ConstantsFile, LayoutFile
    from quenchsim.inputs.quenchant import read_quenchant
    from quenchsim.inputs.reader import read_toml
    from quenchsim.inputs.tempering import TemperingData
    from quenchsim.materials import load_steel
    from quenchsim.sweep import load_sweep

    files = sorted([*ROOT.glob("cases/*.toml"), *ROOT.glob("materials/**/*.toml"), *ROOT.glob("docs/guide/**/*.toml")])
    read: set[Path] = set()
    for path in files:
        table = read_toml(path)
        if path.parent.name == "cases" or path.name == "ring.toml":
            if "geometry" in table:
                for condition in table.get("conditions") or [None]:
                    load_case(path, condition)
            elif "sweep" in table:
                load_sweep(path)
            elif "masses" in table:
                load_big_end(path)
            else:
                load_runout(path)
        elif path.suffixes[-2:] == [".cal", ".toml"]:
            load_calibration(path)
        elif path.parent == ROOT / "materials" and not path.name.endswith(".mechanics.toml"):
            steel = load_steel(str(path))
            mechanics = path.with_name(f"{path.stem}.mechanics.toml")
            read.update({mechanics} if steel.mechanics is not None and mechanics.is_file() else set())
            if isinstance(steel.tempering, TemperingData):   # the tempering data it names (materials/data/...)
                read.add(ROOT / "materials" / "data" / "tempering_1C_Cr.toml")
        elif path.parent.name == "baths":
            read_baths_file(str(path), LayoutFile if table["kind"] == "nozzle_layout" else ConstantsFile, "file")
        elif "quenchants" in path.parts:
            read_quenchant(path, "file")
        elif path.parent.name == "lubricants":
            load_lubricant(path.stem, 70.0)
        elif path.name == "jominy_bar.toml":
            load_bar(path)
        elif path.name == "austenite_flow.toml":   # read by the maintainers' dev/austenite_flow.py only
            assert "zener_hollomon" in table or table
        elif any(key in table for key in ("cct", "ttt", "jominy", "data_from")):
            load_diagram_data(path)
        else:
            continue
        read.add(path)
    assert sorted(set(files) - read) == [], "files no loader read"


def test_a_tempering_data_typo_names_its_file(tmp_path, capsys):
    for original in (STEEL, MECHANICS):
        (tmp_path / original.name).write_text(original.read_text())
    (tmp_path / "data").mkdir()
    bad = _copy(tmp_path / "data", ROOT / "materials" / "data" / "tempering_1C_Cr.toml", r'^law = "quadratic_in_P"',
                'law = "quadratic"')
    err = _one_line(capsys, ["run", str(_steel_case(tmp_path)), "--condition", "1", "--set", "temper.temperature_C=180",
                             "--set", "temper.time_s=7200", "--out", str(tmp_path / "run"), "--quiet"])
    assert err.startswith(f"quenchsim: error: {bad}: hardness.law = 'quadratic': must be one of linear_in_P, "
                          "quadratic_in_P; did you mean quadratic_in_P?"), err
