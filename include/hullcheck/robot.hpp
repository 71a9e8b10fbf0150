// Umbrella header of hullcheck's robot model: URDF loading, forward kinematics, SRDF,
// allowed-collision matrices, convex decomposition (self-collision checks: hullcheck/scene.hpp).
#pragma once

#include <hullcheck/core.hpp>
#include <hullcheck/robot/allowed_collision_matrix.hpp>
#include <hullcheck/robot/convex_decomposition.hpp>
#include <hullcheck/robot/decomposition_cache.hpp>
#include <hullcheck/robot/mesh_file.hpp>
#include <hullcheck/robot/planning_group.hpp>
#include <hullcheck/robot/resource_path.hpp>
#include <hullcheck/robot/robot_model.hpp>
#include <hullcheck/robot/srdf.hpp>
