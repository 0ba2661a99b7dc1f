"""The last VTK frame and probes.csv tell the same end (issue 36: "the last frame is 25.0 C everywhere while
probes.csv says 39.4-39.8 C at the same time"): the last frame's temperature at every probe position equals the last
row of probes.csv, at the same time, for a run that closes at room temperature and for one that ends hot. ~15 s."""

from __future__ import annotations

import csv
import json
import xml.etree.ElementTree as ET
import tomllib
from pathlib import Path

import meshio
import numpy as np
import pytest
from scipy.interpolate import griddata

from quenchsim.cli import main
from quenchsim.results import files

ROOT = Path(__file__).resolve().parents[1]
CYLINDER = ROOT / "cases" / "solid_cylinder_still_oil.toml"
TOLERANCE_K = 0.05
"""Linear interpolation of the frame's P1 nodal temperatures at a probe against the probe's own interpolation of the
same field: equal up to the rounding of the .vtu/.csv output (a hot run) or exactly (room temperature everywhere)."""


@pytest.mark.parametrize("air_time_s, status", [(None, "ok"), ("0", "hot")])
def test_the_last_frame_shows_what_the_last_probe_row_says(tmp_path, air_time_s, status):
    out = tmp_path / "run"
    extra = ["--set", f"air.time_s={air_time_s}"] if air_time_s else []
    assert main(["run", str(CYLINDER), "--mesh-size", "6", "--set", "quench.time_s=30", *extra, "--out", str(out),
                 "--quiet"]) == 0
    assert json.loads((out / files.SUMMARY_JSON).read_text())["status"] == status
    rows = list(csv.reader((out / files.PROBES_CSV).open()))
    header, last = rows[0], [float(x) for x in rows[-1]]
    datasets = ET.parse(out / files.SERIES_PVD).getroot().iter("DataSet")
    final = list(datasets)[-1]
    assert float(final.get("timestep")) == pytest.approx(last[0], abs=1e-6)
    frame = meshio.read(out / final.get("file"))
    case = tomllib.loads((out / files.CASE_TOML).read_text())
    probes_rz = np.array([[p["r_mm"], p["z_mm"]] for p in case["probes"]]) * 1e-3
    T_frame = griddata(frame.points[:, :2], frame.point_data["temperature_C"], probes_rz, method="linear")
    assert [f"{p['name']}_C" for p in case["probes"]] == header[1:]
    np.testing.assert_allclose(T_frame, last[1:], atol=TOLERANCE_K)
    if status == "ok":
        assert last[1:] == pytest.approx([case["process"]["room_temperature_C"]] * len(case["probes"]))
    else:
        assert min(last[1:]) > 100.0
