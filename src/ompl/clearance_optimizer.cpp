// optimize_clearance: gradient rounds on the waypoints of a path against a hinge on signed
// distance plus length, each round certified, then objective-aware shortcuts.
//
// The objective (ClearanceMarginObjective) is the integral over the path of the density
// rho(d) = w + max(0, m - d) / m. Discretised at the waypoints q_0 .. q_n with segment lengths
// l_k = |q_{k+1} - q_k| (joint space, continuous joints the short way) and densities
// rho_k = rho(d(q_k)), it is the trapezoid sum
//   F = sum_k l_k (rho_k + rho_{k+1}) / 2,
// whose only terms holding an interior waypoint q_i are
//   f_i = l_{i-1} (rho_{i-1} + rho_i) / 2 + l_i (rho_i + rho_{i+1}) / 2.
// With u_a = (q_i - q_{i-1}) / l_{i-1}, u_b = (q_i - q_{i+1}) / l_i and
// d rho_i / d q_i = -grad d(q_i) / m where d(q_i) < m (0 beyond the margin),
//   d f_i / d q_i = (rho_{i-1} + rho_i) / 2 u_a + (rho_i + rho_{i+1}) / 2 u_b
//                   + (l_{i-1} + l_i) / 2 d rho_i / d q_i.
// grad d is clearance_gradient's: the closest pair's witness points held on their links.
// Moving one waypoint at a time (Gauss-Seidel) and keeping a move only when f_i falls, F falls
// with every kept move.
#include <ompl/geometric/PathSimplifier.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/ompl/clearance_optimizer.hpp>
#include <hullcheck/ompl/objectives.hpp>
#include <hullcheck/scene/clearance_gradient.hpp>
#include <limits>
#include <memory>
#include <vector>

#include "detail/shortcut_path.hpp"

namespace hullcheck {

namespace ob = ::ompl::base;
namespace og = ::ompl::geometric;

namespace {

using Clock = std::chrono::steady_clock;

// Rounds stop once one saves less than this fraction of the (discretised) cost.
constexpr double kSettled = 1e-3;

void check_options(const ClearanceOptimizationOptions& o) {
  const auto positive = [](double x) { return x > 0.0 && std::isfinite(x); };
  if (!positive(o.margin) || !(o.length_weight >= 0.0) || !std::isfinite(o.length_weight) ||
      !positive(o.time) || !positive(o.waypoint_spacing) || o.max_waypoints < 3 ||
      !positive(o.max_step)) {
    throw InputError(
        "optimize_clearance: margin, time, waypoint_spacing and max_step must be finite and > 0, "
        "length_weight finite and >= 0, max_waypoints >= 3");
  }
}

// The waypoints being optimised: full configurations, their densities and scoped clearances.
struct Waypoints {
  std::vector<Eigen::VectorXd> q;
  std::vector<ClearanceResult> closest;  // the scope's closest pair (distance, witnesses)
  std::vector<double> rho;               // cost density
};

class Optimizer {
 public:
  Optimizer(const ob::SpaceInformationPtr& si, const StateValidityChecker& validity,
            const ClearanceOptimizationOptions& options, const ClearanceMarginObjective& objective)
      : si_(si),
        validity_(validity),
        joints_(validity.joint_space()),
        checker_(validity.collision_checker()),
        model_(joints_.model()),
        options_(options),
        objective_(objective),
        lower_(model_.lower_limits()),
        upper_(model_.upper_limits()),
        state_(si->allocState()),
        other_(si->allocState()),
        middle_(si->allocState()) {}
  ~Optimizer() {
    si_->freeState(state_);
    si_->freeState(other_);
    si_->freeState(middle_);
  }
  Optimizer(const Optimizer&) = delete;
  Optimizer& operator=(const Optimizer&) = delete;

  /// Loads the path's states as waypoints.
  void load(const og::PathGeometric& path) {
    w_.q.clear();
    for (std::size_t i = 0; i < path.getStateCount(); ++i) {
      w_.q.push_back(Eigen::VectorXd(model_.variable_count()));
      joints_.to_configuration(path.getState(i), w_.q.back());
    }
    w_.closest.assign(w_.q.size(), ClearanceResult{});
    w_.rho.assign(w_.q.size(), 0.0);
    for (std::size_t i = 0; i < w_.q.size(); ++i) evaluate(i);
    step_.assign(w_.q.size(), 1.0);
    middle_checked_.assign(w_.q.size(), 0);
  }

