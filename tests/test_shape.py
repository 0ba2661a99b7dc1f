"""Shape measures of the finished outline (quenchsim.results.shape): prescribed displacement fields with a
closed-form taper, crown, straightness and face dish; the exact spherical raceway; rigid motion drops out."""

import numpy as np
import pytest
from skfem import Basis, ElementTriP2, ElementVector

from quenchsim.geometry.profile import MM, spherical_outer_ring
from quenchsim.mechanics import ring_dimensions, section_outline
from quenchsim.mechanics import verification as v
from quenchsim.results.shape import MEASURES, shape_change, shape_measures

R_IN, R_OUT, W = 100.0, 120.0, 50.0   # mm; gauge inset 5 mm: heights 5 / 25 / 45, face radii 102 / 118


def rectangle(n: int = 101) -> np.ndarray:
    """A closed counter-clockwise rectangular section outline (mm) with a vertex every 0.5 mm on the bore and
    the OD (every gauge height a vertex, so a quadratic field is exact on it) and every 0.2 mm on the faces."""
    z = np.linspace(0.0, W, n)
    r = np.linspace(R_IN, R_OUT, n)
    return np.vstack([np.column_stack([r, np.zeros(n)])[:-1], np.column_stack([np.full(n, R_OUT), z])[:-1],
                      np.column_stack([r[::-1], np.full(n, W)])[:-1], np.column_stack([np.full(n, R_IN), z[::-1]])[:-1]])


def moved(outline: np.ndarray, ur, uz) -> np.ndarray:
    r, z = outline[:, 0], outline[:, 1]
    return np.column_stack([r + ur(r, z), z + uz(r, z)])


def zero(r, z):
    return np.zeros_like(r)


def test_conical_field_gives_the_exact_taper_and_no_crown():
    a = 1e-3   # u_r = a z: every diameter grows by 2 a z
    after = moved(rectangle(), lambda r, z: a * z, zero)
    shape = shape_change(rectangle(), after)
    assert shape["gauge"]["inset_mm"] == pytest.approx(5.0)
    for side in ("bore", "od"):
        assert shape["change"][f"{side}_taper"] == pytest.approx(2 * a * (45.0 - 5.0), abs=1e-12)
        assert shape["change"][f"{side}_at_mid"] == pytest.approx(2 * a * 25.0, abs=1e-12)
        assert shape["change"][f"{side}_crown"] == pytest.approx(0.0, abs=1e-12)
        assert shape["after"][f"{side}_straightness"] == pytest.approx(0.0, abs=1e-12)


def test_barrel_field_gives_the_exact_crown_and_straightness():
    b = 1e-4   # u_r = b (z - 25)^2: an hourglass bore and OD (smaller at mid-width): crown -2 b 20^2
    after = moved(rectangle(), lambda r, z: b * (z - 25.0) ** 2, zero)
    m = shape_change(rectangle(), after)["change"]
    for side in ("bore", "od"):
        assert m[f"{side}_crown"] == pytest.approx(-2 * b * 20.0 ** 2, abs=1e-12)
        assert m[f"{side}_straightness"] == pytest.approx(2 * b * 20.0 ** 2, abs=1e-12)
        assert m[f"{side}_taper"] == pytest.approx(0.0, abs=1e-12)
    # an odd (S-shaped) field has no crown at mid-width, but straightness sees it: max |2 c s^3 - line|
    c = 1e-6
    s_shape = shape_measures(moved(rectangle(), lambda r, z: c * (z - 25.0) ** 3, zero), 5.0)
    s = np.linspace(-20.0, 20.0, 41)
    assert s_shape["bore_crown"] == pytest.approx(0.0, abs=1e-12)
    assert s_shape["bore_straightness"] == pytest.approx(np.max(np.abs(2 * c * s ** 3 - 2 * c * 20.0 ** 3 * s / 20.0)),
                                                         rel=1e-9)


def test_coned_face_gives_the_exact_dish():
    c = 2e-3   # u_z = c (r - R_IN) z / W: the top face coned, the bottom one flat, bore and OD stay vertical
    after = moved(rectangle(), zero, lambda r, z: c * (r - R_IN) * z / W)
    m = shape_change(rectangle(), after)["change"]
    assert m["top_face_dish"] == pytest.approx(c * (118.0 - 102.0), abs=1e-12)
    assert m["bottom_face_dish"] == pytest.approx(0.0, abs=1e-12)
    assert m["bore_taper"] == pytest.approx(0.0, abs=1e-12) and m["od_crown"] == pytest.approx(0.0, abs=1e-12)


def test_rigid_axial_translation_changes_no_measure():
    after = moved(rectangle(), lambda r, z: 1e-4 * (z - 25.0) ** 2 + 1e-3 * z, lambda r, z: 1e-3 * (r - R_IN))
    lifted = after + np.array([0.0, 3.7])
    a, b = shape_measures(after, 5.0), shape_measures(lifted, 5.0)
    assert all(a[k] == pytest.approx(b[k], abs=1e-10) for k in MEASURES)


def test_spherical_raceway_crown_is_the_sagitta_of_the_sphere():
    """Ring B's section (raceway 427.0 at mid-width, width 118.5 mm): the crown of the bore over the gauge length
    is 2 (R - sqrt(R^2 - h^2)) with h the half gauge length, to the chord error of the polygon."""
    profile = spherical_outer_ring(427.0 * MM, 460.6 * MM, 118.5 * MM, chamfer_m=1.5 * MM)
    outline = profile.polygon(4000) / MM
    m = shape_measures(outline, 11.85)
    R, h = 213.5, 118.5 / 2 - 11.85
    assert m["bore_at_mid"] == pytest.approx(427.0, abs=1e-4)
    assert m["bore_crown"] == pytest.approx(2 * (R - np.sqrt(R ** 2 - h ** 2)), abs=1e-4)
    assert m["od_crown"] == pytest.approx(0.0, abs=1e-9) and m["bore_taper"] == pytest.approx(0.0, abs=1e-9)


def test_solid_section_has_no_bore_measures():
    solid = np.array([[0.0, 0.0], [20.0, 0.0], [20.0, 50.0], [0.0, 50.0]])
    m = shape_measures(solid, 5.0)
    assert m["bore_at_mid"] is None and m["bore_crown"] is None and m["bore_taper"] is None
    assert m["od_at_mid"] == pytest.approx(40.0) and m["top_face_dish"] == pytest.approx(0.0)


def test_measures_on_a_displaced_P2_mesh_outline_match_the_caliper_dimensions():
    """The run's own outline (mechanics.section_outline of a P2 mesh) with a conical P2 field: the taper is exact
    and the bore/OD at mid-width are the run's ID/OD of dimensions_mm."""
    mesh = v.tube_mesh(0.10, 0.12, 0.05, 6)
    basis = Basis(mesh, ElementVector(ElementTriP2()))
    a = 1e-3
    u = basis.project(lambda x: np.stack([a * x[1], 0.0 * x[0]]))
    before = section_outline(mesh) / MM
    after = section_outline(mesh, u) / MM
    shape = shape_change(before, after)
    dims = ring_dimensions(mesh, u)
    assert shape["after"]["bore_at_mid"] == pytest.approx(dims["id"], abs=1e-9)
    assert shape["after"]["od_at_mid"] == pytest.approx(dims["od"], abs=1e-9)
    assert shape["change"]["bore_taper"] == pytest.approx(2 * a * 40.0, abs=1e-9)
