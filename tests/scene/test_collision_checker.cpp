// CollisionChecker against independent answers:
//  - FCL 0.7 (oracles/fcl_checker: the same hulls and primitives as FCL objects, its own pair
//    list from the same matrix and scene): validity and clearance on random states of the
//    MotionBenchMaker problems (Panda, UR5), every family;
//  - a brute force over the same pairs with hullcheck::signed_distance (the culling must not
//    change the answer);
//  - the motion bound against forward kinematics sampled densely along joint-space segments;
//  - continuity of the signed clearance across contact;
//  - clearance_gradient against finite differences of the pair's signed distance;
//  - concurrent queries on one shared checker.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/core/queries.hpp>
#include <hullcheck/robot.hpp>
#include <hullcheck/scene/clearance_gradient.hpp>
#include <hullcheck/scene/collision_checker.hpp>
#include <hullcheck/scene/motion_plan_request.hpp>
#include <hullcheck/scene/planning_scene.hpp>
#include <memory>
#include <random>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "fcl_checker.hpp"
#include "scene_test_support.hpp"

namespace hullcheck {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// A robot with its SRDF matrix, shared by the tests.
struct RobotSetup {
  std::shared_ptr<const RobotModel> model;
  Srdf srdf;
  AllowedCollisionMatrix matrix;
};

RobotSetup load_robot(const std::string& urdf, const std::string& srdf) {
  RobotSetup r;
  r.model = test::cached_model(urdf);
  r.srdf = read_srdf_file(srdf);
  r.matrix = AllowedCollisionMatrix::from_srdf(*r.model, r.srdf);
  return r;
}

// A scene and its request, with the checker and the FCL oracle.
struct Problem {
  std::string name;
  PlanningScene scene;
  MotionPlanRequest request;
  std::vector<int> group;  // configuration indices the request's group moves
};

Problem load_problem(const test::MbmRobot& robot, const RobotSetup& r, const std::string& family,
                     int number) {
  Problem p;
  p.name = family + "/" + std::to_string(number);
  p.scene = read_planning_scene(test::mbm_file(robot, family, "scene", number), *r.model);
  p.request = read_motion_plan_request(test::mbm_file(robot, family, "request", number), *r.model);
  p.group = group_variables(*r.model, r.srdf, p.request.group);
  return p;
}

// Length scale of a scene: the farthest obstacle point from the origin (at least 1 m).
double scene_scale(const PlanningScene& scene) {
  double s = 1.0;
  for (const Obstacle& o : scene.obstacles) {
    s = std::max(s, o.pose.translation().norm() + o.shape.bounding_radius());
  }
  return s;
}

// hullcheck::signed_distance of one oracle pair at the oracle's current poses.
SignedDistanceResult pair_signed_distance(const RobotModel& model, const PlanningScene& scene,
                                          const test::FclChecker& fcl, std::size_t i) {
  const test::FclPair& p = fcl.pairs()[i];
  const Shape& a = model.link(p.link_a).shapes[static_cast<std::size_t>(p.shape_a)].shape;
  const Shape& b = p.self() ? model.link(p.link_b).shapes[static_cast<std::size_t>(p.shape_b)].shape
                            : scene.obstacles[static_cast<std::size_t>(p.obstacle)].shape;
  return signed_distance(a, fcl.pose_a(i), b, fcl.pose_b(i));
}

// ------------------------------------------------------------------------------------------
// Agreement with FCL on MotionBenchMaker problems.

struct Agreement {
  int states = 0;
  int valid = 0;
  int disagreements_in_band = 0;    // validity differs, |distance| within 1e-9 * scale
  int disagreements_outside = 0;    // validity differs outside the band: failures
  int fcl_gjk_vs_mpr = 0;           // FCL's distance says contact, its collide says apart (or
                                    // the reverse), outside the band: FCL inconsistent
  int compared_distances = 0;       // positive clearances compared with FCL's distance
  double max_distance_error = 0.0;  // |ours - FCL| over those
  double max_bruteforce_error = 0.0;
  double ours_seconds = 0.0, fcl_seconds = 0.0, brute_seconds = 0.0;
};

void compare_with_fcl(const test::MbmRobot& robot, const RobotSetup& r, const Problem& p,
                      int states, std::uint64_t seed, Agreement* out) {
  SCOPED_TRACE(robot.id + " " + p.name);
  const RobotModel& model = *r.model;
  const CollisionChecker checker(r.model, r.matrix, p.scene);
  test::FclChecker fcl(model, r.matrix, p.scene, test::FclSolver::kLibccd);
  const double band = 1e-9 * scene_scale(p.scene);
  std::mt19937_64 rng(seed);
  std::vector<Eigen::Isometry3d> poses;
  int reported = 0;
  for (int n = 0; n < states; ++n) {
    const Eigen::VectorXd q = test::random_configuration(model, p.request.start, p.group, rng);
    model.compute_link_poses(q, poses);
    auto t0 = Clock::now();
    const bool valid = checker.is_valid(q);
    const ClearanceResult c = checker.clearance(q);
    out->ours_seconds += seconds_since(t0);

    t0 = Clock::now();
    fcl.set_link_poses(poses);
    const bool fcl_collides = fcl.in_collision();
    const test::FclDistance fd = fcl.min_distance();
    out->fcl_seconds += seconds_since(t0);

    // Brute force over the oracle's pair list with hullcheck's own signed distance.
    t0 = Clock::now();
    double brute = INFINITY;
    for (std::size_t i = 0; i < fcl.pairs().size(); ++i) {
      brute = std::min(brute, pair_signed_distance(model, p.scene, fcl, i).signed_distance);
    }
    out->brute_seconds += seconds_since(t0);
    const double brute_error = std::abs(brute - c.distance);
    out->max_bruteforce_error = std::max(out->max_bruteforce_error, brute_error);
    // The checker's queries stop early on pairs that cannot beat the best so far and may take
    // another path (boolean GJK then EPA): equal within the query tolerance (1e-10 x size).
    EXPECT_LE(brute_error, 2e-10) << "state " << n << ": clearance " << c.distance
                                  << " vs brute force " << brute;

    ++out->states;
    out->valid += valid ? 1 : 0;
    const bool near = std::abs(c.distance) <= band || (!fd.collision && fd.distance <= band);
    if (valid == fcl_collides) {
      if (near) {
        ++out->disagreements_in_band;
      } else {
        ++out->disagreements_outside;
        if (reported++ < 5) {
          ADD_FAILURE() << "state " << n << ": is_valid " << valid << ", FCL collide "
                        << fcl_collides << ", clearance " << c.distance << " (" << c.name_a << " / "
                        << c.name_b << "), FCL distance " << (fd.collision ? -1.0 : fd.distance)
                        << "\nq = " << q.transpose();
        }
      }
    }
    // Our two queries agree with each other outside the band.
    if (!near) {
      EXPECT_EQ(valid, c.distance > 0) << "state " << n << ": " << c.distance;
    }
    // FCL's two answers (MPR collide, GJK distance) disagreeing with each other.
    if (!near && fd.collision != fcl_collides) ++out->fcl_gjk_vs_mpr;
    // Positive clearance against FCL's distance.
    if (c.distance > band && !fd.collision) {
      const double err = std::abs(c.distance - fd.distance);
      ++out->compared_distances;
      out->max_distance_error = std::max(out->max_distance_error, err);
      EXPECT_LE(err, 1e-6) << "state " << n << ": clearance " << c.distance << " (" << c.name_a
                           << " / " << c.name_b << "), FCL " << fd.distance;
    }
  }
}

// `total` states (10,000 by default; the UR5's decomposed meshes make FCL and the brute force
// over every piece pair about 25 ms per state, so it checks fewer).
void fcl_agreement(const char* id, int total_states = 10000) {
  const auto robots = test::mbm_robots();
  const test::MbmRobot* robot = nullptr;
  for (const auto& r : robots) {
    if (r.id == id) robot = &r;
  }
  if (robot == nullptr) GTEST_SKIP() << "MotionBenchMaker " << id << " absent";
  const RobotSetup setup = load_robot(robot->urdf, robot->srdf);
  // `total_states` over 2 scenes of every family (1/10 under sanitizers).
  const int total = test::sample_count(total_states, "HULLCHECK_FCL_STATES");
  const int scenes = 2 * static_cast<int>(robot->families.size());
  const int per_scene = std::max(1, total / scenes);
  Agreement a;
  const auto t0 = Clock::now();
  std::uint64_t seed = 1;
  for (const std::string& family : robot->families) {
    for (const int number : {7, 64}) {
      const Problem p = load_problem(*robot, setup, family, number);
      compare_with_fcl(*robot, setup, p, per_scene, seed++, &a);
    }
  }
  std::printf(
      "[ %-8s ] %d states (%d valid) in %d scenes: validity disagreements with FCL: %d within "
      "1e-9*scale of contact, %d outside; FCL collide vs distance inconsistent: %d; %d positive "
      "clearances vs FCL distance: max error %.2e m; brute force max error %.2e m; time: ours "
      "%.1f us/state (is_valid + clearance), FCL %.1f us/state, brute force %.1f us/state, "
      "total %.1f s\n",
      id, a.states, a.valid, scenes, a.disagreements_in_band, a.disagreements_outside,
      a.fcl_gjk_vs_mpr, a.compared_distances, a.max_distance_error, a.max_bruteforce_error,
      1e6 * a.ours_seconds / a.states, 1e6 * a.fcl_seconds / a.states,
      1e6 * a.brute_seconds / a.states, seconds_since(t0));
  EXPECT_EQ(a.disagreements_outside, 0);
  EXPECT_GT(a.valid, 0);
  EXPECT_LT(a.valid, a.states);  // both verdicts occur
}

TEST(CollisionCheckerFcl, PandaMbmAgreesWithFcl) { fcl_agreement("panda"); }
TEST(CollisionCheckerFcl, Ur5MbmAgreesWithFcl) { fcl_agreement("ur5", 2000); }

// The own arm in its table_wall scene, with scene-allowed pairs of both kinds (link/object and
// link/link) and a multi-primitive object: the oracle and the checker must drop the same pairs.
TEST(CollisionCheckerFcl, OwnArmSceneAllowedPairs) {
  const RobotSetup setup = load_robot(test::own_arm().urdf, test::own_arm().srdf);
  PlanningScene scene = read_planning_scene(
      test::robots_dir() + "/hullcheck_arm/scenes/table_wall.yaml", *setup.model);
  scene.allowed_pairs = {{"link7", "wall"},         {"bottles", "finger_left"},
                         {"link2", "link6"},        {"table", "link3"},
                         {"not_in_scene", "link4"}, {"link5", "removed_object"}};
  const CollisionChecker checker(setup.model, setup.matrix, scene);
  test::FclChecker fcl(*setup.model, setup.matrix, scene);
  // The oracle's pairs exclude exactly those.
  int env_pairs = 0, self_pairs = 0;
  for (const test::FclPair& p : fcl.pairs()) {
    const std::string a = setup.model->link(p.link_a).name;
    if (p.self()) {
      ++self_pairs;
      EXPECT_FALSE(a == "link2" && setup.model->link(p.link_b).name == "link6");
    } else {
      ++env_pairs;
      const std::string& object = scene.obstacles[static_cast<std::size_t>(p.obstacle)].object;
      EXPECT_FALSE(a == "link7" && object == "wall");
      EXPECT_FALSE(a == "finger_left" && object == "bottles");
      EXPECT_FALSE(a == "link3" && object == "table");
    }
  }
  EXPECT_GT(env_pairs, 0);
  EXPECT_GT(self_pairs, 0);

  const auto variables = test::all_variables(*setup.model);
  const Eigen::VectorXd base = setup.model->default_configuration();
  std::mt19937_64 rng(5);
  std::vector<Eigen::Isometry3d> poses;
  const int states = test::sample_count(3000);
  int valid_count = 0, disagreements = 0, in_band = 0;
  for (int n = 0; n < states; ++n) {
    const Eigen::VectorXd q = test::random_configuration(*setup.model, base, variables, rng);
    setup.model->compute_link_poses(q, poses);
    fcl.set_link_poses(poses);
    const bool valid = checker.is_valid(q);
    const ClearanceResult c = checker.clearance(q);
    double brute = INFINITY;
    for (std::size_t i = 0; i < fcl.pairs().size(); ++i) {
      brute = std::min(brute, pair_signed_distance(*setup.model, scene, fcl, i).signed_distance);
    }
    EXPECT_NEAR(c.distance, brute, 2e-10) << "state " << n;  // query tolerance, as above
    const test::FclDistance fd = fcl.min_distance();
    const bool near = std::abs(c.distance) < 2e-9 || (!fd.collision && fd.distance < 2e-9);
    if (valid == fcl.in_collision()) (near ? in_band : disagreements)++;
    if (c.distance > 2e-9 && !fd.collision) {
      EXPECT_NEAR(c.distance, fd.distance, 1e-6) << "state " << n;
    }
    valid_count += valid;
  }
  std::printf(
      "[ own arm  ] %d states (%d valid), scene-allowed pairs: disagreements with FCL "
      "%d outside the band, %d within\n",
      states, valid_count, disagreements, in_band);
  EXPECT_EQ(disagreements, 0);
  EXPECT_GT(valid_count, 0);
}

// ------------------------------------------------------------------------------------------
// Continuity of the signed clearance across contact, and its Lipschitz bound.

struct Continuity {
  int segments = 0;
  int lipschitz_checks = 0;
  int lipschitz_violations = 0;  // converged answers jumping: failures
  int segments_violating = 0;
  int reported_segment = -1;  // the last segment whose first violation was reported
  double worst_ratio = 0.0;   // max |dc| / (bound + 1e-9) over converged steps
  double max_crossing_jump = 0.0;
};

// |c(t1) - c(t0)| <= motion_bound(q(t0), q(t1)) + 1e-9 for consecutive samples.
void check_step(const CollisionChecker& checker, const Eigen::VectorXd& q0,
                const Eigen::VectorXd& q1, const ClearanceResult& r0, const ClearanceResult& r1,
                Continuity* out) {
  const double bound = checker.motion_bound(q0, q1);
  const double change = std::abs(r1.distance - r0.distance);
  ++out->lipschitz_checks;
  if (change <= bound + 1e-9) {
    out->worst_ratio = std::max(out->worst_ratio, change / (bound + 1e-9));
    return;
  }
  // No slack for answers with Status::kDegenerate (GJK on a curved core near touching contact
  // could not close its duality gap): GJK restarts from a fresh simplex when it stalls, so their
  // values are as exact as converged ones.
  out->worst_ratio = std::max(out->worst_ratio, change / (bound + 1e-9));
  ++out->lipschitz_violations;
  if (out->reported_segment != out->segments && out->segments_violating < 5) {
    out->reported_segment = out->segments;
    ADD_FAILURE() << "clearance jumps by " << change << " (" << r0.distance << " -> " << r1.distance
                  << ") where the motion bound is " << bound << "; pairs " << r0.name_a << "/"
                  << r0.name_b << " (status " << to_string(r0.status) << ") -> " << r1.name_a << "/"
                  << r1.name_b << " (status " << to_string(r1.status)
                  << ")\nq0 = " << q0.transpose() << "\nq1 = " << q1.transpose();
  }
}

void continuity_across_contact(const CollisionChecker& checker, const Eigen::VectorXd& qa,
                               const Eigen::VectorXd& qb, Continuity* out) {
  const int violations_before = out->lipschitz_violations;
  const auto at = [&](double t) -> Eigen::VectorXd { return qa + t * (qb - qa); };
  const auto clearance = [&](double t) { return checker.clearance(at(t)); };
  // Coarse pass over the whole segment.
  const int coarse = 64;
  double crossing_lo = -1.0;
  ClearanceResult prev = clearance(0.0);
  for (int k = 1; k <= coarse; ++k) {
    const double t0 = (k - 1) / static_cast<double>(coarse), t1 = k / static_cast<double>(coarse);
    const ClearanceResult c = clearance(t1);
    check_step(checker, at(t0), at(t1), prev, c, out);
    if (crossing_lo < 0 && prev.distance > 0 && c.distance <= 0) crossing_lo = t0;
    prev = c;
  }
  ASSERT_GE(crossing_lo, 0.0) << "no sign change from a valid to an invalid state";
  // Bisection to the crossing.
  double lo = crossing_lo, hi = crossing_lo + 1.0 / coarse;
  for (int i = 0; i < 60 && hi - lo > 1e-15; ++i) {
    const double mid = 0.5 * (lo + hi);
    (clearance(mid).distance > 0 ? lo : hi) = mid;
  }
  const ClearanceResult c_lo = clearance(lo), c_hi = clearance(hi);
  EXPECT_GT(c_lo.distance, 0.0);
  EXPECT_LE(c_hi.distance, 0.0);
  out->max_crossing_jump = std::max(out->max_crossing_jump, c_lo.distance - c_hi.distance);
  check_step(checker, at(lo), at(hi), c_lo, c_hi, out);
  // Fine sampling around the crossing: a window moving points by at most ~1e-5 m, then 1e-8 m.
  const double full = checker.motion_bound(qa, qb);
  for (const double reach : {1e-5, 1e-8}) {
    const double w = reach / std::max(full, 1e-12);
    const int fine = 100;
    double t_prev = std::max(0.0, lo - w);
    ClearanceResult c_prev = clearance(t_prev);
    for (int k = 1; k <= 2 * fine; ++k) {
      const double t = std::min(1.0, lo - w + w * k / fine);
      if (t <= t_prev) continue;
      const ClearanceResult c = clearance(t);
      check_step(checker, at(t_prev), at(t), c_prev, c, out);
      t_prev = t;
      c_prev = c;
    }
  }
  ++out->segments;
  if (out->lipschitz_violations > violations_before) ++out->segments_violating;
}

// Segments from a valid state to an invalid one (random states of the problem's group).
void continuity_on(const CollisionChecker& checker, const Eigen::VectorXd& base,
                   const std::vector<int>& group, int segments, std::uint64_t seed,
                   Continuity* out) {
  const RobotModel& model = checker.model();
  std::mt19937_64 rng(seed);
  std::vector<Eigen::VectorXd> valid, invalid;
  for (int tries = 0; tries < 4000 && (static_cast<int>(valid.size()) < segments ||
                                       static_cast<int>(invalid.size()) < segments);
       ++tries) {
    const Eigen::VectorXd q = test::random_configuration(model, base, group, rng);
    const double c = checker.clearance(q).distance;
    if (c > 1e-6) valid.push_back(q);
    if (c < -1e-6) invalid.push_back(q);
  }
  const int n =
      std::min({segments, static_cast<int>(valid.size()), static_cast<int>(invalid.size())});
  for (int i = 0; i < n; ++i) {
    continuity_across_contact(checker, valid[static_cast<std::size_t>(i)],
                              invalid[static_cast<std::size_t>(i)], out);
  }
}

TEST(CollisionCheckerContinuity, ClearanceContinuousAcrossContact) {
  Continuity c;
  const auto t0 = Clock::now();
  const int per_problem = test::sample_count(3);
  // The own arm (always present): table_wall, self pairs from its SRDF.
  {
    const RobotSetup setup = load_robot(test::own_arm().urdf, test::own_arm().srdf);
    const PlanningScene scene = read_planning_scene(
        test::robots_dir() + "/hullcheck_arm/scenes/table_wall.yaml", *setup.model);
    const CollisionChecker checker(setup.model, setup.matrix, scene);
    continuity_on(checker, setup.model->default_configuration(), test::all_variables(*setup.model),
                  3 * per_problem, 3, &c);
  }
  for (const test::MbmRobot& robot : test::mbm_robots()) {
    const RobotSetup setup = load_robot(robot.urdf, robot.srdf);
    std::uint64_t seed = 100;
    for (const std::string& family : robot.families) {
      const Problem p = load_problem(robot, setup, family, 7);
      const CollisionChecker checker(setup.model, setup.matrix, p.scene);
      continuity_on(checker, p.request.start, p.group, per_problem, seed++, &c);
    }
  }
  std::printf(
      "[ contin.  ] %d valid->invalid segments, %d steps: %d Lipschitz violations in %d "
      "segments (worst |dc|/(bound+1e-9) = %.3f), largest clearance change across the "
      "crossing %.2e m; %.1f s\n",
      c.segments, c.lipschitz_checks, c.lipschitz_violations, c.segments_violating, c.worst_ratio,
      c.max_crossing_jump, seconds_since(t0));
  EXPECT_GE(c.segments, 3);
  EXPECT_EQ(c.lipschitz_violations, 0);
  EXPECT_LE(c.max_crossing_jump, 1e-9);
}

// ------------------------------------------------------------------------------------------
// motion_bound against forward kinematics.

bool has_self_pairs(const RobotModel& model, const AllowedCollisionMatrix& matrix) {
  const int n = static_cast<int>(model.links().size());
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) {
      if (!matrix.allowed(a, b) && !model.link(a).shapes.empty() && !model.link(b).shapes.empty())
        return true;
    }
  }
  return false;
}

