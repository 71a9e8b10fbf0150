// CollisionChecker's warm-start grids for self pairs moved by at most two configuration values,
// one set per model (and padding revision) shared by its checkers, like the self tables.
#include <cmath>
#include <hullcheck/core/queries.hpp>
#include <hullcheck/scene/collision_checker.hpp>
#include <limits>
#include <memory>
#include <mutex>

#include "collision_checker_internals.hpp"

namespace hullcheck {
namespace {

// Cells per keying value: a finer grid starts GJK nearer its answer but costs memory (one
// WarmStart, 64 bytes, per cell) and construction time (one query per cell).
constexpr int kCellsOneValue = 128;
constexpr int kCellsTwoValues = 32;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

}  // namespace

void CollisionChecker::build_warm_start_grids() {
  const RobotModel& model = *model_;
  warm_grids_.assign(self_pairs_.size(), nullptr);
  ModelSelfTables& shared = *self_tables_->model;
  const std::lock_guard<std::mutex> lock(shared.mutex);
  Eigen::VectorXd q = model.default_configuration();
  std::vector<Eigen::Isometry3d> poses(model.links().size());
  for (std::size_t k = 0; k < self_pairs_.size(); ++k) {
    const RobotShape& a = shapes_[static_cast<std::size_t>(self_pairs_[k].a)];
    const RobotShape& b = shapes_[static_cast<std::size_t>(self_pairs_[k].b)];
    // Not for the pieces of decomposed meshes: their pairs are many, and the grids' cost is per
    // pair (their clearance queries start cold).
    if (model.link(a.link).shapes[static_cast<std::size_t>(a.shape)].piece_count > 1 ||
        model.link(b.link).shapes[static_cast<std::size_t>(b.shape)].piece_count > 1) {
      continue;
    }
    // The values that move one link relative to the other: drivers of the movable joints
    // above exactly one of them.
    int keys[2];
    const int key_count = relative_drivers(a.link, b.link, 2, keys);
    if (key_count > 2) continue;
    std::unique_ptr<WarmStartGrid>& made = shared.warm_grids[{a.link, a.shape, b.link, b.shape}];
    if (made) {
      warm_grids_[k] = made.get();
      continue;
    }
    auto grid = std::make_unique<WarmStartGrid>();
    const std::size_t total =
        grid->setup(model, keys, key_count, key_count == 1 ? kCellsOneValue : kCellsTwoValues);
    grid->starts.resize(total);
    const Shape& shape_a = model.link(a.link).shapes[static_cast<std::size_t>(a.shape)].shape;
    const Shape& shape_b = model.link(b.link).shapes[static_cast<std::size_t>(b.shape)].shape;
    const Eigen::Isometry3d& origin_a =
        model.link(a.link).shapes[static_cast<std::size_t>(a.shape)].origin;
    const Eigen::Isometry3d& origin_b =
        model.link(b.link).shapes[static_cast<std::size_t>(b.shape)].origin;
    const Eigen::VectorXd q_default = q;
    for (std::size_t cell = 0; cell < total; ++cell) {
      grid->center(cell, q);
      model.compute_link_poses(q, poses);
      WarmStart& start = grid->starts[cell];
      const Eigen::Isometry3d pose_a = poses[static_cast<std::size_t>(a.link)] * origin_a;
      const SignedDistanceResult answer = signed_distance_below(
          shape_a, pose_a, shape_b, poses[static_cast<std::size_t>(b.link)] * origin_b, kInfinity,
          start);
      // The direction: minus the normal from A to B (A's frame), for overlapping shapes too
      // (EPA's), so that it also gives the slab bound's direction.
      if (answer.normal.squaredNorm() > 0.0) {
        start.direction = -(pose_a.linear().transpose() * answer.normal);
      }
    }
    q = q_default;
    made = std::move(grid);
    warm_grids_[k] = made.get();
  }
}

}  // namespace hullcheck
