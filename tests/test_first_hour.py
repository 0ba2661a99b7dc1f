"""docs/guide/first_hour.md, tried as a new user would: every command of its ```bash blocks is run, in order, in a
fresh folder (the ```console install block is tests/test_install.py's). `quenchsim` and `python3` run as this
interpreter with this checkout on PYTHONPATH; the guide's own commands copy the example files in. ~60-90 s."""

from __future__ import annotations

import json
import os
import re
import shlex
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
GUIDE = ROOT / "docs" / "guide" / "first_hour.md"
EXAMPLES = ("first_hour_probe_curve.csv", "first_hour_ttt.toml")
"""The example files the guide's last steps read, copied into the user's folder by its `quenchsim cases copy`."""
FENCE = re.compile(r"^```(\w+)\n(.*?)^```", re.MULTILINE | re.DOTALL)


def guide_commands(text: str) -> tuple[list[str], list[str]]:
    """The commands of the guide's ```bash blocks (``\\``-continued lines joined, comments dropped), and those of its
    ```console blocks (shown, not run here)."""
    run, shown = [], []
    for lang, body in FENCE.findall(text):
        lines = [ln.split(" #")[0].rstrip() for ln in body.replace("\\\n", " ").splitlines()]
        commands = [ln.strip() for ln in lines if ln.strip() and not ln.lstrip().startswith("#")]
        (run if lang == "bash" else shown).extend(commands)
    return run, shown


def _argv(command: str) -> list[str]:
    argv = shlex.split(command)
    if argv[0] == "quenchsim":
        return [sys.executable, "-m", "quenchsim.cli", *argv[1:]]
    assert argv[0] == "python3", f"the first-hour guide runs quenchsim and python3 only, not: {command}"
    return [sys.executable, *argv[1:]]


@pytest.fixture(scope="module")
def first_hour(tmp_path_factory) -> dict:
    folder = tmp_path_factory.mktemp("first_hour")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])}
    run, shown = guide_commands(GUIDE.read_text())
    results = []
    for command in run:
        r = subprocess.run(_argv(command), cwd=folder, env=env, capture_output=True, text=True, timeout=300)
        results.append((command, r))
        if r.returncode != 0:
            break
    return {"folder": folder, "run": run, "shown": shown, "results": results}


def test_every_command_of_the_guide_succeeds(first_hour):
    assert len(first_hour["run"]) >= 6
    assert first_hour["shown"] == ['python3 -m pip install -e ".[dev]"']   # the only one not run here
    for command, r in first_hour["results"]:
        assert r.returncode == 0, f"{command}\n{r.stderr}"
    assert len(first_hour["results"]) == len(first_hour["run"])
    for example in EXAMPLES:   # copied by the guide's commands, as shipped
        assert (first_hour["folder"] / example).read_bytes() == (ROOT / "docs" / "guide" / example).read_bytes()


def test_the_guide_lists_copies_and_runs_a_shipped_case_by_name(first_hour):
    folder, outputs = first_hour["folder"], {c: r.stdout for c, r in first_hour["results"]}
    assert "crb_outer_ring" in outputs["quenchsim cases"] and "conditions: 1, 2, 3" in outputs["quenchsim cases"]
    copied = folder / "my_cases" / "crb_outer_ring.toml"
    assert copied.read_text() == (ROOT / "cases" / "crb_outer_ring.toml").read_text()
    summary = json.loads((folder / "runs" / "first" / "summary.json").read_text())
    assert summary["case"] == "crb_outer_ring" and summary["condition"] == "1" and summary["status"] == "ok"
    assert summary["dimensions_mm"]["change"]["od"] > 0.0   # ring A's OD grows in the model (README)
    read = next(r.stdout for c, r in first_hour["results"] if "summary.json" in c)
    assert read.startswith("ok {")


def test_the_guide_fits_an_oil_without_a_source(first_hour):
    oil = tomllib.loads((first_hour["folder"] / "materials" / "quenchants" / "my_oil.toml").read_text())
    assert oil["name"] == "my_oil" and oil["source"] == "not given by the user"
    shown = next(r.stdout for c, r in first_hour["results"] if c.startswith("quenchsim quenchant show"))
    assert shown.startswith("my_oil: bath 40 C") and "not given by the user" in shown


def test_the_guide_runs_the_ring_in_the_users_oil_and_steel_by_name(first_hour):
    folder = first_hour["folder"]
    steel = tomllib.loads((folder / "materials" / "MY_STEEL.toml").read_text())
    assert steel["name"] == "MY_STEEL" and "first_hour_ttt.toml" in steel["description"]
    run = folder / "runs" / "mine"
    case = tomllib.loads((run / "case.toml").read_text())
    assert case["material"] == "MY_STEEL" and case["quench"]["bath"]["quenchant"] == "my_oil"
    assert json.loads((run / "summary.json").read_text())["status"] == "ok"
