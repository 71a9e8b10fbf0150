// AllowedCollisionMatrix: which link pairs of a robot are not checked for collision, and why.
#pragma once

#include <cstdint>
#include <string>
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
  bool allowed(int a, int b) const { return a == b || at(a, b) != CollisionAllowance::kChecked; }
  CollisionAllowance allowance(int a, int b) const { return at(a, b); }
  /// Allows the pair (a != b) for `reason` (not kChecked); throws InputError on bad indices.
  void allow(int a, int b, CollisionAllowance reason);
  /// Checks the pair again.
  void check(int a, int b);
  /// Number of allowed pairs a < b.
  int allowed_pair_count() const;

 private:
  CollisionAllowance at(int a, int b) const {
    return cells_[static_cast<std::size_t>(a) * static_cast<std::size_t>(n_) +
                  static_cast<std::size_t>(b)];
  }
  void set(int a, int b, CollisionAllowance value);

  int n_ = 0;
  std::vector<CollisionAllowance> cells_;
};

}  // namespace hullcheck
