// PairScope: the pairs a clearance query takes its minimum over, chosen pair by pair.
#pragma once

#include <utility>
#include <vector>

namespace hullcheck {

class CollisionChecker;

/// A set of a CollisionChecker's checked pairs for its clearance queries: every robot-obstacle
/// pair or none, and any subset of its checked self link pairs (all shape pairs of a chosen
/// link pair). Made by CollisionChecker::pair_scope (which validates the link pairs); meant for
/// the checker that made it and its copies. A checker of another model, or with another number
/// of checked link pairs, rejects it (InputError).
/// Immutable once made: sharing one among threads is safe.
class PairScope {
 public:
  /// Robot-obstacle pairs are in the scope.
  bool obstacles() const { return obstacles_; }
  /// The self link pairs in the scope (model link indices, a < b), in the checker's order.
  const std::vector<std::pair<int, int>>& self_link_pairs() const { return self_link_pairs_; }

 private:
  friend class CollisionChecker;
  bool obstacles_ = true;
  std::vector<std::pair<int, int>> self_link_pairs_;
  std::vector<char> self_blocks_;  // per checked link pair of the checker: 1 when in the scope
  const void* model_ = nullptr;    // the checker's robot model
};

}  // namespace hullcheck
