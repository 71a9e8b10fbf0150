"""RobotModel, SRDF, scenes and CollisionChecker in Python: loading, names and limits,
analytic checks (a gradient against finite differences, motions through a wall), batch
against per-state, and clear errors for bad arguments."""

import numpy as np
import pytest

import hullcheck as hc
from conftest import random_configurations


def test_model_names_and_limits(arm):
    assert arm.name == "hullcheck_arm"
    assert arm.variable_count == len(arm.variable_names) == 8
    assert arm.variable_index("joint1") == 0
    assert arm.variable_index("no_such_joint") == -1
    assert arm.lower_limits.shape == arm.upper_limits.shape == (8,)
    assert np.isinf(arm.lower_limits[arm.variable_index("joint7")])  # continuous
    assert "link5" in arm.links_with_geometry
    assert arm.shape_count("link5") >= 1
    with pytest.raises(hc.InputError, match="'nope' is not a link of hullcheck_arm"):
        arm.shape_count("nope")
    q = arm.default_configuration()
    assert q.shape == (8,)
    base = arm.forward_kinematics(q)[arm.link_index("base_link")]
    np.testing.assert_array_equal(base, np.eye(4))


def test_load_errors_name_the_file(arm_files, tmp_path):
    with pytest.raises(hc.InputError, match="missing.urdf"):
        hc.RobotModel.from_urdf(str(tmp_path / "missing.urdf"))
    bad = tmp_path / "bad.urdf"
    bad.write_text("<robot name='r'><link name='a'/><joint name='j' type='revolute'>"
                   "<parent link='a'/><child link='b'/></joint></robot>")
    with pytest.raises(hc.InputError, match="bad.urdf"):
        hc.RobotModel.from_urdf(str(bad))
    with pytest.raises(hc.InputError, match="mesh_geometry: expected 'decompose' or 'hull'"):
        hc.RobotModel.from_urdf(str(bad), mesh_geometry="spheres")
    with pytest.raises(hc.InputError, match="package 'arm' maps to '.*nowhere', which is not a"):
        hc.RobotModel.from_urdf(arm_files["urdf"], packages={"arm": str(tmp_path / "nowhere")})


def test_srdf_groups(arm, srdf):
    assert "arm" in srdf.group_names
    assert "home" in srdf.group_state_names("arm")
    group = hc.group_variables(arm, srdf, "arm")
    assert group == list(range(7))
    ready = hc.group_state_configuration(arm, srdf, "arm", "ready")
    assert ready[1] == pytest.approx(0.3) and ready[3] == pytest.approx(-1.6)
    assert len(srdf.disabled_collisions) > 0


def test_scene_and_checker(checker):
    scene = checker.scene
    assert len(scene.obstacles) > 0
    assert all(isinstance(o.name, str) and o.pose.shape == (4, 4) for o in scene.obstacles)
    pairs = checker.checked_link_pairs()
    assert len(pairs) > 0 and all(len(p) == 2 for p in pairs)


def test_batch_equals_per_state_on_many_states(arm, checker):
    q = random_configurations(arm, 5000, seed=2)
    batch = checker.is_valid(q, threads=0)
    assert batch.dtype == bool and batch.shape == (5000,)
    assert 0 < batch.sum() < 5000
    assert [checker.is_valid(row) for row in q[:500]] == list(batch[:500])
    # Any row layout: a transposed (Fortran-ordered) array and float32 give the same verdicts.
    np.testing.assert_array_equal(checker.is_valid(np.asfortranarray(q)), batch)
    assert checker.is_valid(np.empty((0, 8))).shape == (0,)


def test_gradient_matches_finite_differences(arm, checker):
    q = random_configurations(arm, 200, seed=5)
    checked = 0
    for row in q:
        c = checker.clearance(row)
        if c.distance < 0.01:
            continue
        g = checker.clearance_gradient(row)
        h = 1e-6
        for i in range(arm.variable_count):
            step = np.zeros(arm.variable_count)
            step[i] = h
            plus, minus = checker.clearance(row + step), checker.clearance(row - step)
            if (plus.name_a, plus.name_b, minus.name_a, minus.name_b) != (c.name_a, c.name_b) * 2:
                continue  # the closest pair changes within the step: not differentiable there
            fd = (plus.distance - minus.distance) / (2 * h)
            assert g[i] == pytest.approx(fd, abs=2e-5, rel=1e-3)
        checked += 1
    assert checked >= 50


def test_check_motion_through_the_wall(arm, srdf, checker):
    left = hc.group_state_configuration(arm, srdf, "arm", "left")
    right = hc.group_state_configuration(arm, srdf, "arm", "right")
    assert checker.is_valid(left) and checker.is_valid(right)
    m = checker.check_motion(left, right)
    assert not m.free and m.verdict == "contact"
    assert 0 < m.last_free <= m.contact < 1
    assert checker.is_valid(left + m.last_free * (right - left))
    assert not checker.is_valid(left + m.contact * (right - left)) or \
        checker.clearance(left + m.contact * (right - left)).distance < 1e-4
    stay = checker.check_motion(left, left + 1e-3)
    assert stay.free and stay.verdict == "free" and stay.contact == 1.0


@pytest.mark.parametrize("q, message", [
    (np.zeros(7), r"q: expected shape \(8,\) or \(N, 8\), got \(7,\)"),
    (np.zeros((3, 9)), r"q: expected shape \(8,\) or \(N, 8\), got \(3, 9\)"),
    (np.zeros((2, 2, 8)), r"got \(2, 2, 8\)"),
    (np.zeros(8, dtype=bool), "q: expected real numbers .* got dtype bool"),
    (np.full(8, np.nan), "q: value 0 is not finite"),
    (np.array([[0.0] * 8, [0.0] * 7 + [np.inf]]), "q: value 7 of row 1 is not finite"),
    ("zeros", "q: expected real numbers"),
    (None, "q: expected an array, got None"),
])
def test_bad_configurations_are_input_errors(checker, q, message):
    for method in (checker.is_valid, checker.clearance, checker.clearance_gradient):
        with pytest.raises(hc.InputError, match=message):
            method(q)
    with pytest.raises(hc.InputError, match=message):
        checker.model.forward_kinematics(q)


