"""clearance_lower_bound_batch beside clearance() on MotionBenchMaker scenes: for the first
problem of every family, uniform random states of the request's group (the other values from
its start state), the valid ones kept; ns per state of CollisionChecker.clearance_lower_bound(Q)
and of the exact CollisionChecker.clearance(Q) (one thread each), how far the bounds sit under
the clearance (median), and the share of states answered exactly.

Usage: PYTHONPATH=build/rel/python python3 tests/benchmarks/bench_clearance_bound.py
           [--mbm ../shared/benchmarks/mbm] [--states 20000] [--no-tables]
"""

import argparse
import glob
import pathlib
import time

import numpy as np

import hullcheck as hc

ROBOTS = {
    "panda": ("robots/panda_obj/panda.urdf", "robots/panda_obj/panda.srdf"),
    "ur5": ("robots/ur5_robotiq85/ur5.urdf", "robots/ur5_robotiq85/ur5.srdf"),
}


def main():
    root = pathlib.Path(__file__).resolve().parents[2]
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mbm", default=str(root.parent / "shared" / "benchmarks" / "mbm"))
    parser.add_argument("--states", type=int, default=20000, help="random states per scene")
    parser.add_argument("--no-tables", action="store_true",
                        help="do not measure the self-collision tables first")
    args = parser.parse_args()
    for robot, (urdf, srdf) in ROBOTS.items():
        scenes = sorted(glob.glob(f"{args.mbm}/{robot}/*/scene0001.yaml"))
        if not scenes:
            print(f"{robot}: no problems under {args.mbm}")
            continue
        model = hc.RobotModel.from_urdf(f"{args.mbm}/{urdf}")
        parsed = hc.read_srdf(f"{args.mbm}/{srdf}")
        bound_s = exact_s = 0.0
        states, under, exact_share = 0, [], []
        for scene in scenes:
            checker = hc.CollisionChecker(model, srdf=f"{args.mbm}/{srdf}", scene=scene)
            request = hc.read_motion_plan_request(scene.replace("scene", "request"), model)
            group = hc.group_variables(model, parsed, request.group)
            rng = np.random.default_rng(1)
            lo = np.where(np.isfinite(model.lower_limits), model.lower_limits, -np.pi)
            hi = np.where(np.isfinite(model.upper_limits), model.upper_limits, np.pi)
            q = np.tile(request.start, (args.states, 1))
            drawn = lo + (hi - lo) * rng.random((args.states, model.variable_count))
            q[:, group] = drawn[:, group]
            q = q[checker.is_valid(q)]
            if not args.no_tables:
                checker.measure_self_tables()
            checker.clearance_lower_bound(q[:8])  # the thread's scratch, not timed
            t = time.perf_counter()
            lower = checker.clearance_lower_bound(q)
            bound_s += time.perf_counter() - t
            t = time.perf_counter()
            exact = checker.clearance(q)["distance"]
            exact_s += time.perf_counter() - t
            assert (lower <= exact + 1e-9).all(), scene
            states += len(q)
            under.append(np.median(exact - lower))
            exact_share.append(np.mean(np.abs(exact - lower) < 1e-9))
        print(f"| {robot} | {states} | {'no' if args.no_tables else 'yes'} | "
              f"{1e9 * bound_s / states:.0f} | {1e9 * exact_s / states:.0f} | "
              f"{1e3 * np.median(under):.1f} | {np.mean(exact_share):.2f} |")


if __name__ == "__main__":
    main()
