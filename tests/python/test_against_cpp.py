"""Every robot and scene binding against the C++ API's answers for the same configurations
(hullcheck_python_reference, built from tests/python/cpp_reference.cpp): forward kinematics,
validity, clearance with names and witnesses, clearance gradients; single and batch calls,
one thread and several."""

import numpy as np
import pytest

from conftest import random_configurations, run_reference


@pytest.fixture(scope="module")
def states(arm, checker):
    q = random_configurations(arm, 300, seed=11)
    # Add states close to contact: bisect between a valid and an invalid state.
    valid = checker.is_valid(q)
    near = []
    for a, b in zip(q[valid][:10], q[~valid][:10]):
        for _ in range(30):
            mid = 0.5 * (a + b)
            if checker.is_valid(mid):
                a = mid
            else:
                b = mid
        near += [a, b]
    return np.vstack([q, near])


@pytest.fixture(scope="module")
def reference(arm_files, states):
    return run_reference(arm_files, states)


def test_states_cover_both_verdicts(reference):
    verdicts = {r["valid"] for r in reference}
    assert verdicts == {True, False}


def test_is_valid(checker, states, reference):
    expected = np.array([r["valid"] for r in reference])
    np.testing.assert_array_equal(checker.is_valid(states), expected)
    np.testing.assert_array_equal(checker.is_valid(states, threads=3), expected)
    assert [checker.is_valid(q) for q in states] == list(expected)


def test_clearance(checker, states, reference):
    batch = checker.clearance(states, threads=2)
    for i, r in enumerate(reference):
        single = checker.clearance(states[i])
        assert single.distance == r["distance"] == batch["distance"][i]
        assert single.self_collision == r["self_collision"] == batch["self_collision"][i]
        assert (single.name_a, single.name_b) == (r["name_a"], r["name_b"])
        assert (batch["name_a"][i], batch["name_b"][i]) == (r["name_a"], r["name_b"])
        for key in ("point_a", "point_b", "normal"):
            np.testing.assert_array_equal(getattr(single, key), r[key])
            np.testing.assert_array_equal(batch[key][i], r[key])


def test_clearance_gradient(checker, states, reference):
    batch = checker.clearance_gradient(states, threads=4)
    for i, r in enumerate(reference):
        np.testing.assert_array_equal(batch[i], r["gradient"])
    np.testing.assert_array_equal(checker.clearance_gradient(states[5]), reference[5]["gradient"])


def test_forward_kinematics(arm, states, reference):
    poses = arm.forward_kinematics(states, threads=2)
    assert poses.shape == (len(states), len(arm.link_names), 4, 4)
    for i, r in enumerate(reference):
        for k, name in enumerate(arm.link_names):
            np.testing.assert_array_equal(poses[i, k, :3, :], r["links"][name])
            np.testing.assert_array_equal(poses[i, k, 3, :], [0, 0, 0, 1])
    np.testing.assert_array_equal(arm.forward_kinematics(states[7]), poses[7])
