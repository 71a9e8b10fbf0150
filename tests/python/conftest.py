"""Shared fixtures of the Python tests: the project's own arm and its scene, the MBM robots
under ../shared when present (skipped cleanly when not), and the C++ reference program."""

import os
import pathlib
import subprocess

import numpy as np
import pytest

import hullcheck

ROOT = pathlib.Path(__file__).resolve().parents[2]
ARM = ROOT / "robots" / "hullcheck_arm"
SHARED = ROOT.parent / "shared"
MBM = SHARED / "benchmarks" / "mbm"


@pytest.fixture(scope="session")
def arm_files():
    return {
        "urdf": str(ARM / "urdf" / "hullcheck_arm.urdf"),
        "srdf": str(ARM / "srdf" / "hullcheck_arm.srdf"),
        "scene": str(ARM / "scenes" / "table_wall.yaml"),
    }


@pytest.fixture(scope="session")
def arm(arm_files):
    return hullcheck.RobotModel.from_urdf(arm_files["urdf"])


@pytest.fixture(scope="session")
def checker(arm, arm_files):
    return hullcheck.CollisionChecker(arm, srdf=arm_files["srdf"], scene=arm_files["scene"])


@pytest.fixture(scope="session")
def srdf(arm_files):
    return hullcheck.read_srdf(arm_files["srdf"])


def random_configurations(model, count, seed):
    """Uniform configurations within the joint limits (continuous joints over [-pi, pi])."""
    rng = np.random.default_rng(seed)
    lo = np.where(np.isfinite(model.lower_limits), model.lower_limits, -np.pi)
    hi = np.where(np.isfinite(model.upper_limits), model.upper_limits, np.pi)
    return lo + (hi - lo) * rng.random((count, model.variable_count))


@pytest.fixture(scope="session")
def mbm_panda():
    """The MBM Panda with one of its scenes, or a skip when ../shared is absent."""
    robot = MBM / "robots" / "panda_obj"
    scenes = sorted((MBM / "panda").glob("*/scene*.yaml")) if (MBM / "panda").is_dir() else []
    if not (robot / "panda.urdf").is_file() or not scenes:
        pytest.skip("../shared/benchmarks/mbm (Panda) is not present")
    model = hullcheck.RobotModel.from_urdf(str(robot / "panda.urdf"))
    return model, str(robot / "panda.srdf"), scenes


def run_reference(files, q):
    """The C++ answers for configurations q (N, dof), parsed from hullcheck_python_reference."""
    exe = os.environ.get("HULLCHECK_PYTHON_REFERENCE")
    if not exe:
        pytest.skip("HULLCHECK_PYTHON_REFERENCE is not set (run the tests through ctest)")
    text = "\n".join(" ".join(repr(float(v)) for v in row) for row in q) + "\n"
    out = subprocess.run([exe, files["urdf"], files["srdf"], files["scene"]], input=text,
                         capture_output=True, text=True, check=True).stdout
    results, current = [], None
    for line in out.splitlines():
        key, *rest = line.split()
        if key == "valid":
            current = {"valid": rest[0] == "1", "links": {}}
            results.append(current)
        elif key == "clearance":
            current["distance"] = float(rest[0])
            current["self_collision"] = rest[1] == "1"
            current["name_a"], current["name_b"] = rest[2], rest[3]
            values = np.array([float(v) for v in rest[4:]])
            current["point_a"], current["point_b"], current["normal"] = values.reshape(3, 3)
        elif key == "gradient":
            current["gradient"] = np.array([float(v) for v in rest])
        elif key == "link":
            current["links"][rest[0]] = np.array([float(v) for v in rest[1:]]).reshape(3, 4)
    return results
