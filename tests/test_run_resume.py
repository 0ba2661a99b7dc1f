"""Checkpoints and ``--resume``: a run stopped at a random step (SIGTERM from inside the step loop, or a signal
to a CLI process at a random time) and resumed ends with the result of an uninterrupted run (every summary
number within 1e-6 relative, the same probe rows and VTK frames); a checkpoint of another case or format is refused."""

import json
import os
import random
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import tomli_w
from conftest import default_ctrl_c
from test_simulation_final_step import warm_ring

import quenchsim as qs
from quenchsim.case import case_from_dict
from quenchsim.cli import main
from quenchsim.errors import InputError, RunInterrupted
from quenchsim.io.checkpoint import FORMAT_VERSION as CHECKPOINT_FORMAT
from quenchsim.results import files
from quenchsim.thermal.solver import ThermalSolver

ROOT = Path(__file__).resolve().parents[1]
TIMINGS = ("wall_time_s", "stage_time_s")


def plastic_ring() -> dict:
    """The small ring in a steel with plasticity, TRIP and martensite (every part of the state matters)."""
    case = warm_ring()
    case["material"] = "SUJ3"
    case["mechanics"] = {"enabled": True}
    case["quench"]["htc_table"]["h_W_m2K"] = [3000.0, 3000.0]
    case["air"] = {"time_s": 20000.0, "temperature_C": 20.0, "until_max_C": 40.0, "htc_model": "table",
                   "htc_table": {"T_C": [0.0, 900.0], "h_W_m2K": [200.0, 200.0], "ambient_C": 20.0}}
    return case


def assert_same_summary(expected, actual, path="summary", rtol=1e-6):
    """Every number of two summaries within ``rtol`` relative (timings excepted), every other value equal."""
    if isinstance(expected, dict):
        keys = set(expected) - set(TIMINGS)
        assert keys == set(actual) - set(TIMINGS), path
        for key in keys:
            assert_same_summary(expected[key], actual[key], f"{path}.{key}", rtol)
    elif isinstance(expected, list):
        assert len(expected) == len(actual), path
        for i, (a, b) in enumerate(zip(expected, actual)):
            assert_same_summary(a, b, f"{path}[{i}]", rtol)
    elif isinstance(expected, float) and not isinstance(expected, bool):
        assert actual == pytest.approx(expected, rel=rtol, abs=1e-300), path
    else:
        assert actual == expected, path


def assert_same_files(reference: Path, resumed: Path) -> None:
    """The same files, and the same text in the probe, frame-index and traverse files."""
    assert sorted(p.name for p in resumed.iterdir()) == sorted(p.name for p in reference.iterdir())
    for name in (files.PROBES_CSV, files.SERIES_PVD, files.HARDNESS_TRAVERSE_CSV, files.RESIDUAL_TRAVERSE_CSV,
                 files.OUTLINE_CSV):
        if (reference / name).exists():
            assert (resumed / name).read_text() == (reference / name).read_text(), name
    assert not (resumed / files.CHECKPOINT_NPZ).exists()     # a completed run leaves nothing to resume


def handled_ring() -> dict:
    """The plastic ring moved through 2 s of air from the furnace and lowered into the oil at 20 mm/s."""
    case = plastic_ring()
    case["transfer"] = {"time_s": 2.0}
    case["quench"]["immersion_speed_mm_s"] = 20.0
    return case


def solid_cylinder():
    """A solid, non-transforming cylinder hanging in still library oil, thermal only (the other phase model)."""
    return qs.load_case(ROOT / "cases" / "solid_cylinder_still_oil.toml")


@pytest.mark.parametrize("make_case", [lambda: case_from_dict(plastic_ring()), lambda: case_from_dict(handled_ring()),
                                       solid_cylinder],
                         ids=["plastic_ring", "transfer_and_immersion", "solid_cylinder"])
