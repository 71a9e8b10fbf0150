// Planning benchmark: one OMPL planner (RRTConnect by default) on MotionBenchMaker problems,
// once with hullcheck's StateValidityChecker and once with an FCL-based one
// (fcl_broadphase_checker.hpp: the same hull shapes in FCL's dynamic AABB trees), in the same
// run, problem by problem (Release build; scripts/planning_benchmark.sh runs it on every problem).
// Solve time is the wall time of SimpleSetup::solve after SimpleSetup::setup, with the time limit
// checked in the planning thread (no watcher thread).
//
//   bench_planning run --robot URDF --srdf SRDF --problems DIR... --out RESULTS.csv
//                      [--planner RRTConnect] [--time 10] [--shard i/n] [--seed 1]
//                      [--per-family N] [--guaranteed] [--compare-hull]
//   bench_planning summarize RESULTS.csv... [--table FILE] [--title TEXT]
//
// Both checkers plan with OMPL's DiscreteMotionValidator at the same resolution (the FCL checker
// has no guaranteed mode), the same planner settings and a solve time limit; the order of the
// two alternates from problem to problem. Solve time is the wall time of SimpleSetup::solve
// (setup included; building the checkers is not). Problems whose start or goal is in collision
// (by hullcheck; FCL's verdict is recorded beside it) are listed, not planned. Every solution
// path is re-checked with hullcheck's guaranteed motion validator (certified: check_motion)
// and the result recorded: discrete checking can accept motions that cut into an obstacle.
// With --guaranteed, a third attempt plans with that validator itself (same seed). With
// --compare-hull, another plans with one convex hull per mesh instead of the convex pieces.
//
// One CSV line per problem and checker:
//   robot,problem,checker,start_goal_valid,fcl_agrees,solved,time_s,checks,length,path_valid
#include <ompl/base/StateValidityChecker.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <hullcheck/ompl.hpp>
#include <hullcheck/robot.hpp>
#include <hullcheck/scene/motion_plan_request.hpp>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "fcl_broadphase_checker.hpp"
#include "planner_factory.hpp"
#include "problem_list.hpp"

namespace {

namespace ob = ::ompl::base;
using hullcheck::bench::FclBroadphaseChecker;

// ---------------------------------------------------------------------------------------------
// The FCL checker behind OMPL's interface (one planning thread: FclBroadphaseChecker keeps
// per-query state).

class FclValidityChecker : public ob::StateValidityChecker {
 public:
  FclValidityChecker(const ob::SpaceInformationPtr& si,
                     std::shared_ptr<const hullcheck::JointStateSpace> joints,
                     FclBroadphaseChecker* fcl)
      : ob::StateValidityChecker(si),
        joints_(std::move(joints)),
        fcl_(fcl),
        q_(joints_->fixed_configuration()) {}

  bool isValid(const ob::State* state) const override {
    ++checks_;
    joints_->to_configuration(state, q_);
    return fcl_->is_valid(q_);
  }
  unsigned long check_count() const { return checks_; }

