// hullcheck's free functions behind the common interface (default QueryOptions).
#include <hullcheck/core.hpp>
#include <unordered_map>

#include "peers.hpp"

namespace hullcheck::bench {
namespace {

class HullcheckImpl final : public Impl {
 public:
  std::string name() const override { return "hullcheck"; }
  bool supports(Query) const override { return true; }
  std::string api(Query q) const override { return std::string("hullcheck::") + to_string(q); }

  void prepare(const std::vector<Case>& cases) override {
    cases_.clear();
    std::unordered_map<const HullMesh*, std::shared_ptr<const Shape>> shapes;
    auto shape_of = [&](const std::shared_ptr<const HullMesh>& mesh) {
      auto it = shapes.find(mesh.get());
      if (it == shapes.end()) {
        it = shapes.emplace(mesh.get(), std::make_shared<const Shape>(ConvexHull(mesh->vertices)))
                 .first;
      }
      return it->second;
    };
    for (const Case& c : cases)
      cases_.push_back({shape_of(c.a), shape_of(c.b), c.pose_a, c.pose_b});
  }

  bool intersect(std::size_t i) override {
    const Prepared& p = cases_[i];
    return hullcheck::intersect(*p.a, p.pose_a, *p.b, p.pose_b);
  }

  DistanceOut distance(std::size_t i) override {
    const Prepared& p = cases_[i];
    const DistanceResult r = hullcheck::distance(*p.a, p.pose_a, *p.b, p.pose_b);
    DistanceOut out;
    out.flagged = r.status != Status::kConverged;
    out.separated = r.distance > 0;
    out.distance = r.distance;
    out.point_a = r.point_a;
    out.point_b = r.point_b;
    out.iterations = r.iterations;
    return out;
  }

  PenetrationOut penetration(std::size_t i) override {
    const Prepared& p = cases_[i];
    const PenetrationResult r = hullcheck::penetration(*p.a, p.pose_a, *p.b, p.pose_b);
    PenetrationOut out;
    out.flagged = r.status != Status::kConverged;
    out.overlapping = r.depth > 0;
    out.depth = r.depth;
    out.normal = r.normal;
    return out;
  }

  SignedOut signed_distance(std::size_t i) override {
    const Prepared& p = cases_[i];
    const SignedDistanceResult r = hullcheck::signed_distance(*p.a, p.pose_a, *p.b, p.pose_b);
    SignedOut out;
    out.flagged = r.status != Status::kConverged;
    out.value = r.signed_distance;
    return out;
  }

 private:
  struct Prepared {
    std::shared_ptr<const Shape> a, b;
    Eigen::Isometry3d pose_a, pose_b;
  };
  std::vector<Prepared> cases_;
};

}  // namespace

std::unique_ptr<Impl> make_hullcheck_impl() { return std::make_unique<HullcheckImpl>(); }

}  // namespace hullcheck::bench
