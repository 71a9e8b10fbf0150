// is_valid_batch's tables of self blocks moved by at most two configuration values: a grid over
// those values, each cell marked when the block's two links are proven apart over all of it.
//
// The proof for a cell: the links' converged distance at the cell's centre (their bounding hulls'
// when both have one, which is at most any of their pieces' distances; otherwise the smallest over
// the block's pairs) minus how far their points can move relative to each other within the
// cell (half the cell's width per value times the block's lever arm for that value,
// motion_bounds.cpp) exceeds kApartSlack. Out of the grid's range (values beyond the limits),
// nothing is proven.
#include <cmath>
#include <hullcheck/core/queries.hpp>
#include <hullcheck/scene/collision_checker.hpp>
#include <limits>
#include <mutex>

#include "collision_checker_internals.hpp"

namespace hullcheck {
namespace {

constexpr int kCellsOneValue = 256;
constexpr int kCellsTwoValues = 48;
// Blocks without bounding hulls are measured pair by pair: not for blocks with more pairs.
constexpr int kMaxPairsWithoutHulls = 16;
// Metres a cell's proven gap must exceed: far above the queries' tolerance, so that
// is_valid's exact tests cannot call the links touching where the table says apart.
constexpr double kApartSlack = 1e-6;

}  // namespace

const CollisionChecker::FreeCells& CollisionChecker::free_cells() const {
  std::call_once(free_cells_->built, [this] { build_free_cells(*free_cells_); });
  return *free_cells_;
}

void CollisionChecker::build_free_cells(FreeCells& out) const {
  const RobotModel& model = *model_;
  const MotionLevers& levers = motion_levers();
  out.tables.assign(self_blocks_.size(), FreeCells::Table{});
  Eigen::VectorXd q = model.default_configuration();
  std::vector<Eigen::Isometry3d> poses(model.links().size());
  const auto pose_of = [&](int shape) {
    const RobotShape& rs = shapes_[static_cast<std::size_t>(shape)];
    return Eigen::Isometry3d(poses[static_cast<std::size_t>(rs.link)] *
                             model.link(rs.link).shapes[static_cast<std::size_t>(rs.shape)].origin);
  };
  for (std::size_t k = 0; k < self_blocks_.size(); ++k) {
    const SelfBlock& block = self_blocks_[k];
    const LinkBall& ball_a = link_balls_[static_cast<std::size_t>(block.link_a)];
    const LinkBall& ball_b = link_balls_[static_cast<std::size_t>(block.link_b)];
    const bool hulls = ball_a.bound >= 0 && ball_b.bound >= 0;
    if (!hulls && block.end - block.begin > kMaxPairsWithoutHulls) continue;
    int keys[2];
    const int key_count = relative_drivers(ball_a.link, ball_b.link, 2, keys);
    if (key_count > 2) continue;
    FreeCells::Table& table = out.tables[k];
    const std::size_t total =
        table.setup(model, keys, key_count, key_count == 1 ? kCellsOneValue : kCellsTwoValues);
    double reach = 0.0;  // how far the links' points move relative to each other in a cell
    for (int d = 0; d < key_count; ++d) {
      reach += table.half_width(d) *
               levers.self_block_levers(static_cast<Eigen::Index>(k), table.variables[d]);
    }
    table.apart.assign(total, 0);
    const Eigen::VectorXd q_default = q;
    for (std::size_t cell = 0; cell < total; ++cell) {
      table.center(cell, q);
      model.compute_link_poses(q, poses);
      // Only converged distances prove anything; any other answer leaves the cell unproven.
      const auto proven = [](const SignedDistanceResult& r) {
        return r.status == Status::kConverged ? r.signed_distance
                                              : -std::numeric_limits<double>::infinity();
      };
      double distance = std::numeric_limits<double>::infinity();
      if (hulls) {
        distance = proven(signed_distance(bounding_shape(ball_a.bound), pose_of(ball_a.bound),
                                          bounding_shape(ball_b.bound), pose_of(ball_b.bound)));
      } else {
        for (int p = block.begin; p < block.end; ++p) {
          const SelfPair& pair = self_pairs_[static_cast<std::size_t>(p)];
          distance = std::min(distance, proven(signed_distance(shape_of(pair.a), pose_of(pair.a),
                                                               shape_of(pair.b), pose_of(pair.b))));
        }
      }
      table.apart[cell] = distance - reach > kApartSlack ? 1 : 0;
    }
    q = q_default;
  }
}

bool CollisionChecker::self_block_free(const FreeCells& cells, int block, const double* q) const {
  const FreeCells::Table& table = cells.tables[static_cast<std::size_t>(block)];
  if (table.dims < 0) return false;
  const long cell = table.cell(q, false);  // outside the grid (beyond a limit): nothing proven
  return cell >= 0 && table.apart[static_cast<std::size_t>(cell)] != 0;
}

}  // namespace hullcheck