 private:
  std::shared_ptr<const hullcheck::JointStateSpace> joints_;
  FclBroadphaseChecker* fcl_;
  mutable Eigen::VectorXd q_;
  mutable unsigned long checks_ = 0;
};

// ---------------------------------------------------------------------------------------------
// run

struct RunOptions {
  std::string urdf;
  std::string srdf;
  std::vector<std::string> problems;
  std::string planner = "RRTConnect";
  double time = 10.0;
  std::string shard = "0/1";
  unsigned seed = 1;
  int per_family = 0;         // 0: all
  bool guaranteed = false;    // also plan with hullcheck's guaranteed motion validator
  bool compare_hull = false;  // also plan with one convex hull per mesh (MeshGeometry::kHull)
  std::string out;
};

struct Attempt {
  bool solved = false;
  double time = 0.0;
  unsigned long checks = 0;
  double length = NAN;
  int path_valid = -1;  // -1: no path
};

// Every motion of `path` (states of `from`'s space) under hullcheck's guaranteed validator.
bool path_is_valid(const ompl::geometric::PathGeometric& path, const hullcheck::PlanningSetup& from,
                   const hullcheck::PlanningSetup& verify) {
  const auto si = verify.setup->getSpaceInformation();
  ob::ScopedState<> a(si), b(si);
  verify.joints->from_configuration(from.configuration(path.getState(0)), a.get());
  if (!si->isValid(a.get())) return false;
  for (std::size_t k = 1; k < path.getStateCount(); ++k) {
    verify.joints->from_configuration(from.configuration(path.getState(k)), b.get());
    if (!si->checkMotion(a.get(), b.get())) return false;
    a = b;
  }
  return true;
}

Attempt plan(const RunOptions& o, const std::shared_ptr<const hullcheck::CollisionChecker>& hc,
             FclBroadphaseChecker* fcl, const std::vector<int>& variables,
             const hullcheck::MotionPlanRequest& request, const hullcheck::PlanningSetup& verify,
             std::uint_fast32_t seed, hullcheck::MotionChecking motions) {
  // The same random sequence for both checkers: OMPL's seed generator re-seeded before anything
  // of this attempt draws a seed (OMPL logs that sampling already started; silenced). With the
  // same verdicts, both searches then visit the same states and make the same checks.
  ::ompl::msg::setLogLevel(::ompl::msg::LOG_NONE);
  ::ompl::RNG::setSeed(seed);
  ::ompl::msg::setLogLevel(::ompl::msg::LOG_ERROR);
  hullcheck::PlanningSetup planning =
      hullcheck::make_planning_setup(hc, variables, request.start, motions);
  auto& ss = *planning.setup;
  const auto si = ss.getSpaceInformation();
  std::shared_ptr<FclValidityChecker> fcl_validity;
  if (fcl != nullptr) {
    fcl_validity = std::make_shared<FclValidityChecker>(si, planning.joints, fcl);
    ss.setStateValidityChecker(fcl_validity);
  }
  ss.setPlanner(hullcheck::cli::make_planner(o.planner, si));
  ss.setStartAndGoalStates(planning.state(request.start), planning.state(request.goal));
  ss.setup();  // space, planner and motion validator set-up: the same for both checkers
  const auto t0 = std::chrono::steady_clock::now();
  // The time limit checked in the planning thread: SimpleSetup::solve(double) starts a watcher
  // thread for limits >= 1 s, whose start and join alone cost about 1 ms per solve.
  const ob::PlannerStatus status = ss.solve(ob::timedPlannerTerminationCondition(o.time));
  Attempt a;
  a.time = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  a.checks = fcl_validity ? fcl_validity->check_count() : planning.validity->check_count();
  a.solved = status == ob::PlannerStatus::EXACT_SOLUTION;
  if (a.solved) {
    a.length = ss.getSolutionPath().length();
    a.path_valid = path_is_valid(ss.getSolutionPath(), planning, verify) ? 1 : 0;
  }
  return a;
}

void run(const RunOptions& o) {
  ::ompl::msg::setLogLevel(::ompl::msg::LOG_ERROR);
  int shard_index = 0, shard_count = 1;
  hullcheck::cli::parse_shard(o.shard, &shard_index, &shard_count);
  std::vector<hullcheck::cli::ProblemFiles> problems = hullcheck::cli::find_problems(o.problems);
  if (o.per_family > 0) {  // the first problems of each family (names "family/NNNN", sorted)
    std::map<std::string, int> taken;
    problems.erase(std::remove_if(problems.begin(), problems.end(),
                                  [&](const hullcheck::cli::ProblemFiles& p) {
                                    const std::string family = p.name.substr(0, p.name.find('/'));
                                    return ++taken[family] > o.per_family;
                                  }),
                   problems.end());
  }
  problems = hullcheck::cli::shard(problems, shard_index, shard_count);
  auto model =
      std::make_shared<const hullcheck::RobotModel>(hullcheck::RobotModel::from_urdf_file(o.urdf));
  const hullcheck::Srdf srdf = hullcheck::read_srdf_file(o.srdf);
  const hullcheck::AllowedCollisionMatrix matrix =
      hullcheck::AllowedCollisionMatrix::from_srdf(*model, srdf);
  // The self blocks' distance tables, once for the model (shared by every problem's checker
  // while this one lives); not included in any solve time.
  const hullcheck::CollisionChecker self_checker(model, matrix);
  const auto tables_start = std::chrono::steady_clock::now();
  self_checker.measure_self_tables();
  std::fprintf(
      stderr, "self-collision tables measured in %.2f s\n",
      std::chrono::duration<double>(std::chrono::steady_clock::now() - tables_start).count());
  // --compare-hull: the same robot with one hull per mesh (same links, joints and variables).
  hullcheck::RobotLoadOptions hull_options;
  hull_options.mesh_geometry = hullcheck::MeshGeometry::kHull;
  const auto hull_model = o.compare_hull
                              ? std::make_shared<const hullcheck::RobotModel>(
                                    hullcheck::RobotModel::from_urdf_file(o.urdf, hull_options))
                              : nullptr;
  const hullcheck::AllowedCollisionMatrix hull_matrix =
      o.compare_hull ? hullcheck::AllowedCollisionMatrix::from_srdf(*hull_model, srdf)
                     : hullcheck::AllowedCollisionMatrix();

  std::ofstream out(o.out);
  out << "robot,problem,checker,start_goal_valid,fcl_agrees,solved,time_s,checks,length,"
         "path_valid\n";
  if (!out) throw std::runtime_error("--out '" + o.out + "': cannot write");
  const auto t0 = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < problems.size(); ++i) {
    const hullcheck::cli::ProblemFiles& problem = problems[i];
    auto hc = std::make_shared<const hullcheck::CollisionChecker>(
        model, matrix, hullcheck::read_planning_scene(problem.scene, *model));
    FclBroadphaseChecker fcl(*hc);
    const hullcheck::MotionPlanRequest request =
        hullcheck::read_motion_plan_request(problem.request, *model);
    const std::vector<int> variables =
        request.group.empty() ? request.goal_variables
                              : hullcheck::group_variables(*model, srdf, request.group);
    const bool valid = hc->is_valid(request.start) && hc->is_valid(request.goal);
    const bool fcl_valid = fcl.is_valid(request.start) && fcl.is_valid(request.goal);
    const char* names[4] = {"hullcheck", "fcl", "hullcheck_guaranteed", "hullcheck_hull"};
    Attempt attempts[4];
    std::vector<int> checkers = {0, 1};
    if (o.guaranteed) checkers.push_back(2);
    if (o.compare_hull) checkers.push_back(3);
    bool hull_valid = false;
    if (o.compare_hull) {
      auto hull = std::make_shared<const hullcheck::CollisionChecker>(
          hull_model, hull_matrix, hullcheck::read_planning_scene(problem.scene, *hull_model));
      hull_valid = hull->is_valid(request.start) && hull->is_valid(request.goal);
      if (hull_valid) {
        const hullcheck::PlanningSetup verify_hull = hullcheck::make_planning_setup(
            hull, variables, request.start, hullcheck::MotionChecking::kGuaranteed);
        attempts[3] = plan(o, hull, nullptr, variables, request, verify_hull,
                           static_cast<std::uint_fast32_t>(o.seed + shard_index + i * shard_count),
                           hullcheck::MotionChecking::kDiscrete);
      }
    }
    if (valid) {
      const hullcheck::PlanningSetup verify = hullcheck::make_planning_setup(
          hc, variables, request.start, hullcheck::MotionChecking::kGuaranteed);
      const auto seed =
          static_cast<std::uint_fast32_t>(o.seed + shard_index + i * shard_count);  // list position
      for (int k = 0; k < 2; ++k) {
        const int which = (static_cast<int>(i) + k) % 2;  // alternate who goes first
        attempts[which] = plan(o, hc, which == 1 ? &fcl : nullptr, variables, request, verify, seed,
                               hullcheck::MotionChecking::kDiscrete);
      }
      if (o.guaranteed) {
        attempts[2] = plan(o, hc, nullptr, variables, request, verify, seed,
                           hullcheck::MotionChecking::kGuaranteed);
      }
    }
    for (int c : checkers) {
      const Attempt& a = attempts[c];
      out << model->name() << ',' << problem.name << ',' << names[c] << ','
          << ((c == 3 ? hull_valid : valid) ? 1 : 0) << ',' << (valid == fcl_valid ? 1 : 0) << ','
          << (a.solved ? 1 : 0) << ',' << std::setprecision(6) << a.time << ',' << a.checks << ','
          << a.length << ',' << a.path_valid << '\n';
    }
    out.flush();
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::fprintf(
        stderr, "\r[%zu/%zu problems] %.0f s elapsed, ETA %.0f s   ", i + 1, problems.size(),
        elapsed,
        elapsed / static_cast<double>(i + 1) * static_cast<double>(problems.size() - i - 1));
  }
  std::fprintf(stderr, "\n");
  if (!out) throw std::runtime_error("--out '" + o.out + "': write failed");
}

