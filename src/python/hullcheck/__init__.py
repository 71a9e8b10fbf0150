"""hullcheck: exact proximity queries, robot collision checking and OMPL planning.

Units are metres and radians. Poses are 4x4 homogeneous matrices (local -> world) or pairs
(position, X-Y-Z angles). Configurations are float arrays of shape (dof,) or (N, dof), one
value per active joint in ``RobotModel.variable_names`` order. Bad input raises
``hullcheck.InputError`` (a ``ValueError``) with a message naming the argument, file or
element and the problem.

The compiled module is ``hullcheck._hullcheck``; everything public is re-exported here.
"""

from ._hullcheck import (  # noqa: F401
    Box,
    Capsule,
    Clearance,
    CollisionChecker,
    ConvexHull,
    Cylinder,
    DistanceResult,
    InputError,
    MotionCheck,
    MotionPlanRequest,
    Obstacle,
    PenetrationResult,
    PlanningScene,
    ProximityPair,
    QueryOptions,
    RobotModel,
    Shape,
    ShapeKind,
    SignedDistanceResult,
    Sphere,
    Srdf,
    Status,
    convex_hull_volume,
    distance,
    group_state_configuration,
    group_variables,
    intersect,
    optimize_clearance,
    parse_planning_scene,
    parse_srdf,
    penetration,
    plan,
    pose_from_xyz_angles,
    read_motion_plan_request,
    read_planning_scene,
    read_srdf,
    signed_distance,
    validate,
    within_distance,
)
from .planning import benchmark  # noqa: F401

__all__ = [name for name in dir() if not name.startswith("_") and name != "planning"]
