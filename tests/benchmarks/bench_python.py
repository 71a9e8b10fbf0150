#!/usr/bin/env python3
"""Overhead of the Python binding's batch validity: CollisionChecker.is_valid(Q) for N
configurations against the C++ loop over the same states, in the same run.

For each scene: N random configurations within the joint limits (and, when asked, states on
straight lines between random pairs, as a planner's motions sample them) are written to a file;
bench_python_reference times them in C++ (a loop of is_valid, and is_valid_batch), then this
script times checker.is_valid(Q) (one thread); --rounds rounds alternate the two, each the best
of --repeats passes, and the best of all counts; the verdicts must agree. A Python loop of
checker.is_valid(q) is timed once on the first --loop-states states. Prints a markdown table with ns per state and the
ratios. Target (issue: Python package): Python batch / C++ loop <= 1.10.

    PYTHONPATH=build/rel/python python3 tests/benchmarks/bench_python.py \\
        --reference build/rel/tests/benchmarks/bench_python_reference [--robot mbm-panda] \\
        [--states 100000] [--scenes 3] [--repeats 3] [--rounds 3]
"""

import argparse
import pathlib
import subprocess
import sys
import tempfile
import time

import numpy as np

import hullcheck as hc

ROOT = pathlib.Path(__file__).resolve().parents[2]


def robots(name):
    """(urdf, srdf, [scene, ...]) for a robot name."""
    if name == "arm":
        arm = ROOT / "robots" / "hullcheck_arm"
        return (arm / "urdf" / "hullcheck_arm.urdf", arm / "srdf" / "hullcheck_arm.srdf",
                [arm / "scenes" / "table_wall.yaml"])
    mbm = ROOT.parent / "shared" / "benchmarks" / "mbm"
    robot = {"mbm-panda": ("panda_obj", "panda", "panda"),
             "mbm-ur5": ("ur5_robotiq85", "ur5", "ur5")}[name]
    folder = mbm / "robots" / robot[0]
    scenes = sorted((mbm / robot[2]).glob("*/scene*.yaml"))
    if not scenes:
        sys.exit(f"bench_python: {mbm} is not present (use --robot arm)")
    return folder / f"{robot[1]}.urdf", folder / f"{robot[1]}.srdf", scenes


def states(model, count, lines, rng):
    lo = np.where(np.isfinite(model.lower_limits), model.lower_limits, -np.pi)
    hi = np.where(np.isfinite(model.upper_limits), model.upper_limits, np.pi)
    uniform = lambda n: lo + (hi - lo) * rng.random((n, model.variable_count))  # noqa: E731
    if not lines:
        return uniform(count)
    # 50 states on each straight line between two random configurations.
    a, b = uniform(count // 50 + 1), uniform(count // 50 + 1)
    t = np.linspace(0, 1, 50)[None, :, None]
    return (a[:, None, :] + t * (b - a)[:, None, :]).reshape(-1, model.variable_count)[:count]


def best_ns(repeats, count, body):
    best = float("inf")
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = body()
        best = min(best, (time.perf_counter() - t0) * 1e9 / count)
    return best, out


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--reference", required=True, help="bench_python_reference program")
    parser.add_argument("--robot", default="mbm-panda", choices=["arm", "mbm-panda", "mbm-ur5"])
    parser.add_argument("--states", type=int, default=100_000)
    parser.add_argument("--scenes", type=int, default=3, help="scenes, spread over the list")
    parser.add_argument("--repeats", type=int, default=3, help="timed passes per round")
    parser.add_argument("--rounds", type=int, default=3,
                        help="rounds, alternating the C++ program and Python")
    parser.add_argument("--loop-states", type=int, default=20_000,
                        help="states of the Python per-state loop (it is slow)")
    args = parser.parse_args()
    urdf, srdf, scenes = robots(args.robot)
    chosen = scenes[:: max(1, len(scenes) // args.scenes)][: args.scenes]
    model = hc.RobotModel.from_urdf(str(urdf))
    rng = np.random.default_rng(1)
    print(f"| scene | states | C++ loop ns/state | C++ batch | Python batch | Python loop "
          f"| Python batch / C++ loop | Python batch / C++ batch |")
    print("|---|---|---|---|---|---|---|---|")
    ratios = []
    with tempfile.TemporaryDirectory() as tmp:
        for scene in chosen:
            checker = hc.CollisionChecker(model, srdf=str(srdf), scene=str(scene))
            for lines in (False, True):
                q = states(model, args.states, lines, rng)
                path = pathlib.Path(tmp) / "states.f64"
                q.tofile(path)
                # Rounds alternate between the two programs, so that the machine's drift over
                # time falls on both; the best of every round counts.
                cpp = {"loop_ns_per_state": float("inf"), "batch_ns_per_state": float("inf")}
                py_batch = float("inf")
                for _ in range(args.rounds):
                    out = subprocess.run([args.reference, str(urdf), str(srdf), str(scene),
                                          str(path), str(model.variable_count),
                                          str(args.repeats)],
                                         capture_output=True, text=True, check=True).stdout
                    for key, value in (line.split() for line in out.splitlines()):
                        cpp[key] = min(cpp.get(key, float("inf")), float(value))
                    ns, valid = best_ns(args.repeats, len(q), lambda: checker.is_valid(q))
                    py_batch = min(py_batch, ns)
                    if int(valid.sum()) != int(cpp["valid"]):
                        sys.exit(f"{scene}: Python finds {valid.sum()} valid, C++ "
                                 f"{cpp['valid']:.0f}")
                few = q[: args.loop_states]
                py_loop, _ = best_ns(1, len(few), lambda: [checker.is_valid(x) for x in few])
                ratio = py_batch / cpp["loop_ns_per_state"]
                ratios.append(ratio)
                name = f"{scene.parent.name}/{scene.stem}" + (" lines" if lines else " random")
                print(f"| {name} | {len(q)} | {cpp['loop_ns_per_state']:.0f} | "
                      f"{cpp['batch_ns_per_state']:.0f} | {py_batch:.0f} | {py_loop:.0f} | "
                      f"{ratio:.3f} | {py_batch / cpp['batch_ns_per_state']:.3f} |")
    print(f"\nPython batch / C++ loop: median {np.median(ratios):.3f}, max {max(ratios):.3f}")


if __name__ == "__main__":
    main()
