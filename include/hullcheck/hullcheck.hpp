// Umbrella header of all of hullcheck: the core, robot, scene and OMPL layers (target
// hullcheck::hullcheck). A program using only the proximity queries includes
// <hullcheck/core.hpp> and links hullcheck::core, which needs neither OMPL nor the loaders.
#pragma once

#include <hullcheck/core.hpp>
#include <hullcheck/ompl.hpp>
#include <hullcheck/robot.hpp>
#include <hullcheck/scene.hpp>
