// Helpers shared by the OMPL integration tests: robots with their SRDF and scenes, checkers,
// MotionBenchMaker problem files, random valid states, dense re-checks of motions.
#pragma once

#include <ompl/base/SpaceInformation.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <hullcheck/ompl.hpp>
#include <limits>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "robot_test_support.hpp"

// Sanitizer builds run the same tests about 10x slower: the tests scale their problem counts.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define HULLCHECK_TEST_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define HULLCHECK_TEST_SANITIZED 1
#endif
#endif

namespace hullcheck::test {

#ifdef HULLCHECK_TEST_SANITIZED
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif

/// `normal` in an optimised build, `sanitized` under a sanitizer.
inline int scaled(int normal, int sanitized) { return kSanitized ? sanitized : normal; }

/// OMPL draws every generator's seed from one global sequence; setting its seed again restarts
/// that sequence (OMPL logs an error that it may not be deterministic: it is, for generators
/// created afterwards, so the message is silenced).
inline void reseed_ompl(std::uint_fast32_t seed) {
  const ::ompl::msg::LogLevel level = ::ompl::msg::getLogLevel();
  ::ompl::msg::setLogLevel(::ompl::msg::LOG_NONE);
  ::ompl::RNG::setSeed(seed);
  ::ompl::msg::setLogLevel(level);
}

/// A robot model with its SRDF (empty when the robot has none).
struct LoadedRobot {
  std::shared_ptr<const RobotModel> model;
  Srdf srdf;
};

inline LoadedRobot load_robot(const RobotFile& file) {
  LoadedRobot r;
  r.model = std::make_shared<const RobotModel>(RobotModel::from_urdf_file(file.urdf));
  if (!file.srdf.empty()) r.srdf = read_srdf_file(file.srdf);
  return r;
}

/// The shared robot `id` (robot_test_support.hpp's names), or nothing when ../shared lacks it.
inline std::optional<RobotFile> shared_robot(const std::string& id) {
  for (const RobotFile& r : shared_robots()) {
    if (r.id == id) return r;
  }
  return std::nullopt;
}

/// The own arm's scene with a table, a wall, bottles and a lamp.
inline std::string own_arm_scene() {
  return robots_dir() + "/hullcheck_arm/scenes/table_wall.yaml";
}

/// Checker for `robot` (SRDF collision matrix) in `scene`; with `check_self` false every link
/// pair is allowed (only the robot against the obstacles is checked).
inline std::shared_ptr<const CollisionChecker> make_checker(const LoadedRobot& robot,
                                                            PlanningScene scene,
                                                            bool check_self = true) {
  AllowedCollisionMatrix matrix = AllowedCollisionMatrix::from_srdf(*robot.model, robot.srdf);
  if (!check_self) {
    for (int a = 0; a < matrix.link_count(); ++a) {
      for (int b = a + 1; b < matrix.link_count(); ++b) {
        if (!matrix.allowed(a, b)) matrix.allow(a, b, CollisionAllowance::kUser);
      }
    }
  }
  return std::make_shared<const CollisionChecker>(robot.model, std::move(matrix), std::move(scene));
}

/// MotionBenchMaker: "panda" or "ur5"; family such as "box"; problem 1..100.
inline std::string mbm_file(const std::string& robot, const std::string& family, int problem,
                            const std::string& kind /* "scene" or "request" */) {
  char number[16];
  std::snprintf(number, sizeof number, "%04d", problem);
  return shared_dir() + "/benchmarks/mbm/" + robot + "/" + family + "_" + robot + "/" + kind +
         number + ".yaml";
}

inline const std::vector<std::string>& mbm_families() {
  static const std::vector<std::string> families = {
      "bookshelf_small", "bookshelf_tall",  "bookshelf_thin", "box", "cage",
      "table_pick",      "table_under_pick"};
  return families;
}

/// The MBM robot ("mbm_panda" / "mbm_ur5") for an MBM robot folder name ("panda" / "ur5").
inline std::optional<RobotFile> mbm_robot(const std::string& robot) {
  return shared_robot(robot == "panda" ? "mbm_panda" : "mbm_ur5");
}

/// Deterministic random states of a JointStateSpace (OMPL's samplers draw from a global seed
/// that other tests have already started): group values uniform within the joint limits
/// (continuous joints in [-pi, pi)), held joints at the space's fixed values.
class StateSampler {
 public:
  StateSampler(const JointStateSpace& joints, unsigned seed)
      : joints_(joints),
        rng_(seed),
        lower_(joints.model().lower_limits()),
        upper_(joints.model().upper_limits()),
        q_(joints.fixed_configuration()) {}

  void uniform(::ompl::base::State* state) {
    q_ = joints_.fixed_configuration();
    for (int v : joints_.variables()) {
      const double lo = std::isfinite(lower_[v]) ? lower_[v] : -M_PI;
      const double hi = std::isfinite(upper_[v]) ? upper_[v] : M_PI;
      q_[v] = std::uniform_real_distribution<double>(lo, hi)(rng_);
    }
    joints_.from_configuration(q_, state);
  }