struct BoundStats {
  int segments = 0;
  double worst_ratio = 0.0;  // max over segments of (largest path length) / world bound
};

// For random segments q0 -> q1 (values from `sample`): every shape point's path length in the
// world (polyline through `steps` FK samples, >= its displacement) is at most the world bound
// (motion_bound, halved when self pairs are checked: the documented doubling covers two links
// moving towards each other), and every self pair's relative displacement is at most
// motion_bound.
template <typename Sample>
void check_motion_bound(const CollisionChecker& checker, int segments, int steps, Sample sample,
                        BoundStats* stats) {
  const RobotModel& model = checker.model();
  const bool self = has_self_pairs(model, checker.matrix());
  std::vector<std::vector<Eigen::Vector3d>> points;  // per link, link frame
  for (const Link& link : model.links()) {
    std::vector<Eigen::Vector3d> pts;
    for (const CollisionShape& cs : link.shapes) {
      for (const Eigen::Vector3d& p : test::shape_points(cs.shape)) pts.push_back(cs.origin * p);
    }
    points.push_back(std::move(pts));
  }
  std::vector<Eigen::Isometry3d> poses;
  for (int s = 0; s < segments; ++s) {
    const Eigen::VectorXd q0 = sample(), q1 = sample();
    const double bound = checker.motion_bound(q0, q1);
    const double world_bound = self ? bound / 2 : bound;
    // Path length per point.
    std::vector<std::vector<double>> length(points.size());
    std::vector<std::vector<Eigen::Vector3d>> prev(points.size()), first(points.size());
    double worst_relative = 0.0;
    for (int k = 0; k <= steps; ++k) {
      const double t = k / static_cast<double>(steps);
      model.compute_link_poses(q0 + t * (q1 - q0), poses);
      for (std::size_t l = 0; l < points.size(); ++l) {
        if (k == 0) length[l].assign(points[l].size(), 0.0);
        for (std::size_t i = 0; i < points[l].size(); ++i) {
          const Eigen::Vector3d w = poses[l] * points[l][i];
          if (k == 0) {
            prev[l].push_back(w);
            first[l].push_back(w);
          } else {
            length[l][i] += (w - prev[l][i]).norm();
            prev[l][i] = w;
          }
        }
      }
      // Self pairs: relative displacement of one point of each link (their first points).
      if (self && k > 0) {
        for (int a = 0; a < static_cast<int>(points.size()); ++a) {
          for (int b = a + 1; b < static_cast<int>(points.size()); ++b) {
            if (checker.matrix().allowed(a, b) || points[static_cast<std::size_t>(a)].empty() ||
                points[static_cast<std::size_t>(b)].empty()) {
              continue;
            }
            const auto ua = static_cast<std::size_t>(a), ub = static_cast<std::size_t>(b);
            const Eigen::Vector3d now = prev[ua][0] - prev[ub][0];
            const Eigen::Vector3d then = first[ua][0] - first[ub][0];
            worst_relative = std::max(worst_relative, (now - then).norm());
          }
        }
      }
    }
    double worst = 0.0;
    std::string worst_link;
    for (std::size_t l = 0; l < points.size(); ++l) {
      for (const double len : length[l]) {
        if (len > worst) {
          worst = len;
          worst_link = model.links()[l].name;
        }
      }
    }
    EXPECT_LE(worst, world_bound * (1 + 1e-12) + 1e-15)
        << "a point of " << worst_link << " travels " << worst << " m, bound " << world_bound
        << " (motion_bound " << bound << ")\nq0 = " << q0.transpose()
        << "\nq1 = " << q1.transpose();
    EXPECT_LE(worst_relative, bound * (1 + 1e-12) + 1e-15);
    if (world_bound > 0) stats->worst_ratio = std::max(stats->worst_ratio, worst / world_bound);
    ++stats->segments;
  }
}

