// PairScope (any subset of a checker's self link pairs, with or without the obstacles) against
// brute force over the same pairs, its errors, and approaching_self_pairs against a brute-force
// sampling of every checked pair's distance range: the own arm in its table-and-wall scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <hullcheck/scene.hpp>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "robot_test_support.hpp"
#include "scene_test_support.hpp"

namespace hullcheck {
namespace {

using LinkPair = std::pair<int, int>;

using test::arm_in_scene;
using test::ArmInScene;

/// Minimum signed distance over every shape pair of the link pairs listed, each query cold.
double brute_force_link_pairs(const RobotModel& model, const std::vector<LinkPair>& pairs,
                              const std::vector<Eigen::Isometry3d>& poses) {
  double best = INFINITY;
  for (const auto& [a, b] : pairs) {
    for (const CollisionShape& sa : model.link(a).shapes) {
      for (const CollisionShape& sb : model.link(b).shapes) {
        best =
            std::min(best, signed_distance(sa.shape, poses[static_cast<std::size_t>(a)] * sa.origin,
                                           sb.shape, poses[static_cast<std::size_t>(b)] * sb.origin)
                               .signed_distance);
      }
    }
  }
  return best;
}

TEST(PairScope, RandomSubsetsEqualBruteForceOverTheirPairs) {
  const ArmInScene w = arm_in_scene();
  ASSERT_TRUE(w.scene.allowed_pairs.empty());  // the obstacle brute force checks every pair
  const CollisionChecker checker(w.model, w.matrix, w.scene);
  const std::vector<LinkPair> checked = checker.checked_link_pairs();
  ASSERT_GE(checked.size(), 3u);
  std::mt19937_64 rng(41);
  std::vector<Eigen::Isometry3d> poses;
  int subsets_with_obstacles = 0, finite = 0;
  const int states = test::sample_count(300);
  for (int n = 0; n < states; ++n) {
    // A random subset of the checked pairs, listed in random order and either orientation.
    std::vector<LinkPair> subset;
    for (const LinkPair& p : checked) {
      if (rng() % 2 == 0) subset.push_back(rng() % 2 == 0 ? p : LinkPair{p.second, p.first});
    }
    std::shuffle(subset.begin(), subset.end(), rng);
    const bool obstacles = rng() % 2 == 0;
    const PairScope scope = checker.pair_scope(obstacles, subset);
    EXPECT_EQ(scope.obstacles(), obstacles);
    ASSERT_EQ(scope.self_link_pairs().size(), subset.size());
    // Listed in the checker's order, a < b.
    for (std::size_t k = 1; k < scope.self_link_pairs().size(); ++k) {
      const auto at = [&](const LinkPair& p) {
        return std::find(checked.begin(), checked.end(), p) - checked.begin();
      };
      EXPECT_LT(at(scope.self_link_pairs()[k - 1]), at(scope.self_link_pairs()[k]));
    }

    const Eigen::VectorXd q = test::random_configuration(*w.model, rng);
    w.model->compute_link_poses(q, poses);
    double expected = brute_force_link_pairs(*w.model, scope.self_link_pairs(), poses);
    if (obstacles) {
      expected = std::min(expected, test::brute_force_obstacle_clearance(*w.model, w.scene, poses));
    }
    const ClearanceResult r = checker.clearance(q, scope);
    const ClearanceResult at_poses = checker.clearance_at(poses, scope);
    if (!std::isfinite(expected)) {
      EXPECT_TRUE(std::isinf(r.distance) && r.distance > 0) << r.distance;
      EXPECT_TRUE(std::isinf(at_poses.distance) && at_poses.distance > 0);
      continue;
    }
    ++finite;
    subsets_with_obstacles += obstacles;
    // Deep overlaps of vertex-rich pieces may stop EPA at its cap (flagged): near, not equal.
    const double tolerance = r.status == Status::kConverged ? 2e-10 : 1e-3;
    ASSERT_NEAR(r.distance, expected, tolerance) << "q = " << q.transpose();
    ASSERT_NEAR(at_poses.distance, expected, tolerance) << "q = " << q.transpose();
    // The pair reported is one of the scope's.
    if (!r.self) {
      EXPECT_TRUE(obstacles);
    } else {
      const LinkPair p{std::min(r.link_a, r.link_b), std::max(r.link_a, r.link_b)};
      EXPECT_NE(std::find(scope.self_link_pairs().begin(), scope.self_link_pairs().end(), p),
                scope.self_link_pairs().end())
          << r.name_a << " - " << r.name_b;
    }
  }
  EXPECT_GT(finite, states / 2);
  EXPECT_GT(subsets_with_obstacles, states / 5);
}

TEST(PairScope, WholeScopesEqualClearanceScopes) {
  const ArmInScene w = arm_in_scene();
  const CollisionChecker checker(w.model, w.matrix, w.scene);
  std::mt19937_64 rng(43);
  for (int n = 0; n < 50; ++n) {
    const Eigen::VectorXd q = test::random_configuration(*w.model, rng);
    for (ClearanceScope s :
         {ClearanceScope::kAll, ClearanceScope::kObstacles, ClearanceScope::kSelf}) {
      EXPECT_EQ(checker.clearance(q, checker.pair_scope(s)).distance,
                checker.clearance(q, s).distance);
    }
    EXPECT_EQ(checker.clearance(q, checker.pair_scope(true, checker.checked_link_pairs())).distance,
              checker.clearance(q).distance);
  }
}

TEST(PairScope, RejectsUncheckedPairsAndOtherCheckers) {
  const ArmInScene w = arm_in_scene();
  const CollisionChecker checker(w.model, w.matrix, w.scene);
  const std::vector<LinkPair> checked = checker.checked_link_pairs();
  // An adjacent pair the SRDF allows to touch is not checked: named in the error.
  const int n = static_cast<int>(w.model->links().size());
  LinkPair unchecked{-1, -1};
  for (int a = 0; a < n && unchecked.first < 0; ++a) {
    for (int b = a + 1; b < n; ++b) {
      if (!w.model->link(a).shapes.empty() && !w.model->link(b).shapes.empty() &&
          std::find(checked.begin(), checked.end(), LinkPair{a, b}) == checked.end()) {
        unchecked = {a, b};
        break;
      }
    }
  }
  ASSERT_GE(unchecked.first, 0);
  try {
    checker.pair_scope(true, {unchecked});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(w.model->link(unchecked.first).name), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find(w.model->link(unchecked.second).name), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(checker.pair_scope(false, {{-1, 2}}), InputError);
  EXPECT_THROW(checker.pair_scope(false, {{0, n}}), InputError);
  EXPECT_THROW(checker.pair_scope(false, {{checked[0].first, checked[0].first}}), InputError);

  // A checker with fewer checked pairs (one more pair allowed) rejects the scope.
  AllowedCollisionMatrix fewer = w.matrix;
  fewer.allow(checked[0].first, checked[0].second, CollisionAllowance::kUser);
  const CollisionChecker other(w.model, fewer, w.scene);
  const PairScope scope = checker.pair_scope(ClearanceScope::kAll);
  const Eigen::VectorXd q = w.model->default_configuration();
  EXPECT_THROW(other.clearance(q, scope), InputError);
  // A checker of another model (the same file loaded again) rejects it too.
  const auto reloaded =
      std::make_shared<const RobotModel>(RobotModel::from_urdf_file(test::own_arm().urdf));
  const CollisionChecker other_model(reloaded, w.matrix, PlanningScene{});
  EXPECT_THROW(other_model.clearance(q, scope), InputError);
  // A copy of the checker accepts it.
  const CollisionChecker copy = checker;
  EXPECT_EQ(copy.clearance(q, scope).distance, checker.clearance(q).distance);
}

/// Every checked pair's smallest and largest signed distance over `samples` random
/// configurations of the listed values (the others at the default configuration), brute force.
std::vector<std::pair<double, double>> brute_force_ranges(const ArmInScene& w,
                                                          const std::vector<LinkPair>& checked,
                                                          const std::vector<int>& variables,
                                                          int samples, unsigned seed) {
  std::vector<std::pair<double, double>> range(checked.size(), {INFINITY, -INFINITY});
  std::mt19937_64 rng(seed);
  std::vector<Eigen::Isometry3d> poses;
  for (int n = 0; n < samples; ++n) {
    Eigen::VectorXd q = w.model->default_configuration();
    const Eigen::VectorXd random = test::random_configuration(*w.model, rng);
    for (int v : variables) q[v] = random[v];
    w.model->compute_link_poses(q, poses);
    for (std::size_t k = 0; k < checked.size(); ++k) {
      const double d = brute_force_link_pairs(*w.model, {checked[k]}, poses);
      range[k].first = std::min(range[k].first, d);
      range[k].second = std::max(range[k].second, d);
    }
  }
  return range;
}

TEST(ApproachingSelfPairs, AgreesWithBruteForceRanges) {
  const ArmInScene w = arm_in_scene();
  const CollisionChecker checker(w.model, w.matrix, w.scene);
  const std::vector<LinkPair> checked = checker.checked_link_pairs();
  std::vector<int> all(static_cast<std::size_t>(w.model->variable_count()));
  for (int v = 0; v < w.model->variable_count(); ++v) all[static_cast<std::size_t>(v)] = v;
  const double margin = 0.05;
  const std::vector<LinkPair> listed =
      approaching_self_pairs(checker, all, w.model->default_configuration(), margin);
  EXPECT_EQ(
      optimization_scope(checker, all, w.model->default_configuration(), margin).self_link_pairs(),
      listed);
  EXPECT_TRUE(
      optimization_scope(checker, all, w.model->default_configuration(), margin).obstacles());
  const auto range = brute_force_ranges(w, checked, all, test::sample_count(600), 97);
  int clearly_moving = 0, held_close = 0;
  for (std::size_t k = 0; k < checked.size(); ++k) {
    const bool in = std::find(listed.begin(), listed.end(), checked[k]) != listed.end();
    const std::string name =
        w.model->link(checked[k].first).name + " - " + w.model->link(checked[k].second).name;
    // Sampling decides: pairs whose independent brute-force range moves and clearly exceeds
    // the margin are listed, pairs clearly never clear of it are not.
    if (range[k].second > margin + 0.01 && range[k].second - range[k].first > 0.01) {
      EXPECT_TRUE(in) << name << " [" << range[k].first << ", " << range[k].second << "]";
      ++clearly_moving;
    } else if (range[k].second < margin - 0.005) {
      EXPECT_FALSE(in) << name << " [" << range[k].first << ", " << range[k].second << "]";
      ++held_close;
    }
  }
  EXPECT_GT(clearly_moving, 0);
  EXPECT_GT(held_close, 0);
  // The arm's links 1 and 3 stay about 0.02 m apart by design: never worth optimising.
  const LinkPair link1_link3{w.model->link_index("link1"), w.model->link_index("link3")};
  ASSERT_NE(std::find(checked.begin(), checked.end(), link1_link3), checked.end());
  EXPECT_EQ(std::find(listed.begin(), listed.end(), link1_link3), listed.end());
  // Deterministic for a seed.
  EXPECT_EQ(approaching_self_pairs(checker, all, w.model->default_configuration(), margin), listed);
}

/// Whether `link` is `ancestor` or below it in the kinematic tree.
bool descends_from(const RobotModel& model, int link, int ancestor) {
  for (int l = link; l >= 0;) {
    if (l == ancestor) return true;
    const int joint = model.link(l).parent_joint;
    l = joint < 0 ? -1 : model.joint(joint).parent_link;
  }
  return false;
}

TEST(ApproachingSelfPairs, OnlyPairsTheValuesMove) {
  const ArmInScene w = arm_in_scene();
  const CollisionChecker checker(w.model, w.matrix, w.scene);
  const Eigen::VectorXd q = w.model->default_configuration();
  // No value moves: no pair changes its distance, none is listed.
  EXPECT_TRUE(approaching_self_pairs(checker, {}, q, 0.05).empty());
  // The last value (the distal joint) moves only pairs with a link beyond it.
  const int last = w.model->variable_count() - 1;
  const int joint_child = w.model->joint(w.model->variable_joint(last)).child_link;
  for (const LinkPair& p : approaching_self_pairs(checker, {last}, q, 0.05)) {
    EXPECT_TRUE(descends_from(*w.model, p.first, joint_child) ||
                descends_from(*w.model, p.second, joint_child))
        << w.model->link(p.first).name << " - " << w.model->link(p.second).name;
  }
}

TEST(ApproachingSelfPairs, RejectsBadInput) {
  const ArmInScene w = arm_in_scene();
  const CollisionChecker checker(w.model, w.matrix, w.scene);
  const Eigen::VectorXd q = w.model->default_configuration();
  EXPECT_THROW(approaching_self_pairs(checker, {0}, q, 0.0), InputError);
  EXPECT_THROW(approaching_self_pairs(checker, {0}, q, -0.1), InputError);
  EXPECT_THROW(approaching_self_pairs(checker, {0}, q, NAN), InputError);
  EXPECT_THROW(approaching_self_pairs(checker, {0}, q, INFINITY), InputError);
  EXPECT_THROW(approaching_self_pairs(checker, {-1}, q, 0.05), InputError);
  EXPECT_THROW(approaching_self_pairs(checker, {w.model->variable_count()}, q, 0.05), InputError);
  EXPECT_THROW(approaching_self_pairs(checker, {0}, Eigen::VectorXd::Zero(1), 0.05), InputError);
  SelfPairSampling none;
  none.samples = 0;
  EXPECT_THROW(approaching_self_pairs(checker, {0}, q, 0.05, none), InputError);
}

}  // namespace
}  // namespace hullcheck
