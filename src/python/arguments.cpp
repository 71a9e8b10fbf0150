#include "arguments.hpp"

#include <cmath>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/core/pose.hpp>
#include <sstream>

namespace hullcheck::python {

RealArray real_array(py::handle object, const char* name) {
  if (object.is_none()) throw InputError(std::string(name) + ": expected an array, got None");
  py::array any;
  try {
    any = py::array::ensure(object);
  } catch (const py::error_already_set&) {
    any = py::array();
  }
  if (!any) {
    throw InputError(std::string(name) + ": expected an array of numbers, got " +
                     std::string(py::str(py::type::handle_of(object).attr("__name__"))));
  }
  const char kind = any.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u') {
    throw InputError(std::string(name) + ": expected real numbers (a float or integer array), " +
                     "got dtype " + std::string(py::str(any.dtype())));
  }
  return RealArray::ensure(any);
}

std::string shape_text(const py::array& array) {
  std::ostringstream out;
  out << '(';
  for (py::ssize_t d = 0; d < array.ndim(); ++d) {
    out << (d ? ", " : "") << array.shape(d);
  }
  out << (array.ndim() == 1 ? ",)" : ")");
  return out.str();
}

Eigen::Vector3d vector3(py::handle object, const char* name) {
  const RealArray a = real_array(object, name);
  if (a.ndim() != 1 || a.shape(0) != 3) {
    throw InputError(std::string(name) + ": expected shape (3,), got " + shape_text(a));
  }
  return Eigen::Vector3d(a.at(0), a.at(1), a.at(2));
}

Eigen::Isometry3d pose(py::handle object, const char* name) {
  if (object.is_none()) return Eigen::Isometry3d::Identity();
  if (py::isinstance<py::tuple>(object) || py::isinstance<py::list>(object)) {
    const py::sequence pair = py::reinterpret_borrow<py::sequence>(object);
    if (pair.size() == 2) {
      const std::string n(name);
      return pose_from_xyz_angles(vector3(pair[0], (n + " position").c_str()),
                                  vector3(pair[1], (n + " xyz angles").c_str()));
    }
  }
  const RealArray m = real_array(object, name);
  if (m.ndim() != 2 || m.shape(0) != 4 || m.shape(1) != 4) {
    throw InputError(std::string(name) +
                     ": expected a 4x4 matrix or (position, xyz_angles), got shape " +
                     shape_text(m));
  }
  const auto v = m.unchecked<2>();
  if (v(3, 0) != 0.0 || v(3, 1) != 0.0 || v(3, 2) != 0.0 || v(3, 3) != 1.0) {
    throw InputError(std::string(name) + ": the last row of a pose matrix must be [0, 0, 0, 1]");
  }
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) pose.matrix()(r, c) = v(r, c);
  }
  validate_pose(pose, name);
  return pose;
}

Configurations configurations(py::handle object, const char* name, int dof) {
  Configurations c;
  c.array = real_array(object, name);
  c.dof = dof;
  const std::string expected =
      "expected shape (" + std::to_string(dof) + ",) or (N, " + std::to_string(dof) + ")";
  if (c.array.ndim() == 1 && c.array.shape(0) == dof) {
    c.single = true;
    c.count = 1;
  } else if (c.array.ndim() == 2 && c.array.shape(1) == dof) {
    c.count = static_cast<Eigen::Index>(c.array.shape(0));
  } else {
    throw InputError(std::string(name) + ": " + expected + ", got " + shape_text(c.array));
  }
  c.data = c.array.data();
  const Eigen::Index n = c.count * dof;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!std::isfinite(c.data[i])) {
      throw InputError(std::string(name) + ": value " + std::to_string(i % dof) +
                       (c.single ? "" : " of row " + std::to_string(i / dof)) + " is not finite");
    }
  }
  return c;
}

ClearanceScope clearance_scope(const std::string& scope) {
  if (scope == "all") return ClearanceScope::kAll;
  if (scope == "obstacles") return ClearanceScope::kObstacles;
  if (scope == "self") return ClearanceScope::kSelf;
  throw InputError("scope: expected 'all', 'obstacles' or 'self', got '" + scope + "'");
}

int thread_count(py::handle threads, Eigen::Index work) {
  long n = 1;
  if (!threads.is_none()) {
    if (!py::isinstance<py::int_>(threads) || py::isinstance<py::bool_>(threads)) {
      throw InputError("threads: expected None or an integer >= 0, got " +
                       std::string(py::str(py::type::handle_of(threads).attr("__name__"))));
    }
    n = threads.cast<long>();
  }
  if (n < 0)
    throw InputError("threads: expected >= 0 (0: every hardware thread), got " + std::to_string(n));
  if (n == 0) n = std::max(1u, std::thread::hardware_concurrency());
  return static_cast<int>(std::max<long>(1, std::min<long>(n, std::max<Eigen::Index>(1, work))));
}

}  // namespace hullcheck::python