TEST(CollisionCheckerMotionBound, UpperBoundsPointTravel) {
  BoundStats stats;
  const int segments = test::sample_count(150);
  std::vector<std::pair<std::string, std::string>> robots = {
      {test::own_arm().urdf, test::own_arm().srdf}};
  for (const test::RobotFile& r : test::shared_robots()) {
    if (r.id == "panda" || r.id == "mbm_panda" || r.id == "mbm_ur5")
      robots.emplace_back(r.urdf, r.srdf);
  }
  for (const auto& [urdf, srdf] : robots) {
    SCOPED_TRACE(urdf);
    const RobotSetup setup = load_robot(urdf, srdf);
    const RobotModel& model = *setup.model;
    std::mt19937_64 rng(17);
    const auto variables = test::all_variables(model);
    const Eigen::VectorXd base = model.default_configuration();
    const auto in_limits = [&] { return test::random_configuration(model, base, variables, rng); };
    // With the SRDF's self pairs (bound doubled) and without any (bound for the world).
    const CollisionChecker with_self(setup.model, setup.matrix, PlanningScene{});
    ASSERT_TRUE(has_self_pairs(model, setup.matrix));
    check_motion_bound(with_self, segments, 48, in_limits, &stats);
    AllowedCollisionMatrix none(static_cast<int>(model.links().size()));
    for (int a = 0; a < none.link_count(); ++a) {
      for (int b = a + 1; b < none.link_count(); ++b) none.allow(a, b, CollisionAllowance::kUser);
    }
    const CollisionChecker env_only(setup.model, none, PlanningScene{});
    check_motion_bound(env_only, segments, 48, in_limits, &stats);
    // The bound is not absurdly loose for the environment-only checker.
    Eigen::VectorXd q0 = base, q1 = base;
    q1[0] += 0.1;
    EXPECT_LE(env_only.motion_bound(q0, q1), 0.1 * 5.0);
    EXPECT_EQ(with_self.motion_bound(q0, q1), 2 * env_only.motion_bound(q0, q1));
  }
  std::printf("[ bound    ] %d segments: largest point travel / bound = %.3f\n", stats.segments,
              stats.worst_ratio);
  EXPECT_GT(stats.worst_ratio, 0.05);  // the check sees real motion
}

