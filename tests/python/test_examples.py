"""The Python examples end to end: plan_example.py plans, optimizes and validates over the
wall; label_configurations.py writes labels equal to the checker's own answers."""

import pathlib
import subprocess
import sys

import numpy as np

import hullcheck as hc
from conftest import ROOT

PLANNERS = ROOT / "planners"


def run(args):
    return subprocess.run([sys.executable, *map(str, args)], capture_output=True, text=True,
                          timeout=300)


def test_plan_example(arm_files):
    r = run([PLANNERS / "plan_example.py", arm_files["urdf"], arm_files["srdf"], "arm",
             arm_files["scene"], "left", "right", "10"])
    assert r.returncode == 0, r.stderr
    assert "RRTConnect:" in r.stdout and "optimized:" in r.stdout
    assert "validate: VALID" in r.stdout


def test_plan_example_errors(arm_files):
    r = run([PLANNERS / "plan_example.py", arm_files["urdf"], arm_files["srdf"], "arm",
             arm_files["scene"], "left", "1,2", "10"])
    assert r.returncode == 1 and "error: '1,2': expected 7 joint values" in r.stderr
    r = run([PLANNERS / "plan_example.py"])
    assert r.returncode == 2 and "usage:" in r.stderr


def test_label_configurations(arm, checker, arm_files, tmp_path):
    out = tmp_path / "labels.npz"
    r = run([PLANNERS / "label_configurations.py", arm_files["urdf"], arm_files["srdf"],
             arm_files["scene"], out, "--count", "3000", "--batch", "700", "--group", "arm",
             "--threads", "2"])
    assert r.returncode == 0, r.stderr
    assert "3000/3000" in r.stderr and "3000 configurations labelled" in r.stdout
    data = np.load(out)
    q = data["q"]
    assert q.shape == (3000, 8)
    assert list(data["variable_names"]) == arm.variable_names
    np.testing.assert_array_equal(q[:, 7], q[0, 7])  # the gripper is not in the group
    np.testing.assert_array_equal(data["valid"], checker.is_valid(q))
    for i in range(0, 3000, 150):
        c = checker.clearance(q[i])
        assert data["clearance"][i] == c.distance
        assert (data["name_a"][i], data["name_b"][i]) == (c.name_a, c.name_b)
    assert 0 < data["valid"].sum() < 3000
    # A valid state has clearance > 0; a colliding one <= 0.
    assert (data["clearance"][data["valid"]] > 0).all()
    assert (data["clearance"][~data["valid"]] <= 0).all()


def test_label_configurations_bad_group(arm_files, tmp_path):
    r = run([PLANNERS / "label_configurations.py", arm_files["urdf"], arm_files["srdf"],
             arm_files["scene"], tmp_path / "x.npz", "--count", "10", "--group", "legs"])
    assert r.returncode == 1 and "legs" in r.stderr
