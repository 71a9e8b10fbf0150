"""plan, validate and benchmark in Python: a plan over the wall is certified and validates,
validate finds the contact of a straight motion through the wall, invalid start and bad
arguments are reported, and on the MBM Panda (when ../shared is present) every planned path
validates."""

import numpy as np
import pytest

import hullcheck as hc


@pytest.fixture(scope="module")
def problem(arm, srdf):
    left = hc.group_state_configuration(arm, srdf, "arm", "left")
    right = hc.group_state_configuration(arm, srdf, "arm", "right")
    return left, right, hc.group_variables(arm, srdf, "arm")


def test_plan_over_the_wall_validates(checker, problem):
    left, right, group = problem
    r = hc.plan(checker, left, right, joints=group, time=10.0, simplify=True)
    assert r["solved"] and r["status"] == "Exact solution" and r["certified"]
    path = r["path"]
    assert path.ndim == 2 and path.shape[1] == 8 and len(path) >= 3  # a direct motion collides
    np.testing.assert_array_equal(path[0], left)
    np.testing.assert_allclose(path[-1], right, atol=1e-12)
    np.testing.assert_array_equal(path[:, 7], left[7])  # the gripper is not planned
    assert r["motion_checks"] > 0 and r["state_checks"] > 0
    # OMPL's metric of the group's space: Euclidean over the bounded joints plus the wrapped
    # angle of the continuous joint7 (a compound space sums its parts).
    steps = np.diff(path, axis=0)
    turn = np.abs((steps[:, 6] + np.pi) % (2 * np.pi) - np.pi)
    segments = (np.linalg.norm(steps[:, :6], axis=1) + turn).sum()
    assert r["length"] == pytest.approx(segments, rel=1e-9)
    v = hc.validate(checker, path)
    assert v["valid"] and v["state_valid"].all() and v["motion_free"].all()
    assert (v["contact"] == 1.0).all()
    assert r["min_clearance"] == pytest.approx(v["clearance"].min())
    np.testing.assert_array_equal(v["clearance"],
                                  np.minimum(v["obstacle_clearance"], v["self_clearance"]))
    assert len(v["name_a"]) == len(path)


def test_joint_names_select_the_same_group(checker, problem, arm):
    left, right, group = problem
    names = [arm.variable_names[i] for i in group]
    r = hc.plan(checker, left, right, joints=names, time=10.0, discrete=True)
    assert r["solved"] and not r["certified"]


def test_validate_finds_the_wall(checker, problem):
    left, right, _ = problem
    v = hc.validate(checker, np.vstack([left, right]))
    assert not v["valid"]
    assert v["state_valid"].all() and not v["motion_free"][0]
    assert 0 < v["contact"][0] < 1


def test_invalid_start_is_reported(checker, problem, arm):
    left, right, group = problem
    q = left.copy()
    inside = None
    rng = np.random.default_rng(0)
    for _ in range(1000):
        q[:7] = rng.uniform(-2, 2, 7)
        if not checker.is_valid(q):
            inside = q
            break
    assert inside is not None
    r = hc.plan(checker, inside, right, joints=group, time=1.0)
    assert not r["solved"] and r["status"] == "invalid start"
    assert "start state is in collision" in r["message"]
    assert r["path"].shape == (0, 8)


@pytest.mark.parametrize("kwargs, message", [
    ({"joints": ["joint1", "nope"]}, "joints: 'nope' is not an active joint of robot"),
    ({"joints": [12]}, r"joints: index 12 is outside \[0, 8\)"),
    ({"joints": "joint1"}, "joints: expected None or a list"),
    ({"planner": "NoSuchPlanner"}, "NoSuchPlanner"),
    ({"objective": "speed"}, "speed"),
    ({"time": 0.0}, "time: expected a finite number of seconds > 0"),
])
def test_plan_errors(checker, problem, kwargs, message):
    left, right, _ = problem
    with pytest.raises(hc.InputError, match=message):
        hc.plan(checker, left, right, **kwargs)


def test_validate_errors(checker, problem):
    left, right, _ = problem
    with pytest.raises(hc.InputError, match=r"path: expected shape \(K, 8\)"):
        hc.validate(checker, left)
    far = left.copy()
    far[1] = 40.0
    with pytest.raises(hc.InputError, match="path: waypoint 1: .*joint2"):
        hc.validate(checker, np.vstack([left, far]))
    with pytest.raises(hc.InputError, match="resolution"):
        hc.validate(checker, np.vstack([left, right]), resolution=0.0)