// Prismatic joints beyond their limits (the MBM Panda start states hold the fingers at 0.065,
// limit 0.04; RobotModel does not clamp): a rotation above them moves the far points by more.
TEST(CollisionCheckerMotionBound, HoldsBeyondPrismaticLimits) {
  const auto model = std::make_shared<const RobotModel>(RobotModel::from_urdf_string(
      R"(<robot name="slider_arm">
  <link name="base"/>
  <link name="arm"/>
  <link name="carriage"><collision><geometry><box size="0.02 0.02 0.02"/></geometry></collision></link>
  <joint name="turn" type="revolute">
    <parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/>
  </joint>
  <joint name="slide" type="prismatic">
    <parent link="arm"/><child link="carriage"/><axis xyz="1 0 0"/>
    <limit lower="0" upper="0.1" effort="1" velocity="1"/>
  </joint>
</robot>)",
      ".", {}, "slider_arm.urdf"));
  AllowedCollisionMatrix matrix(static_cast<int>(model->links().size()));
  const CollisionChecker checker(model, matrix, PlanningScene{});
  BoundStats stats;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> turn(-3, 3), slide(0.5, 1.0);
  check_motion_bound(
      checker, 20, 64,
      [&] {
        Eigen::VectorXd q(2);
        q << turn(rng), slide(rng);
        return q;
      },
      &stats);
  // The mimic case on the MoveIt Panda with MBM's finger value.
  const std::string urdf =
      test::shared_dir() + "/robots/panda/moveit_resources_panda_description/urdf/panda.urdf";
  if (!test::shared_dir().empty() && std::filesystem::exists(urdf)) {
    const auto panda = test::cached_model(urdf);
    const AllowedCollisionMatrix none = [&] {
      AllowedCollisionMatrix m(static_cast<int>(panda->links().size()));
      for (int a = 0; a < m.link_count(); ++a) {
        for (int b = a + 1; b < m.link_count(); ++b) m.allow(a, b, CollisionAllowance::kUser);
      }
      return m;
    }();
    const CollisionChecker env_only(panda, none, PlanningScene{});
    const int finger = panda->variable_index("panda_finger_joint1");
    const auto variables = test::all_variables(*panda);
    check_motion_bound(
        env_only, 50, 48,
        [&] {
          Eigen::VectorXd q =
              test::random_configuration(*panda, panda->default_configuration(), variables, rng);
          q[finger] = 0.065;
          return q;
        },
        &stats);
  }
}

