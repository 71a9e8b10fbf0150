#include <cmath>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/robot/robot_model.hpp>
#include <hullcheck/scene/collision_checker.hpp>
#include <hullcheck/scene/collision_matrix_generation.hpp>
#include <memory>
#include <random>
#include <unordered_map>
#include <vector>

namespace hullcheck {
GeneratedCollisionMatrix generate_collision_matrix(const RobotModel& model,
                                                   const CollisionMatrixOptions& options) {
  if (options.samples < 1) throw InputError("generate_collision_matrix: samples must be >= 1");
  if (!(options.always_fraction > 0.0 && options.always_fraction <= 1.0)) {
    throw InputError("generate_collision_matrix: always_fraction must be in (0, 1]");
  }
  GeneratedCollisionMatrix out{AllowedCollisionMatrix::from_adjacency(model)};
  out.samples = options.samples;
  // Only pairs of links with geometry are reported (and checked): quadratic in those links,
  // not in all links.
  const std::vector<int> solid = model.links_with_geometry();
  for (std::size_t i = 0; i < solid.size(); ++i) {
    for (std::size_t k = i + 1; k < solid.size(); ++k) {
      if (out.matrix.allowed(solid[i], solid[k])) ++out.adjacent;
    }
  }
  // The checker copies nothing but shares the model; give it a non-owning pointer.
  const std::shared_ptr<const RobotModel> shared(&model, [](const RobotModel*) {});
  std::vector<Eigen::Isometry3d> poses;
  std::vector<std::pair<int, int>> colliding;

  {  // Default configuration.
    const CollisionChecker checker(shared, out.matrix);
    model.compute_link_poses(model.default_configuration(), poses);
    checker.colliding_link_pairs_at(poses, colliding);
    for (const auto& [a, b] : colliding) out.matrix.allow(a, b, CollisionAllowance::kDefault);
    out.default_pose = static_cast<int>(colliding.size());
  }

  const CollisionChecker checker(shared, out.matrix);
  // Collision counts per checked pair, found by the pair's key (a < b).
  const auto key = [](int a, int b) {
    return static_cast<std::uint64_t>(a) << 32 | static_cast<std::uint64_t>(b);
  };
  std::unordered_map<std::uint64_t, int> counts;
  counts.reserve(checker.checked_link_pairs().size());
  for (const auto& [a, b] : checker.checked_link_pairs()) counts.emplace(key(a, b), 0);
  std::mt19937_64 rng(options.seed);
  const Eigen::VectorXd lower = model.lower_limits();
  const Eigen::VectorXd upper = model.upper_limits();
  Eigen::VectorXd q(model.variable_count());
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int s = 0; s < options.samples; ++s) {
    for (int i = 0; i < q.size(); ++i) {
      const double lo = std::isfinite(lower[i]) ? lower[i] : -M_PI;
      const double hi = std::isfinite(upper[i]) ? upper[i] : M_PI;
      q[i] = lo + (hi - lo) * unit(rng);
    }
    model.compute_link_poses(q, poses);
    colliding.clear();
    checker.colliding_link_pairs_at(poses, colliding);
    for (const auto& [a, b] : colliding) ++counts[key(a, b)];
  }
  for (const auto& [a, b] : checker.checked_link_pairs()) {
    const int c = counts[key(a, b)];
    if (c == 0) {
      out.matrix.allow(a, b, CollisionAllowance::kNever);
      ++out.never;
    } else if (c >= options.always_fraction * options.samples) {
      out.matrix.allow(a, b, CollisionAllowance::kAlways);
      ++out.always;
    } else {
      ++out.checked;
    }
  }
  return out;
}

Srdf collision_matrix_to_srdf(const RobotModel& model, const AllowedCollisionMatrix& matrix) {
  if (matrix.link_count() != static_cast<int>(model.links().size())) {
    throw InputError("collision_matrix_to_srdf: matrix size does not match robot '" + model.name() +
                     "'");
  }
  Srdf srdf;
  srdf.robot_name = model.name();
  const std::vector<int> solid = model.links_with_geometry();
  for (std::size_t i = 0; i < solid.size(); ++i) {
    for (std::size_t k = i + 1; k < solid.size(); ++k) {
      const int a = solid[i];
      const int b = solid[k];
      const CollisionAllowance reason = matrix.allowance(a, b);
      if (reason == CollisionAllowance::kChecked) continue;
      srdf.disabled_collisions.push_back(
          {model.link(a).name, model.link(b).name, to_string(reason)});
    }
  }
  return srdf;
}

}  // namespace hullcheck
