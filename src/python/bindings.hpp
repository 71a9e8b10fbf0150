// The bindings of each layer, added to the module `hullcheck._hullcheck` by module.cpp.
#pragma once

#include <pybind11/pybind11.h>

namespace hullcheck::python {

void bind_core(pybind11::module_& m);      // shapes, poses, queries, ProximityPair
void bind_robot(pybind11::module_& m);     // RobotModel, SRDF, forward kinematics
void bind_scene(pybind11::module_& m);     // scenes, requests, CollisionChecker and its batches
void bind_planning(pybind11::module_& m);  // plan, validate, benchmark (OMPL)

}  // namespace hullcheck::python
