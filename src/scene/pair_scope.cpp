// CollisionChecker::pair_scope: a chosen set of checked pairs for clearance queries.
#include <algorithm>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/scene/collision_checker.hpp>
#include <string>

namespace hullcheck {

PairScope CollisionChecker::pair_scope(
    bool obstacles, const std::vector<std::pair<int, int>>& self_link_pairs) const {
  PairScope scope;
  scope.obstacles_ = obstacles;
  scope.model_ = model_.get();
  scope.self_blocks_.assign(self_blocks_.size(), 0);
  const std::vector<std::pair<int, int>> checked = checked_link_pairs();
  for (const auto& [x, y] : self_link_pairs) {
    const std::pair<int, int> key(std::min(x, y), std::max(x, y));
    const auto it = std::find(checked.begin(), checked.end(), key);
    if (it == checked.end()) {
      const auto name = [&](int link) {
        return link >= 0 && link < static_cast<int>(model_->links().size())
                   ? "'" + model_->link(link).name + "'"
                   : "index " + std::to_string(link);
      };
      throw InputError("pair_scope: links " + name(x) + " and " + name(y) +
                       " are not a checked self pair (allowed to touch, without geometry, or "
                       "not links of the model)");
    }
    scope.self_blocks_[static_cast<std::size_t>(it - checked.begin())] = 1;
  }
  for (std::size_t b = 0; b < checked.size(); ++b) {
    if (scope.self_blocks_[b] != 0) scope.self_link_pairs_.push_back(checked[b]);
  }
  return scope;
}

PairScope CollisionChecker::pair_scope(ClearanceScope scope) const {
  return pair_scope(scope != ClearanceScope::kSelf, scope == ClearanceScope::kObstacles
                                                        ? std::vector<std::pair<int, int>>{}
                                                        : checked_link_pairs());
}

const char* CollisionChecker::self_mask(const PairScope& scope) const {
  if (scope.model_ != model_.get() || scope.self_blocks_.size() != self_blocks_.size()) {
    throw InputError(
        "clearance: the PairScope was made by a checker of another model or with other checked "
        "pairs (make it with this checker's pair_scope)");
  }
  return scope.self_blocks_.data();
}

}  // namespace hullcheck
