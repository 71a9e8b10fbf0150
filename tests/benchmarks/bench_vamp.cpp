// hullcheck beside VAMP (../shared/peers/vamp) on MotionBenchMaker Panda and UR5 problems, in
// the same run (Release; the VAMP translation unit is built with AVX2 and FMA):
//  - OMPL's RRTConnect with VAMP's checker (its spheres; motions at 1/32 of joint-space
//    distance, 8 states per SIMD call) in a RealVectorStateSpace of VAMP's joints and limits;
//  - the same planner, seed and space with hullcheck's certified motions
//    (GuaranteedMotionValidator, CollisionChecker::check_motion) and with OMPL's discrete
//    validator at its default resolution and at VAMP's;
//  - VAMP's own RRTConnect (range 1.0 Panda, 1.5 UR5; Halton sampler reset per problem).
// Solve times are the best of --repeats attempts per problem (same seed each); medians over the
// problems valid for both checkers.
//
//   bench_vamp --robot panda|ur5 --mbm DIR [--per-family N] [--time S] [--repeats K] [--no-tables]
#include <ompl/base/MotionValidator.h>
#include <ompl/base/StateValidityChecker.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <hullcheck/ompl.hpp>
#include <hullcheck/robot.hpp>
#include <hullcheck/scene/motion_plan_request.hpp>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "problem_list.hpp"
#include "vamp_peer.hpp"

namespace {

namespace ob = ::ompl::base;
namespace og = ::ompl::geometric;
using hullcheck::bench::VampObstacle;
using hullcheck::bench::VampPeer;

std::vector<VampObstacle> vamp_obstacles(const hullcheck::PlanningScene& scene, bool box_family) {
  std::vector<VampObstacle> out;
  for (const hullcheck::Obstacle& o : scene.obstacles) {
    VampObstacle v;
    for (int i = 0; i < 3; ++i) {
      v.center[i] = static_cast<float>(o.pose.translation()[i]);
      for (int j = 0; j < 3; ++j) v.rotation[3 * i + j] = static_cast<float>(o.pose.linear()(i, j));
    }
    const auto& g = o.shape.geometry();
    if (const auto* box = std::get_if<hullcheck::Box>(&g)) {
      v.kind = VampObstacle::kBox;
      for (int i = 0; i < 3; ++i) v.half_extents[i] = static_cast<float>(box->half_extents[i]);
    } else if (const auto* cyl = std::get_if<hullcheck::Cylinder>(&g)) {
      v.kind = VampObstacle::kCylinder;
      v.radius = static_cast<float>(cyl->radius);
      v.half_length = static_cast<float>(cyl->half_length);
      v.as_box = box_family;
    } else if (const auto* sphere = std::get_if<hullcheck::Sphere>(&g)) {
      v.kind = VampObstacle::kSphere;
      v.radius = static_cast<float>(sphere->radius);
    } else {
      continue;  // meshes: not in the MotionBenchMaker scenes used here
    }
    out.push_back(v);
  }
  return out;
}

// hullcheck on a RealVectorStateSpace of VAMP's joints: a state's values go to `variables` of a
// full configuration (the request's start state for the rest).
class HullcheckValidity : public ob::StateValidityChecker {
 public:
  HullcheckValidity(const ob::SpaceInformationPtr& si,
                    std::shared_ptr<const hullcheck::CollisionChecker> checker,
                    std::vector<int> variables, Eigen::VectorXd fixed)
      : ob::StateValidityChecker(si),
        checker_(std::move(checker)),
        variables_(std::move(variables)),
        fixed_(std::move(fixed)) {}
  void configuration(const ob::State* state, Eigen::VectorXd& q) const {
    q = fixed_;
    const double* v = state->as<ob::RealVectorStateSpace::StateType>()->values;
    for (std::size_t i = 0; i < variables_.size(); ++i) q[variables_[i]] = v[i];
  }
  bool isValid(const ob::State* state) const override {
    thread_local Eigen::VectorXd q;
    configuration(state, q);
    last_valid_ = checker_->is_valid(q);
    last_ = q;
    return last_valid_;
  }
  // As hullcheck::StateValidityChecker::last_valid_is (one planning thread here).
  bool last_valid_is(const Eigen::VectorXd& q) const { return last_valid_ && last_ == q; }
  const hullcheck::CollisionChecker& checker() const { return *checker_; }

