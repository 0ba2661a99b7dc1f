"""The revolved 3-D view (volumes, wedge orientation, vector rotation) and the off-screen `quenchsim view`."""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path

import matplotlib.image as mpimg
import meshio
import numpy as np
import pytest

from quenchsim.io import VtkSeries
from quenchsim.io.revolve import revolve_mesh, revolve_vtu


def rectangle(r0: float, r1: float, z0: float, z1: float, n: int = 4) -> tuple[np.ndarray, np.ndarray]:
    """A structured triangulation of [r0, r1] x [z0, z1]; every other triangle clockwise on purpose."""
    r, z = np.meshgrid(np.linspace(r0, r1, n + 1), np.linspace(z0, z1, n + 1), indexing="ij")
    pts = np.column_stack([r.ravel(), z.ravel(), np.zeros(r.size)])
    idx = np.arange(r.size).reshape(n + 1, n + 1)
    tris = []
    for i in range(n):
        for j in range(n):
            a, b, c, d = idx[i, j], idx[i + 1, j], idx[i + 1, j + 1], idx[i, j + 1]
            tris += [[a, b, c], [a, d, c]]          # the second is clockwise in (r, z)
    return pts, np.array(tris)


def _volumes(mesh: meshio.Mesh) -> np.ndarray:
    import pyvista

    return np.asarray(pyvista.from_meshio(mesh).compute_cell_sizes(length=False, area=False)["Volume"])


@pytest.mark.parametrize("angle, segments", [(270.0, 54), (360.0, 36), (90.0, 3)])
def test_revolved_volume_is_the_polygonal_ring_and_every_wedge_is_positive(angle, segments):
    r0, r1, z0, z1 = 0.10, 0.15, 0.0, 0.17
    pts, tris = rectangle(r0, r1, z0, z1)
    mesh = revolve_mesh(pts, tris, {}, angle, segments)
    vol = _volumes(mesh)
    assert np.all(vol > 0)
    step = math.radians(angle) / segments
    # the chord-sided (polygonal) annulus: N sectors of area (r1^2 - r0^2) sin(step) / 2, times the height
    exact = segments * 0.5 * (r1 ** 2 - r0 ** 2) * math.sin(step) * (z1 - z0)
    assert vol.sum() == pytest.approx(exact, rel=1e-9)
    # and Pappus (area x centroid path) within the chord error sin(step)/step
    pappus = (r1 - r0) * (z1 - z0) * 0.5 * (r0 + r1) * math.radians(angle)
    assert vol.sum() / pappus == pytest.approx(math.sin(step) / step, rel=1e-9)
    n_stations = segments if angle == 360.0 else segments + 1
    assert len(mesh.points) == n_stations * len(pts)
    assert len(mesh.cells_dict["wedge"]) == segments * len(tris)


def test_vectors_are_rotated_and_scalars_copied():
    pts, tris = rectangle(0.02, 0.03, 0.0, 0.01, n=2)
    radial = np.column_stack([pts[:, 0] * 1e-3, np.full(len(pts), 2e-5), np.zeros(len(pts))])   # (u_r, u_z, u_t)
    mesh = revolve_mesh(pts, tris, {"displacement_m": radial, "hardness_HRC": pts[:, 1] * 1e3}, 270.0, 9)
    x, y, z = mesh.points.T
    u = mesh.point_data["displacement_m"]
    rho = np.hypot(x, y)
    assert np.allclose(u[:, 0] * x + u[:, 1] * y, rho * rho * 1e-3, atol=1e-15)   # radial part u_r = 1e-3 r
    assert np.allclose(u[:, 0] * y - u[:, 1] * x, 0.0, atol=1e-15)                 # no tangential part
    assert np.allclose(u[:, 2], 2e-5)
    assert np.allclose(mesh.point_data["hardness_HRC"], z * 1e3)
    angles = np.degrees(np.arctan2(y, x)) % 360.0
    assert angles.max() == pytest.approx(270.0)


def test_revolve_vtu_writes_a_wedge_file_with_all_point_data(tmp_path):
    pts, tris = rectangle(0.02, 0.03, 0.0, 0.01, n=2)
    data = {"temperature_C": pts[:, 0] * 1e4, "displacement_m": np.zeros((len(pts), 3))}
    meshio.write(tmp_path / "s.vtu", meshio.Mesh(pts, [("triangle", tris)], point_data=data))
    out = revolve_vtu(tmp_path / "s.vtu", tmp_path / "final_3d.vtu")
    back = meshio.read(out)
    assert list(back.cells_dict) == ["wedge"] and len(back.cells_dict["wedge"]) == 54 * len(tris)
    assert set(back.point_data) == set(data)
    assert back.point_data["displacement_m"].shape == (55 * len(pts), 3)


def _run_dir(tmp_path: Path) -> Path:
    pts, tris = rectangle(0.10915, 0.1505, 0.0, 0.173, n=6)
    run = tmp_path / "run"
    run.mkdir()
    series = VtkSeries(run, pts[:, :2].T, tris.T)
    hrc = 60.0 - 200.0 * np.minimum(pts[:, 0] - 0.10915, 0.1505 - pts[:, 0])
    disp = np.column_stack([1e-4 * np.ones(len(pts)), -5e-5 * pts[:, 1] / 0.173, np.zeros(len(pts))])
    for t in (0.0, 10.0):
        series.write(t, {"hardness_HRC": hrc + t, "displacement_m": disp})
    return run


def _renders() -> tuple[bool, str]:
    """Can VTK render off-screen here? (It needs Mesa EGL or an X server.)"""
    code = ("import pyvista as pv; pv.OFF_SCREEN = True; p = pv.Plotter(off_screen=True, window_size=(64, 64)); "
            "p.add_mesh(pv.Sphere()); p.screenshot(None); print('rendered')")
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    return "rendered" in res.stdout, res.stderr[-500:]


def test_view_renders_the_section_and_the_3d_sector_off_screen(tmp_path):
    ok, why = _renders()
    if not ok:
        pytest.skip(f"VTK cannot render off-screen here (Debian: libegl1 libegl-mesa0 libgl1-mesa-dri): {why}")
    run = _run_dir(tmp_path)
    for extra, name in (([], "flat.png"), (["--3d", "--warp", "10"], "sector.png")):
        res = subprocess.run([sys.executable, "-m", "quenchsim.cli", "view", str(run), "--field", "hardness_HRC",
                              "--png", str(tmp_path / name), "--size", "400", "300", *extra],
                             capture_output=True, text=True, timeout=180)
        assert res.returncode == 0, res.stderr
        img = mpimg.imread(tmp_path / name)
        assert img.shape[:2] == (300, 400)
        colours = np.unique((img[..., :3] * 255).astype(np.uint8).reshape(-1, 3), axis=0)
        assert len(colours) > 50                      # a coloured field, not a blank window


def test_view_names_an_unknown_field(tmp_path):
    run = _run_dir(tmp_path)
    res = subprocess.run([sys.executable, "-m", "quenchsim.cli", "view", str(run), "--field", "nonsense"],
                         capture_output=True, text=True, timeout=120)
    assert res.returncode == 2
    assert "--field = 'nonsense'" in res.stderr and "hardness_HRC" in res.stderr
