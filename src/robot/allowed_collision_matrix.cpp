#include <hullcheck/errors.hpp>
#include <hullcheck/robot/allowed_collision_matrix.hpp>
#include <hullcheck/robot/robot_model.hpp>
#include <hullcheck/robot/srdf.hpp>
#include <map>
#include <string>

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

AllowedCollisionMatrix::AllowedCollisionMatrix(int link_count)
    : n_(link_count),
      cells_(static_cast<std::size_t>(link_count) * static_cast<std::size_t>(link_count),
             CollisionAllowance::kChecked) {
  if (link_count < 0) throw InputError("AllowedCollisionMatrix: negative link count");
}

void AllowedCollisionMatrix::set(int a, int b, CollisionAllowance value) {
  if (a < 0 || b < 0 || a >= n_ || b >= n_) {
    throw InputError("AllowedCollisionMatrix: link index out of range (" + std::to_string(a) +
                     ", " + std::to_string(b) + "; " + std::to_string(n_) + " links)");
  }
  if (a == b) return;
  cells_[static_cast<std::size_t>(a) * static_cast<std::size_t>(n_) + static_cast<std::size_t>(b)] =
      value;
  cells_[static_cast<std::size_t>(b) * static_cast<std::size_t>(n_) + static_cast<std::size_t>(a)] =
      value;
}

void AllowedCollisionMatrix::allow(int a, int b, CollisionAllowance reason) {
  if (reason == CollisionAllowance::kChecked) {
    throw InputError("AllowedCollisionMatrix::allow: reason must not be kChecked");
  }
  set(a, b, reason);
}

void AllowedCollisionMatrix::check(int a, int b) { set(a, b, CollisionAllowance::kChecked); }

int AllowedCollisionMatrix::allowed_pair_count() const {
  int count = 0;
  for (int a = 0; a < n_; ++a) {
    for (int b = a + 1; b < n_; ++b) count += at(a, b) != CollisionAllowance::kChecked ? 1 : 0;
  }
  return count;
}

AllowedCollisionMatrix AllowedCollisionMatrix::from_adjacency(const RobotModel& model) {
  const int n = static_cast<int>(model.links().size());
  const auto cell = [n](int a, int b) {
    return static_cast<std::size_t>(a) * static_cast<std::size_t>(n) + static_cast<std::size_t>(b);
  };
  // MoveIt's connection graph: the two links of every joint are joined ...
  std::vector<char> joined(static_cast<std::size_t>(n) * static_cast<std::size_t>(n), 0);
  for (const Joint& j : model.joints()) {
    joined[cell(j.parent_link, j.child_link)] = joined[cell(j.child_link, j.parent_link)] = 1;
  }
  // ... and so are all neighbours of a link without geometry, repeated until nothing changes
  // (a chain of such links joins its two ends; siblings under a bare link are joined too).
  for (bool changed = true; changed;) {
    changed = false;
    for (int l = 0; l < n; ++l) {
      if (!model.link(l).shapes.empty()) continue;
      for (int a = 0; a < n; ++a) {
        if (a == l || !joined[cell(l, a)]) continue;
        for (int b = a + 1; b < n; ++b) {
          if (b == l || !joined[cell(l, b)] || joined[cell(a, b)]) continue;
          joined[cell(a, b)] = joined[cell(b, a)] = 1;
          changed = true;
        }
      }
    }
  }
  // Links of one rigid body (joined by fixed joints) are adjacent too. Not body to body: a
  // tool fixed to link7 is two joints from link6 and can swing into it (MoveIt's Panda SRDF
  // lists panda_hand / panda_link6 as "Never", not "Adjacent").
  std::vector<int> body(static_cast<std::size_t>(n));
  for (int l = 0; l < n; ++l) {  // links are ordered parents first
    const int j = model.link(l).parent_joint;
    body[static_cast<std::size_t>(l)] =
        (j >= 0 && model.joint(j).type == JointType::kFixed)
            ? body[static_cast<std::size_t>(model.joint(j).parent_link)]
            : l;
  }
  AllowedCollisionMatrix acm(n);
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) {
      if (joined[cell(a, b)] ||
          body[static_cast<std::size_t>(a)] == body[static_cast<std::size_t>(b)]) {
        acm.allow(a, b, CollisionAllowance::kAdjacent);
      }
    }
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
