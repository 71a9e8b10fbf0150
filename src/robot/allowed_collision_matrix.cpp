#include <algorithm>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/robot/allowed_collision_matrix.hpp>
#include <hullcheck/robot/robot_model.hpp>
#include <hullcheck/robot/srdf.hpp>
#include <map>
#include <string>
#include <unordered_map>

namespace hullcheck {

const char* to_string(CollisionAllowance allowance) {
  switch (allowance) {
    case CollisionAllowance::kChecked:
      return "Checked";
    case CollisionAllowance::kAdjacent:
      return "Adjacent";
    case CollisionAllowance::kNever:
      return "Never";
    case CollisionAllowance::kDefault:
      return "Default";
    case CollisionAllowance::kAlways:
      return "Always";
    case CollisionAllowance::kUser:
      return "User";
  }
  return "?";
}

namespace {

// Cliques of mutually adjacent links and the number of distinct pairs they hold.
struct AdjacencyGroups {
  std::vector<std::vector<int>> groups;
  std::int64_t pairs = 0;
};

std::int64_t pair_count(std::size_t k) {
  return static_cast<std::int64_t>(k) * (static_cast<std::int64_t>(k) - 1) / 2;
}

// Root of `l` in a union-find forest (path halving).
int find_root(std::vector<int>& parent, int l) {
  while (parent[static_cast<std::size_t>(l)] != l) {
    parent[static_cast<std::size_t>(l)] =
        parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(l)])];
    l = parent[static_cast<std::size_t>(l)];
  }
  return l;
}

// Rigid bodies: links joined by fixed joints (links are ordered parents first).
std::vector<int> rigid_bodies(const RobotModel& model) {
  const std::size_t n = model.links().size();
  std::vector<int> body(n);
  for (std::size_t l = 0; l < n; ++l) {
    const int j = model.links()[l].parent_joint;
    body[l] = (j >= 0 && model.joint(j).type == JointType::kFixed)
                  ? body[static_cast<std::size_t>(model.joint(j).parent_link)]
                  : static_cast<int>(l);
  }
  return body;
}

// MoveIt's joining through links without geometry, in closed form: two links are joined when
// the tree path between them passes through links without geometry only. Such pairs are the
// cliques "a connected set C of links without geometry plus the links next to C".
std::vector<std::vector<int>> bare_closures(const RobotModel& model) {
  const int n = static_cast<int>(model.links().size());
  const auto bare = [&](int l) { return model.link(l).shapes.empty(); };
  std::vector<int> parent(static_cast<std::size_t>(n));
  for (int l = 0; l < n; ++l) parent[static_cast<std::size_t>(l)] = l;
  for (const Joint& j : model.joints()) {
    if (bare(j.parent_link) && bare(j.child_link)) {
      parent[static_cast<std::size_t>(find_root(parent, j.child_link))] =
          find_root(parent, j.parent_link);
    }
  }
  std::vector<int> closure_of(static_cast<std::size_t>(n), -1);  // by component root
  std::vector<std::vector<int>> closures;
  const auto closure = [&](int bare_link) -> std::vector<int>& {
    int& id = closure_of[static_cast<std::size_t>(find_root(parent, bare_link))];
    if (id < 0) {
      id = static_cast<int>(closures.size());
      closures.emplace_back();
    }
    return closures[static_cast<std::size_t>(id)];
  };
  for (int l = 0; l < n; ++l) {
    if (bare(l)) closure(l).push_back(l);
  }
  for (const Joint& j : model.joints()) {
    if (bare(j.parent_link) && !bare(j.child_link)) closure(j.parent_link).push_back(j.child_link);
    if (bare(j.child_link) && !bare(j.parent_link)) closure(j.child_link).push_back(j.parent_link);
  }
  return closures;
}

