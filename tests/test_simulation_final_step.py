"""The end of a run: the closing step to room temperature (only once the part has cooled to the air
stage's tolerance, and then only athermal martensite), the honest hot state of a stage that ended early,
and interruption by SIGTERM / Ctrl-C (status "interrupted", no traceback)."""

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

import quenchsim.closing
from quenchsim.case import case_from_dict
from quenchsim.closing import close_at_room_temperature
from quenchsim.pipeline import QuenchRun


def warm_ring() -> dict:
    """A 5 mm wall 100Cr6 ring (the peer's kinetics) whose air stage ends while it is still ~150-250 C."""
    htc = {"T_C": [0.0, 900.0], "h_W_m2K": [1500.0, 1500.0], "ambient_C": 60.0}
    return {
        "name": "warm_ring", "material": "100Cr6_furlan",
        "geometry": {"type": "rectangular", "inner_diameter_mm": 40.0, "outer_diameter_mm": 50.0,
                     "width_mm": 10.0, "chamfer_mm": 0.5},
        "mesh": {"size_mm": 2.5, "surface_size_mm": 1.25, "surface_layer_mm": 2.5},
        "process": {"austenitising_temperature_C": 850.0, "room_temperature_C": 20.0},
        "quench": {"time_s": 10.0, "htc_model": "table", "htc_table": htc},
        "air": {"time_s": 1.0, "htc_model": "table", "htc_table": {**htc, "h_W_m2K": [10.0, 10.0]}},
        "output": {"frames": 3},
        "mechanics": {"enabled": False},
        "probes": [{"name": "mid", "r_mm": 22.5, "z_mm": 5.0}],
    }


def test_closing_step_forms_martensite_but_no_diffusional_product(tmp_path, monkeypatch):
    seen = {}
    closing = close_at_room_temperature

    def recorded(run):
        seen["T_C"] = run.thermal.T_qp.copy()
        seen["before"] = {p: v.copy() for p, v in run.thermal.fractions().items()}
        closing(run)
        seen["after"] = run.thermal.fractions()

    monkeypatch.setattr(quenchsim.closing, "close_at_room_temperature", recorded)
    case = warm_ring()
    case["air"]["until_max_C"] = 260.0   # the user's tolerance: close the run once the part is below 260 C
    QuenchRun(case_from_dict(case), tmp_path, progress=False).run()
    before, after = seen["before"], seen["after"]
    assert seen["T_C"].max() > 150.0 and seen["T_C"].min() < 229.0   # warm, partly below Ms: KM still to go
    for phase in ("bainite", "pearlite"):
        assert np.array_equal(after[phase], before[phase])
    assert after["martensite"].mean() > before["martensite"].mean() + 0.2


def test_a_stage_that_ends_hot_reports_the_hot_state_without_martensite_above_Ms(tmp_path):
    """A 3 s quench and a 1 s air stage end with the core still above Ms, far above air.until_max_C: no closing
    step, the summary says so, and no martensite exists where the part is still above Ms."""
    case = warm_ring()
    case["quench"]["time_s"] = 3.0
    run = QuenchRun(case_from_dict(case), tmp_path, progress=False)
    result = run.run()
    end = result.summary["end_state"]
    assert end["at_room_temperature"] is False
    assert end["max_temperature_C"] > 150.0 and "still hot" in end["note"]
    hot = run.thermal.T_qp > run.kin.Ms_C + 1.0
    assert hot.any()
    assert float(run.thermal.fractions()["martensite"][hot].max()) < 1e-12
    assert json.loads((tmp_path / "summary.json").read_text())["end_state"]["at_room_temperature"] is False


def _slow_ring_case(path: Path) -> Path:
    case = warm_ring()
    case["air"] = {"time_s": 5000.0, "temperature_C": 20.0, "until_max_C": 21.0, "htc_model": "table",
                   "htc_table": {"T_C": [0.0, 900.0], "h_W_m2K": [2.0, 2.0], "ambient_C": 20.0}}
    case["time"] = {"dt_max_s": 0.05}
    path.write_text(tomli_w.dumps(case))
    return path


@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGINT])
def test_a_signal_leaves_status_interrupted_and_no_traceback(tmp_path, sig):
    case = _slow_ring_case(tmp_path / "slow.toml")
    out = tmp_path / "run"
    proc = subprocess.Popen([sys.executable, "-m", "quenchsim.cli", "run", str(case), "--out", str(out), "--quiet"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=Path(__file__).parents[1],
                            env={**os.environ, "PYTHONPATH": str(Path(__file__).parents[1])},
                            preexec_fn=default_ctrl_c)
    deadline = time.time() + 120
    while time.time() < deadline and not (out / "probes.csv").is_file():
        time.sleep(0.2)
    wait_s = random.Random().uniform(0.2, 2.5)  # somewhere in the quench stage
    print(f"{sig.name} {wait_s:.2f} s after the first probe row")
    time.sleep(wait_s)
    proc.send_signal(sig)
    stdout, stderr = proc.communicate(timeout=120)
    summary = json.loads((out / "summary.json").read_text())
    assert proc.returncode == 130, stderr
    assert "Traceback" not in stderr and len(stderr.strip().splitlines()) <= 3, stderr
    assert summary["status"] == "interrupted"
    assert 0.0 < summary["stopped_at_s"] < 5000.0
    assert summary["end_state"]["at_room_temperature"] is False
    assert (out / "checkpoint.npz").is_file()        # the last committed step, to continue with --resume
