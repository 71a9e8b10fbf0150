// Umbrella header of hullcheck's OMPL integration: scenes, the collision checker, the joint
// state space, validity checker, guaranteed motion validator, clearance objectives and path
// optimization.
#pragma once

#include <hullcheck/ompl/joint_state_space.hpp>
#include <hullcheck/ompl/motion_validator.hpp>
#include <hullcheck/ompl/objectives.hpp>
#include <hullcheck/ompl/path_optimization.hpp>
#include <hullcheck/ompl/planning_setup.hpp>
#include <hullcheck/ompl/state_validity_checker.hpp>
#include <hullcheck/robot.hpp>
#include <hullcheck/scene/clearance_gradient.hpp>
#include <hullcheck/scene/collision_checker.hpp>
#include <hullcheck/scene/motion_plan_request.hpp>
#include <hullcheck/scene/planning_scene.hpp>
