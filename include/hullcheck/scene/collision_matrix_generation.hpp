// Automatic allowed-collision matrix, as MoveIt's setup assistant computes it.
#pragma once

#include <cstdint>
#include <hullcheck/robot/allowed_collision_matrix.hpp>
#include <hullcheck/robot/srdf.hpp>

namespace hullcheck {

class RobotModel;

/// Settings of generate_collision_matrix.
struct CollisionMatrixOptions {
  /// Random configurations sampled (uniform within joint limits; continuous joints in
  /// [-pi, pi]). More samples make "Never" more trustworthy. >= 1.
  int samples = 10000;
  /// Seed of the sampler (the result is deterministic for a seed).
  std::uint64_t seed = 1;
  /// A pair colliding in at least this fraction of the samples is disabled as "Always".
  double always_fraction = 0.95;
};

/// The generated matrix and how many pairs each reason disabled.
struct GeneratedCollisionMatrix {
  AllowedCollisionMatrix matrix;
  int adjacent = 0;
  int default_pose = 0;  ///< Colliding in RobotModel::default_configuration().
  int always = 0;
  int never = 0;
  int checked = 0;  ///< Link pairs with geometry left checked.
  int samples = 0;
};

/// Disables, among link pairs that both have collision geometry: adjacent pairs (kAdjacent),
/// pairs colliding in the default configuration (kDefault), pairs colliding in at least
/// `always_fraction` of the samples (kAlways), and pairs never colliding in any sample
/// (kNever). Uses the model's current padding. Pairs where a link has no geometry are left
/// checked (there is nothing to check). Throws InputError on bad options.
GeneratedCollisionMatrix generate_collision_matrix(const RobotModel& model,
                                                   const CollisionMatrixOptions& options = {});

/// The `disable_collisions` entries of `matrix` (every allowed pair, with its reason, link
/// names in link order), with robot name set; groups and states are left empty.
Srdf collision_matrix_to_srdf(const RobotModel& model, const AllowedCollisionMatrix& matrix);

}  // namespace hullcheck