 private:
  std::shared_ptr<const hullcheck::CollisionChecker> checker_;
  std::vector<int> variables_;
  Eigen::VectorXd fixed_;
  mutable Eigen::VectorXd last_;
  mutable bool last_valid_ = false;
};

// What the certified motions cost, over the whole run (one thread).
struct MotionTally {
  long motions = 0, free = 0, located = 0, states = 0, exact_queries = 0;
  long free_states = 0, free_queries = 0;  // of the free motions
} tally;

// Certified motions: CollisionChecker::check_motion (as GuaranteedMotionValidator, whose space is
// a JointStateSpace).
class HullcheckMotions : public ob::MotionValidator {
 public:
  HullcheckMotions(const ob::SpaceInformationPtr& si, std::shared_ptr<const HullcheckValidity> v)
      : ob::MotionValidator(si), validity_(std::move(v)) {}
  bool checkMotion(const ob::State* a, const ob::State* b) const override {
    return check(a, b, nullptr);
  }
  bool checkMotion(const ob::State* a, const ob::State* b,
                   std::pair<ob::State*, double>& last) const override {
    double t = 0.0;
    if (check(a, b, &t)) return true;
    last.second = t;
    if (last.first != nullptr) si_->getStateSpace()->interpolate(a, b, t, last.first);
    return false;
  }

