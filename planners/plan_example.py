#!/usr/bin/env python3
"""The smallest complete planning script with hullcheck; the Python twin of plan_example.cpp.

Loads a robot and a MoveIt scene, plans with RRTConnect between two configurations (SRDF
group states or comma-separated joint values of the group) with certified motions, optimizes
the path for clearance, validates it, and prints its length and minimum clearance.
    plan_example.py URDF SRDF GROUP SCENE.yaml START GOAL [SECONDS]
"""

import sys

import numpy as np

import hullcheck as hc


def configuration(text, model, srdf, group, variables):
    """A group state name of the SRDF, or comma-separated values for the group's joints."""
    if text in srdf.group_state_names(group):
        return hc.group_state_configuration(model, srdf, group, text)
    values = [float(v) for v in text.split(",")]
    if len(values) != len(variables):
        raise hc.InputError(f"'{text}': expected {len(variables)} joint values")
    q = model.default_configuration()
    q[variables] = values
    return q


def main(argv):
    if len(argv) < 7:
        print(f"usage: {argv[0]} URDF SRDF GROUP SCENE.yaml START GOAL [SECONDS]",
              file=sys.stderr)
        return 2
    urdf, srdf_path, group, scene, start_text, goal_text = argv[1:7]
    seconds = float(argv[7]) if len(argv) > 7 else 5.0
    # Robot, its collision matrix, the scene: one thread-safe checker.
    model = hc.RobotModel.from_urdf(urdf)
    srdf = hc.read_srdf(srdf_path)
    variables = hc.group_variables(model, srdf, group)
    checker = hc.CollisionChecker(model, srdf=srdf, scene=scene)

    start = configuration(start_text, model, srdf, group, variables)
    goal = configuration(goal_text, model, srdf, group, variables)
    result = hc.plan(checker, start, goal, joints=variables, planner="RRTConnect", time=seconds)
    if not result["solved"]:
        print(f"no path found in {seconds:.1f} s ({result['status']}) {result['message']}",
              file=sys.stderr)
        return 1
    print(f"RRTConnect: {len(result['path'])} states, length {result['length']:.3f}, "
          f"min clearance {result['min_clearance']:.4f} m")

    # Optimize for clearance: obstacles and the self pairs the group moves, a hinge at 5 cm
    # against path length; every motion certified, never worse than the planner's path.
    optimized = hc.optimize_clearance(checker, result["path"], joints=variables, margin=0.05)
    print(f"optimized: {len(optimized['path'])} states, length {optimized['length_before']:.3f} "
          f"-> {optimized['length']:.3f}, min clearance {optimized['min_clearance_before']:.4f} "
          f"-> {optimized['min_clearance']:.4f} m ({optimized['moves']} waypoint moves, "
          f"{1e3 * optimized['seconds']:.1f} ms)")
    closest = checker.clearance(optimized["path"][0])
    print(f"closest pair at the start: {closest.name_a} - {closest.name_b}, "
          f"{closest.distance:.4f} m")

    # Every waypoint and every motion between them, certified again.
    report = hc.validate(checker, optimized["path"])
    print(f"validate: {'VALID' if report['valid'] else 'INVALID'}, min clearance "
          f"{np.min(report['clearance']):.4f} m over {len(report['clearance'])} waypoints")
    return 0 if report["valid"] else 1


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv))
    except hc.InputError as e:
        print(f"error: {e}", file=sys.stderr)
        sys.exit(1)
