"""Planning benchmarks in Python: ``benchmark`` repeats ``hullcheck.plan`` over problems,
planners and runs, as ``hullcheck benchmark`` does on the command line."""

import numpy as np

from ._hullcheck import InputError, plan


def benchmark(checker, problems, planners=("RRTConnect",), runs=1, time=10.0, joints=None,
              objective="length", simplify=False, discrete=False):
    """Plans every problem with every planner ``runs`` times; one row per attempt.

    problems: a sequence of (start, goal) pairs of full configurations (each shape (dof,)).
    planners: OMPL planner names (see ``plan``); time: seconds per attempt; joints, objective,
    simplify and discrete as in ``plan`` (certified motions unless discrete=True).

    Returns a dict of columns, each of one row per attempt in (problem, planner, run) order:
    'problem' (int), 'planner' (list of str), 'run' (int), 'solved' (bool), 'time' (s),
    'length' (joint-space; NaN when not solved), 'min_clearance' (m over waypoints; NaN when
    not solved), 'waypoints' (int), 'state_checks' (int); and 'summary', a dict per planner:
    {'solved': count, 'attempts': count, 'median_time': s, 'median_length': ...}.
    """
    problems = list(problems)
    planners = [planners] if isinstance(planners, str) else list(planners)
    if not problems:
        raise InputError("problems: expected at least one (start, goal) pair")
    if not planners:
        raise InputError("planners: expected at least one planner name")
    if int(runs) != runs or runs < 1:
        raise InputError(f"runs: expected an integer >= 1, got {runs!r}")
    for i, problem in enumerate(problems):
        if len(problem) != 2:
            raise InputError(f"problems[{i}]: expected a (start, goal) pair")
    columns = {k: [] for k in ("problem", "planner", "run", "solved", "time", "length",
                               "min_clearance", "waypoints", "state_checks")}
    for i, (start, goal) in enumerate(problems):
        for name in planners:
            for run in range(int(runs)):
                r = plan(checker, start, goal, joints=joints, planner=name, objective=objective,
                         time=time, simplify=simplify, discrete=discrete)
                columns["problem"].append(i)
                columns["planner"].append(name)
                columns["run"].append(run)
                columns["solved"].append(r["solved"])
                columns["time"].append(r["time"])
                columns["length"].append(r["length"])
                columns["min_clearance"].append(r["min_clearance"])
                columns["waypoints"].append(len(r["path"]))
                columns["state_checks"].append(r["state_checks"])
    out = {k: (v if k == "planner" else np.asarray(v)) for k, v in columns.items()}
    out["solved"] = out["solved"].astype(bool)
    summary = {}
    planner_column = np.asarray(out["planner"])
    for name in planners:
        rows = planner_column == name
        solved = rows & out["solved"]
        summary[name] = {
            "attempts": int(rows.sum()),
            "solved": int(solved.sum()),
            "median_time": float(np.median(out["time"][rows])),
            "median_length": float(np.median(out["length"][solved])) if solved.any() else
            float("nan"),
            "median_min_clearance": float(np.median(out["min_clearance"][solved]))
            if solved.any() else float("nan"),
        }
    out["summary"] = summary
    return out