 private:
  bool check(const ob::State* a, const ob::State* b, double* last_free) const {
    thread_local Eigen::VectorXd q0, q1;
    validity_->configuration(a, q0);
    validity_->configuration(b, q1);
    hullcheck::MotionCheckOptions options;
    options.locate_contact = last_free != nullptr;
    options.end_first = !validity_->last_valid_is(q0);  // as GuaranteedMotionValidator
    const hullcheck::MotionCheckResult r = validity_->checker().check_motion(q0, q1, options);
    ++tally.motions;
    tally.free += r.free();
    tally.located += options.locate_contact;
    tally.states += r.states;
    tally.exact_queries += r.exact_queries;
    if (r.free()) tally.free_states += r.states, tally.free_queries += r.exact_queries;
    if (last_free != nullptr) *last_free = r.last_free;
    return r.free();
  }
  std::shared_ptr<const HullcheckValidity> validity_;
};

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"hullcheck beside VAMP on MotionBenchMaker problems"};
  std::string robot_id, mbm;
  int per_family = 5, repeats = 3;
  double time_limit = 10.0;
  app.add_option("--robot", robot_id, "panda or ur5")->required();
  app.add_option("--mbm", mbm, "the MotionBenchMaker folder (robots/, panda/, ur5/)")->required();
  app.add_option("--per-family", per_family, "problems per family");
  app.add_option("--time", time_limit, "solve time limit, s");
  app.add_option("--repeats", repeats, "attempts per problem and planner (best kept)");
  bool no_tables = false;
  app.add_flag("--no-tables", no_tables,
               "do not measure the self-collision tables (CollisionChecker::measure_self_tables)");
  std::vector<std::string> checkers{"vamp", "hullcheck certified", "hullcheck discrete 1/32",
                                    "hullcheck discrete default", "vamp own RRTC"};
  app.add_option("--checkers", checkers,
                 "the checkers to run (default: all; e.g. for a profile of one)")
      ->delimiter(',');
  CLI11_PARSE(app, argc, argv);
  const auto chosen = [&](const std::string& name) {
    return std::find(checkers.begin(), checkers.end(), name) != checkers.end();
  };
  // Re-seeding OMPL per attempt makes it log that sampling already started: silenced.
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
  using namespace hullcheck;
  const std::string urdf = robot_id == "panda" ? mbm + "/robots/panda_obj/panda.urdf"
                                               : mbm + "/robots/ur5_robotiq85/ur5.urdf";
  const std::string srdf_path = robot_id == "panda" ? mbm + "/robots/panda_obj/panda.srdf"
                                                    : mbm + "/robots/ur5_robotiq85/ur5.srdf";
  auto model = std::make_shared<const RobotModel>(RobotModel::from_urdf_file(urdf));
  const Srdf srdf = read_srdf_file(srdf_path);
  const AllowedCollisionMatrix matrix = AllowedCollisionMatrix::from_srdf(*model, srdf);
  // The self blocks' distance tables, once per model: shared by every problem's checker while
  // this one lives.
  const CollisionChecker self_checker(model, matrix);
  const auto measure_start = std::chrono::steady_clock::now();
  if (!no_tables) self_checker.measure_self_tables();
  std::printf(
      "self tables measured in %.2f s\n",
      std::chrono::duration<double>(std::chrono::steady_clock::now() - measure_start).count());
  std::map<std::string, int> taken;
  std::map<std::string, std::vector<double>> times;  // per planner, solved problems
  std::map<std::string, int> solved;
  int problems = 0, both_valid = 0;
  std::uint_fast32_t seed = 1;
  for (const cli::ProblemFiles& files : cli::find_problems({mbm + "/" + robot_id})) {
    const std::string family = files.name.substr(0, files.name.find('/'));
    if (taken[family]++ >= per_family) continue;
    ++problems;
    const PlanningScene scene = read_planning_scene(files.scene, *model);
    const MotionPlanRequest request = read_motion_plan_request(files.request, *model);
    auto checker = std::make_shared<const CollisionChecker>(model, matrix, scene);
    const auto peer = VampPeer::make(robot_id, vamp_obstacles(scene, family.rfind("box", 0) == 0));
    // VAMP's joints in our configuration.
    std::vector<int> variables;
    for (const std::string& name : peer->joint_names()) {
      variables.push_back(model->variable_index(name));
    }
    const auto pick = [&](const Eigen::VectorXd& q) {
      std::vector<double> v;
      for (int i : variables) v.push_back(q[i]);
      return v;
    };
    const std::vector<double> start = pick(request.start), goal = pick(request.goal);
    if (!peer->valid(start) || !peer->valid(goal) || !checker->is_valid(request.start) ||
        !checker->is_valid(request.goal)) {
      continue;
    }
    ++both_valid;
    ++seed;
    // The OMPL attempts: one space (VAMP's joints and limits), four checkers.
    const auto attempt = [&](const std::string& name) {
      auto space =
          std::make_shared<ob::RealVectorStateSpace>(static_cast<unsigned>(variables.size()));
      ob::RealVectorBounds bounds(static_cast<unsigned>(variables.size()));
      const std::vector<double> lo = peer->lower(), hi = peer->upper();
      // VAMP's limits (float), widened to hold the problem's start and goal.
      for (std::size_t i = 0; i < variables.size(); ++i) {
        bounds.setLow(i, std::min({lo[i], start[i], goal[i]}));
        bounds.setHigh(i, std::max({hi[i], start[i], goal[i]}));
      }
      space->setBounds(bounds);
      og::SimpleSetup ss(space);
      const ob::SpaceInformationPtr& si = ss.getSpaceInformation();
      if (name == "vamp") {
        peer->attach(si);
      } else {
        auto validity = std::make_shared<HullcheckValidity>(si, checker, variables, request.start);
        si->setStateValidityChecker(validity);
        if (name == "hullcheck certified") {
          si->setMotionValidator(std::make_shared<HullcheckMotions>(si, validity));
        } else if (name == "hullcheck discrete 1/32") {
          // VAMP's resolution: 32 states per unit of joint-space distance.
          si->setStateValidityCheckingResolution(1.0 / (32.0 * space->getMaximumExtent()));
        }  // else OMPL's discrete validator at its default resolution
      }
      ob::ScopedState<> s(space), g(space);
      for (std::size_t i = 0; i < variables.size(); ++i) s[i] = start[i], g[i] = goal[i];
      ss.setStartAndGoalStates(s, g);
      ss.setPlanner(std::make_shared<og::RRTConnect>(si));
      ss.setup();
      double best = -1.0;
      for (int r = 0; r < repeats; ++r) {
        ompl::RNG::setSeed(seed);
        ss.clear();
        const auto t0 = std::chrono::steady_clock::now();
        // A plain timed condition: solve(seconds) with seconds >= 1 runs a thread that polls
        // the clock every millisecond and is joined at the end (about 1 ms per solve).
        const bool ok = ss.solve(ob::timedPlannerTerminationCondition(time_limit)) ==
                        ob::PlannerStatus::EXACT_SOLUTION;
        const double t =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (ok && (best < 0.0 || t < best)) best = t;
      }
      return best;
    };
    for (const std::string name :
         {"vamp", "hullcheck certified", "hullcheck discrete 1/32", "hullcheck discrete default"}) {
      if (!chosen(name)) continue;
      const double t = attempt(name);
      if (t >= 0.0) {
        ++solved[name];
        times[name].push_back(t);
      }
    }
    if (!chosen("vamp own RRTC")) continue;
    double best = -1.0;
    for (int r = 0; r < repeats; ++r) {
      const double t = peer->plan(start, goal);
      if (t >= 0.0 && (best < 0.0 || t < best)) best = t;
    }
    if (best >= 0.0) {
      ++solved["vamp own RRTC"];
      times["vamp own RRTC"].push_back(best);
    }
  }
  std::printf("%s: %d problems, %d valid for both checkers\n", robot_id.c_str(), problems,
              both_valid);
  for (const auto& [name, t] : times) {
    std::printf("| %s | %d | %.3f ms |\n", name.c_str(), solved[name], 1e3 * median(t));
  }
  if (tally.motions > 0) {
    std::printf(
        "certified motions: %ld checked (%ld free, %ld locating the contact); per motion %.1f "
        "states, %.1f exact queries (free ones: %.1f, %.1f)\n",
        tally.motions, tally.free, tally.located,
        static_cast<double>(tally.states) / static_cast<double>(tally.motions),
        static_cast<double>(tally.exact_queries) / static_cast<double>(tally.motions),
        static_cast<double>(tally.free_states) / static_cast<double>(std::max(1L, tally.free)),
        static_cast<double>(tally.free_queries) / static_cast<double>(std::max(1L, tally.free)));
  }
  return 0;
}