// ---------------------------------------------------------------------------------------------
// summarize

struct Row {
  std::string robot, problem, checker;
  bool valid = false, fcl_agrees = true, solved = false;
  double time = 0.0;
  double checks = 0.0;
  int path_valid = -1;
};

std::vector<Row> read_rows(const std::vector<std::string>& files) {
  std::vector<Row> rows;
  for (const std::string& file : files) {
    std::ifstream in(file);
    if (!in) throw std::runtime_error("cannot read '" + file + "'");
    std::string line;
    std::getline(in, line);  // header
    int line_number = 1;
    while (std::getline(in, line)) {
      ++line_number;
      std::vector<std::string> f;
      std::stringstream fields(line);
      for (std::string item; std::getline(fields, item, ',');) f.push_back(item);
      if (f.size() != 10) {
        throw std::runtime_error(file + ":" + std::to_string(line_number) +
                                 ": expected 10 fields, got " + std::to_string(f.size()));
      }
      Row r;
      r.robot = f[0];
      r.problem = f[1];
      r.checker = f[2];
      r.valid = f[3] == "1";
      r.fcl_agrees = f[4] == "1";
      r.solved = f[5] == "1";
      r.time = std::stod(f[6]);
      r.checks = std::stod(f[7]);
      r.path_valid = std::stoi(f[9]);
      rows.push_back(r);
    }
  }
  return rows;
}

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string ms(double seconds) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(seconds < 0.1 ? 2 : 1) << 1e3 * seconds;
  return s.str();
}

