"""Shapes, poses and the four proximity queries against analytic answers; ProximityPair
against the free functions; errors for bad arguments."""

import math

import numpy as np
import pytest

import hullcheck as hc


def translation(x, y, z):
    m = np.eye(4)
    m[:3, 3] = (x, y, z)
    return m


def test_spheres_apart_and_overlapping():
    a, b = hc.Sphere(0.5), hc.Sphere(0.25)
    r = hc.distance(a, translation(0, 0, 0), b, translation(2, 0, 0))
    assert r.status == hc.Status.CONVERGED
    assert r.distance == pytest.approx(1.25, abs=1e-9)
    np.testing.assert_allclose(r.point_a, [0.5, 0, 0], atol=1e-9)
    np.testing.assert_allclose(r.point_b, [1.75, 0, 0], atol=1e-9)
    np.testing.assert_allclose(r.normal, [1, 0, 0], atol=1e-9)
    assert not hc.intersect(a, None, b, translation(2, 0, 0))
    p = hc.penetration(a, None, b, translation(0.6, 0, 0))
    assert p.depth == pytest.approx(0.15, abs=1e-6)
    s = hc.signed_distance(a, None, b, translation(0.6, 0, 0))
    assert s.signed_distance == pytest.approx(-0.15, abs=1e-6)
    assert hc.intersect(a, None, b, translation(0.6, 0, 0))
    # 1.25 apart: within 1.25 + 1e-6, not within 1.25 - 1e-6; overlapping ones within 0.
    assert hc.within_distance(a, None, b, translation(2, 0, 0), 1.25 + 1e-6)
    assert not hc.within_distance(a, None, b, translation(2, 0, 0), 1.25 - 1e-6)
    assert hc.within_distance(a, None, b, translation(0.6, 0, 0), 0.0)
    with pytest.raises(hc.InputError, match="distance"):
        hc.within_distance(a, None, b, None, -1.0)


def test_boxes_and_angles():
    # A unit cube turned 45 degrees about z reaches sqrt(2)/2 along x.
    cube = hc.Box(1, 1, 1)
    turned = ((0, 0, 0), (0, 0, math.pi / 4))
    r = hc.distance(cube, turned, hc.Sphere(0.1), translation(2, 0, 0))
    assert r.distance == pytest.approx(2 - math.sqrt(0.5) - 0.1, abs=1e-9)
    # The same pose as a matrix gives the same answer.
    m = hc.pose_from_xyz_angles((0, 0, 0), (0, 0, math.pi / 4))
    np.testing.assert_allclose(m[:3, :3] @ [1, 0, 0], [math.sqrt(0.5), math.sqrt(0.5), 0],
                               atol=1e-12)
    r2 = hc.distance(cube, m, hc.Sphere(0.1), translation(2, 0, 0))
    assert r2.distance == pytest.approx(r.distance, abs=1e-12)


def test_capsule_cylinder_and_hull():
    capsule = hc.Capsule(radius=0.1, length=1.0)  # z in [-0.6, 0.6] with the caps
    r = hc.distance(capsule, None, hc.Sphere(0.2), translation(0, 0, 1.0))
    assert r.distance == pytest.approx(1.0 - 0.6 - 0.2, abs=1e-9)
    cylinder = hc.Cylinder(radius=0.3, length=0.4)
    r = hc.distance(cylinder, None, hc.Sphere(0.1), translation(1.0, 0, 0))
    assert r.distance == pytest.approx(1.0 - 0.3 - 0.1, abs=1e-9)
    corners = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
    hull = hc.ConvexHull(np.vstack([corners, [[0.5, 0.5, 0.5]]]))
    assert len(hull) == 8 and hull.dimension == 3
    assert hc.convex_hull_volume(corners) == pytest.approx(1.0)
    r = hc.distance(hull, None, hc.Box(1, 1, 1), translation(3, 0.5, 0.5))
    assert r.distance == pytest.approx(1.5, abs=1e-9)
    grown = hc.Shape(hc.Sphere(0.5)).inflated(0.25)
    assert grown.margin == pytest.approx(0.25)
    assert grown.kind == hc.ShapeKind.SPHERE
    np.testing.assert_allclose(hc.Shape(hc.Box(2, 2, 2)).support(np.array([1.0, 1, 1])), [1, 1, 1])


def test_proximity_pair_matches_free_functions():
    pair = hc.ProximityPair()
    pair.set_shape_a(hc.Box(0.4, 0.4, 0.4))
    pair.set_shape_b(hc.Capsule(0.05, 0.3), translation(0.5, 0.1, 0))
    rng = np.random.default_rng(3)
    for _ in range(50):
        pose_b = ((rng.uniform(-0.6, 0.6, 3)), rng.uniform(-math.pi, math.pi, 3))
        pair.set_pose_b(pose_b)
        free = hc.signed_distance(hc.Box(0.4, 0.4, 0.4), None, hc.Capsule(0.05, 0.3), pose_b)
        cached = pair.signed_distance()
        assert cached.signed_distance == pytest.approx(free.signed_distance, abs=1e-9)
        assert pair.in_collision() == (free.signed_distance <= 0)
        assert pair.signed_distance().signed_distance == cached.signed_distance
        assert pair.last_was_cached


@pytest.mark.parametrize("pose, message", [
    (np.eye(3), r"pose_b: expected a 4x4 matrix or \(position, xyz_angles\), got shape \(3, 3\)"),
    (np.zeros((4, 4)), r"pose_b: the last row of a pose matrix must be \[0, 0, 0, 1\]"),
    (((0, 0), (0, 0, 0)), r"pose_b position: expected shape \(3,\), got \(2,\)"),
    (((0, 0, 0), ("a", "b", "c")), r"pose_b xyz angles: expected real numbers"),
    ("up", r"pose_b: expected real numbers"),
])
def test_bad_poses_are_input_errors(pose, message):
    with pytest.raises(hc.InputError, match=message):
        hc.distance(hc.Sphere(1), None, hc.Sphere(1), pose)


def test_input_error_is_a_value_error_with_the_cpp_message():
    assert issubclass(hc.InputError, ValueError)
    with pytest.raises(ValueError, match="radius"):
        hc.Sphere(-1.0)
    skewed = np.eye(4)
    skewed[0, 1] = 0.5
    with pytest.raises(hc.InputError, match="rotation"):
        hc.distance(hc.Sphere(1), skewed, hc.Sphere(1), None)
    with pytest.raises(hc.InputError, match=r"points: expected shape \(N, 3\)"):
        hc.ConvexHull(np.zeros((4, 2)))
    with pytest.raises(hc.InputError, match="got NoneType|got None"):
        hc.ConvexHull(None)