  /// Writes the waypoints into `path`.
  void store(og::PathGeometric& path) const {
    path.clear();
    for (const Eigen::VectorXd& q : w_.q) {
      joints_.from_configuration(q, state_);
      path.append(state_);
    }
  }

  /// One Gauss-Seidel pass over the interior waypoints; returns the moves kept and adds the
  /// discretised cost they saved to `gain`. Stops early at `deadline`.
  int round(Clock::time_point deadline, double& gain) {
    int moves = 0;
    Eigen::VectorXd g(model_.variable_count()), trial(model_.variable_count());
    for (std::size_t i = 1; i + 1 < w_.q.size(); ++i) {
      if (Clock::now() > deadline) break;
      if (!(step_[i] > kSmallestStep)) continue;
      gradient(i, g);
      const double largest = g.cwiseAbs().maxCoeff();
      if (!(largest > 0.0)) continue;
      const double before = local_cost(i, w_.q[i], w_.rho[i]);
      bool kept = false;
      for (int attempt = 0; attempt < 3 && step_[i] > kSmallestStep; ++attempt) {
        trial = w_.q[i] - (step_[i] * options_.max_step / largest) * g;
        clamp(trial);
        double d = -1.0;
        if (checker_.is_valid(trial)) {
          trial_closest_ = scoped_clearance(trial);
          d = trial_closest_.distance;
        }
        if (d > 0.0) {
          const double rho = objective_.density(d);
          const double after = local_cost(i, trial, rho);
          if (after < before - 1e-12 * std::abs(before)) {
            gain += before - after;
            w_.q[i] = trial;
            w_.closest[i] = trial_closest_;
            w_.rho[i] = rho;
            step_[i] = std::min(1.0, 2.0 * step_[i]);
            moved(i);
            kept = true;
            break;
          }
        }
        step_[i] *= 0.5;
      }
      moves += kept ? 1 : 0;
    }
    return moves;
  }

  /// Checks every motion between consecutive waypoints with the motion validator; waypoints
  /// that moved since `certified` and border a failing motion go back to their certified
  /// values until all pass. Returns true when nothing had to go back.
  bool certify(const Waypoints& certified) {
    bool clean = true;
    for (bool again = true; again;) {
      again = false;
      for (std::size_t k = 0; k + 1 < w_.q.size(); ++k) {
        if (w_.q[k] == certified.q[k] && w_.q[k + 1] == certified.q[k + 1]) continue;
        joints_.from_configuration(w_.q[k], state_);
        joints_.from_configuration(w_.q[k + 1], other_);
        if (si_->checkMotion(state_, other_)) continue;
        clean = false;
        again = true;
        for (std::size_t j : {k, k + 1}) {
          w_.q[j] = certified.q[j];
          w_.closest[j] = certified.closest[j];
          w_.rho[j] = certified.rho[j];
          step_[j] *= 0.25;
          moved(j);
        }
      }
    }
    return clean;
  }

  /// Splits the motions whose middle is closer than the margin and than both their ends (the
  /// waypoint discretisation misses that dip) at their middle, while the path has fewer than
  /// `limit` waypoints. A middle lies on its certified motion, so the split motions stay
  /// certified. Returns the waypoints added.
  int refine(std::size_t limit) {
    int added = 0;
    for (std::size_t k = 0; k + 1 < w_.q.size() && w_.q.size() < limit; ++k) {
      if (middle_checked_[k]) continue;  // neither end moved since its middle was checked
      middle_checked_[k] = 1;
      joints_.from_configuration(w_.q[k], state_);
      joints_.from_configuration(w_.q[k + 1], other_);
      si_->getStateSpace()->interpolate(state_, other_, 0.5, middle_);
      Eigen::VectorXd q(w_.q[k]);
      joints_.to_configuration(middle_, q);
      const ClearanceResult closest = scoped_clearance(q);
      const double d = closest.distance;
      if (!(d < options_.margin) ||
          !(d < std::min(w_.closest[k].distance, w_.closest[k + 1].distance))) {
        continue;
      }
      w_.q.insert(w_.q.begin() + static_cast<std::ptrdiff_t>(k + 1), q);
      w_.closest.insert(w_.closest.begin() + static_cast<std::ptrdiff_t>(k + 1), closest);
      w_.rho.insert(w_.rho.begin() + static_cast<std::ptrdiff_t>(k + 1), objective_.density(d));
      step_.insert(step_.begin() + static_cast<std::ptrdiff_t>(k + 1), 1.0);
      middle_checked_[k] = 0;  // the two halves' middles are new
      middle_checked_.insert(middle_checked_.begin() + static_cast<std::ptrdiff_t>(k + 1), 0);
      ++added;
      ++k;  // past the new waypoint
    }
    return added;
  }

