"""Parameter sweeps: spec parsing, results table, failures, resume after a kill, Dask by address."""

from __future__ import annotations

import importlib.util
import json
import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import pytest
import tomli_w
from conftest import default_ctrl_c

from quenchsim.errors import InputError
from quenchsim.results import files
from quenchsim.sweep import (RESULTS_CSV, case_hash, case_names, finished, load_sweep, make_sweep, read_results,
                             run_sweep)

ROOT = Path(__file__).resolve().parents[1]


def _example():
    spec = importlib.util.spec_from_file_location("example_sweep_script", ROOT / "cases" / "example_sweep_script.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def small_case() -> dict:
    """A 5 mm wall ring on a 4 mm mesh, 20 s oil + 10 s air, thermal and phases only: ~1 s of CPU per case (the
    part is still warm at the end: status "hot", a finished case)."""
    case = _example().build_case(wall_mm=5.0, mesh_mm=4.0, quench_time_s=20.0, air_time_s=10.0)
    case["mechanics"] = {"enabled": False}
    return case


def test_grid_times_zip_gives_every_combination_once():
    spec = make_sweep(small_case(), grid={"quench": {"time_s": [10.0, 20.0]}, "mesh.size_mm": [3.0, 4.0, 5.0]},
                      zipped={"process.austenitising_temperature_C": [830.0, 860.0], "air.time_s": [5.0, 6.0]},
                      fixed={"output.frames": 3})
    assert spec.parameters == ["quench.time_s", "mesh.size_mm", "process.austenitising_temperature_C", "air.time_s"]
    assert len(spec.points) == 2 * 3 * 2
    combos = {tuple(p[k] for k in spec.parameters) for p in spec.points}
    assert len(combos) == 12
    # zipped fields move together
    assert all((p["process.austenitising_temperature_C"], p["air.time_s"]) in ((830.0, 5.0), (860.0, 6.0))
               for p in spec.points)
    assert all(spec.overrides(p)["output.frames"] == 3 for p in spec.points)
    names = case_names(spec.parameters, spec.points)
    assert len(set(names)) == len(names)
    assert names[0] == "quench.time_s=10_size_mm=3_austenitising_temperature_C=830_air.time_s=5"


def test_colliding_short_names_use_longer_tails():
    names = case_names(["quench.time_s", "air.time_s"], [{"quench.time_s": 1.0, "air.time_s": 2.0}])
    assert names == ["quench.time_s=1_air.time_s=2"]


@pytest.mark.parametrize("kwargs, field", [
    ({"grid": {"quench.time_s": 10.0}}, "grid.quench.time_s"),
    ({"grid": {"quench.time_s": []}}, "grid.quench.time_s"),
    ({"grid": {"quench.nonexistent.speed": [1.0]}}, "quench.nonexistent.speed"),
    ({"zipped": {"quench.time_s": [1.0, 2.0], "air.time_s": [1.0]}}, "zip"),
    ({"grid": {"quench.time_s": [1.0]}, "fixed": {"quench.time_s": 2.0}}, "sweep parameters"),
    ({}, "grid"),
    ({"grid": {"quench.time_s": [1.0]}, "fixed": {"mesh.size_mm": -2.0}}, "mesh.size_mm"),
])
def test_bad_sweep_inputs_name_the_field(kwargs, field):
    with pytest.raises(InputError) as err:
        make_sweep(small_case(), **kwargs)
    assert err.value.field == field


def test_sweep_file_resolves_the_case_relative_to_itself(tmp_path):
    (tmp_path / "ring.toml").write_text(tomli_w.dumps(small_case()))
    (tmp_path / "s.toml").write_text('[sweep]\ncase = "ring.toml"\n[set]\n"output.frames" = 3\n'
                                     '[grid.quench]\ntime_s = [5.0, 6.0]\n')
    spec = load_sweep(tmp_path / "s.toml")
    assert spec.case_path == (tmp_path / "ring.toml").resolve()
    assert spec.fixed == {"output.frames": 3} and len(spec.points) == 2
    (tmp_path / "bad.toml").write_text('[sweep]\ncase = "missing.toml"\n[grid]\n"quench.time_s" = [1.0]\n')
    with pytest.raises(InputError, match="sweep.case"):
        load_sweep(tmp_path / "bad.toml")


def test_nozzle_sweep_file_has_six_ring_a_cases_over_jet_speeds():
    spec = load_sweep(ROOT / "cases" / "sweep_nozzles.toml")
    assert spec.case_path.name == "crb_outer_ring.toml"
    assert len(spec.points) >= 6
    ids = {p["quench.bath.id_jet_speed_mm_s"] for p in spec.points}
    ods = {p["quench.bath.od_jet_speed_mm_s"] for p in spec.points}
    assert len(ids) >= 2 and len(ods) >= 2


def test_an_invalid_case_value_stops_the_sweep_before_any_run(tmp_path):
    with pytest.raises(InputError, match=r"sweep case size_mm=-1: mesh.size_mm = -1.0: must be > 0"):
        make_sweep(small_case(), grid={"mesh.size_mm": [-1.0, 4.0]})
    assert not any(tmp_path.iterdir())


def test_failed_case_is_recorded_and_the_rest_go_on_and_rerun_skips_finished(tmp_path, monkeypatch):
    import quenchsim.pipeline
    from quenchsim.errors import SolverError

    real_run = quenchsim.pipeline.run

    def run_failing_at_3mm(case, out, progress=True):
        if case.mesh.size_mm == 3.0:
            raise SolverError("the stress solver did not converge (a failure during the run)")
        return real_run(case, out, progress)

    monkeypatch.setattr(quenchsim.pipeline, "run", run_failing_at_3mm)
    spec = make_sweep(small_case(), grid={"mesh.size_mm": [3.0, 4.0]})
    first = run_sweep(spec, tmp_path, workers=0, progress=False)
    assert (first.ran, first.failed, first.skipped) == (2, 1, 0)
    rows = {r["case"]: r for r in read_results(tmp_path / RESULTS_CSV)}
    assert rows["size_mm=3"]["status"] == "failed" and "did not converge" in rows["size_mm=3"]["error"]
    ok = rows["size_mm=4"]
    summary = json.loads((tmp_path / "size_mm=4" / "summary.json").read_text())
    assert ok["status"] == "hot" and ok["mesh.size_mm"] == 4.0
    assert ok["hardness.core_HRC"] == pytest.approx(summary["hardness"]["core_HRC"])
    assert ok["probes.near_bore.t_to_500C_s"] == pytest.approx(summary["probes"]["near_bore"]["t_to_500C_s"])
    mtime = (tmp_path / "size_mm=4" / "summary.json").stat().st_mtime_ns

    second = run_sweep(spec, tmp_path, workers=0, progress=False)
    assert (second.skipped, second.ran, second.failed) == (1, 1, 1)      # the failed case is tried again
    assert (tmp_path / "size_mm=4" / "summary.json").stat().st_mtime_ns == mtime

    # a changed input (here the base case) is not mistaken for a finished case
    changed = make_sweep({**small_case(), "output": {"frames": 3}}, grid={"mesh.size_mm": [4.0]})
    third = run_sweep(changed, tmp_path, workers=0, progress=False)
    assert (third.skipped, third.ran) == (0, 1)

    # nor is a case that another quenchsim version or other material data computed
    import quenchsim.sweep
    monkeypatch.setattr(quenchsim.sweep, "run_fingerprint", lambda: "another version")
    fourth = run_sweep(changed, tmp_path, workers=0, progress=False)
    assert (fourth.skipped, fourth.ran) == (0, 1)


def test_ctrl_c_keeps_every_finished_case_and_a_rerun_does_the_rest(tmp_path):
    spec = make_sweep(small_case(), grid={"quench.time_s": [20.0, 21.0, 22.0]})

    def ctrl_c_after_the_first_case(row):
        raise KeyboardInterrupt

    first = run_sweep(spec, tmp_path, workers=0, progress=False, on_result=ctrl_c_after_the_first_case)
    assert first.interrupted and (first.ran, first.pending) == (1, 2)
    assert [r["status"] for r in read_results(tmp_path / RESULTS_CSV)] == ["hot"]
    second = run_sweep(spec, tmp_path, workers=0, progress=False)
    assert (second.skipped, second.ran, second.pending, second.interrupted) == (1, 2, 0, False)


def _sweep_file(tmp_path: Path, n: int) -> Path:
    (tmp_path / "ring.toml").write_text(tomli_w.dumps(small_case()))
    times = ", ".join(str(20.0 + i) for i in range(n))
    path = tmp_path / "sweep.toml"
    path.write_text(f'[sweep]\ncase = "ring.toml"\n[grid]\n"quench.time_s" = [{times}]\n')
    return path


def _hash(sweep: Path, case: str) -> str:
    spec = load_sweep(sweep)
    point = dict(zip(case_names(spec.parameters, spec.points), spec.points))[case]
    return case_hash(spec.raw_case, spec.condition, spec.overrides(point))


def _ok_rows(csv_path: Path) -> list[dict]:
    try:
        return [r for r in read_results(csv_path) if r["status"] in files.FINISHED_STATUSES]
    except (OSError, KeyError):
        return []


@pytest.mark.parametrize("sig", [signal.SIGKILL, signal.SIGINT], ids=["kill -9", "ctrl-c"])
def test_killed_sweep_rerun_finishes_only_the_missing_cases(tmp_path, sig):
    # ten ~1 s cases on two workers: a Dask worker may hold a second queued case besides the running one,
    # so a sweep interrupted after its first results still has cases that never started
    n = 10
    sweep, out = _sweep_file(tmp_path, n), tmp_path / "out"
    cmd = [sys.executable, "-m", "quenchsim.cli", "sweep", str(sweep), "--workers", "2", "--out", str(out), "--quiet"]
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True,
                            preexec_fn=default_ctrl_c)
    try:
        deadline = time.monotonic() + 240
        while not _ok_rows(out / RESULTS_CSV) and proc.poll() is None and time.monotonic() < deadline:
            time.sleep(0.05)
        # the whole process group, like a terminal's Ctrl-C; SIGKILL: the sweep and its workers, no clean-up
        os.killpg(proc.pid, sig)
    finally:
        stdout, _ = proc.communicate(timeout=120)
    if sig == signal.SIGINT:
        assert proc.returncode == 130 and '"interrupted": true' in stdout
    # finished = a case folder whose summary.json says ok; a worker may finish a case after the last
    # results.csv update and before the kill lands: that case is finished too (and must not run again)
    listed = {r["case"] for r in _ok_rows(out / RESULTS_CSV)}
    done = {p.parent.name for p in out.glob("*/summary.json") if finished(p.parent, _hash(sweep, p.parent.name))}
    assert listed <= done and 1 <= len(done) < n, "the sweep was to be killed midway"
    mtimes = {c: (out / c / "summary.json").stat().st_mtime_ns for c in done}

    rerun = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    assert rerun.returncode == 0, rerun.stderr
    outcome = json.loads(rerun.stdout[rerun.stdout.index("{"):rerun.stdout.rindex("}") + 1])
    assert outcome["skipped"] == len(done) and outcome["ran"] == n - len(done) and outcome["pending"] == 0
    assert {c: (out / c / "summary.json").stat().st_mtime_ns for c in done} == mtimes
    assert len(_ok_rows(out / RESULTS_CSV)) == n


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def test_sweep_runs_on_a_separately_started_scheduler(tmp_path):
    from dask.distributed import Client

    port = _free_port()
    address = f"tcp://127.0.0.1:{port}"
    dask = [sys.executable, "-m", "dask"]
    procs = [subprocess.Popen([*dask, "scheduler", "--host", "127.0.0.1", "--port", str(port), "--no-dashboard"],
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)]
    try:
        procs.append(subprocess.Popen([*dask, "worker", address, "--nworkers", "1", "--nthreads", "1",
                                       "--no-dashboard", "--local-directory", str(tmp_path / "worker")],
                                      stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        with Client(address, timeout="60s") as client:
            client.wait_for_workers(1, timeout=120)
            worker_pids = set(client.run(os.getpid).values())
        spec = make_sweep(small_case(), grid={"quench.time_s": [20.0, 25.0]})
        outcome = run_sweep(spec, tmp_path / "out", scheduler=address, progress=False)
        assert (outcome.ran, outcome.failed) == (2, 0)
        assert all(r["status"] == "hot" for r in read_results(tmp_path / "out" / RESULTS_CSV))
        assert os.getpid() not in worker_pids
    finally:
        for p in reversed(procs):
            p.terminate()
        for p in procs:
            try:
                p.wait(timeout=30)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait()


def test_example_case_script_runs_and_a_thicker_wall_ends_softer(tmp_path):
    res = subprocess.run([sys.executable, str(ROOT / "cases" / "example_sweep_script.py"), "--out", str(tmp_path),
                          "--walls-mm", "5", "15", "--quench-time-s", "60", "--air-time-s", "20"],
                         capture_output=True, text=True, timeout=300)
    assert res.returncode == 0, res.stderr
    assert (tmp_path / "hardness_vs_wall.png").stat().st_size > 5000
    rows = read_results(tmp_path / RESULTS_CSV)
    assert [r["status"] for r in rows] == ["hot", "hot"] and "note: still hot at the end" in res.stdout
    thin, thick = rows
    assert thick["hardness.core_HRC"] < thin["hardness.core_HRC"]


_FAULTS_SCRIPT = """
import resource, sys
import numpy as np
from quenchsim.sweep import keep_freed_memory

def faults_per_array():
    before = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
    for _ in range(20):
        a = np.ones(500_000)
        del a
    return (resource.getrusage(resource.RUSAGE_SELF).ru_minflt - before) / 20

under_dask = faults_per_array()
ok = keep_freed_memory()
faults_per_array()  # the first array grows the heap once
print(under_dask, ok, faults_per_array())
"""


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="glibc malloc")
def test_keep_freed_memory_stops_page_faults_of_reallocated_arrays():
    """A fresh interpreter started like a Dask nanny's worker (MALLOC_TRIM_THRESHOLD_=65536, which also fixes
    glibc's mmap threshold at 128 KiB) maps every 4 MB array afresh (~1000 page faults); after
    keep_freed_memory() the freed block is reused (none)."""
    env = {**os.environ, "MALLOC_TRIM_THRESHOLD_": "65536"}
    out = subprocess.run([sys.executable, "-c", _FAULTS_SCRIPT], capture_output=True, text=True, env=env, timeout=120)
    assert out.returncode == 0, out.stderr
    under_dask, ok, after = out.stdout.split()
    assert float(under_dask) > 500 and ok == "True" and float(after) < 10, out.stdout


def test_an_unreachable_scheduler_is_one_line(tmp_path, monkeypatch):
    import quenchsim.sweep

    monkeypatch.setattr(quenchsim.sweep, "SCHEDULER_TIMEOUT_S", 1.0)
    spec = make_sweep(small_case(), grid={"quench.time_s": [20.0]})
    address = f"tcp://127.0.0.1:{_free_port()}"        # nothing listens there
    with pytest.raises(InputError, match=r"--scheduler = 'tcp://127\.0\.0\.1:\d+': no Dask scheduler answered within 1 s"):
        run_sweep(spec, tmp_path, scheduler=address, progress=False)


def test_run_on_dask_keeps_different_case_tables_apart(monkeypatch):
    """Two base case tables in one call, and another in a second call on the same scheduler (a design study's next
    batch): each case runs its own table (a scattered dict shares its keys with every other dict on the scheduler)."""
    from dask.distributed import LocalCluster

    from quenchsim import sweep

    monkeypatch.setattr(sweep, "run_point", lambda raw, *rest: {"status": "ok", "error": None,
                                                               "summary": {"t": raw["quench"]["time_s"]}})
    seen: dict = {}
    cluster = LocalCluster(n_workers=1, threads_per_worker=1, processes=False, dashboard_address=":0")
    try:
        record = lambda name, result: seen.__setitem__(name, result["summary"]["t"])  # noqa: E731
        sweep.run_on_dask({"a": ({"quench": {"time_s": 1.0}}, None, None, {}, "a"),
                           "b": ({"quench": {"time_s": 2.0}}, None, None, {}, "b")}, cluster.scheduler_address, 0, record)
        sweep.run_on_dask({"c": ({"quench": {"time_s": 3.0}}, None, None, {}, "c")}, cluster.scheduler_address, 0, record)
    finally:
        cluster.close()
    assert seen == {"a": 1.0, "b": 2.0, "c": 3.0}
