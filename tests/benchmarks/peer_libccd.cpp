// libccd 2.1 (double precision) behind the common interface.
//
// libccd has no shape types: the caller supplies support and centre callbacks. The support
// callback here is what a careful libccd user would write: rotate the direction into the local
// frame, then a linear scan over the hull vertices for up to 32 vertices, and above that a hill
// climb over the hull's vertex adjacency from vertex 0 (FCL's Convex does the same). The centre
// (used by MPR) is the mean of the hull vertices.
//
// libccd 2.1 has no distance query (ccdGJKSeparate is penetration, not distance), and no signed
// distance; only intersect and penetration are offered. Tolerances are libccd's defaults
// (CCD_INIT: epa_tolerance = mpr_tolerance = 1e-4, dist_tolerance = 1e-6), with max_iterations
// capped at 1000 instead of "unlimited".
#include <ccd/ccd.h>

#include <cmath>

#include "peers.hpp"

namespace hullcheck::bench {
namespace {

struct CcdHull {
  const HullMesh* mesh = nullptr;
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  Eigen::Vector3d center_world = Eigen::Vector3d::Zero();
};

constexpr std::size_t kHillClimbAbove = 32;

void support(const void* obj, const ccd_vec3_t* dir, ccd_vec3_t* out) {
  const auto* hull = static_cast<const CcdHull*>(obj);
  const Eigen::Vector3d d =
      hull->rotation.transpose() * Eigen::Vector3d(dir->v[0], dir->v[1], dir->v[2]);
  const std::vector<Eigen::Vector3d>& vs = hull->mesh->vertices;
  std::size_t best = 0;
  double best_value = d.dot(vs[0]);
  if (vs.size() <= kHillClimbAbove) {
    for (std::size_t i = 1; i < vs.size(); ++i) {
      const double value = d.dot(vs[i]);
      if (value > best_value) {
        best_value = value;
        best = i;
      }
    }
  } else {
    // Strict hill climbing: on a convex polytope a vertex with no strictly better neighbour
    // maximises the linear function, and the strict increase guarantees termination.
    bool improved = true;
    while (improved) {
      improved = false;
      for (int n : hull->mesh->neighbors[best]) {
        const double value = d.dot(vs[static_cast<std::size_t>(n)]);
        if (value > best_value) {
          best_value = value;
          best = static_cast<std::size_t>(n);
          improved = true;
        }
      }
    }
  }
  const Eigen::Vector3d p = hull->rotation * vs[best] + hull->translation;
  out->v[0] = p.x();
  out->v[1] = p.y();
  out->v[2] = p.z();
}

void center(const void* obj, ccd_vec3_t* out) {
  const auto* hull = static_cast<const CcdHull*>(obj);
  out->v[0] = hull->center_world.x();
  out->v[1] = hull->center_world.y();
  out->v[2] = hull->center_world.z();
}

class LibccdImpl final : public Impl {
 public:
  explicit LibccdImpl(bool mpr) : mpr_(mpr) {
    CCD_INIT(&ccd_);
    ccd_.support1 = support;
    ccd_.support2 = support;
    ccd_.center1 = center;
    ccd_.center2 = center;
    ccd_.max_iterations = 1000;
  }

  std::string name() const override { return mpr_ ? "libccd MPR" : "libccd GJK"; }
  bool supports(Query q) const override {
    return q == Query::kIntersect || q == Query::kPenetration;
  }
  std::string api(Query q) const override {
    if (q == Query::kIntersect) return mpr_ ? "ccdMPRIntersect" : "ccdGJKIntersect";
    if (q == Query::kPenetration) return mpr_ ? "ccdMPRPenetration" : "ccdGJKPenetration";
    return "not available in libccd 2.1";
  }

  void prepare(const std::vector<Case>& cases) override {
    hulls_.clear();
    hulls_.reserve(cases.size());
    for (const Case& c : cases) {
      hulls_.push_back({make(*c.a, c.pose_a), make(*c.b, c.pose_b)});
    }
  }

  bool intersect(std::size_t i) override {
    const auto& h = hulls_[i];
    return (mpr_ ? ccdMPRIntersect(&h[0], &h[1], &ccd_) : ccdGJKIntersect(&h[0], &h[1], &ccd_)) !=
           0;
  }

  DistanceOut distance(std::size_t) override {
    DistanceOut out;
    out.ok = false;
    return out;
  }

  PenetrationOut penetration(std::size_t i) override {
    const auto& h = hulls_[i];
    ccd_real_t depth = 0;
    ccd_vec3_t dir{{0, 0, 0}};
    ccd_vec3_t pos{{0, 0, 0}};
    const int r = mpr_ ? ccdMPRPenetration(&h[0], &h[1], &ccd_, &depth, &dir, &pos)
                       : ccdGJKPenetration(&h[0], &h[1], &ccd_, &depth, &dir, &pos);
    PenetrationOut out;
    if (r == -1) return out;  // not intersecting
    if (r != 0) {
      out.ok = false;
      return out;
    }
    out.overlapping = true;
    out.depth = depth;
    // libccd: translating obj2 by depth * dir separates the shapes, so dir (unit, world
    // frame) already points from A towards B (checked on rotated unit cubes at known offsets).
    out.normal = Eigen::Vector3d(dir.v[0], dir.v[1], dir.v[2]);
    return out;
  }

  SignedOut signed_distance(std::size_t) override {
    SignedOut out;
    out.ok = false;
    return out;
  }

 private:
  static CcdHull make(const HullMesh& mesh, const Eigen::Isometry3d& pose) {
    CcdHull h;
    h.mesh = &mesh;
    h.rotation = pose.linear();
    h.translation = pose.translation();
    h.center_world = pose * mesh.centroid;
    return h;
  }

  bool mpr_;
  ccd_t ccd_;
  std::vector<std::array<CcdHull, 2>> hulls_;
};

}  // namespace

std::unique_ptr<Impl> make_libccd_gjk_impl() { return std::make_unique<LibccdImpl>(false); }
std::unique_ptr<Impl> make_libccd_mpr_impl() { return std::make_unique<LibccdImpl>(true); }

}  // namespace hullcheck::bench