  const Waypoints& waypoints() const { return w_; }

  /// The objective's waypoint discretisation F (see the file's comment).
  double cost() const {
    double f = 0.0;
    for (std::size_t k = 0; k + 1 < w_.q.size(); ++k) {
      f += 0.5 * distance(w_.q[k], w_.q[k + 1]) * (w_.rho[k] + w_.rho[k + 1]);
    }
    return f;
  }

 private:
  static constexpr double kSmallestStep = 1.0 / 64.0;

  // Waypoint i changed: the middles of its motions need checking again.
  void moved(std::size_t i) {
    middle_checked_[i] = 0;
    if (i > 0) middle_checked_[i - 1] = 0;
  }
  // The scope's closest pair when closer than the margin; +inf (no pair) otherwise: the cost
  // density is flat from the margin up and the gradient needs no pair there.
  ClearanceResult scoped_clearance(const Eigen::VectorXd& q) const {
    return validity_.scoped_clearance(q, options_.margin);
  }
  void evaluate(std::size_t i) {
    w_.closest[i] = scoped_clearance(w_.q[i]);
    w_.rho[i] = objective_.density(w_.closest[i].distance);
  }
  // Group values of b - a, continuous joints the short way round.
  double difference(int v, const Eigen::VectorXd& a, const Eigen::VectorXd& b) const {
    const double x = b[v] - a[v];
    return std::isfinite(lower_[v]) ? x : std::remainder(x, 2.0 * M_PI);
  }
  double distance(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const {
    double sum = 0.0;
    for (int v : joints_.variables()) sum += difference(v, a, b) * difference(v, a, b);
    return std::sqrt(sum);
  }
  double local_cost(std::size_t i, const Eigen::VectorXd& q, double rho) const {
    return 0.5 * distance(w_.q[i - 1], q) * (w_.rho[i - 1] + rho) +
           0.5 * distance(q, w_.q[i + 1]) * (rho + w_.rho[i + 1]);
  }
  // d f_i / d q_i over the group's values (zero elsewhere); see the file's comment.
  void gradient(std::size_t i, Eigen::VectorXd& g) {
    g.setZero();
    const double la = distance(w_.q[i - 1], w_.q[i]), lb = distance(w_.q[i], w_.q[i + 1]);
    const double wa = 0.5 * (w_.rho[i - 1] + w_.rho[i]), wb = 0.5 * (w_.rho[i] + w_.rho[i + 1]);
    for (int v : joints_.variables()) {
      if (la > 0.0) g[v] += wa * difference(v, w_.q[i - 1], w_.q[i]) / la;
      if (lb > 0.0) g[v] += wb * difference(v, w_.q[i + 1], w_.q[i]) / lb;
    }
    // The closest pair and its witnesses as found when q_i was evaluated (same q, same pair).
    const ClearanceResult& closest = w_.closest[i];
    if (!(closest.distance < options_.margin) || closest.link_a < 0) return;
    model_.compute_link_poses(w_.q[i], poses_);
    const Eigen::VectorXd dd = clearance_gradient(model_, poses_, closest);
    const double weight = 0.5 * (la + lb) / options_.margin;
    for (int v : joints_.variables()) g[v] -= weight * dd[v];
  }
  void clamp(Eigen::VectorXd& q) const {
    for (int v : joints_.variables()) {
      if (std::isfinite(lower_[v])) q[v] = std::min(upper_[v], std::max(lower_[v], q[v]));
    }
  }

  ob::SpaceInformationPtr si_;
  const StateValidityChecker& validity_;
  const JointStateSpace& joints_;
  const CollisionChecker& checker_;
  const RobotModel& model_;
  const ClearanceOptimizationOptions& options_;
  const ClearanceMarginObjective& objective_;
  Eigen::VectorXd lower_, upper_;
  ob::State* state_;
  ob::State* other_;
  ob::State* middle_;
  Waypoints w_;
  std::vector<double> step_;  // per waypoint: its step as a fraction of max_step
  // Per motion k (waypoints k, k + 1): its middle was checked by refine since either end moved.
  std::vector<char> middle_checked_;
  std::vector<Eigen::Isometry3d> poses_;
  ClearanceResult trial_closest_;
};

// Minimum of the validity checker's (scoped) clearance over the path's states.
double min_waypoint_clearance(const StateValidityChecker& validity, const og::PathGeometric& path) {
  double m = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < path.getStateCount(); ++i) {
    m = std::min(m, validity.clearance(path.getState(i)));
  }
  return m;
}

// Every motion of the path passes the motion validator.
bool all_motions_pass(const ob::SpaceInformationPtr& si, const og::PathGeometric& path) {
  for (std::size_t i = 0; i + 1 < path.getStateCount(); ++i) {
    if (!si->checkMotion(path.getState(i), path.getState(i + 1))) return false;
  }
  return true;
}

}  // namespace

ClearanceOptimizationResult optimize_clearance(const ob::SpaceInformationPtr& si,
                                               const StateValidityChecker& validity,
                                               og::PathGeometric& path,
                                               const ClearanceOptimizationOptions& options) {
  check_options(options);
  if (!si || path.getSpaceInformation() != si || si->getStateValidityChecker().get() != &validity) {
    throw InputError(
        "optimize_clearance: the path and the validity checker must belong to the space "
        "information given");
  }
  const Clock::time_point start = Clock::now();
  const Clock::time_point deadline = start + std::chrono::duration_cast<Clock::duration>(
                                                 std::chrono::duration<double>(options.time));
  const auto objective =
      std::make_shared<ClearanceMarginObjective>(si, options.margin, options.length_weight);
  ClearanceOptimizationResult result;
  result.cost_before = path.cost(objective).value();
  result.length_before = path.length();
  result.min_clearance_before = min_waypoint_clearance(validity, path);
  const auto finish = [&](const og::PathGeometric& final_path, double cost) {
    result.cost_after = cost;
    result.length_after = final_path.length();
    result.min_clearance_after = min_waypoint_clearance(validity, final_path);
    result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return result;
  };
  if (path.getStateCount() < 2) return finish(path, result.cost_before);

  og::PathGeometric work(path);
  Optimizer optimizer(si, validity, options, *objective);
  og::PathSimplifier simplifier(si, ob::GoalPtr(), objective);
  // Two passes at most: gradient rounds, then shortcuts; when a shortcut changed the path, the
  // rounds run again on it, so that the path returned ends with rounds (a shortcut's straight
  // motion may pass closer than the margin between its ends).
  for (int pass = 0; pass < 2 && Clock::now() < deadline; ++pass) {
    // The path interpolated to waypoint_spacing (up to max_waypoints, never fewer states than
    // it has): its motions are parts of its certified motions, certified as those are.
    const auto wanted =
        static_cast<std::size_t>(std::ceil(work.length() / options.waypoint_spacing)) + 1;
    const std::size_t count = std::min<std::size_t>(
        std::max(wanted, work.getStateCount()),
        std::max<std::size_t>(work.getStateCount(),
                              static_cast<std::size_t>(options.max_waypoints)));
    work.interpolate(static_cast<unsigned>(count));
    optimizer.load(work);
    Waypoints certified = optimizer.waypoints();
    // Once the rounds settle, motions that dip below the margin between their waypoints are
    // split (up to twice the interpolated count) and the rounds go on.
    const std::size_t refine_limit = 2 * work.getStateCount();
    // Settled: a round that moved nothing, or saved less than kSettled of the cost.
    while (Clock::now() < deadline) {
      double gain = 0.0;
      const int moves = optimizer.round(deadline, gain);
      ++result.rounds;
      if (moves > 0) {
        optimizer.certify(certified);
        result.moves += moves;
        certified = optimizer.waypoints();
      }
      if (moves == 0 || gain < kSettled * optimizer.cost()) {
        const int added = optimizer.refine(refine_limit);
        if (added == 0) break;
        result.refined += added;
        certified = optimizer.waypoints();
      }
    }
    optimizer.store(work);
    if (pass == 1 || !(Clock::now() < deadline)) break;
    // One pass of shortcuts: as many attempts as waypoints, up to 8.
    const auto attempts = static_cast<unsigned>(std::min<std::size_t>(work.getStateCount(), 8));
    if (!detail::shortcut_path(simplifier, work, attempts, attempts)) break;
    ++result.shortcuts;
  }

  // The contract, checked on the result itself: every motion passes, and the objective's cost
  // is no higher than the input's.
  const double cost = work.cost(objective).value();
  if (cost <= result.cost_before && all_motions_pass(si, work)) {
    path = work;
    result.changed = true;
    return finish(path, cost);
  }
  return finish(path, result.cost_before);
}

}  // namespace hullcheck
