// Umbrella header of hullcheck's OMPL layer: the joint state space, validity checker,
// guaranteed motion validator, clearance objectives and path optimization (and the scene,
// robot and core layers below them).
#pragma once

#include <hullcheck/ompl/clearance_optimizer.hpp>
#include <hullcheck/ompl/joint_state_space.hpp>
#include <hullcheck/ompl/motion_validator.hpp>
#include <hullcheck/ompl/objectives.hpp>
#include <hullcheck/ompl/path_simplification.hpp>
#include <hullcheck/ompl/planning_setup.hpp>
#include <hullcheck/ompl/state_validity_checker.hpp>
#include <hullcheck/scene.hpp>
