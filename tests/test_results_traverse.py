"""The mid-width traverses of the final part stay on the P1 mesh the nodal fields live on, where a curved
(quadratic) surface of the outline bulges beyond the mesh's straight edges (a calibration draw of ring A failed
there with 'Point is outside of the mesh')."""

import numpy as np
import skfem

from quenchsim.results.summary import FinalSection, hardness_traverse, residual_traverse


def _section(bulge_m: float) -> FinalSection:
    """A 40 x 20 mm wall (r 100-140 mm) as a P1 mesh, its outline with the OD's mid-height point pushed out by
    ``bulge_m`` (as a quadratic edge's middle node would be)."""
    mesh = skfem.MeshTri.init_tensor(np.linspace(0.100, 0.140, 9), np.linspace(0.0, 0.020, 5))
    outline = np.array([[0.100, 0.0], [0.140, 0.0], [0.140 + bulge_m, 0.010], [0.140, 0.020], [0.100, 0.020]])
    return FinalSection.of(mesh.p, mesh.t, outline)


def test_traverses_start_inside_the_mesh_where_the_outline_bulges_beyond_it():
    final = _section(5e-6)
    z, r_bore, r_od = final.mid_width()
    assert abs(r_od - 0.140 - 5e-6) < 1e-12
    gap_bore, gap_od = final.mesh_gaps(z, r_bore, r_od)
    assert gap_bore == 0.0 and abs(gap_od - 5e-6) < 1e-12
    nodal = final.p1.mesh.p[0] * 1e3   # a linear field: HRC = r in mm
    depth_od, hrc_od = hardness_traverse(final, nodal, "od")
    # the depth is from the outline's surface: it starts at the gap (5 um) + 1 um, on the mesh
    assert abs(depth_od[0] - 6e-3) < 1e-9 and abs(hrc_od[0] - 139.999) < 1e-9
    depth_bore, hrc_bore = hardness_traverse(final, nodal, "bore")
    assert abs(depth_bore[-1] - 39.999) < 1e-9   # mm: the wall 40.005 mm at the outline, ending 6 um short and abs(hrc_bore[-1] - 139.999) < 1e-9
    r_mm, hoop, _ = residual_traverse(final, {"stress_tt_Pa": nodal * 1e6, "stress_zz_Pa": nodal * 0})
    assert abs(r_mm[-1] - 139.999) < 1e-9 and np.allclose(hoop, r_mm)


def test_traverses_are_unchanged_where_the_outline_is_the_mesh_boundary():
    final = _section(0.0)
    nodal = final.p1.mesh.p[0] * 1e3
    depth, hrc = hardness_traverse(final, nodal, "bore")
    assert np.allclose(depth, np.linspace(1e-6, 0.040 - 1e-6, 400) * 1e3, rtol=0, atol=1e-12)
    assert np.allclose(hrc, 100.0 + depth)