std::string ratio(double a, double b) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(1) << a / b;
  return s.str();
}

// Figures of one checker on a group of problems.
struct Figures {
  int valid = 0, solved = 0, paths_invalid = 0;
  double median_time = NAN;       // over valid problems, unsolved counted at the time taken
  double median_time_both = NAN;  // over problems both checkers solved
  double total_time = 0.0;
  double median_check_us = NAN;  // median over problems of time / checks
};

struct Group {
  std::string name;
  int problems = 0, valid = 0, disagreements = 0;
  Figures hc, fcl;
};

// A checker's figures over the problems of `rows` that have a valid start and goal (all but
// median_time_both, which needs both checkers).
Figures checker_figures(const std::vector<const Row*>& rows) {
  Figures f;
  std::vector<double> times, per_check;
  for (const Row* row : rows) {
    if (!row->valid) continue;
    ++f.valid;
    f.solved += row->solved ? 1 : 0;
    f.paths_invalid += row->path_valid == 0 ? 1 : 0;
    f.total_time += row->time;
    times.push_back(row->time);
    if (row->checks > 0) per_check.push_back(1e6 * row->time / row->checks);
  }
  f.median_time = median(times);
  f.median_check_us = median(per_check);
  return f;
}

Group summarize_group(const std::string& name, const std::vector<const Row*>& hc_rows,
                      const std::vector<const Row*>& fcl_rows) {
  Group g;
  g.name = name;
  g.problems = static_cast<int>(hc_rows.size());
  g.hc = checker_figures(hc_rows);
  g.fcl = checker_figures(fcl_rows);
  g.valid = g.hc.valid;
  std::vector<double> both_hc, both_fcl;
  for (std::size_t i = 0; i < hc_rows.size(); ++i) {
    const Row& h = *hc_rows[i];
    const Row& f = *fcl_rows[i];
    g.disagreements += h.fcl_agrees ? 0 : 1;
    if (h.valid && h.solved && f.solved) {
      both_hc.push_back(h.time);
      both_fcl.push_back(f.time);
    }
  }
  g.hc.median_time_both = median(both_hc);
  g.fcl.median_time_both = median(both_fcl);
  return g;
}