// The cliques of from_adjacency (joint neighbours aside): rigid bodies and bare closures.
// Bodies are disjoint, two closures share at most one link (the joints form a tree), so a
// pair lies in at most one body and one closure: pairs = sum of clique pairs - overlaps.
AdjacencyGroups adjacency_groups(const RobotModel& model) {
  AdjacencyGroups out;
  const std::vector<int> body = rigid_bodies(model);
  std::unordered_map<int, std::vector<int>> members;
  for (std::size_t l = 0; l < body.size(); ++l) members[body[l]].push_back(static_cast<int>(l));
  for (auto& [root, links] : members) {
    if (links.size() < 2) continue;
    out.pairs += pair_count(links.size());
    out.groups.push_back(std::move(links));
  }
  for (std::vector<int>& closure : bare_closures(model)) {
    if (closure.size() < 2) continue;
    out.pairs += pair_count(closure.size());
    std::unordered_map<int, std::size_t> per_body;
    for (int l : closure) ++per_body[body[static_cast<std::size_t>(l)]];
    for (const auto& [b, k] : per_body) out.pairs -= pair_count(k);
    out.groups.push_back(std::move(closure));
  }
  return out;
}

}  // namespace

AllowedCollisionMatrix::AllowedCollisionMatrix(int link_count)
    : n_(link_count), group_offsets_(static_cast<std::size_t>(std::max(link_count, 0)) + 1, 0) {
  if (link_count < 0) throw InputError("AllowedCollisionMatrix: negative link count");
}

std::uint64_t AllowedCollisionMatrix::key(int a, int b) {
  const auto lo = static_cast<std::uint64_t>(std::min(a, b));
  const auto hi = static_cast<std::uint64_t>(std::max(a, b));
  return lo << 32 | hi;
}

void AllowedCollisionMatrix::check_index(int a, int b, const char* what) const {
  if (a < 0 || b < 0 || a >= n_ || b >= n_) {
    throw InputError(std::string("AllowedCollisionMatrix::") + what +
                     ": link index out of range (" + std::to_string(a) + ", " + std::to_string(b) +
                     "; " + std::to_string(n_) + " links)");
  }
}

bool AllowedCollisionMatrix::in_common_group(int a, int b) const {
  const int* a_begin = group_ids_.data() + group_offsets_[static_cast<std::size_t>(a)];
  const int* a_end = group_ids_.data() + group_offsets_[static_cast<std::size_t>(a) + 1];
  const int* b_begin = group_ids_.data() + group_offsets_[static_cast<std::size_t>(b)];
  const int* b_end = group_ids_.data() + group_offsets_[static_cast<std::size_t>(b) + 1];
  if (a_end - a_begin > b_end - b_begin) {
    std::swap(a_begin, b_begin);
    std::swap(a_end, b_end);
  }
  for (const int* g = a_begin; g != a_end; ++g) {
    if (std::binary_search(b_begin, b_end, *g)) return true;
  }
  return false;
}

void AllowedCollisionMatrix::set_groups(const std::vector<std::vector<int>>& groups) {
  std::vector<std::vector<int>> of_link(static_cast<std::size_t>(n_));
  for (std::size_t g = 0; g < groups.size(); ++g) {
    for (int l : groups[g]) of_link[static_cast<std::size_t>(l)].push_back(static_cast<int>(g));
  }
  group_ids_.clear();
  for (int l = 0; l < n_; ++l) {
    group_offsets_[static_cast<std::size_t>(l)] = static_cast<int>(group_ids_.size());
    group_ids_.insert(group_ids_.end(), of_link[static_cast<std::size_t>(l)].begin(),
                      of_link[static_cast<std::size_t>(l)].end());  // ascending already
  }
  group_offsets_[static_cast<std::size_t>(n_)] = static_cast<int>(group_ids_.size());
}

CollisionAllowance AllowedCollisionMatrix::allowance(int a, int b) const {
  check_index(a, b, "allowance");
  if (a == b) return CollisionAllowance::kChecked;
  const auto it = pairs_.find(key(a, b));
  if (it != pairs_.end()) return it->second;
  return in_common_group(a, b) ? CollisionAllowance::kAdjacent : CollisionAllowance::kChecked;
}

