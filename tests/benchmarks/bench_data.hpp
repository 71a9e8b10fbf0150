// Benchmark data: the hull pairs every implementation is timed and scored on, and the oracle's
// reference answers for them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "peers.hpp"

namespace hullcheck::bench {

struct DataSet {
  std::string name;         ///< e.g. "n=8" or "robots"
  std::string description;  ///< one line for the report
  std::vector<Case> cases;
};

/// oracle::make_hull_pairs(seed, count, vertices, 0.3, 1.0), each point set hulled with qhull.
DataSet make_random_set(std::uint64_t seed, int count, int vertices);

/// Hulls of the collision meshes (binary STL, read with assimp) of the robots under
/// `shared_dir`/robots (panda, ur5e, abb_irb2400), paired at random: random orientations, B
/// translated along a random direction to overlap A (30% of the pairs, inside the oracle's
/// overlap interval) or to be separated by up to one shape size. Empty `cases` when the
/// directory or the meshes are absent.
DataSet make_robot_set(const std::string& shared_dir, std::uint64_t seed, int count);

/// Reference answers for one case, from the oracles (exhaustive search / qhull on A - B).
struct Truth {
  bool overlapping = false;
  double distance = 0.0;  ///< 0 when overlapping
  double depth = 0.0;     ///< 0 when separated
  double scale = 1.0;     ///< max(extent(A), extent(B)), extents about the local origins
  std::vector<Eigen::Vector3d> world_a, world_b;  ///< hull vertices in the world frame
};

/// Oracle answers for every case, computed on `threads` threads.
std::vector<Truth> compute_truth(const std::vector<Case>& cases, unsigned threads);

/// Distance from a world point to the hull of `mesh` placed at `pose` (0 inside).
double point_hull_distance(const Eigen::Vector3d& world_point, const HullMesh& mesh,
                           const Eigen::Isometry3d& pose);

/// Penetration depth of A - B along unit `normal`: the translation of B along `normal` that
/// separates them, max_a a.n - min_b b.n. It equals the true depth for a correct normal and
/// exceeds it otherwise.
double depth_along(const Truth& truth, const Eigen::Vector3d& normal);

}  // namespace hullcheck::bench
