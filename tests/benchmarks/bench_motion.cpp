// Motion validation on MotionBenchMaker problems, three ways on the same motions in the same
// run (Release build):
//  - discrete: OMPL's DiscreteMotionValidator at the space's default resolution (states only);
//  - advancement: conservative advancement with CollisionChecker::safe_advance (certified);
//  - bisection: CollisionChecker::check_motion through GuaranteedMotionValidator (certified).
// Motions are what RRTConnect asks: from a valid state towards a uniform random one, cut to the
// planner's default range (0.2 x the space's extent). Reports per motion: mean and median time,
// states evaluated, accepted counts, and motions the discrete check accepts that the certified
// ones prove colliding (or the reverse, which would be a defect: exit code 3).
//
//   bench_motion --robot URDF --srdf SRDF --problems DIR... [--per-family N] [--motions M]
#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <hullcheck/ompl.hpp>
#include <hullcheck/robot.hpp>
#include <hullcheck/scene/motion_plan_request.hpp>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "problem_list.hpp"

namespace {

namespace ob = ::ompl::base;
using Clock = std::chrono::steady_clock;

struct Series {
  std::vector<double> micros;
  long states = 0;
  int accepted = 0;
  void add(double us, long n, bool ok) {
    micros.push_back(us);
    states += n;
    accepted += ok ? 1 : 0;
  }
  double median() const {
    std::vector<double> v = micros;
    if (v.empty()) return 0.0;
    std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
    return v[v.size() / 2];
  }
  double mean() const {
    double s = 0.0;
    for (double x : micros) s += x;
    return micros.empty() ? 0.0 : s / static_cast<double>(micros.size());
  }
};

// Conservative advancement along q0 -> q1 (GuaranteedMotionValidator's method before
// check_motion): true when certified free; `steps` receives the safe_advance calls.
bool advance(const hullcheck::CollisionChecker& checker, const Eigen::VectorXd& q0,
             const Eigen::VectorXd& q1, long* steps) {
  const Eigen::VectorXd dq = q1 - q0;
  double t = 0.0;
  for (*steps = 0; *steps < 100000;) {
    ++*steps;
    const double s = checker.safe_advance(q0 + t * dq, dq, 1e-6);
    if (s < 0.0) return false;
    if (t + s >= 1.0) return true;
    t += s;
  }
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Motion validation: discrete, conservative advancement, interval bisection"};
  std::string urdf, srdf_path;
  std::vector<std::string> sources;
  int per_family = 5, motions = 200;
  app.add_option("--robot", urdf, "URDF")->required();
  app.add_option("--srdf", srdf_path, "SRDF")->required();
  app.add_option("--problems", sources, "problem folders or lists")->required();
  app.add_option("--per-family", per_family, "problems per family folder");
  app.add_option("--motions", motions, "motions per problem");
  bool tables = false, skip_advancement = false;
  app.add_flag("--tables", tables,
               "measure the self-collision tables first (CollisionChecker::measure_self_tables, "
               "once per model, not timed)");
  app.add_flag("--skip-advancement", skip_advancement, "do not time conservative advancement");
  CLI11_PARSE(app, argc, argv);
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  ompl::RNG::setSeed(7);
  using namespace hullcheck;
  auto model = std::make_shared<const RobotModel>(RobotModel::from_urdf_file(urdf));
  const Srdf srdf = read_srdf_file(srdf_path);
  const AllowedCollisionMatrix matrix = AllowedCollisionMatrix::from_srdf(*model, srdf);
  std::map<std::string, int> taken;
  Series discrete, advancement, bisection;
  int discrete_only = 0, certified_only = 0, methods_disagree = 0;
  for (const cli::ProblemFiles& files : cli::find_problems(sources)) {
    const std::string family = files.name.substr(0, files.name.find('/'));
    if (taken[family]++ >= per_family) continue;
    const PlanningScene scene = read_planning_scene(files.scene, *model);
    const MotionPlanRequest request = read_motion_plan_request(files.request, *model);
    const std::vector<int> group = group_variables(*model, srdf, request.group);
    auto checker = std::make_shared<const CollisionChecker>(model, matrix, scene);
    if (tables) checker->measure_self_tables();  // measured once: the model's checkers share them
    PlanningSetup certified = make_planning_setup(checker, group, request.start);
    PlanningSetup sampled =
        make_planning_setup(checker, group, request.start, MotionChecking::kDiscrete);
    const ob::SpaceInformationPtr& si = certified.setup->getSpaceInformation();
    const ob::SpaceInformationPtr& dsi = sampled.setup->getSpaceInformation();
    si->setup();
    dsi->setup();
    const auto* validator =
        dynamic_cast<const GuaranteedMotionValidator*>(si->getMotionValidator().get());
    const double range = 0.2 * si->getMaximumExtent();  // RRTConnect's default
    ob::StateSamplerPtr sampler = si->allocStateSampler();
    ob::ScopedState<> a(si->getStateSpace()), b(si->getStateSpace());
    for (int k = 0; k < motions; ++k) {
      do {
        sampler->sampleUniform(a.get());
      } while (!si->isValid(a.get()));
      sampler->sampleUniform(b.get());
      const double d = si->distance(a.get(), b.get());
      if (d > range) si->getStateSpace()->interpolate(a.get(), b.get(), range / d, b.get());
      // Discrete.
      auto t0 = Clock::now();
      const bool ok_discrete = dsi->checkMotion(a.get(), b.get());
      auto t1 = Clock::now();
      discrete.add(std::chrono::duration<double, std::micro>(t1 - t0).count(),
                   dsi->getStateSpace()->validSegmentCount(a.get(), b.get()), ok_discrete);
      // Bisection (the validator's check_motion).
      const unsigned long states_before = validator->step_count();
      t0 = Clock::now();
      const bool ok_bisection = si->checkMotion(a.get(), b.get());
      t1 = Clock::now();
      bisection.add(std::chrono::duration<double, std::micro>(t1 - t0).count(),
                    static_cast<long>(validator->step_count() - states_before), ok_bisection);
      // Advancement (on the same configurations as the validator's).
      const Eigen::VectorXd q0 = certified.configuration(a.get());
      Eigen::VectorXd q1 = certified.configuration(b.get());
      for (int v : group) {
        if (model->joint(model->variable_joint(v)).type == JointType::kContinuous) {
          q1[v] = q0[v] + std::remainder(q1[v] - q0[v], 2.0 * M_PI);
        }
      }
      long steps = 0;
      t0 = Clock::now();
      const bool ok_advance = skip_advancement ? ok_bisection : advance(*checker, q0, q1, &steps);
      t1 = Clock::now();
      if (!skip_advancement) {
        advancement.add(std::chrono::duration<double, std::micro>(t1 - t0).count(), steps,
                        ok_advance);
      }
      if (ok_discrete && !ok_bisection) ++discrete_only;
      if (!ok_discrete && ok_bisection) ++certified_only;
      if (ok_advance != ok_bisection) ++methods_disagree;
    }
  }
  const auto row = [&](const char* name, const Series& s) {
    std::printf("| %s | %zu | %d | %.2f | %.2f | %.1f |\n", name, s.micros.size(), s.accepted,
                s.mean(), s.median(), static_cast<double>(s.states) / s.micros.size());
  };
  std::printf("| method | motions | accepted | mean (us) | median (us) | states per motion |\n");
  std::printf("|---|---|---|---|---|---|\n");
  row("discrete (OMPL default resolution)", discrete);
  if (!skip_advancement) row("conservative advancement", advancement);
  row("interval bisection (check_motion)", bisection);
  if (!skip_advancement) {
    std::printf("\nmean time / discrete: advancement %.2f; advancement and bisection differ: %d",
                advancement.mean() / discrete.mean(), methods_disagree);
  }
  std::printf(
      "\nmean time / discrete: bisection %.2f. Discrete accepts, bisection rejects: %d motions; "
      "bisection accepts, discrete rejects: %d (a defect if > 0)\n",
      bisection.mean() / discrete.mean(), discrete_only, certified_only);
  return certified_only > 0 ? 3 : 0;
}
