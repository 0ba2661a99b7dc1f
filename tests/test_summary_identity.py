"""summary.json names what ran (the quenchsim version, a hash of the resolved case) and compares the finished part
with the case's ``[measured]`` dimensions when they belong to the run's condition (issue 36)."""

from __future__ import annotations

import doctest
import json

import quenchsim as qs
import quenchsim.results.measured as measured_module
from quenchsim.case import case_from_dict
from quenchsim.commands.run import summary_table
from quenchsim.results import files
from quenchsim.results.measured import compare_with_measured, measured_dimensions
from test_run_resume import plastic_ring


def test_the_measured_module_examples_hold():
    assert doctest.testmod(measured_module).failed == 0


def test_measured_values_of_another_condition_are_not_compared():
    case = {"measured": {"before_mm": {"id": 218.3, "od": 301.0}, "after_mm": {"id": 217.9, "od": 300.7},
                         "condition": "1", "source": "Table 3"}}
    assert measured_dimensions(case, "2") == {"before": {}, "after": {}, "change": {}}
    one = compare_with_measured({"change": {"id": 0.032, "od": 0.238}}, case, "1")
    assert one["source"] == "Table 3"
    assert abs(one["change"]["od"]["measured"] + 0.3) < 1e-9
    assert abs(one["change"]["od"]["simulated_minus_measured"] - 0.538) < 1e-9
    unconditioned = {"measured": {k: v for k, v in case["measured"].items() if k != "condition"}}
    assert compare_with_measured({"change": {"id": 0.0}}, unconditioned, "7") is not None   # one-condition cases


def test_the_case_digest_follows_the_inputs_not_the_files_location(tmp_path):
    data = plastic_ring()
    a = case_from_dict(data)
    assert a.digest() == case_from_dict(plastic_ring()).digest() and len(a.digest()) == 16
    assert a.with_overrides({"quench.time_s": a.quench.time_s + 1.0}).digest() != a.digest()


def test_summary_names_the_version_and_the_case_and_compares_with_measured(tmp_path):
    data = plastic_ring()
    case = case_from_dict(data)
    first = qs.run(case, tmp_path / "run", progress=False).summary
    assert first["quenchsim_version"] == qs.__version__ and first["case_sha256"] == case.digest()
    assert "measured" not in first    # the case has no [measured] table
    before = first["dimensions_mm"]["before"]["od"]
    data["measured"] = {"source": "made up for the test", "before_mm": {"od": before}, "after_mm": {"od": before - 0.1}}
    second = qs.run(case_from_dict(data), tmp_path / "run2", progress=False).summary
    row = second["measured"]["change"]["od"]
    assert abs(row["simulated"] - second["dimensions_mm"]["change"]["od"]) < 1e-12
    assert abs(row["simulated_minus_measured"] - (row["simulated"] + 0.1)) < 1e-9
    assert json.loads((tmp_path / "run2" / files.SUMMARY_JSON).read_text())["measured"] == second["measured"]
    table = summary_table(second, tmp_path / "run2")     # the terminal shows the comparison too
    od_row = next(line for line in table.splitlines() if line.startswith("od "))
    assert "sim - meas" in table and "measured: made up for the test" in table
    assert od_row.split()[-2:] == [f"{-0.1:+.3f}", f"{row['simulated_minus_measured']:+.3f}"]
