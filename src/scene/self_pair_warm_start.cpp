// CollisionChecker's warm-start grids for self pairs moved by at most two configuration values.
#include <cmath>
#include <hullcheck/core/queries.hpp>
#include <hullcheck/scene/collision_checker.hpp>
#include <limits>

namespace hullcheck {
namespace {

// Cells per keying value: a finer grid starts GJK nearer its answer but costs memory (one
// WarmStart, 64 bytes, per cell) and construction time (one query per cell).
constexpr int kCellsOneValue = 128;
constexpr int kCellsTwoValues = 32;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

}  // namespace

const WarmStart& CollisionChecker::WarmStartGrid::at(const double* q) const {
  int cell = 0;
  for (int d = 0; d < dims; ++d) {
    double x = q[variables[d]];
    if (wraps[d]) x -= 2.0 * M_PI * std::floor((x - lower[d]) / (2.0 * M_PI));
    const double t = (x - lower[d]) * cells_per_unit[d];
    const int i = t <= 0.0 ? 0 : t >= cells[d] ? cells[d] - 1 : static_cast<int>(t);
    cell = cell * cells[d] + i;
  }
  return starts[static_cast<std::size_t>(cell)];
}

void CollisionChecker::build_warm_start_grids() {
  const RobotModel& model = *model_;
  warm_grids_.assign(self_pairs_.size(), WarmStartGrid{});
  const Eigen::VectorXd lower = model.lower_limits();
  const Eigen::VectorXd upper = model.upper_limits();
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
    WarmStartGrid& grid = warm_grids_[k];
    grid.dims = key_count;
    const int cells = grid.dims == 1 ? kCellsOneValue : kCellsTwoValues;
    std::size_t total = 1;
    for (int d = 0; d < grid.dims; ++d) {
      const int v = keys[d];
      double lo = lower[v], hi = upper[v];
      grid.wraps[d] = !std::isfinite(lo) || !std::isfinite(hi);
      if (grid.wraps[d]) {
        lo = -M_PI;
        hi = M_PI;
      }
      grid.variables[d] = v;
      grid.lower[d] = lo;
      grid.cells[d] = hi > lo ? cells : 1;
      grid.cells_per_unit[d] = hi > lo ? cells / (hi - lo) : 0.0;
      total *= static_cast<std::size_t>(grid.cells[d]);
    }
    grid.starts.resize(total);
    const Shape& shape_a = model.link(a.link).shapes[static_cast<std::size_t>(a.shape)].shape;
    const Shape& shape_b = model.link(b.link).shapes[static_cast<std::size_t>(b.shape)].shape;
    const Eigen::Isometry3d& origin_a =
        model.link(a.link).shapes[static_cast<std::size_t>(a.shape)].origin;
    const Eigen::Isometry3d& origin_b =
        model.link(b.link).shapes[static_cast<std::size_t>(b.shape)].origin;
    const Eigen::VectorXd q_default = q;
    for (std::size_t cell = 0; cell < total; ++cell) {
      std::size_t rest = cell;
      for (int d = grid.dims - 1; d >= 0; --d) {
        const auto i = static_cast<int>(rest % static_cast<std::size_t>(grid.cells[d]));
        rest /= static_cast<std::size_t>(grid.cells[d]);
        q[grid.variables[d]] = grid.cells_per_unit[d] > 0.0
                                   ? grid.lower[d] + (i + 0.5) / grid.cells_per_unit[d]
                                   : lower[grid.variables[d]];
      }
      model.compute_link_poses(q, poses);
      WarmStart& start = grid.starts[cell];
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
  }
}

}  // namespace hullcheck
