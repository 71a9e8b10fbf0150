// Umbrella header of hullcheck's scene layer: planning scenes, the collision checker, motion
// plan requests and the clearance gradient (and the robot and core layers below them).
#pragma once

#include <hullcheck/robot.hpp>
#include <hullcheck/scene/approaching_self_pairs.hpp>
#include <hullcheck/scene/clearance_gradient.hpp>
#include <hullcheck/scene/collision_checker.hpp>
#include <hullcheck/scene/collision_matrix_generation.hpp>
#include <hullcheck/scene/motion_plan_request.hpp>
#include <hullcheck/scene/pair_scope.hpp>
#include <hullcheck/scene/planning_scene.hpp>