def test_benchmark_columns(checker, problem):
    left, right, group = problem
    b = hc.benchmark(checker, [(left, right)], planners=["RRTConnect", "KPIECE1"], runs=2,
                     time=10.0, joints=group)
    assert list(b["planner"]) == ["RRTConnect"] * 2 + ["KPIECE1"] * 2
    np.testing.assert_array_equal(b["run"], [0, 1, 0, 1])
    assert b["solved"].dtype == bool and b["solved"].all()
    assert (b["min_clearance"] > 0).all() and (b["waypoints"] >= 2).all()
    assert b["summary"]["RRTConnect"]["solved"] == 2
    with pytest.raises(hc.InputError, match="runs: expected an integer >= 1"):
        hc.benchmark(checker, [(left, right)], runs=0)
    with pytest.raises(hc.InputError, match=r"problems\[0\]: expected a \(start, goal\) pair"):
        hc.benchmark(checker, [(left,)])


def test_mbm_panda_paths_validate(mbm_panda):
    model, srdf_path, scenes = mbm_panda
    srdf = hc.read_srdf(srdf_path)
    solved = 0
    for scene in scenes[:: max(1, len(scenes) // 4)][:4]:
        request = scene.with_name(scene.name.replace("scene", "request"))
        checker = hc.CollisionChecker(model, srdf=srdf, scene=str(scene))
        req = hc.read_motion_plan_request(str(request), model)
        group = hc.group_variables(model, srdf, req.group)
        if not (checker.is_valid(req.start) and checker.is_valid(req.goal)):
            continue
        r = hc.plan(checker, req.start, req.goal, joints=group, time=10.0)
        if r["solved"]:
            solved += 1
            assert hc.validate(checker, r["path"])["valid"]
    assert solved >= 2


def test_optimize_clearance_buys_obstacle_clearance(checker, problem):
    left, right, group = problem
    r = hc.plan(checker, left, right, joints=group, time=10.0, simplify=True)
    assert r["solved"]
    for scope in ("auto", "all", "obstacles"):
        o = hc.optimize_clearance(checker, r["path"], joints=group, margin=0.05, scope=scope)
        assert o["cost"] <= o["cost_before"]
        assert o["length_before"] == pytest.approx(r["length"], rel=1e-9)
        assert o["rounds"] >= 1 and o["moves"] >= 0 and o["refined"] >= 0
        path = o["path"]
        np.testing.assert_array_equal(path[0], left)
        np.testing.assert_allclose(path[-1], right, atol=1e-12)
        np.testing.assert_array_equal(path[:, 7], left[7])
        v = hc.validate(checker, path)
        assert v["valid"]  # every motion certified again, independently of the optimizer
        if not o["changed"]:
            np.testing.assert_array_equal(path, r["path"])
    # The obstacle scope buys clearance along the whole middle of the path, not only at its
    # waypoints: densely sampled, the middle 80% (by joint-space length; the ends cannot move)
    # keeps 0.8 of the margin, or twice what the planner's path kept. The hinge trades clearance
    # above the margin for length, and the length term settles the optimum slightly below the
    # margin, hence 0.8 rather than 1.
    o = hc.optimize_clearance(checker, r["path"], joints=group, margin=0.05, scope="obstacles")
    assert o["self_pairs"] == 0
    before_middle = middle_obstacle_clearance(checker, r["path"])
    after_middle = middle_obstacle_clearance(checker, o["path"])
    assert after_middle >= min(2.0 * before_middle, 0.8 * 0.05), (before_middle, after_middle)


def middle_obstacle_clearance(checker, path, samples_per_motion=40):
    """Smallest obstacle clearance, m, over the middle 80% of `path` sampled densely."""
    lengths = np.linalg.norm(np.diff(path, axis=0), axis=1)
    total, start, smallest = lengths.sum(), 0.0, np.inf
    for i, length in enumerate(lengths):
        for t in np.linspace(0.0, 1.0, samples_per_motion, endpoint=False):
            if 0.1 * total <= start + t * length <= 0.9 * total:
                q = path[i] + t * (path[i + 1] - path[i])
                smallest = min(smallest, checker.clearance(q, scope="obstacles").distance)
        start += length
    return smallest


@pytest.mark.parametrize("kwargs, message", [
    ({"scope": "everything"}, "scope: expected 'auto'"),
    ({"margin": 0.0}, "margin"),
    ({"margin": float("nan")}, "margin"),
    ({"length_weight": -1.0}, "length_weight"),
    ({"time": 0.0}, "time"),
])
def test_optimize_clearance_errors(checker, problem, kwargs, message):
    left, right, group = problem
    path = np.array([left, left])
    with pytest.raises(hc.InputError, match=message):
        hc.optimize_clearance(checker, path, joints=group, **kwargs)


def test_optimize_clearance_rejects_an_invalid_path(checker, problem):
    left, right, group = problem
    with pytest.raises(hc.InputError, match="is not free"):
        hc.optimize_clearance(checker, np.array([left, right]), joints=group)
