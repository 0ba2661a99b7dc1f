"""`quenchsim bench`: the mesh scaling it asks for, the results it compares, and its bad-input errors."""

import subprocess
import sys

from quenchsim.commands import bench


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
        proc = subprocess.run([sys.executable, "-m", "quenchsim.cli", "bench", *extra], capture_output=True, text=True)
        assert proc.returncode == 2 and "--baseline" in proc.stderr
