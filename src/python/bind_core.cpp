// The core layer in Python: shapes, poses, the four queries and their results, ProximityPair.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <hullcheck/core.hpp>

#include "arguments.hpp"
#include "bindings.hpp"

namespace hullcheck::python {
namespace {

// Each query as Python sees it: shapes, then poses in any form pose() takes.
template <class Result, class Query>
Result run_query(const Shape& a, py::handle pose_a, const Shape& b, py::handle pose_b,
                 const QueryOptions& options, Query query) {
  const Eigen::Isometry3d pa = pose(pose_a, "pose_a"), pb = pose(pose_b, "pose_b");
  return query(a, pa, b, pb, options);
}

std::vector<Eigen::Vector3d> points(py::handle object, const char* name) {
  const RealArray a = real_array(object, name);
  if (a.ndim() != 2 || a.shape(1) != 3) {
    throw InputError(std::string(name) + ": expected shape (N, 3), got " + shape_text(a));
  }
  std::vector<Eigen::Vector3d> out(static_cast<std::size_t>(a.shape(0)));
  const auto v = a.unchecked<2>();
  for (std::size_t i = 0; i < out.size(); ++i) {
    const auto r = static_cast<py::ssize_t>(i);
    out[i] = Eigen::Vector3d(v(r, 0), v(r, 1), v(r, 2));
  }
  return out;
}

Eigen::MatrixXd rows_of(const std::vector<Eigen::Vector3d>& v) {
  Eigen::MatrixXd m(static_cast<Eigen::Index>(v.size()), 3);
  for (std::size_t i = 0; i < v.size(); ++i) m.row(static_cast<Eigen::Index>(i)) = v[i];
  return m;
}

constexpr const char* kPoseDoc =
    "Poses (local -> world): a 4x4 homogeneous matrix, (position, xyz_angles) with X-Y-Z angles "
    "in radians (R = Rx Ry Rz), or None for the identity. Results are in the world frame, "
    "metres.";

}  // namespace

void bind_core(py::module_& m) {
  py::enum_<Status>(m, "Status", "How a query reached its answer.")
      .value("CONVERGED", Status::kConverged, "Tolerance met: exact to the stated tolerance.")
      .value("ITERATION_CAP", Status::kIterationCap, "Stopped at the iteration cap.")
      .value("DEGENERATE", Status::kDegenerate, "Numerical limit reached; best bound found.")
      .value("ABOVE_CUTOFF", Status::kAboveCutoff, "Proven at least the caller's cutoff.");

  py::class_<QueryOptions>(m, "QueryOptions",
                           "Tolerances and iteration caps of the proximity queries. Tolerances "
                           "are relative to the pair's scale (the larger shape's extent).")
      .def(py::init<>())
      .def_readwrite("relative_tolerance", &QueryOptions::relative_tolerance)
      .def_readwrite("max_gjk_iterations", &QueryOptions::max_gjk_iterations)
      .def_readwrite("max_epa_iterations", &QueryOptions::max_epa_iterations);

  py::class_<Sphere>(m, "Sphere", "Ball of `radius` (m) about the local origin.")
      .def(py::init<double>(), py::arg("radius"))
      .def_readonly("radius", &Sphere::radius)
      .def("__repr__", [](const Sphere& s) { return "Sphere(" + std::to_string(s.radius) + ")"; });
  py::class_<Capsule>(m, "Capsule",
                      "Segment along local z of `length` (without the caps) grown by `radius`.")
      .def(py::init<double, double>(), py::arg("radius"), py::arg("length"))
      .def_readonly("radius", &Capsule::radius)
      .def_readonly("half_length", &Capsule::half_length);
  py::class_<Box>(m, "Box", "Box centred on the local origin, from its full side lengths (m).")
      .def(py::init<double, double, double>(), py::arg("size_x"), py::arg("size_y"),
           py::arg("size_z"))
      .def_readonly("half_extents", &Box::half_extents);
  py::class_<Cylinder>(m, "Cylinder",
                       "Solid cylinder of `radius`, axis local z, total `length`, centred.")
      .def(py::init<double, double>(), py::arg("radius"), py::arg("length"))
      .def_readonly("radius", &Cylinder::radius)
      .def_readonly("half_length", &Cylinder::half_length);
  py::class_<ConvexHull>(m, "ConvexHull",
                         "Convex hull (qhull) of an (N, 3) point array in its local frame; "
                         "degenerate sets (flat, a segment, a point) are valid shapes.")
      .def(py::init([](py::handle p) { return ConvexHull(points(p, "points")); }),
           py::arg("points"))
      .def_property_readonly(
          "vertices", [](const ConvexHull& h) { return rows_of(h.vertices()); },
          "Hull vertices, (V, 3), local frame.")
      .def_property_readonly("triangles", &ConvexHull::triangles,
                             "Boundary triangles (indices into vertices).")
      .def_property_readonly("dimension", &ConvexHull::dimension)
      .def_property_readonly("extent", &ConvexHull::extent)
      .def("__len__", &ConvexHull::vertex_count);
  m.def(
      "convex_hull_volume", [](py::handle p) { return convex_hull_volume(points(p, "points")); },
      py::arg("points"), "Volume (m^3) of the convex hull of (N, 3) points; 0 when degenerate.");

  py::enum_<ShapeKind>(m, "ShapeKind")
      .value("SPHERE", ShapeKind::kSphere)
      .value("CAPSULE", ShapeKind::kCapsule)
      .value("BOX", ShapeKind::kBox)
      .value("CYLINDER", ShapeKind::kCylinder)
      .value("CONVEX_HULL", ShapeKind::kConvexHull);
  py::class_<Shape>(m, "Shape",
                    "A convex shape (a primitive or a hull) grown by a margin; every query "
                    "takes a Shape or any primitive directly.")
      .def(py::init<const Sphere&>())
      .def(py::init<const Capsule&>())
      .def(py::init<const Box&>())
      .def(py::init<const Cylinder&>())
      .def(py::init<const ConvexHull&>())
      .def("inflated", &Shape::inflated, py::arg("margin"),
           "The same geometry grown by `margin` m (>= 0); margins add.")
      .def_property_readonly("kind", &Shape::kind)
      .def_property_readonly("margin", &Shape::margin)
      .def_property_readonly("bounding_radius", &Shape::bounding_radius)
      .def(
          "support",
          [](const Shape& s, py::handle d) { return Eigen::Vector3d(s.support(vector3(d, "d"))); },
          py::arg("direction"), "A point of the shape maximising dot(p, direction), local frame.");
  py::implicitly_convertible<Sphere, Shape>();
  py::implicitly_convertible<Capsule, Shape>();
  py::implicitly_convertible<Box, Shape>();
  py::implicitly_convertible<Cylinder, Shape>();
  py::implicitly_convertible<ConvexHull, Shape>();

  m.def(
      "pose_from_xyz_angles",
      [](py::handle position, py::handle angles) {
        return Eigen::Matrix4d(
            pose_from_xyz_angles(vector3(position, "position"), vector3(angles, "angles"))
                .matrix());
      },
      py::arg("position"), py::arg("angles"),
      "4x4 pose: translation `position` (m), rotation Rx(gx) Ry(gy) Rz(gz) (radians).");

  py::class_<DistanceResult>(m, "DistanceResult", "distance(): world frame, metres.")
      .def_readonly("distance", &DistanceResult::distance)
      .def_readonly("point_a", &DistanceResult::point_a)
      .def_readonly("point_b", &DistanceResult::point_b)
      .def_readonly("normal", &DistanceResult::normal)
      .def_readonly("status", &DistanceResult::status)
      .def_readonly("iterations", &DistanceResult::iterations)
      .def("__repr__", [](const DistanceResult& r) {
        return "DistanceResult(distance=" + std::to_string(r.distance) + ")";
      });
  py::class_<PenetrationResult>(m, "PenetrationResult", "penetration(): world frame, metres.")
      .def_readonly("depth", &PenetrationResult::depth)
      .def_readonly("normal", &PenetrationResult::normal)
      .def_readonly("point_a", &PenetrationResult::point_a)
      .def_readonly("point_b", &PenetrationResult::point_b)
      .def_readonly("status", &PenetrationResult::status)
      .def_readonly("iterations", &PenetrationResult::iterations)
      .def_readonly("epa_iterations", &PenetrationResult::epa_iterations)
      .def("__repr__", [](const PenetrationResult& r) {
        return "PenetrationResult(depth=" + std::to_string(r.depth) + ")";
      });
  py::class_<SignedDistanceResult>(m, "SignedDistanceResult",
                                   "signed_distance(): distance apart, minus depth overlapping.")
      .def_readonly("signed_distance", &SignedDistanceResult::signed_distance)
      .def_readonly("point_a", &SignedDistanceResult::point_a)
      .def_readonly("point_b", &SignedDistanceResult::point_b)
      .def_readonly("normal", &SignedDistanceResult::normal)
      .def_readonly("status", &SignedDistanceResult::status)
      .def_readonly("iterations", &SignedDistanceResult::iterations)
      .def_readonly("epa_iterations", &SignedDistanceResult::epa_iterations)
      .def("__repr__", [](const SignedDistanceResult& r) {
        return "SignedDistanceResult(signed_distance=" + std::to_string(r.signed_distance) + ")";
      });

  const auto query_args = [] {
    return std::make_tuple(py::arg("a"), py::arg("pose_a"), py::arg("b"), py::arg("pose_b"),
                           py::arg("options") = QueryOptions{});
  };
  const auto [a1, a2, a3, a4, a5] = query_args();
  m.def(
      "intersect",
      [](const Shape& a, py::handle pa, const Shape& b, py::handle pb, const QueryOptions& o) {
        return run_query<bool>(a, pa, b, pb, o, [](auto&&... x) { return intersect(x...); });
      },
      a1, a2, a3, a4, a5,
      (std::string("True when A and B overlap or touch (GJK). ") + kPoseDoc).c_str());
  m.def(
      "within_distance",
      [](const Shape& a, py::handle pa, const Shape& b, py::handle pb, double d,
         const QueryOptions& o) {
        return run_query<bool>(a, pa, b, pb, o,
                               [d](const Shape& sa, const Eigen::Isometry3d& ta, const Shape& sb,
                                   const Eigen::Isometry3d& tb, const QueryOptions& options) {
                                 return within_distance(sa, ta, sb, tb, d, options);
                               });
      },
      a1, a2, a3, a4, py::arg("distance"), a5,
      (std::string("True when A and B are at most `distance` (m, >= 0) apart, overlapping "
                   "included (boolean GJK on A grown by it; no distance computed). ") +
       kPoseDoc)
          .c_str());
  m.def(
      "distance",
      [](const Shape& a, py::handle pa, const Shape& b, py::handle pb, const QueryOptions& o) {
        return run_query<DistanceResult>(a, pa, b, pb, o,
                                         [](auto&&... x) { return distance(x...); });
      },
      a1, a2, a3, a4, a5,
      (std::string("Separation distance and closest points (GJK); 0 when overlapping. ") + kPoseDoc)
          .c_str());
  m.def(
      "penetration",
      [](const Shape& a, py::handle pa, const Shape& b, py::handle pb, const QueryOptions& o) {
        return run_query<PenetrationResult>(a, pa, b, pb, o,
                                            [](auto&&... x) { return penetration(x...); });
      },
      a1, a2, a3, a4, a5,
      (std::string("Penetration depth, direction and witnesses (GJK + EPA); 0 when apart. ") +
       kPoseDoc)
          .c_str());
  m.def(
      "signed_distance",
      [](const Shape& a, py::handle pa, const Shape& b, py::handle pb, const QueryOptions& o) {
        return run_query<SignedDistanceResult>(a, pa, b, pb, o,
                                               [](auto&&... x) { return signed_distance(x...); });
      },
      a1, a2, a3, a4, a5,
      (std::string("Distance when apart, minus the depth when overlapping. ") + kPoseDoc).c_str());

  py::class_<ProximityPair>(m, "ProximityPair",
                            "Two shapes with poses and cached, warm-started queries: each "
                            "answer is computed at most once per configuration. Not "
                            "thread-safe: one pair per thread.")
      .def(py::init<const QueryOptions&>(), py::arg("options") = QueryOptions{})
      .def(
          "set_shape_a",
          [](ProximityPair& p, const Shape& s, py::handle pa) {
            p.set_shape_a(s, pose(pa, "pose"));
          },
          py::arg("shape"), py::arg("pose") = py::none())
      .def(
          "set_shape_b",
          [](ProximityPair& p, const Shape& s, py::handle pb) {
            p.set_shape_b(s, pose(pb, "pose"));
          },
          py::arg("shape"), py::arg("pose") = py::none())
      .def(
          "set_pose_a", [](ProximityPair& p, py::handle pa) { p.set_pose_a(pose(pa, "pose")); },
          py::arg("pose"), "Move A, keeping the warm start.")
      .def(
          "set_pose_b", [](ProximityPair& p, py::handle pb) { p.set_pose_b(pose(pb, "pose")); },
          py::arg("pose"), "Move B, keeping the warm start.")
      .def("in_collision", &ProximityPair::in_collision)
      .def("distance", &ProximityPair::distance, py::return_value_policy::copy)
      .def("penetration", &ProximityPair::penetration, py::return_value_policy::copy)
      .def("signed_distance", &ProximityPair::signed_distance, py::return_value_policy::copy)
      .def_property_readonly("last_iterations", &ProximityPair::last_iterations)
      .def_property_readonly("last_was_cached", &ProximityPair::last_was_cached);
}

}  // namespace hullcheck::python