void summarize(const std::vector<std::string>& files, const std::string& table_file,
               const std::string& title) {
  const std::vector<Row> rows = read_rows(files);
  // problem key -> (hullcheck row, fcl row); guaranteed-mode rows apart
  std::map<std::string, std::pair<const Row*, const Row*>> by_problem;
  std::map<std::string, std::vector<const Row*>> guaranteed;  // per robot
  std::map<std::string, std::vector<const Row*>> hull_rows;   // per robot (--compare-hull)
  for (const Row& r : rows) {
    if (r.checker == "hullcheck_guaranteed") {
      guaranteed[r.robot].push_back(&r);
      continue;
    }
    if (r.checker == "hullcheck_hull") {
      hull_rows[r.robot].push_back(&r);
      continue;
    }
    auto& slot = by_problem[r.robot + "/" + r.problem];
    (r.checker == "fcl" ? slot.second : slot.first) = &r;
  }
  std::map<std::string, std::pair<std::vector<const Row*>, std::vector<const Row*>>> robots,
      families;
  std::vector<const Row*> all_hc, all_fcl;
  for (const auto& [key, pair] : by_problem) {
    if (pair.first == nullptr || pair.second == nullptr) {
      throw std::runtime_error("problem " + key + " lacks a hullcheck or fcl line");
    }
    const Row& h = *pair.first;
    const std::string family = h.robot + " " + h.problem.substr(0, h.problem.find('/'));
    for (auto* bucket : {&robots[h.robot], &families[family]}) {
      bucket->first.push_back(pair.first);
      bucket->second.push_back(pair.second);
    }
    all_hc.push_back(pair.first);
    all_fcl.push_back(pair.second);
  }
  std::vector<Group> groups;
  for (const auto& [name, pair] : robots) {
    groups.push_back(summarize_group(name, pair.first, pair.second));
  }
  if (robots.size() > 1) groups.push_back(summarize_group("all", all_hc, all_fcl));
  std::vector<Group> family_groups;
  for (const auto& [name, pair] : families) {
    family_groups.push_back(summarize_group(name, pair.first, pair.second));
  }

  std::ostringstream t;
  if (!title.empty()) t << title << "\n\n";
  t << "| robot | problems | valid start/goal | solved hullcheck | solved FCL | median solve "
       "hullcheck (ms) | median solve FCL (ms) | FCL / hullcheck | median, both solved: "
       "hullcheck / FCL (ms) | per check hullcheck / FCL (us) | paths failing guaranteed "
       "re-check hullcheck / FCL |\n"
       "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const Group& g : groups) {
    t << "| " << g.name << " | " << g.problems << " | " << g.valid << " | " << g.hc.solved << " ("
      << ratio(100.0 * g.hc.solved, g.valid) << "%) | " << g.fcl.solved << " ("
      << ratio(100.0 * g.fcl.solved, g.valid) << "%) | " << ms(g.hc.median_time) << " | "
      << ms(g.fcl.median_time) << " | **" << ratio(g.fcl.median_time, g.hc.median_time) << "** | "
      << ms(g.hc.median_time_both) << " / " << ms(g.fcl.median_time_both) << " | "
      << std::setprecision(3) << g.hc.median_check_us << " / " << g.fcl.median_check_us << " | "
      << g.hc.paths_invalid << " / " << g.fcl.paths_invalid << " |\n";
  }
  t << "\nPer scene family:\n\n"
       "| family | valid start/goal | solved hullcheck / FCL | median solve hullcheck / FCL (ms) "
       "| FCL / hullcheck |\n|---|---|---|---|---|\n";
  for (const Group& g : family_groups) {
    t << "| " << g.name << " | " << g.valid << " / " << g.problems << " | " << g.hc.solved << " / "
      << g.fcl.solved << " | " << ms(g.hc.median_time) << " / " << ms(g.fcl.median_time) << " | "
      << ratio(g.fcl.median_time, g.hc.median_time) << " |\n";
  }
  if (!guaranteed.empty()) {
    t << "\nhullcheck with its guaranteed motion validator (certified motions, "
         "CollisionChecker::check_motion; same seeds):"
         "\n\n| robot | valid start/goal | solved | median solve (ms) | paths failing the "
         "guaranteed re-check |\n|---|---|---|---|---|\n";
    for (const auto& [robot, list] : guaranteed) {
      const Figures f = checker_figures(list);
      t << "| " << robot << " | " << f.valid << " | " << f.solved << " ("
        << ratio(100.0 * f.solved, f.valid) << "%) | " << ms(f.median_time) << " | "
        << f.paths_invalid << " |\n";
    }
  }
  if (!hull_rows.empty()) {
    t << "\nConvex pieces (the default) against one convex hull per mesh (OMPL's discrete motion "
         "validator for both; same seeds):\n\n| robot | problems | valid start/goal: pieces / "
         "hull | solved: pieces / hull | median solve (ms): pieces / hull | per check (us): "
         "pieces / hull |\n|---|---|---|---|---|---|\n";
    for (const auto& [robot, list] : hull_rows) {
      const Figures h = checker_figures(list);
      const Group& g = *std::find_if(groups.begin(), groups.end(),
                                     [&](const Group& x) { return x.name == robot; });
      t << "| " << robot << " | " << list.size() << " | " << g.valid << " / " << h.valid << " | "
        << g.hc.solved << " / " << h.solved << " | " << ms(g.hc.median_time) << " / "
        << ms(h.median_time) << " | " << std::setprecision(3) << g.hc.median_check_us << " / "
        << h.median_check_us << " |\n";
    }
  }
  int disagreements = 0;
  double planning_time = 0.0;
  for (const Group& g : family_groups) {
    disagreements += g.disagreements;
    planning_time += g.hc.total_time + g.fcl.total_time;
  }
  t << "\nStart/goal validity: FCL's verdict differs from hullcheck's on " << disagreements
    << " problem(s). Time spent in solve() over all attempts: " << std::fixed
    << std::setprecision(0) << planning_time << " s.\n";
  std::cout << t.str();
  if (!table_file.empty()) {
    std::ofstream file(table_file);
    file << t.str();
    if (!file) throw std::runtime_error("cannot write '" + table_file + "'");
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"hullcheck planning benchmark: hullcheck's validity checker beside FCL's"};
  app.require_subcommand(1);
  RunOptions o;
  CLI::App* run_command = app.add_subcommand("run", "Plan every problem with both checkers");
  run_command->add_option("--robot", o.urdf, "URDF")->required();
  run_command->add_option("--srdf", o.srdf, "SRDF (groups, disabled collisions)")->required();
  run_command->add_option("--problems", o.problems, "Folders or list files of problems")
      ->required();
  run_command->add_option("--planner", o.planner, "OMPL planner (default RRTConnect)");
  run_command->add_option("--time", o.time, "Solve time limit per attempt, s (default 10)");
  run_command->add_option("--shard", o.shard, "Run shard i of n, e.g. 0/2");
  run_command->add_option(
      "--seed", o.seed,
      "OMPL's seed for the first problem (the i-th of the list: seed + i; default 1)");
  run_command->add_flag("--guaranteed", o.guaranteed,
                        "Also plan with hullcheck's guaranteed motion validator (checker "
                        "'hullcheck_guaranteed')");
  run_command->add_flag("--compare-hull", o.compare_hull,
                        "Also plan with one convex hull per mesh instead of convex pieces");
  run_command->add_option("--per-family", o.per_family,
                          "Only the first N problems of each scene family (default: all)");
  run_command->add_option("--out", o.out, "Results CSV to write")->required();
  std::vector<std::string> files;
  std::string table_file, title;
  CLI::App* summarize_command =
      app.add_subcommand("summarize", "Tables (markdown) from results CSVs");
  summarize_command->add_option("files", files, "Results CSVs")->required();
  summarize_command->add_option("--table", table_file, "Markdown file to write");
  summarize_command->add_option("--title", title, "Text above the tables");
  try {
    app.parse(argc, argv);
    if (run_command->parsed()) run(o);
    if (summarize_command->parsed()) summarize(files, table_file, title);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_planning: %s\n", e.what());
    return 1;
  }
  return 0;
}
