"""What a user meets in the first hour (issue 36): statuses that are true in every output, run folders that hold
one run's outputs only, and refusals before any work."""

from __future__ import annotations

import contextlib
import io
import json
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from quenchsim.cli import main
from quenchsim.commands.run import summary_table
from quenchsim.report.run_report import write_report
from quenchsim.results import files

ROOT = Path(__file__).resolve().parents[1]
CYLINDER = ROOT / "cases" / "solid_cylinder_still_oil.toml"
STALE_FRAMES = 61


@pytest.fixture(scope="module")
def hot_run(tmp_path_factory) -> dict:
    """The still-oil cylinder quenched 30 s and not cooled in air (`--set air.time_s=0`, the part still hot), run
    with --json into the folder of an earlier run that wrote more frames than this one does."""
    out = tmp_path_factory.mktemp("hot") / "run"
    out.mkdir()
    (out / files.CASE_TOML).write_text('name = "earlier"\n')
    (out / files.SUMMARY_JSON).write_text(json.dumps({"status": "ok", "end_state": {"at_room_temperature": True}}))
    for i in range(STALE_FRAMES):
        (out / f"{files.SERIES_NAME}_{i:04d}.vtu").write_text("stale")
    stdout, raised = io.StringIO(), None
    with contextlib.redirect_stdout(stdout):
        try:
            rc = main(["run", str(CYLINDER), "--set", "quench.time_s=30", "--set", "air.time_s=0", "--out", str(out),
                       "--quiet", "--json"])
        except Exception as exc:  # noqa: BLE001 -- the test of --json says what was raised; the others go on
            rc, raised = None, exc
    return {"out": out, "rc": rc, "stdout": stdout.getvalue(), "raised": raised}


def test_a_material_without_hardness_prints_its_json(hot_run):
    """`quenchsim run cases/solid_cylinder_still_oil.toml --json` raised KeyError 'hardness' after writing the
    results (the steel of the example does not transform)."""
    assert hot_run["raised"] is None and hot_run["rc"] == 0
    printed = json.loads(hot_run["stdout"])
    assert "hardness" not in printed and "does not transform" in printed["notes"][0]
    assert printed["status"] == "hot"


def test_a_part_still_hot_at_the_end_is_not_ok(hot_run, tmp_path):
    """summary.json, --json and the report said "ok" for a part at hundreds of degrees at the end of the run."""
    summary = json.loads((hot_run["out"] / files.SUMMARY_JSON).read_text())
    assert not summary["end_state"]["at_room_temperature"]
    assert summary["status"] == "hot"
    table = summary_table(summary, hot_run["out"])
    assert "status hot" in table and "WARNING: the part is still hot" in table
    html = write_report([hot_run["out"]], tmp_path / "r.html")[0].read_text()
    assert "Status: hot." in html and "Status: ok" not in html and "WARNING: the part is still hot" in html


def test_a_rerun_clears_the_earlier_runs_frames_and_summary(hot_run):
    """A second run into a folder with fewer frames left the first run's results_*.vtu beside a .pvd listing
    its own (and an earlier summary.json would say "ok" for a run killed before writing its own)."""
    out = hot_run["out"]
    listed = {ds.get("file") for ds in ET.parse(out / files.SERIES_PVD).getroot().iter("DataSet")}
    on_disk = {p.name for p in out.glob(f"{files.SERIES_NAME}_*.vtu")}
    assert len(listed) < STALE_FRAMES and on_disk == listed
    assert all("stale" not in (out / name).read_text()[:10] for name in on_disk)


def test_a_run_refuses_a_foreign_non_empty_folder_before_writing(tmp_path, capsys):
    folder = tmp_path / "my_documents"
    folder.mkdir()
    (folder / "thesis.tex").write_text("precious")
    assert main(["run", str(CYLINDER), "--out", str(folder), "--quiet"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and str(folder) in err and "--force" in err
    assert sorted(p.name for p in folder.iterdir()) == ["thesis.tex"]


def test_a_mesh_size_larger_than_the_section_is_refused_before_any_work(tmp_path, capsys):
    """`--mesh-size 1000` ran the whole simulation and then failed with "Point is outside of the mesh"."""
    out = tmp_path / "run"
    assert main(["run", str(CYLINDER), "--mesh-size", "1000", "--out", str(out), "--quiet"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "mesh.size_mm = 1000.0: must be > 0 and at most 100 mm" in err[0]
    assert not out.exists()


def test_force_writes_into_a_foreign_folder_and_removes_nothing_of_its_own(tmp_path):
    from quenchsim.results.writer import claim_run_folder

    (tmp_path / "notes.txt").write_text("mine")
    claim_run_folder(tmp_path, force=True)
    assert (tmp_path / "notes.txt").read_text() == "mine"


def test_the_terminal_says_through_hardened_instead_of_the_wall(tmp_path):
    """Ring B through-hardened printed "HRC58 depth ... bore 16.83, od 16.83": the wall, read as a case depth."""
    summary = {"case": "ring_b", "condition": "4", "status": "ok", "solver": {"steps": 10, "wall_time_s": 1.0},
               "end_state": {"at_room_temperature": True}, "probes": {},
               "hardness": {"depth_mm": {"HRC58_bore_mid": 16.83, "HRC58_od_mid": 16.83}, "core_HRC": 61.2,
                            "threshold_HRC": 58.0, "through_hardened": True, "through_hardened_mid": True}}
    table = summary_table(summary, tmp_path)
    assert "through-hardened" in table and "16.83" not in table


@pytest.mark.parametrize("summary, status", [
    ({"status": "interrupted", "stopped_at_s": 12.5, "end_state": {"at_room_temperature": False}}, "interrupted"),
    ({"status": "ok", "end_state": {"at_room_temperature": False, "max_temperature_C": 752.0, "time_s": 65.0}},
     "hot"),   # written before the status "hot" existed
])
def test_the_report_of_an_unfinished_run_says_so(tmp_path, summary, status):
    run = tmp_path / "run"
    run.mkdir()
    (run / files.CASE_TOML).write_text('name = "ring"\n')
    (run / files.SUMMARY_JSON).write_text(json.dumps({"case": "ring", "condition": "1", **summary}))
    html = write_report([run], tmp_path / "r.html")[0].read_text()
    assert f"Status: {status}." in html and "WARNING: " in html


def test_the_top_level_help_names_every_command(capsys):
    """Its description listed 10 of the 14 commands."""
    from quenchsim.cli import COMMANDS

    with pytest.raises(SystemExit):
        main(["--help"])
    description = capsys.readouterr().out.split("positional arguments")[0]
    words = set(description.replace("|", " ").split())
    assert set(COMMANDS) | {"bearings"} <= words


def test_mesh_help_documents_its_arguments(capsys):
    with pytest.raises(SystemExit):
        main(["mesh", "--help"])
    lines = capsys.readouterr().out.splitlines()
    case_line = next(line for line in lines if line.strip().startswith("case "))
    assert "case file (TOML)" in case_line
    at = next(i for i, line in enumerate(lines) if line.strip().startswith("--condition"))
    assert "named condition" in " ".join(lines[at:at + 2])
