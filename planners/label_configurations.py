#!/usr/bin/env python3
"""Labels random configurations of a robot in a scene with validity and clearance: the
dataset-generation use (learned collision checkers, sampling distributions, clearance fields).

Configurations are drawn uniformly within the joint limits (continuous joints over [-pi, pi])
of the planned joints; the others stay at the scene's robot state (else the model's default).
Each is labelled with its validity (exact: the same verdict as is_valid one state at a time),
its signed clearance in m (minimum over the checked pairs; < 0 overlapping, by EPA) and the
closest pair's names. Progress goes to stderr.

    label_configurations.py URDF SRDF SCENE.yaml OUT.npz [--count N] [--group NAME]
                            [--seed S] [--threads T] [--batch B] [--no-clearance]

OUT.npz holds 'q' (N, dof), 'valid' (N,) bool, 'clearance' (N,) float64, 'name_a', 'name_b'
(N,) str, and 'variable_names'.
"""

import argparse
import sys
import time

import numpy as np

import hullcheck as hc


def progress(done, total, started):
    elapsed = time.monotonic() - started
    rate = done / elapsed if elapsed > 0 else 0.0
    width = 30
    filled = int(width * done / total) if total else width
    eta = (total - done) / rate if rate > 0 else float("nan")
    sys.stderr.write(f"\r[{'#' * filled}{'.' * (width - filled)}] {done}/{total} "
                     f"({rate:,.0f} states/s, {eta:.0f} s left)   ")
    sys.stderr.flush()


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("urdf")
    parser.add_argument("srdf")
    parser.add_argument("scene")
    parser.add_argument("out", help="output file (.npz)")
    parser.add_argument("--count", type=int, default=1_000_000, help="configurations (1000000)")
    parser.add_argument("--group", help="SRDF group to sample (default: every active joint)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--threads", type=int, default=0, help="0: every hardware thread")
    parser.add_argument("--batch", type=int, default=20_000, help="configurations per call")
    parser.add_argument("--no-clearance", action="store_true", help="validity labels only")
    args = parser.parse_args(argv)
    if args.count < 1 or args.batch < 1:
        parser.error("--count and --batch must be >= 1")

    model = hc.RobotModel.from_urdf(args.urdf)
    srdf = hc.read_srdf(args.srdf)
    checker = hc.CollisionChecker(model, srdf=srdf, scene=args.scene)
    variables = (hc.group_variables(model, srdf, args.group) if args.group
                 else list(range(model.variable_count)))
    base = model.default_configuration()
    for name, value in checker.scene.robot_joint_values.items():
        if model.variable_index(name) >= 0:
            base[model.variable_index(name)] = value
    lo = np.where(np.isfinite(model.lower_limits), model.lower_limits, -np.pi)[variables]
    hi = np.where(np.isfinite(model.upper_limits), model.upper_limits, np.pi)[variables]

    rng = np.random.default_rng(args.seed)
    q = np.tile(base, (args.count, 1))
    valid = np.empty(args.count, dtype=bool)
    clearance = np.full(args.count, np.nan)
    name_a = np.full(args.count, "", dtype=object)
    name_b = np.full(args.count, "", dtype=object)
    started = time.monotonic()
    for begin in range(0, args.count, args.batch):
        end = min(begin + args.batch, args.count)
        q[begin:end, variables] = lo + (hi - lo) * rng.random((end - begin, len(variables)))
        valid[begin:end] = checker.is_valid(q[begin:end], threads=args.threads)
        if not args.no_clearance:
            c = checker.clearance(q[begin:end], threads=args.threads)
            clearance[begin:end] = c["distance"]
            name_a[begin:end] = c["name_a"]
            name_b[begin:end] = c["name_b"]
        progress(end, args.count, started)
    sys.stderr.write("\n")
    elapsed = time.monotonic() - started
    np.savez_compressed(args.out, q=q, valid=valid, clearance=clearance,
                        name_a=name_a.astype(str), name_b=name_b.astype(str),
                        variable_names=np.array(model.variable_names))
    print(f"{args.count} configurations labelled in {elapsed:.1f} s "
          f"({args.count / elapsed:,.0f} per s): {valid.mean():.1%} valid; written to {args.out}")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except hc.InputError as e:
        print(f"error: {e}", file=sys.stderr)
        sys.exit(1)
