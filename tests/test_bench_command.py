"""dev/bench.py (the maintainers' benchmark): the mesh scaling it asks for, the results it compares, and its bad-input
errors."""

import subprocess
import sys

import importlib.util
from pathlib import Path

BENCH = Path(__file__).resolve().parents[1] / "dev" / "bench.py"
_spec = importlib.util.spec_from_file_location("dev_bench", BENCH)
bench = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(bench)


def test_mesh_overrides_scale_both_element_sizes_of_the_case(tmp_path):
    case = tmp_path / "c.toml"
    case.write_text("[mesh]\nsize_mm = 5.0\nsurface_size_mm = 1.2\n")
    assert bench.mesh_overrides(case, 1.0) == []
    assert bench.mesh_overrides(case, 0.5) == ["--set", "mesh.size_mm=2.5", "--set", "mesh.surface_size_mm=0.6"]


def test_compared_results_and_their_differences():
    summary = {"dimensions_mm": {"change": {"id": 0.29, "od": 0.45}},
               "probes": {"P1": {"t_to_500C_s": 44.1}, "P2": {"t_to_500C_s": None}},
               "hardness": {"depth_mm": {"HRC58_bore_mid": 41.7}},
               "residual_stress_MPa": {"hoop": {"od_surface_mid": 114.0}}}
    old = bench.results_of(summary)
    assert old == {"dimension_change_id_mm": 0.29, "dimension_change_od_mm": 0.45, "t500_P1_s": 44.1,
                   "HRC58_bore_mid_mm": 41.7, "hoop_od_surface_mid_MPa": 114.0}
    new = dict(old, t500_P1_s=44.15)
    diff = bench.largest_differences([{"results": old}], [{"results": new}])
    assert abs(diff["t500_s"] - 0.05) < 1e-12 and diff["dimension_mm"] == 0.0


def test_a_baseline_is_required_exactly_once():
    for extra in ([], ["--baseline-python", sys.executable, "--baseline-commit", "HEAD"]):
        proc = subprocess.run([sys.executable, str(BENCH), *extra], capture_output=True, text=True)
        assert proc.returncode == 2 and "--baseline" in proc.stderr


def test_a_reference_without_summary_is_refused_before_any_run(tmp_path):
    proc = subprocess.run([sys.executable, str(BENCH), "--baseline-python", sys.executable,
                           "--reference", str(tmp_path), "--work", str(tmp_path / "work")],
                          capture_output=True, text=True)
    assert proc.returncode == 2 and "--reference" in proc.stderr
    assert not (tmp_path / "work").exists() or not any((tmp_path / "work").iterdir())


def test_report_states_cpu_ratio_overrides_and_differences_from_the_reference():
    diffs = {"dimension_mm": 0.0015, "t500_s": 0.3, "depth_mm": 0.2, "hoop_MPa": 2.3}
    row = {"mesh_factor": 1.0, "dofs": 4941, "steps": 725, "baseline_steps": 725, "baseline_wall_s": 60.0,
           "current_wall_s": 40.0, "speedup": 1.5, "baseline_cpu_s": 50.0, "current_cpu_s": 25.0, "cpu_speedup": 2.0,
           "baseline_loop_us_per_dof_step": 20.0, "current_loop_us_per_dof_step": 10.0, "largest_differences": diffs,
           "from_reference": {"baseline": diffs, "current": dict(diffs, hoop_MPa=1.0)},
           "stages": {"thermal_metallurgy_s": (30.0, 10.0), "mechanics_s": (20.0, 15.0)},
           "equality": {"summary_numbers": 141, "summary_max_rel": 1.4e-12, "summary_max_rel_key": "residual.hoop",
                        "only_baseline": [], "only_current": ["probes.P1.HRC"], "probe_values": 1962,
                        "probes_same_shape": True, "probes_max_rel": 0.0},
           "runs": {"baseline": [{"load_1min": 4.2}], "current": [{"load_1min": 5.5}]}}
    record = {"case": "c.toml", "condition": "1", "machine": "m", "repeat": 1, "load_before": 1.0, "load_after": 1.0,
              "baseline": "b", "current": "c", "rows": [row], "overrides": ["time.max_dX=0.01"], "reference": "runs/fine"}
    text = bench.markdown(record)
    assert "**2.00**" in text and "`time.max_dX=0.01`" in text and "725 / 725" in text
    assert "`runs/fine`" in text and "hoop 1 MPa" in text
    assert "| thermal_metallurgy_s | 30.00 | 10.00 | **3.00** |" in text and "4.2-5.5 before the single runs" in text
    assert "| 141 | 1.4e-12 (`residual.hoop`) | 1962 | 0 | none | `probes.P1.HRC` |" in text


def _run_folder(path, summary, probes):
    path.mkdir()
    (path / "summary.json").write_text(__import__("json").dumps(summary))
    (path / "probes.csv").write_text("time_s,P1\n" + "\n".join(f"{t},{T}" for t, T in probes) + "\n")
    return path


def test_the_sides_are_compared_on_every_summary_number_and_probe_value_but_the_timings(tmp_path):
    old = _run_folder(tmp_path / "old", {"solver": {"wall_time_s": 30.0, "stage_time_s": {"mechanics_s": 20.0},
                                                    "steps": 325}, "dims": [1.0, 2.0], "status": "ok",
                                         "probes": {"P1": {"t_to_500C_s": 8.0}}},
                      [(0.0, 845.0), (1.0, 700.0)])
    new = _run_folder(tmp_path / "new", {"solver": {"wall_time_s": 10.0, "stage_time_s": {"mechanics_s": 5.0},
                                                    "steps": 325}, "dims": [1.0, 2.0 * (1 + 1e-12)], "status": "ok",
                                         "probes": {"P1": {"t_to_500C_s": 8.0, "HRC": 61.0}}},
                      [(0.0, 845.0), (1.0, 700.0 * (1 - 2e-13))])
    eq = bench.equality(old, new)
    assert eq["summary_numbers"] == 4      # steps, the two dims, t500: the timings are left out
    assert abs(eq["summary_max_rel"] - 1e-12) < 1e-15 and eq["summary_max_rel_key"] == "dims[1]"
    assert eq["only_current"] == ["probes.P1.HRC"] and eq["only_baseline"] == []
    assert eq["probe_values"] == 4 and abs(eq["probes_max_rel"] - 2e-13) < 1e-16