// ------------------------------------------------------------------------------------------
// clearance_gradient against finite differences.

struct GradientStats {
  int compared = 0;
  int environment = 0;  // compared pairs of a robot shape and an obstacle
  int self = 0;         // ... of two robot shapes
  int mimic = 0;        // ... with a link moved by a mimic joint
  int skipped = 0;      // the pair's witness features switch within the step (a kink)
  double worst_relative = 0.0;
};

// Signed distance of the pair `pair` names (link/shape against obstacle or link/shape).
double pair_distance_at(const CollisionChecker& checker, const ClearanceResult& pair,
                        const Eigen::VectorXd& q, std::vector<Eigen::Isometry3d>& poses) {
  const RobotModel& model = checker.model();
  model.compute_link_poses(q, poses);
  const CollisionShape& a = model.link(pair.link_a).shapes[static_cast<std::size_t>(pair.shape_a)];
  const Eigen::Isometry3d pose_a = poses[static_cast<std::size_t>(pair.link_a)] * a.origin;
  if (pair.self) {
    const CollisionShape& b =
        model.link(pair.link_b).shapes[static_cast<std::size_t>(pair.shape_b)];
    return signed_distance(a.shape, pose_a, b.shape,
                           poses[static_cast<std::size_t>(pair.link_b)] * b.origin)
        .signed_distance;
  }
  const Obstacle& o = checker.scene().obstacles[static_cast<std::size_t>(pair.obstacle)];
  return signed_distance(a.shape, pose_a, o.shape, o.pose).signed_distance;
}

