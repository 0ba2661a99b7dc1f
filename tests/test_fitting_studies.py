"""The material pages (validation/materials/<steel>/): each study's metrics meet its targets (open targets excepted)."""

from __future__ import annotations

import importlib.util
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _study(steel: str):
    spec = importlib.util.spec_from_file_location(f"study_{steel}", ROOT / "validation" / "materials" / steel / "study.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _missed(metrics: dict, steel: str) -> list[str]:
    with (ROOT / "validation" / "materials" / steel / "targets.toml").open("rb") as fh:
        targets = tomllib.load(fh)["targets"]
    missed = []
    for t in targets:
        assert t["source"].strip(), t["metric"]
        if t.get("status") == "open":
            continue
        v = metrics[t["metric"]]
        ok = (("min" not in t or v >= t["min"]) and ("max" not in t or v <= t["max"])
              and ("tolerance" not in t or abs(v - t["value"]) <= t["tolerance"])
              and ("rel_tolerance" not in t or abs(v - t["value"]) <= t["rel_tolerance"] * abs(t["value"])))
        if not ok:
            missed.append(f"{t['metric']} = {v}")
    return missed


@pytest.mark.slow
@pytest.mark.parametrize("steel", ["SUJ2", "SUJ3"])
def test_material_study_meets_its_targets(steel, tmp_path):
    study = _study(steel)
    metrics = study.run(tmp_path)
    assert not _missed(metrics, steel)
    assert study.page(metrics).count("|") > 20
    assert any(p.suffix == ".png" for p in tmp_path.iterdir())
