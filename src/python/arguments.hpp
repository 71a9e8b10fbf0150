// Python arguments of the bindings, checked and converted: numpy arrays of configurations,
// vectors and poses, thread counts. Every failure is a hullcheck.InputError (a ValueError)
// naming the argument, the expected shape and what was given.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Geometry>
#include <hullcheck/scene/collision_checker.hpp>
#include <string>

namespace hullcheck::python {

namespace py = pybind11;

/// A float64, C-contiguous array (a view when `object` already is one, else a converted copy).
using RealArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// `object` (a numpy array or a nested sequence of numbers) as a RealArray; InputError unless
/// its dtype is a real number type (float, int, uint: not bool, complex, strings or objects).
RealArray real_array(py::handle object, const char* name);

/// "(3, 6)": an array's shape as Python prints it.
std::string shape_text(const py::array& array);

/// A 3-vector (shape (3,)), finite values.
Eigen::Vector3d vector3(py::handle object, const char* name);

/// A pose, local -> world: None (the identity), a 4x4 homogeneous matrix whose last row is
/// (0, 0, 0, 1), or a pair (position (3,), X-Y-Z angles (3,), radians: pose_from_xyz_angles).
/// The rotation is checked where the pose is used (validate_pose: a rotation to 1e-6).
Eigen::Isometry3d pose(py::handle object, const char* name);

/// Configurations for a robot with `dof` values: shape (dof,) (one; `single` true) or
/// (N, dof) (N >= 0 rows). Rows are contiguous, so `data` is also the column-major
/// dof x N matrix CollisionChecker's batch entry points take.
struct Configurations {
  RealArray array;
  const double* data = nullptr;
  Eigen::Index count = 0;
  int dof = 0;
  bool single = false;
  /// Configuration i as an Eigen map.
  Eigen::Map<const Eigen::VectorXd> row(Eigen::Index i) const {
    return Eigen::Map<const Eigen::VectorXd>(data + i * dof, dof);
  }
};
Configurations configurations(py::handle object, const char* name, int dof);

/// "all", "obstacles" or "self" as a ClearanceScope; InputError naming `scope` otherwise.
ClearanceScope clearance_scope(const std::string& scope);

/// Threads for a batch of `work` items: None or 1 -> 1, 0 -> every hardware thread, n > 1 ->
/// n; never more than `work`. InputError for a negative count.
int thread_count(py::handle threads, Eigen::Index work);

/// Runs body(begin, end) over [0, count) split into `threads` contiguous chunks, one thread
/// each (the calling thread takes the first). The caller releases the GIL around it.
template <class Body>
void parallel_chunks(Eigen::Index count, int threads, const Body& body);

}  // namespace hullcheck::python

#include "parallel_chunks.hpp"
