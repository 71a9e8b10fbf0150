// AllowedCollisionMatrix: which link pairs of a robot are not checked for collision, and why.
#pragma once

#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

namespace hullcheck {

class RobotModel;
struct Srdf;

/// Why a link pair is not checked (MoveIt's reasons), or kChecked.
enum class CollisionAllowance : std::uint8_t {
  kChecked,   ///< The pair is checked.
  kAdjacent,  ///< Joined by a joint (directly, through fixed joints, or through links without
              ///< collision geometry).
  kNever,     ///< Never collided in random sampling.
  kDefault,   ///< Collides in the default configuration.
  kAlways,    ///< Collided in (nearly) every random sample.
  kUser,      ///< Disabled by an SRDF or a caller for another reason.
};

/// MoveIt's name of a reason ("Adjacent", "Never", "Default", "Always", "User", "Checked").
const char* to_string(CollisionAllowance allowance);

/// A symmetric matrix over a robot's links: which pairs are allowed to touch (not checked).
/// A link is never checked against itself. Plain value type; const use is thread-safe.
class AllowedCollisionMatrix {
 public:
  /// Every pair of `link_count` links checked.
  explicit AllowedCollisionMatrix(int link_count = 0);

  /// Adjacent pairs of `model` allowed (kAdjacent): links in one rigid body (joined by fixed
  /// joints), and links joined by one movable joint, where links without collision geometry
  /// are skipped over (their neighbours count as joined), as MoveIt's setup assistant does.
  static AllowedCollisionMatrix from_adjacency(const RobotModel& model);

  /// from_adjacency(model), then the SRDF's <disable_collisions> (reason kept when it is one
  /// of MoveIt's, else kUser), <disable_default_collisions>, then <enable_collisions>.
  /// Names the model does not have are skipped and reported in `warnings` when given (MoveIt
  /// does the same); throws nothing for them.
  static AllowedCollisionMatrix from_srdf(const RobotModel& model, const Srdf& srdf,
                                          std::vector<std::string>* warnings = nullptr);

  int link_count() const { return n_; }
  /// Whether the pair is not checked (always true for a == b). Throws InputError on bad
  /// indices. O(log k) for links in k adjacency groups; not for query hot loops (the checkers
  /// read it once, when they are built).
  bool allowed(int a, int b) const {
    return a == b || allowance(a, b) != CollisionAllowance::kChecked;
  }
  /// The pair's reason (kChecked for a == b); throws InputError on bad indices.
  CollisionAllowance allowance(int a, int b) const;
  /// Allows the pair (a != b) for `reason` (not kChecked); throws InputError on bad indices.
  void allow(int a, int b, CollisionAllowance reason);
  /// Checks the pair again.
  void check(int a, int b);
  /// Number of allowed pairs a < b (kept up to date: O(1)).
  std::int64_t allowed_pair_count() const { return allowed_count_; }

 private:
  // Storage is linear in the links plus the explicitly set pairs: from_adjacency's pairs are
  // cliques ("groups": a rigid body, or links joined through links without geometry) stored
  // as their member lists, not as pairs (a chain of 100000 links without geometry is one clique
  // of 5e9 pairs); allow() and check() store the pair itself, which takes precedence.
  static std::uint64_t key(int a, int b);
  void check_index(int a, int b, const char* what) const;
  bool in_common_group(int a, int b) const;
  void set(int a, int b, CollisionAllowance value);
  void set_groups(const std::vector<std::vector<int>>& groups);

  int n_ = 0;
  std::unordered_map<std::uint64_t, CollisionAllowance> pairs_;
  // Sorted group ids of link l: group_ids_[group_offsets_[l] .. group_offsets_[l + 1]).
  std::vector<int> group_offsets_;
  std::vector<int> group_ids_;
  std::int64_t allowed_count_ = 0;
};

}  // namespace hullcheck