def test_bad_thread_counts(checker):
    with pytest.raises(hc.InputError, match="threads: expected >= 0"):
        checker.is_valid(np.zeros((4, 8)), threads=-1)
    with pytest.raises(hc.InputError, match="threads: expected None or an integer >= 0, got str"):
        checker.is_valid(np.zeros((4, 8)), threads="many")
    with pytest.raises(hc.InputError, match="got float"):
        checker.model.forward_kinematics(np.zeros((4, 8)), threads=2.5)


def test_measure_self_tables_threads(arm_files):
    # A model object of its own (tables are shared per model object): measured on two
    # threads, the verdicts are those of an unmeasured checker of another model object.
    def make():
        model = hc.RobotModel.from_urdf(arm_files["urdf"])
        return hc.CollisionChecker(model, srdf=arm_files["srdf"], scene=arm_files["scene"])

    measured, plain = make(), make()
    with pytest.raises(hc.InputError, match="threads: expected >= 0"):
        measured.measure_self_tables(threads=-1)
    measured.measure_self_tables(threads=2)
    q = random_configurations(measured.model, 2000, 3)
    np.testing.assert_array_equal(measured.is_valid(q), plain.is_valid(q))


def test_scene_errors_name_the_file(arm, tmp_path):
    bad = tmp_path / "scene.yaml"
    bad.write_text("world:\n  collision_objects: [ {id: box, primitives: [{type: box, "
                   "dimensions: [1, -1, 1]}], primitive_poses: [{position: [0, 0, 0]}]} ]\n")
    with pytest.raises(hc.InputError, match="scene.yaml"):
        hc.read_planning_scene(str(bad), arm)
    with pytest.raises(hc.InputError, match="no_such_scene.yaml"):
        hc.CollisionChecker(arm, scene=str(tmp_path / "no_such_scene.yaml"))


def test_checker_model_outlives_its_python_object(arm_files):
    # The model object made here is dropped at once: the checker's model is still usable and can
    # build another checker.
    checker = hc.CollisionChecker(hc.RobotModel.from_urdf(arm_files["urdf"]))
    model = checker.model
    again = hc.CollisionChecker(model, scene=arm_files["scene"])
    assert again.model.name == "hullcheck_arm" and len(again.scene.obstacles) > 0


def test_clearance_scopes(arm, checker):
    q = random_configurations(arm, 300, seed=9)
    every = checker.clearance(q)
    obstacles = checker.clearance(q, scope="obstacles")
    own = checker.clearance(q, scope="self", threads=2)
    np.testing.assert_array_equal(every["distance"],
                                  np.minimum(obstacles["distance"], own["distance"]))
    assert not obstacles["self_collision"].any() and own["self_collision"].all()
    names = {o.name for o in checker.scene.obstacles}
    assert set(obstacles["name_b"]) <= names
    assert (obstacles["distance"] < own["distance"]).any()  # the scopes differ in places
    assert (obstacles["distance"] > own["distance"]).any()
    for i in range(0, 300, 30):
        single = checker.clearance(q[i], scope="obstacles")
        assert single.distance == obstacles["distance"][i]
        assert (single.name_a, single.name_b) == (obstacles["name_a"][i], obstacles["name_b"][i])
    g = checker.clearance_gradient(q[:5], scope="obstacles")
    assert g.shape == (5, 8)
    bare = hc.CollisionChecker(arm)
    assert np.isinf(bare.clearance(q[0], scope="obstacles").distance)
    with pytest.raises(hc.InputError, match="scope: expected 'all', 'obstacles' or 'self'"):
        checker.clearance(q, scope="world")


def test_clearance_lower_bound(arm, checker):
    q = random_configurations(arm, 400, seed=11)
    exact = checker.clearance(q)["distance"]
    for exact_below in (0.0, 0.01):
        lower = checker.clearance_lower_bound(q, exact_below=exact_below, threads=2)
        assert lower.shape == (400,)
        assert (lower <= exact + 1e-9).all()
        assert (lower >= np.minimum(exact, exact_below) - 1e-9).all()
        measured = lower < exact_below
        np.testing.assert_allclose(lower[measured], exact[measured], rtol=0, atol=1e-9)
        assert (lower < exact - 1e-6).any()  # bounds, not only exact values
    assert checker.clearance_lower_bound(q[3]) == pytest.approx(
        checker.clearance_lower_bound(q[:8])[3], abs=0)
    with pytest.raises(hc.InputError, match="exact_below is NaN"):
        checker.clearance_lower_bound(q, exact_below=float("nan"))


def test_clearance_below_a_cap(arm, checker):
    q = random_configurations(arm, 300, seed=10)
    exact = checker.clearance(q, scope="obstacles")["distance"]
    capped = checker.clearance(q, scope="obstacles", below=0.05, threads=2)
    under = exact < 0.05 - 1e-9
    assert under.any() and (~under).any()
    np.testing.assert_allclose(capped["distance"][under], exact[under], rtol=0, atol=1e-12)
    assert np.isinf(capped["distance"][exact > 0.05 + 1e-9]).all()
    assert all(name == "" for name, u in zip(capped["name_a"], under) if not u)
    assert checker.clearance(q[0], below=-np.inf).distance == np.inf
    with pytest.raises(hc.InputError, match="below"):
        checker.clearance(q[0], below=float("nan"))
