// The compiled part of the Python package `hullcheck` (hullcheck/__init__.py re-exports it).
#include <hullcheck/core/errors.hpp>

#include "bindings.hpp"

PYBIND11_MODULE(_hullcheck, m) {
  m.doc() =
      "hullcheck: exact proximity queries (GJK + EPA), robot models from URDF, collision "
      "checking of configurations and motions, and OMPL planning. Units: metres and radians.";
  // InputError is a ValueError carrying the C++ message (file, element and problem).
  pybind11::register_exception<hullcheck::InputError>(m, "InputError", PyExc_ValueError);
  hullcheck::python::bind_core(m);
  hullcheck::python::bind_robot(m);
  hullcheck::python::bind_scene(m);
  hullcheck::python::bind_planning(m);
}