def test_a_run_stopped_at_a_random_step_resumes_to_the_uninterrupted_result(tmp_path, monkeypatch, make_case):
    case = make_case()
    reference = qs.run(case, tmp_path / "reference", progress=False)
    steps = reference.summary["solver"]["steps"]
    stop_at = random.Random().randint(1, steps - 1)
    print(f"SIGTERM after step {stop_at} of {steps}")
    commit, committed = ThermalSolver.commit, []

    def commit_then_signal(solver, step):
        commit(solver, step)
        committed.append(solver.time_s)
        if len(committed) == stop_at:
            os.kill(os.getpid(), signal.SIGTERM)     # handled as a stop request after this step

    monkeypatch.setattr(ThermalSolver, "commit", commit_then_signal)
    with pytest.raises(RunInterrupted, match="--resume"):
        qs.run(case, tmp_path / "run", progress=False)
    monkeypatch.setattr(ThermalSolver, "commit", commit)
    stopped = json.loads((tmp_path / "run" / files.SUMMARY_JSON).read_text())
    assert stopped["status"] == "interrupted" and stopped["stopped_at_s"] == committed[-1]
    assert (tmp_path / "run" / files.CHECKPOINT_NPZ).is_file()
    resumed = qs.run(case, tmp_path / "run", progress=False, resume=True)
    assert resumed.summary["status"] == "ok"
    assert_same_summary(reference.summary, resumed.summary)
    assert_same_files(tmp_path / "reference", tmp_path / "run")


@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGINT])
def test_kill_at_a_random_time_then_resume_on_the_command_line(tmp_path, sig):
    raw = plastic_ring()
    raw["time"] = {"dt_max_s": 0.05}            # ~1500 steps: a few seconds to be stopped in
    raw["output"] = {"checkpoint_minutes": 0.01}
    case_file = tmp_path / "ring.toml"
    case_file.write_text(tomli_w.dumps(raw))
    command = [sys.executable, "-m", "quenchsim.cli", "run", str(case_file), "--out", str(tmp_path / "run"), "--quiet"]
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    proc = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=ROOT, env=env,
                            preexec_fn=default_ctrl_c)
    deadline = time.time() + 120
    while time.time() < deadline and not (tmp_path / "run" / files.PROBES_CSV).is_file():
        time.sleep(0.05)
    wait_s = random.Random().uniform(0.0, 2.0)
    print(f"signal {sig.name} {wait_s:.2f} s after the first probe row")
    time.sleep(wait_s)
    proc.send_signal(sig)
    _, stderr = proc.communicate(timeout=120)
    assert proc.returncode == 130, stderr
    assert "Traceback" not in stderr and "--resume" in stderr, stderr
    stopped = json.loads((tmp_path / "run" / files.SUMMARY_JSON).read_text())
    assert stopped["status"] == "interrupted"
    resumed = subprocess.run(command + ["--resume"], capture_output=True, text=True, cwd=ROOT, env=env, timeout=300)
    assert resumed.returncode == 0, resumed.stderr
    reference = qs.run(case_from_dict(raw), tmp_path / "reference", progress=False)
    assert_same_summary(reference.summary, json.loads((tmp_path / "run" / files.SUMMARY_JSON).read_text()))
    assert_same_files(tmp_path / "reference", tmp_path / "run")