void AllowedCollisionMatrix::set(int a, int b, CollisionAllowance value) {
  check_index(a, b, "allow/check");
  if (a == b) return;
  const bool before = allowed(a, b);
  const bool implicit = in_common_group(a, b);
  const bool same_as_groups =
      implicit ? value == CollisionAllowance::kAdjacent : value == CollisionAllowance::kChecked;
  if (same_as_groups) {
    pairs_.erase(key(a, b));
  } else {
    pairs_[key(a, b)] = value;
  }
  allowed_count_ += (value != CollisionAllowance::kChecked ? 1 : 0) - (before ? 1 : 0);
}

void AllowedCollisionMatrix::allow(int a, int b, CollisionAllowance reason) {
  if (reason == CollisionAllowance::kChecked) {
    throw InputError("AllowedCollisionMatrix::allow: reason must not be kChecked");
  }
  set(a, b, reason);
}

void AllowedCollisionMatrix::check(int a, int b) { set(a, b, CollisionAllowance::kChecked); }

AllowedCollisionMatrix AllowedCollisionMatrix::from_adjacency(const RobotModel& model) {
  // MoveIt's connection graph: the two links of every joint are joined, and so are all
  // neighbours of a link without geometry, repeated until nothing changes (a chain of such
  // links joins its two ends; siblings under a bare link are joined too); links of one rigid
  // body (joined by fixed joints) are adjacent too. Not body to body: a tool fixed to link7 is
  // two joints from link6 and can swing into it (MoveIt's Panda SRDF lists panda_hand /
  // panda_link6 as "Never", not "Adjacent"). Linear in the links (adjacency_groups).
  AllowedCollisionMatrix acm(static_cast<int>(model.links().size()));
  const AdjacencyGroups groups = adjacency_groups(model);
  acm.set_groups(groups.groups);
  acm.allowed_count_ = groups.pairs;
  for (const Joint& j : model.joints()) {
    acm.allow(j.parent_link, j.child_link, CollisionAllowance::kAdjacent);
  }
  return acm;
}

AllowedCollisionMatrix AllowedCollisionMatrix::from_srdf(const RobotModel& model, const Srdf& srdf,
                                                         std::vector<std::string>* warnings) {
  AllowedCollisionMatrix acm = from_adjacency(model);
  static const std::map<std::string, CollisionAllowance> kReasons = {
      {"Adjacent", CollisionAllowance::kAdjacent},
      {"Never", CollisionAllowance::kNever},
      {"Default", CollisionAllowance::kDefault},
      {"Always", CollisionAllowance::kAlways},
      {"User", CollisionAllowance::kUser}};
  const auto find = [&](const std::string& name, const char* what) {
    const int i = model.link_index(name);
    if (i < 0 && warnings != nullptr) {
      warnings->push_back(std::string("SRDF ") + what + ": robot '" + model.name() +
                          "' has no link '" + name + "' (skipped)");
    }
    return i;
  };
  for (const SrdfLinkPair& p : srdf.disabled_collisions) {
    const int a = find(p.link1, "disable_collisions");
    const int b = find(p.link2, "disable_collisions");
    if (a < 0 || b < 0) continue;
    const auto reason = kReasons.find(p.reason);
    acm.allow(a, b, reason == kReasons.end() ? CollisionAllowance::kUser : reason->second);
  }
  for (const std::string& name : srdf.disabled_links) {
    const int a = find(name, "disable_default_collisions");
    if (a < 0) continue;
    for (int b = 0; b < acm.link_count(); ++b) {
      if (b != a && !acm.allowed(a, b)) acm.allow(a, b, CollisionAllowance::kUser);
    }
  }
  for (const SrdfLinkPair& p : srdf.enabled_collisions) {
    const int a = find(p.link1, "enable_collisions");
    const int b = find(p.link2, "enable_collisions");
    if (a >= 0 && b >= 0) acm.check(a, b);
  }
  return acm;
}

}  // namespace hullcheck
