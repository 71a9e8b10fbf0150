// FCL 0.7 behind the common interface: fcl::Convex<double> built from the hull vertices and the
// hull triangulation, queried through the narrow-phase solvers directly (no broad phase, no
// CollisionObject), with the solvers' default tolerances.
//
// What each query calls (and what FCL runs underneath):
//  - intersect:   solver.shapeIntersect(a, tf_a, b, tf_b, nullptr)
//                 libccd: ccdMPRIntersect; indep: FCL's own GJK (no EPA without contacts).
//  - distance:    solver.shapeDistance(..., &dist, &p1, &p2)
//                 libccd: libccd_extension::ccdGJKDist2; indep: FCL's own GJK.
//  - penetration: solver.shapeIntersect(..., &contacts), one ContactPoint
//                 libccd: ccdMPRPenetration; indep: FCL's GJK + EPA.
//  - signed_distance: solver.shapeSignedDistance(..., &dist, &p1, &p2)
//                 libccd: ccdGJKSignedDist (GJK, then libccd's EPA when overlapping);
//                 indep: not implemented by FCL 0.7 (it runs shapeDistance and returns -1 when
//                 overlapping), so it is not offered.
#include <fcl/geometry/shape/convex.h>
#include <fcl/narrowphase/contact_point.h>
#include <fcl/narrowphase/detail/gjk_solver_indep.h>
#include <fcl/narrowphase/detail/gjk_solver_libccd.h>

#include <cmath>
#include <exception>

#include "peers.hpp"

namespace hullcheck::bench {
namespace {

using Convex = fcl::Convex<double>;

template <typename Solver>
class FclImpl final : public Impl {
 public:
  static constexpr bool kIndep = std::is_same_v<Solver, fcl::detail::GJKSolver_indep<double>>;

  std::string name() const override { return kIndep ? "FCL indep" : "FCL libccd"; }
  bool supports(Query q) const override { return !(kIndep && q == Query::kSignedDistance); }
  std::string api(Query q) const override {
    const std::string solver = kIndep ? "GJKSolver_indep" : "GJKSolver_libccd";
    switch (q) {
      case Query::kIntersect:
        return solver + "::shapeIntersect (no contacts)" +
               (kIndep ? " [GJK]" : " [ccdMPRIntersect]");
      case Query::kDistance:
        return solver + "::shapeDistance" + (kIndep ? " [GJK]" : " [ccdGJKDist2]");
      case Query::kPenetration:
        return solver + "::shapeIntersect (contacts)" +
               (kIndep ? " [GJK+EPA]" : " [ccdMPRPenetration]");
      case Query::kSignedDistance:
        return kIndep ? "not implemented in FCL 0.7 (returns -1 when overlapping)"
                      : solver + "::shapeSignedDistance [ccdGJKSignedDist: GJK+EPA]";
    }
    return "";
  }

  void prepare(const std::vector<Case>& cases) override {
    shapes_.clear();
    cases_.clear();
    for (const Case& c : cases) {
      const std::size_t ia = shape_index(c.a);
      const std::size_t ib = shape_index(c.b);
      cases_.push_back({ia, ib, c.pose_a, c.pose_b});
    }
  }

  bool intersect(std::size_t i) override {
    const Prepared& p = cases_[i];
    try {
      return solver_.shapeIntersect(*shapes_[p.a].convex, p.tf_a, *shapes_[p.b].convex, p.tf_b,
                                    nullptr);
    } catch (const std::exception&) {
      return false;
    }
  }

  DistanceOut distance(std::size_t i) override {
    const Prepared& p = cases_[i];
    DistanceOut out;
    double d = 0;
    Eigen::Vector3d p1 = Eigen::Vector3d::Zero(), p2 = Eigen::Vector3d::Zero();
    try {
      out.separated = solver_.shapeDistance(*shapes_[p.a].convex, p.tf_a, *shapes_[p.b].convex,
                                            p.tf_b, &d, &p1, &p2);
    } catch (const std::exception&) {
      out.ok = false;
      return out;
    }
    if (!out.separated) return out;  // both solvers return false (distance -1) when overlapping
    out.distance = d;
    out.point_a = p1;
    out.point_b = p2;
    return out;
  }

  PenetrationOut penetration(std::size_t i) override {
    const Prepared& p = cases_[i];
    PenetrationOut out;
    contacts_.clear();
    try {
      out.overlapping = solver_.shapeIntersect(*shapes_[p.a].convex, p.tf_a, *shapes_[p.b].convex,
                                               p.tf_b, &contacts_);
    } catch (const std::exception&) {
      out.ok = false;
      return out;
    }
    if (!out.overlapping) return out;
    if (contacts_.empty()) {
      out.ok = false;
      return out;
    }
    const fcl::ContactPoint<double>& c = contacts_.front();
    if constexpr (kIndep) {
      // FCL 0.7 GJKSolver_indep: the depth is stored negated and the normal is EPA's normal in
      // A's local frame (not rotated to the world frame), pointing from A towards B.
      out.depth = -c.penetration_depth;
      out.normal = p.tf_a.linear() * c.normal;
    } else {
      // libccd (MPR): world-frame normal from A towards B, positive depth.
      out.depth = c.penetration_depth;
      out.normal = c.normal;
    }
    return out;
  }

  SignedOut signed_distance(std::size_t i) override {
    const Prepared& p = cases_[i];
    SignedOut out;
    if constexpr (kIndep) {
      out.ok = false;
      (void)p;
    } else {
      double d = 0;
      try {
        solver_.shapeSignedDistance(*shapes_[p.a].convex, p.tf_a, *shapes_[p.b].convex, p.tf_b, &d,
                                    nullptr, nullptr);
      } catch (const std::exception&) {
        out.ok = false;
      }
      out.value = d;
    }
    return out;
  }

 private:
  struct Shape {
    const HullMesh* mesh;
    std::shared_ptr<Convex> convex;
  };
  struct Prepared {
    std::size_t a, b;
    fcl::Transform3d tf_a, tf_b;
  };

  std::size_t shape_index(const std::shared_ptr<const HullMesh>& mesh) {
    for (std::size_t k = 0; k < shapes_.size(); ++k) {
      if (shapes_[k].mesh == mesh.get()) return k;
    }
    auto vertices = std::make_shared<std::vector<Eigen::Vector3d>>(mesh->vertices);
    auto faces = std::make_shared<std::vector<int>>();
    faces->reserve(mesh->triangles.size() * 4);
    for (const auto& t : mesh->triangles) faces->insert(faces->end(), {3, t[0], t[1], t[2]});
    // throw_if_invalid: the qhull triangulation must be watertight, else FCL silently falls
    // back to a linear-scan support (and the comparison would not be what it claims).
    auto convex = std::make_shared<Convex>(vertices, static_cast<int>(mesh->triangles.size()),
                                           faces, /*throw_if_invalid=*/true);
    convex->computeLocalAABB();
    shapes_.push_back({mesh.get(), convex});
    return shapes_.size() - 1;
  }

  Solver solver_;
  std::vector<Shape> shapes_;
  std::vector<Prepared> cases_;
  std::vector<fcl::ContactPoint<double>> contacts_;
};

}  // namespace

std::unique_ptr<Impl> make_fcl_libccd_impl() {
  return std::make_unique<FclImpl<fcl::detail::GJKSolver_libccd<double>>>();
}
std::unique_ptr<Impl> make_fcl_indep_impl() {
  return std::make_unique<FclImpl<fcl::detail::GJKSolver_indep<double>>>();
}

}  // namespace hullcheck::bench