// A ClearanceResult for oracle pair i at the oracle's current poses (what clearance_gradient
// reads: links, shapes, obstacle, witnesses, normal).
ClearanceResult pair_result(const RobotModel& model, const PlanningScene& scene,
                            const test::FclChecker& fcl, std::size_t i) {
  const test::FclPair& p = fcl.pairs()[i];
  const SignedDistanceResult r = pair_signed_distance(model, scene, fcl, i);
  ClearanceResult c;
  c.distance = r.signed_distance;
  c.self = p.self();
  c.link_a = p.link_a;
  c.shape_a = p.shape_a;
  c.link_b = p.link_b;
  c.shape_b = p.shape_b;
  c.obstacle = p.obstacle;
  c.name_a = model.link(p.link_a).name;
  c.name_b = p.self()
                 ? std::string_view(model.link(p.link_b).name)
                 : std::string_view(scene.obstacles[static_cast<std::size_t>(p.obstacle)].name);
  c.point_a = r.point_a;
  c.point_b = r.point_b;
  c.normal = r.normal;
  c.status = r.status;
  return c;
}

bool below_mimic(const RobotModel& model, int link) {
  for (int l = link; l >= 0 && model.link(l).parent_joint >= 0;) {
    const Joint& j = model.joint(model.link(l).parent_joint);
    if (j.mimic_variable >= 0) return true;
    l = j.parent_link;
  }
  return false;
}