  /// Each group value moved by up to `distance` (rad or m) from `near`'s, within the limits.
  void near(const ::ompl::base::State* near, double distance, ::ompl::base::State* state) {
    joints_.to_configuration(near, q_);
    for (int v : joints_.variables()) {
      q_[v] += std::uniform_real_distribution<double>(-distance, distance)(rng_);
      q_[v] = std::min(std::max(q_[v], lower_[v]), upper_[v]);
    }
    joints_.from_configuration(q_, state);
  }

  std::mt19937_64& rng() { return rng_; }

 private:
  const JointStateSpace& joints_;
  std::mt19937_64 rng_;
  Eigen::VectorXd lower_, upper_, q_;
};

/// Samples a valid state uniformly (up to `attempts` tries); false when none was found.
inline bool sample_valid(const ::ompl::base::SpaceInformation& si, StateSampler& sampler,
                         ::ompl::base::State* state, int attempts = 1000) {
  for (int i = 0; i < attempts; ++i) {
    sampler.uniform(state);
    if (si.isValid(state)) return true;
  }
  return false;
}

/// Samples a valid state near `near` (StateSampler::near).
inline bool sample_valid_near(const ::ompl::base::SpaceInformation& si, StateSampler& sampler,
                              const ::ompl::base::State* near, double distance,
                              ::ompl::base::State* state, int attempts = 1000) {
  for (int i = 0; i < attempts; ++i) {
    sampler.near(near, distance, state);
    if (si.isValid(state)) return true;
  }
  return false;
}

/// A motion re-checked at `samples` + 1 evenly spaced states (the space's interpolation).
struct DenseCheck {
  bool valid = true;                                               ///< Every state valid.
  double min_clearance = std::numeric_limits<double>::infinity();  ///< Over all states, m.
  double first_invalid = -1.0;  ///< Fraction of the first invalid state, -1 when none.
};

/// Dense re-check with the checker's boolean test and its exact clearance at every state.
inline DenseCheck dense_check(const ::ompl::base::SpaceInformation& si,
                              const StateValidityChecker& validity, const ::ompl::base::State* a,
                              const ::ompl::base::State* b, int samples) {
  DenseCheck out;
  ::ompl::base::State* s = si.allocState();
  for (int i = 0; i <= samples; ++i) {
    const double t = static_cast<double>(i) / samples;
    si.getStateSpace()->interpolate(a, b, t, s);
    const double d = validity.clearance(s);
    out.min_clearance = std::min(out.min_clearance, d);
    if (!validity.isValid(s) || !(d > 0.0)) {
      if (out.valid) out.first_invalid = t;
      out.valid = false;
    }
  }
  si.freeState(s);
  return out;
}

/// Conservative-advancement steps a motion takes. When the validator counts its steps
/// (GuaranteedMotionValidator::step_count(), where available) that count is used; otherwise the
/// steps of the advancement its documentation describes (exact clearance d, global motion
/// bound B of the rest: advance by d / B) are counted here.
template <class V>
auto validator_step_count(const V& mv, int) -> decltype(static_cast<long>(mv.step_count())) {
  return static_cast<long>(mv.step_count());
}
template <class V>
long validator_step_count(const V&, long) {
  return -1;
}

inline int count_advancement_steps(const GuaranteedMotionValidator& mv,
                                   const StateValidityChecker& validity,
                                   const ::ompl::base::State* a, const ::ompl::base::State* b) {
  const long before = validator_step_count(mv, 0);
  if (before >= 0) {
    mv.checkMotion(a, b);
    return static_cast<int>(validator_step_count(mv, 0) - before);
  }
  const JointStateSpace& joints = validity.joint_space();
  const CollisionChecker& checker = validity.collision_checker();
  const auto n = joints.fixed_configuration().size();
  Eigen::VectorXd q0(n), q1(n);
  joints.to_configuration(a, q0);
  joints.to_configuration(b, q1);
  for (int v : joints.variables()) {
    if (joints.model().joint(joints.model().variable_joint(v)).type == JointType::kContinuous) {
      q1[v] = q0[v] + std::remainder(q1[v] - q0[v], 2.0 * M_PI);
    }
  }
  const double bound = checker.motion_bound(q0, q1);
  int steps = 0;
  double t = 0.0;
  while (steps < 100000) {
    ++steps;
    const double d = checker.clearance(q0 + t * (q1 - q0)).distance;
    if (!(d > 1e-6)) break;
    const double rest = (1.0 - t) * bound;
    if (rest < d) break;
    t += (1.0 - t) * (d / rest);
  }
  return steps;
}

/// Configuration indices of `names` (each must be an active joint).
inline std::vector<int> indices_of(const RobotModel& model, const std::vector<std::string>& names) {
  std::vector<int> out;
  for (const std::string& n : names) out.push_back(model.variable_index(n));
  return out;
}

/// Names of configuration indices.
inline std::vector<std::string> names_of(const RobotModel& model, const std::vector<int>& indices) {
  std::vector<std::string> out;
  for (int i : indices) out.push_back(model.variable_names()[static_cast<std::size_t>(i)]);
  return out;
}

}  // namespace hullcheck::test