def test_resume_refuses_another_case_and_a_folder_without_checkpoint(tmp_path, monkeypatch, capsys):
    raw = plastic_ring()
    case = case_from_dict(raw)
    with pytest.raises(InputError, match="holds no checkpoint.npz"):
        qs.run(case, tmp_path / "empty", progress=False, resume=True)
    assert not (tmp_path / "empty").exists()
    commit = ThermalSolver.commit

    def stop_after_a_second(solver, step):
        commit(solver, step)
        if solver.time_s - step.dt_s < 1.0 <= solver.time_s:
            os.kill(os.getpid(), signal.SIGTERM)

    monkeypatch.setattr(ThermalSolver, "commit", stop_after_a_second)
    with pytest.raises(RunInterrupted):
        qs.run(case, tmp_path / "run", progress=False)
    monkeypatch.setattr(ThermalSolver, "commit", commit)
    case_file = tmp_path / "ring.toml"
    case_file.write_text(tomli_w.dumps(raw))
    before = sorted(p.name for p in (tmp_path / "run").iterdir())
    assert main(["run", str(case_file), "--out", str(tmp_path / "run"), "--resume", "--quiet",
                 "--set", "quench.time_s=12.0"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "its run is of another case (quench.time_s: 10.0 there, 12.0 here)" in err[0], err
    assert sorted(p.name for p in (tmp_path / "run").iterdir()) == before   # nothing touched
    # a checkpoint of another format version (written by an older quenchsim) is refused by its format
    checkpoint = tmp_path / "run" / files.CHECKPOINT_NPZ
    written = checkpoint.read_bytes()
    with np.load(checkpoint) as data:
        arrays = dict(data)
    header = json.loads(str(arrays["__header__"]))
    arrays["__header__"] = np.array(json.dumps({**header, "format": CHECKPOINT_FORMAT - 1}))
    np.savez(checkpoint, **arrays)
    assert main(["run", str(case_file), "--out", str(tmp_path / "run"), "--resume", "--quiet"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and f"is of checkpoint format {CHECKPOINT_FORMAT - 1}, this version reads " \
        f"{CHECKPOINT_FORMAT}" in err[0], err
    checkpoint.write_bytes(written)
    # how often to checkpoint changes no result: resuming with another interval is the same case
    assert main(["run", str(case_file), "--out", str(tmp_path / "run"), "--resume", "--quiet",
                 "--set", "output.checkpoint_minutes=1"]) == 0


def test_ctrl_c_while_meshing_leaves_an_interrupted_summary(tmp_path, monkeypatch):
    import quenchsim.quench_setup as quench_setup

    def interrupted_meshing(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(quench_setup, "build_section", interrupted_meshing)
    with pytest.raises(RunInterrupted, match="during setup"):
        qs.run(case_from_dict(plastic_ring()), tmp_path / "run", progress=False)
    stopped = json.loads((tmp_path / "run" / files.SUMMARY_JSON).read_text())
    assert stopped["status"] == "interrupted" and stopped["stopped_at_s"] == 0.0
    assert "setup" in stopped["error"]


def test_ctrl_c_while_post_processing_is_finished_by_resume(tmp_path, monkeypatch):
    import quenchsim.pipeline as pipeline

    case = case_from_dict(plastic_ring())
    reference = qs.run(case, tmp_path / "reference", progress=False)
    summary = pipeline.QuenchRun.summary

    def interrupted_summary(self, *args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(pipeline.QuenchRun, "summary", interrupted_summary)
    with pytest.raises(RunInterrupted, match="post-processing"):
        qs.run(case, tmp_path / "run", progress=False)
    monkeypatch.setattr(pipeline.QuenchRun, "summary", summary)
    stopped = json.loads((tmp_path / "run" / files.SUMMARY_JSON).read_text())
    assert stopped["status"] == "interrupted" and "post-processing" in stopped["error"]
    resumed = qs.run(case, tmp_path / "run", progress=False, resume=True)
    assert_same_summary(reference.summary, resumed.summary)
    assert_same_files(tmp_path / "reference", tmp_path / "run")


def test_a_second_ctrl_c_while_the_stresses_catch_up_still_leaves_a_summary(tmp_path, monkeypatch):
    """Issue 36: a double Ctrl-C left no summary.json. The first stops the step loop; the second lands in the
    stress catch-up of the interrupted state: the run still records what it computed, as interrupted."""
    import quenchsim.pipeline as pipeline

    def stop_after_a_second(solver, step):
        commit(solver, step)
        if solver.time_s > 1.0:
            os.kill(os.getpid(), signal.SIGINT)

    def catch_up_interrupted(self):
        if self.stop.requested:     # the second Ctrl-C, in the catch-up of the interrupted state
            raise KeyboardInterrupt
        return catch_up(self)

    commit, catch_up = ThermalSolver.commit, pipeline.QuenchRun.catch_up_stresses
    monkeypatch.setattr(ThermalSolver, "commit", stop_after_a_second)
    monkeypatch.setattr(pipeline.QuenchRun, "catch_up_stresses", catch_up_interrupted)
    with pytest.raises(RunInterrupted, match="--resume"):
        qs.run(case_from_dict(plastic_ring()), tmp_path / "run", progress=False)
    stopped = json.loads((tmp_path / "run" / files.SUMMARY_JSON).read_text())
    assert stopped["status"] == "interrupted" and stopped["stopped_at_s"] > 1.0
    assert "interrupted again" in stopped["end_state"]["note"]
    assert (tmp_path / "run" / files.CHECKPOINT_NPZ).exists()