// For random states with clearance > 1e-4: the gradient of the checker's closest pair, of the
// closest robot/obstacle pair and of the closest pair moved by a mimic joint, against central
// differences of that pair's signed distance (every variable, group or not).
void compare_gradients(const CollisionChecker& checker, const Eigen::VectorXd& base,
                       const std::vector<int>& group, int states, std::uint64_t seed,
                       GradientStats* stats) {
  const RobotModel& model = checker.model();
  test::FclChecker pairs(model, checker.matrix(), checker.scene());
  std::mt19937_64 rng(seed);
  std::vector<Eigen::Isometry3d> poses, scratch;
  int reported = 0;
  for (int n = 0, tries = 0; n < states && tries < 50 * states; ++tries) {
    const Eigen::VectorXd q = test::random_configuration(model, base, group, rng);
    model.compute_link_poses(q, poses);
    const ClearanceResult closest = checker.clearance_at(poses);
    if (!(closest.distance > 1e-4) || !std::isfinite(closest.distance)) continue;
    ++n;
    std::vector<ClearanceResult> candidates{closest};
    pairs.set_link_poses(poses);
    ClearanceResult env, mimic;
    for (std::size_t i = 0; i < pairs.pairs().size(); ++i) {
      const test::FclPair& p = pairs.pairs()[i];
      const bool moved_by_mimic =
          below_mimic(model, p.link_a) || (p.self() && below_mimic(model, p.link_b));
      if (p.self() && !moved_by_mimic) continue;
      const ClearanceResult r = pair_result(model, checker.scene(), pairs, i);
      if (!p.self() && r.distance < env.distance) env = r;
      if (moved_by_mimic && r.distance < mimic.distance) mimic = r;
    }
    if (std::isfinite(env.distance)) candidates.push_back(env);
    if (std::isfinite(mimic.distance)) candidates.push_back(mimic);
    for (const ClearanceResult& c : candidates) {
      const Eigen::VectorXd g = clearance_gradient(model, poses, c);
      ASSERT_EQ(g.size(), model.variable_count());
      // Central differences with steps h and 4h: where they differ, a witness feature switches
      // inside the step (the distance has a kink there) and the pair is skipped.
      Eigen::VectorXd fd = Eigen::VectorXd::Zero(model.variable_count());
      bool kink = false;
      for (int i = 0; i < model.variable_count(); ++i) {
        double d[2];
        for (int s = 0; s < 2; ++s) {
          const double h = s == 0 ? 1e-6 : 4e-6;
          Eigen::VectorXd qp = q, qm = q;
          qp[i] += h;
          qm[i] -= h;
          d[s] = (pair_distance_at(checker, c, qp, scratch) -
                  pair_distance_at(checker, c, qm, scratch)) /
                 (2 * h);
        }
        fd[i] = d[0];
        if (std::abs(d[0] - d[1]) > 1e-6 * (std::abs(d[0]) + 1e-3)) kink = true;
      }
      if (kink) {
        ++stats->skipped;
        continue;
      }
      const double scale = std::max(fd.cwiseAbs().maxCoeff(), 1e-3);
      const double relative = (g - fd).cwiseAbs().maxCoeff() / scale;
      stats->worst_relative = std::max(stats->worst_relative, relative);
      ++stats->compared;
      (c.self ? stats->self : stats->environment)++;
      stats->mimic += below_mimic(model, c.link_a) || (c.self && below_mimic(model, c.link_b));
      if (relative > 1e-4 && reported++ < 3) {
        ADD_FAILURE() << "gradient " << g.transpose() << "\nfinite differences " << fd.transpose()
                      << "\npair " << c.name_a << " / " << c.name_b << " at distance " << c.distance
                      << "\nq = " << q.transpose();
      }
    }
  }
}

