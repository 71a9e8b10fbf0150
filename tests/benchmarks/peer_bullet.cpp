// Bullet 3.24 in double precision (BT_USE_DOUBLE_PRECISION, libraries *-float64) behind the
// common interface: btGjkEpaSolver2 on btConvexHullShape built from the hull vertices, margin 0.
//
//  - intersect:   !btGjkEpaSolver2::Distance(...) — Bullet's cheapest exact boolean for convex
//                 pairs (GJK run to convergence; Bullet has no early-exit GJK intersect).
//  - distance:    btGjkEpaSolver2::Distance (false when penetrating).
//  - penetration: btGjkEpaSolver2::Penetration (GJK + EPA).
//  - signed_distance: btGjkEpaSolver2::SignedDistance (Distance, then Penetration if that fails).
// The initial guess is the centre difference (A minus B) in A's local frame, which is the frame
// btGjkEpaSolver2 works in.
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpa2.h>

#include "peers.hpp"

#ifndef BT_USE_DOUBLE_PRECISION
#error "Bullet must be the double-precision build (pkg-config bullet-float64)"
#endif

namespace hullcheck::bench {
namespace {

btVector3 to_bt(const Eigen::Vector3d& v) { return btVector3(v.x(), v.y(), v.z()); }
Eigen::Vector3d to_eigen(const btVector3& v) { return Eigen::Vector3d(v.x(), v.y(), v.z()); }

btTransform to_bt(const Eigen::Isometry3d& pose) {
  const Eigen::Matrix3d& r = pose.linear();
  btMatrix3x3 basis(r(0, 0), r(0, 1), r(0, 2), r(1, 0), r(1, 1), r(1, 2), r(2, 0), r(2, 1),
                    r(2, 2));
  return btTransform(basis, to_bt(pose.translation()));
}

class BulletImpl final : public Impl {
 public:
  std::string name() const override { return "Bullet"; }
  bool supports(Query) const override { return true; }
  std::string api(Query q) const override {
    switch (q) {
      case Query::kIntersect:
        return "!btGjkEpaSolver2::Distance (GJK to convergence)";
      case Query::kDistance:
        return "btGjkEpaSolver2::Distance";
      case Query::kPenetration:
        return "btGjkEpaSolver2::Penetration (GJK+EPA)";
      case Query::kSignedDistance:
        return "btGjkEpaSolver2::SignedDistance";
    }
    return "";
  }

  void prepare(const std::vector<Case>& cases) override {
    shapes_.clear();
    cases_.clear();
    for (const Case& c : cases) {
      Prepared p;
      p.a = shape_index(c.a);
      p.b = shape_index(c.b);
      p.tf_a = to_bt(c.pose_a);
      p.tf_b = to_bt(c.pose_b);
      const Eigen::Vector3d guess =
          c.pose_a.linear().transpose() * (c.pose_a * c.a->centroid - c.pose_b * c.b->centroid);
      p.guess = to_bt(guess);
      p.rotation_a = c.pose_a.linear();
      cases_.push_back(p);
    }
  }

  bool intersect(std::size_t i) override {
    const Prepared& p = cases_[i];
    btGjkEpaSolver2::sResults r;
    return !btGjkEpaSolver2::Distance(shapes_[p.a].shape.get(), p.tf_a, shapes_[p.b].shape.get(),
                                      p.tf_b, p.guess, r);
  }

  DistanceOut distance(std::size_t i) override {
    const Prepared& p = cases_[i];
    btGjkEpaSolver2::sResults r;
    DistanceOut out;
    out.separated = btGjkEpaSolver2::Distance(shapes_[p.a].shape.get(), p.tf_a,
                                              shapes_[p.b].shape.get(), p.tf_b, p.guess, r);
    if (!out.separated) {
      // Penetrating is an answer; GJK_Failed ("probably touching") is reported as overlapping.
      return out;
    }
    out.distance = r.distance;
    out.point_a = to_eigen(r.witnesses[0]);
    out.point_b = to_eigen(r.witnesses[1]);
    return out;
  }

  PenetrationOut penetration(std::size_t i) override {
    const Prepared& p = cases_[i];
    btGjkEpaSolver2::sResults r;
    PenetrationOut out;
    const bool hit = btGjkEpaSolver2::Penetration(shapes_[p.a].shape.get(), p.tf_a,
                                                  shapes_[p.b].shape.get(), p.tf_b, p.guess, r);
    if (!hit) {
      out.ok = r.status == btGjkEpaSolver2::sResults::Separated;
      return out;
    }
    out.overlapping = true;
    // Bullet 3.24 Penetration: distance = -depth, and `normal` is -(EPA normal) in A's *local*
    // frame (not rotated to the world frame, unlike the witnesses), i.e. it points from B
    // towards A. Rotate and flip it to the common convention.
    out.depth = -r.distance;
    out.normal = -(p.rotation_a * to_eigen(r.normal));
    return out;
  }

  SignedOut signed_distance(std::size_t i) override {
    const Prepared& p = cases_[i];
    btGjkEpaSolver2::sResults r;
    SignedOut out;
    out.ok = btGjkEpaSolver2::SignedDistance(shapes_[p.a].shape.get(), p.tf_a,
                                             shapes_[p.b].shape.get(), p.tf_b, p.guess, r);
    out.value = r.distance;
    return out;
  }

 private:
  struct Shape {
    const HullMesh* mesh;
    std::shared_ptr<btConvexHullShape> shape;
  };
  struct Prepared {
    std::size_t a = 0, b = 0;
    btTransform tf_a, tf_b;
    btVector3 guess;
    Eigen::Matrix3d rotation_a;
  };

  std::size_t shape_index(const std::shared_ptr<const HullMesh>& mesh) {
    for (std::size_t k = 0; k < shapes_.size(); ++k) {
      if (shapes_[k].mesh == mesh.get()) return k;
    }
    auto shape = std::make_shared<btConvexHullShape>();
    for (const Eigen::Vector3d& v : mesh->vertices) shape->addPoint(to_bt(v), false);
    shape->recalcLocalAabb();
    shape->setMargin(0);
    shapes_.push_back({mesh.get(), shape});
    return shapes_.size() - 1;
  }

  std::vector<Shape> shapes_;
  std::vector<Prepared> cases_;
};

}  // namespace

std::unique_ptr<Impl> make_bullet_impl() { return std::make_unique<BulletImpl>(); }

}  // namespace hullcheck::bench