TEST(CollisionCheckerGradient, MatchesFiniteDifferences) {
  GradientStats stats;
  const int states = test::sample_count(100);
  const auto t0 = Clock::now();
  {
    // Own arm (mimic fingers included) in table_wall, every variable moving.
    const RobotSetup setup = load_robot(test::own_arm().urdf, test::own_arm().srdf);
    const PlanningScene scene = read_planning_scene(
        test::robots_dir() + "/hullcheck_arm/scenes/table_wall.yaml", *setup.model);
    const CollisionChecker checker(setup.model, setup.matrix, scene);
    compare_gradients(checker, setup.model->default_configuration(),
                      test::all_variables(*setup.model), states, 21, &stats);
  }
  for (const test::MbmRobot& robot : test::mbm_robots()) {
    const RobotSetup setup = load_robot(robot.urdf, robot.srdf);
    for (const std::string& family : {robot.families.front(), robot.families.back()}) {
      const Problem p = load_problem(robot, setup, family, 7);
      const CollisionChecker checker(setup.model, setup.matrix, p.scene);
      compare_gradients(checker, p.request.start, p.group, states / 2, 22, &stats);
    }
  }
  // The MoveIt Panda: prismatic fingers, one a mimic of the other.
  const std::string urdf =
      test::shared_dir() + "/robots/panda/moveit_resources_panda_description/urdf/panda.urdf";
  if (!test::shared_dir().empty() && std::filesystem::exists(urdf)) {
    const RobotSetup setup = load_robot(urdf, test::shared_dir() + "/robots/panda/srdf/panda.srdf");
    // An obstacle close to the hand so that fingers are often the closest pair.
    PlanningScene scene = parse_planning_scene(R"(
world:
  collision_objects:
    - id: post
      primitives: [{type: box, dimensions: [0.05, 0.05, 1.2]}]
      primitive_poses: [{position: [0.45, 0.0, 0.6]}]
    - id: ball
      primitives: [{type: sphere, dimensions: [0.08]}]
      primitive_poses: [{position: [0.3, 0.3, 0.5]}]
)",
                                               *setup.model);
    const CollisionChecker checker(setup.model, setup.matrix, scene);
    compare_gradients(checker, setup.model->default_configuration(),
                      test::all_variables(*setup.model), states, 23, &stats);
  }
  std::printf(
      "[ gradient ] %d pairs compared (%d robot/obstacle, %d self; %d moved by a mimic "
      "joint; %d skipped at kinks): worst relative error %.2e; %.1f s\n",
      stats.compared, stats.environment, stats.self, stats.mimic, stats.skipped,
      stats.worst_relative, seconds_since(t0));
  EXPECT_LE(stats.worst_relative, 1e-4);
  EXPECT_GE(stats.compared, states / 2);
  EXPECT_GT(stats.environment, 0);
  EXPECT_GT(stats.self, 0);
  EXPECT_GT(stats.mimic, 0);
  EXPECT_LE(stats.skipped, stats.compared);
}

// ------------------------------------------------------------------------------------------
// Thread safety.

TEST(CollisionCheckerThreads, SharedCheckerGivesSequentialAnswers) {
  std::shared_ptr<const CollisionChecker> checker;
  Eigen::VectorXd base;
  std::vector<int> group;
  const auto robots = test::mbm_robots();
  if (!robots.empty()) {
    const RobotSetup setup = load_robot(robots[0].urdf, robots[0].srdf);
    const Problem p = load_problem(robots[0], setup, robots[0].families[0], 7);
    checker = std::make_shared<const CollisionChecker>(setup.model, setup.matrix, p.scene);
    base = p.request.start;
    group = p.group;
  } else {
    const RobotSetup setup = load_robot(test::own_arm().urdf, test::own_arm().srdf);
    checker = std::make_shared<const CollisionChecker>(
        setup.model, setup.matrix,
        read_planning_scene(test::robots_dir() + "/hullcheck_arm/scenes/table_wall.yaml",
                            *setup.model));
    base = setup.model->default_configuration();
    group = test::all_variables(*setup.model);
  }
  const int n = test::sample_count(400);
  std::mt19937_64 rng(9);
  std::vector<Eigen::VectorXd> qs;
  for (int i = 0; i < n; ++i) {
    qs.push_back(test::random_configuration(checker->model(), base, group, rng));
  }
  struct Answer {
    bool valid;
    ClearanceResult c;
  };
  std::vector<Answer> expected;
  for (const auto& q : qs) expected.push_back({checker->is_valid(q), checker->clearance(q)});
  std::atomic<int> mismatches{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      // Each thread walks the states from a different start, interleaving the two queries.
      for (int k = 0; k < 2 * n; ++k) {
        const std::size_t i = static_cast<std::size_t>((k + t * n / 4) % n);
        const bool valid = checker->is_valid(qs[i]);
        const ClearanceResult c = checker->clearance(qs[i]);
        const Answer& e = expected[i];
        if (valid != e.valid || c.distance != e.c.distance || c.link_a != e.c.link_a ||
            c.obstacle != e.c.obstacle || c.link_b != e.c.link_b || c.point_a != e.c.point_a ||
            c.point_b != e.c.point_b || c.name_b != e.c.name_b) {
          ++mismatches;
        }
      }
    });
  }
  for (auto& th : threads) th.join();
  EXPECT_EQ(mismatches.load(), 0);
  int valid = 0;
  for (const Answer& e : expected) valid += e.valid;
  EXPECT_GT(valid, 0);
  EXPECT_LT(valid, n);
}

}  // namespace
}  // namespace hullcheck
