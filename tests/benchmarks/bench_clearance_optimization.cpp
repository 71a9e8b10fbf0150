// Clearance optimization benchmark on MotionBenchMaker problems (Release build;
// scripts/optimization_benchmark.sh runs it on every Panda and UR5 problem). Per problem, with
// certified motions (GuaranteedMotionValidator) and the clearance scope of optimization
// (optimization_scope at the margin: obstacles and the self pairs the group moves and can take
// clear of the margin):
//   1. RRTConnect, then OMPL's simplifier (SimpleSetup::simplifySolution, 1 s at most);
//   2. that path through optimize_clearance;
//   3. RRT* and 4. BIT*, each with OMPL's MaximizeMinClearanceObjective (on the same scoped
//      clearance) and the time 1 and 2 took together, simplified as 1 was within that time.
// Reported per path: joint-space length; the minimum obstacle clearance over the middle 80% of
// the path (by arc length, 201 evenly spaced states between 10% and 90%: start and goal cannot
// move, and a goal in a shelf has its clearance whatever the path); the minimum over every
// checked pair on the whole path (201 states); whether every motion passes the certified
// validator.
//
//   bench_clearance_optimization run --robot URDF --srdf SRDF --problems DIR... --out CSV
//        [--time 5] [--optimize-time 0.1] [--margin 0.05] [--length-weight W] [--shard i/n]
//        [--per-family N] [--seed 1] [--no-peers]
//   bench_clearance_optimization summarize CSV... [--table FILE] [--title TEXT] [--margin 0.05]
#include <ompl/base/objectives/MaximizeMinClearanceObjective.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <hullcheck/ompl.hpp>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "planner_factory.hpp"
#include "problem_list.hpp"

namespace {

namespace ob = ::ompl::base;
namespace og = ::ompl::geometric;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

struct RunOptions {
  std::string urdf, srdf, out;
  std::vector<std::string> problems;
  double time = 5.0;
  std::string shard = "0/1";
  int per_family = 0;
  unsigned seed = 1;
  bool peers = true;
  hullcheck::ClearanceOptimizationOptions optimize;
};

// What one path measures.
struct PathStats {
  bool solved = false;
  double time = 0.0;  // s
  double length = NAN;
  double middle_obstacle_clearance = NAN;  // m, middle 80%
  double min_clearance = NAN;              // m, every checked pair, whole path
  bool certified = false;
};

// The state at fraction f of the path's arc length, written to `out`.
void state_at(const ob::SpaceInformationPtr& si, const og::PathGeometric& path,
              const std::vector<double>& cumulative, double f, ob::State* out) {
  const double target = f * cumulative.back();
  std::size_t k = 0;
  while (k + 2 < cumulative.size() && cumulative[k + 1] < target) ++k;
  const double segment = cumulative[k + 1] - cumulative[k];
  const double t = segment > 0.0 ? (target - cumulative[k]) / segment : 0.0;
  si->getStateSpace()->interpolate(path.getState(k), path.getState(k + 1),
                                   std::min(1.0, std::max(0.0, t)), out);
}

PathStats measure(const hullcheck::PlanningSetup& setup, const og::PathGeometric& path,
                  const hullcheck::PairScope& obstacles) {
  PathStats stats;
  stats.solved = true;
  const auto si = setup.setup->getSpaceInformation();
  stats.length = path.length();
  std::vector<double> cumulative{0.0};
  for (std::size_t i = 0; i + 1 < path.getStateCount(); ++i) {
    cumulative.push_back(cumulative.back() + si->distance(path.getState(i), path.getState(i + 1)));
  }
  const hullcheck::CollisionChecker& checker = setup.validity->collision_checker();
  ob::State* s = si->allocState();
  double middle = INFINITY, all = INFINITY;
  const int samples = 200;
  for (int k = 0; k <= samples && path.getStateCount() >= 2; ++k) {
    state_at(si, path, cumulative, 0.1 + 0.8 * k / samples, s);
    middle = std::min(middle, checker.clearance(setup.configuration(s), obstacles).distance);
    state_at(si, path, cumulative, static_cast<double>(k) / samples, s);
    all = std::min(all, checker.clearance(setup.configuration(s)).distance);
  }
  si->freeState(s);
  stats.middle_obstacle_clearance = middle;
  stats.min_clearance = all;
  stats.certified = true;
  for (std::size_t i = 0; i + 1 < path.getStateCount(); ++i) {
    stats.certified = stats.certified && si->checkMotion(path.getState(i), path.getState(i + 1));
  }
  return stats;
}

// Plans with `planner` and `objective` (null: OMPL's default) for `limit` seconds, then
// simplifies within what is left of `simplify_until` seconds from the start (at most 1 s).
// Returns the path's stats and leaves the path in the setup.
PathStats plan(hullcheck::PlanningSetup& setup, const std::string& planner,
               const ob::OptimizationObjectivePtr& objective, double limit, bool simplify,
               const hullcheck::PairScope& obstacles, std::uint_fast32_t seed) {
  og::SimpleSetup& ss = *setup.setup;
  ss.clear();
  // Each planner's random sequence from the problem's seed: OMPL's seed generator re-seeded
  // before the planner (and its samplers) draw seeds (OMPL's notice that sampling already
  // started is silenced).
  ::ompl::msg::setLogLevel(::ompl::msg::LOG_NONE);
  ::ompl::RNG::setSeed(seed);
  ::ompl::msg::setLogLevel(::ompl::msg::LOG_ERROR);
  ss.setPlanner(hullcheck::cli::make_planner(planner, ss.getSpaceInformation()));
  if (objective) {
    ss.setOptimizationObjective(objective);
  } else {
    ss.getProblemDefinition()->setOptimizationObjective(nullptr);
  }
  ss.setup();
  const Clock::time_point t0 = Clock::now();
  const ob::PlannerStatus status = ss.solve(limit);
  PathStats stats;
  if (status != ob::PlannerStatus::EXACT_SOLUTION || !ss.haveExactSolutionPath()) {
    stats.time = seconds_since(t0);
    return stats;
  }
  if (simplify) ss.simplifySolution(1.0);
  stats = measure(setup, ss.getSolutionPath(), obstacles);
  stats.time = ss.getLastPlanComputationTime() + (simplify ? ss.getLastSimplificationTime() : 0.0);
  return stats;
}

void write(std::ostream& out, const PathStats& s) {
  out << ',' << (s.solved ? 1 : 0) << ',' << s.time << ',' << s.length << ','
      << s.middle_obstacle_clearance << ',' << s.min_clearance << ',' << (s.certified ? 1 : 0);
}

void run(const RunOptions& o) {
  ::ompl::msg::setLogLevel(::ompl::msg::LOG_ERROR);
  int shard_index = 0, shard_count = 1;
  hullcheck::cli::parse_shard(o.shard, &shard_index, &shard_count);
  std::vector<hullcheck::cli::ProblemFiles> problems = hullcheck::cli::find_problems(o.problems);
  if (o.per_family > 0) {
    std::map<std::string, int> taken;
    problems.erase(std::remove_if(problems.begin(), problems.end(),
                                  [&](const hullcheck::cli::ProblemFiles& p) {
                                    return ++taken[p.name.substr(0, p.name.find('/'))] >
                                           o.per_family;
                                  }),
                   problems.end());
  }
  problems = hullcheck::cli::shard(problems, shard_index, shard_count);
  auto model =
      std::make_shared<const hullcheck::RobotModel>(hullcheck::RobotModel::from_urdf_file(o.urdf));
  const hullcheck::Srdf srdf = hullcheck::read_srdf_file(o.srdf);
  const hullcheck::AllowedCollisionMatrix matrix =
      hullcheck::AllowedCollisionMatrix::from_srdf(*model, srdf);
  const hullcheck::CollisionChecker self_checker(model, matrix);
  self_checker.measure_self_tables();

  std::ofstream out(o.out);
  out << "robot,problem,self_pairs,scope_self_pairs";
  for (const char* who : {"rrtc", "optimized", "rrtstar", "bitstar"}) {
    out << ',' << who << "_solved," << who << "_time," << who << "_length," << who
        << "_middle_obstacle_clearance," << who << "_min_clearance," << who << "_certified";
  }
  out << ",optimizer_time,optimizer_changed\n";
  out << std::setprecision(6);
  const Clock::time_point t0 = Clock::now();
  for (std::size_t i = 0; i < problems.size(); ++i) {
    const hullcheck::cli::ProblemFiles& problem = problems[i];
    auto checker = std::make_shared<const hullcheck::CollisionChecker>(
        model, matrix, hullcheck::read_planning_scene(problem.scene, *model));
    const hullcheck::MotionPlanRequest request =
        hullcheck::read_motion_plan_request(problem.request, *model);
    if (!checker->is_valid(request.start) || !checker->is_valid(request.goal)) continue;
    const std::vector<int> variables =
        request.group.empty() ? request.goal_variables
                              : hullcheck::group_variables(*model, srdf, request.group);
    hullcheck::PlanningSetup setup =
        hullcheck::make_planning_setup(checker, variables, request.start);
    auto scope = std::make_shared<const hullcheck::PairScope>(
        hullcheck::optimization_scope(*checker, variables, request.start, o.optimize.margin));
    setup.validity->set_clearance_scope(scope);
    const hullcheck::PairScope obstacles =
        checker->pair_scope(hullcheck::ClearanceScope::kObstacles);
    og::SimpleSetup& ss = *setup.setup;
    ss.setStartAndGoalStates(setup.state(request.start), setup.state(request.goal));
    const auto si = ss.getSpaceInformation();
    const auto seed = static_cast<std::uint_fast32_t>(o.seed + shard_index + i * shard_count);

    PathStats rrtc = plan(setup, "RRTConnect", nullptr, o.time, true, obstacles, seed);
    PathStats optimized;
    hullcheck::ClearanceOptimizationResult result;
    if (rrtc.solved) {
      og::PathGeometric path = ss.getSolutionPath();
      result = hullcheck::optimize_clearance(si, *setup.validity, path, o.optimize);
      optimized = measure(setup, path, obstacles);
      optimized.time = rrtc.time + result.seconds;
    }
    PathStats peers[2];
    if (o.peers && rrtc.solved) {
      const double budget = optimized.time;
      const char* names[2] = {"RRT*", "BIT*"};
      for (int k = 0; k < 2; ++k) {
        // The planner gets the budget; its simplification (as RRTConnect's) comes out of it too,
        // approximately: OMPL's simplifier gets what the plan left of 1 s.
        peers[k] = plan(setup, names[k], std::make_shared<ob::MaximizeMinClearanceObjective>(si),
                        budget, false, obstacles, seed);
      }
    }
    out << model->name() << ',' << problem.name << ',' << checker->checked_link_pairs().size()
        << ',' << scope->self_link_pairs().size();
    write(out, rrtc);
    write(out, optimized);
    write(out, peers[0]);
    write(out, peers[1]);
    out << ',' << result.seconds << ',' << (result.changed ? 1 : 0) << '\n';
    out.flush();
    std::fprintf(stderr, "\r[%zu/%zu problems] %.0f s elapsed   ", i + 1, problems.size(),
                 seconds_since(t0));
  }
  std::fprintf(stderr, "\n");
}

// ---------------------------------------------------------------------------------------------
// summarize

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void summarize(const std::vector<std::string>& files, const std::string& table,
               const std::string& title, double margin) {
  // robot -> rows (column name -> value)
  std::map<std::string, std::vector<std::map<std::string, double>>> rows;
  for (const std::string& file : files) {
    std::ifstream in(file);
    if (!in) throw std::runtime_error("cannot read '" + file + "'");
    std::string line;
    std::getline(in, line);
    std::vector<std::string> header;
    {
      std::stringstream h(line);
      std::string cell;
      while (std::getline(h, cell, ',')) header.push_back(cell);
    }
    while (std::getline(in, line)) {
      std::stringstream l(line);
      std::string cell, robot;
      std::map<std::string, double> row;
      for (std::size_t c = 0; std::getline(l, cell, ','); ++c) {
        if (c == 0) robot = cell;
        if (c >= 2 && c < header.size()) row[header[c]] = std::stod(cell);
      }
      rows[robot].push_back(row);
    }
  }
  std::ostringstream md;
  md << title << "\n\n";
  md << "| robot | path | solved | median length | median length / RRTConnect's | median min "
        "obstacle clearance, middle 80% (m) | median clearance / RRTConnect's | median time "
        "(ms) | certified |\n|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& [robot, list] : rows) {
    const char* names[4] = {"rrtc", "optimized", "rrtstar", "bitstar"};
    const char* labels[4] = {"RRTConnect + simplify", "+ optimize_clearance",
                             "RRT* (MaximizeMinClearance, same total time)",
                             "BIT* (MaximizeMinClearance, same total time)"};
    for (int k = 0; k < 4; ++k) {
      const std::string p = names[k];
      std::vector<double> length, clearance, time, length_ratio, clearance_ratio;
      int solved = 0, certified = 0, attempted = 0;
      for (const auto& r : list) {
        if (r.at("rrtc_solved") == 0.0 && k > 0) continue;
        ++attempted;
        if (r.at(p + "_solved") == 0.0) continue;
        ++solved;
        certified += r.at(p + "_certified") != 0.0 ? 1 : 0;
        length.push_back(r.at(p + "_length"));
        clearance.push_back(r.at(p + "_middle_obstacle_clearance"));
        time.push_back(k == 1 ? r.at("optimizer_time") : r.at(p + "_time"));
        if (r.at("rrtc_solved") != 0.0) {
          length_ratio.push_back(r.at(p + "_length") / r.at("rrtc_length"));
          const double base = r.at("rrtc_middle_obstacle_clearance");
          if (base > 0.0 && std::isfinite(base)) {
            clearance_ratio.push_back(r.at(p + "_middle_obstacle_clearance") / base);
          }
        }
      }
      char buf[512];
      std::snprintf(buf, sizeof buf,
                    "| %s | %s | %d / %d | %.3f | %.3f | %.4f | %.2f | %.1f%s | %d / %d |\n",
                    robot.c_str(), labels[k], solved, attempted, median(length),
                    median(length_ratio), median(clearance), median(clearance_ratio),
                    1e3 * median(time), k == 1 ? " (optimizer alone)" : "", certified, solved);
      md << buf;
    }
  }
  // Problem by problem against the peers, where they solved. The optimizer aims at the margin,
  // MaximizeMinClearance at as much clearance as there is: "reaches" counts the problems where
  // the optimized path is at least as clear as the peer's or as the margin.
  md << "\n| robot | peer | problems the peer solved | median clearance there, optimized / peer "
        "(m) "
        "| optimized clearance >= the peer's | optimized clearance >= min(peer's, margin) | "
        "median length there, optimized / peer | optimized path shorter |\n"
        "|---|---|---|---|---|---|---|---|\n";
  for (const auto& [robot, list] : rows) {
    for (const auto& [p, label] : {std::pair<std::string, const char*>{"rrtstar", "RRT*"},
                                   std::pair<std::string, const char*>{"bitstar", "BIT*"}}) {
      int both = 0, clearer = 0, reaches = 0, shorter = 0;
      std::vector<double> ours, theirs, our_length, their_length;
      for (const auto& r : list) {
        if (r.at(p + "_solved") == 0.0 || r.at("optimized_solved") == 0.0) continue;
        ++both;
        const double mine = r.at("optimized_middle_obstacle_clearance");
        const double peer = r.at(p + "_middle_obstacle_clearance");
        ours.push_back(mine);
        theirs.push_back(peer);
        our_length.push_back(r.at("optimized_length"));
        their_length.push_back(r.at(p + "_length"));
        clearer += mine >= peer ? 1 : 0;
        reaches += mine >= std::min(peer, margin) ? 1 : 0;
        shorter += r.at("optimized_length") < r.at(p + "_length") ? 1 : 0;
      }
      char buf[512];
      std::snprintf(buf, sizeof buf,
                    "| %s | %s | %d | %.4f / %.4f | %d | %d | %.3f / %.3f | %d |\n", robot.c_str(),
                    label, both, median(ours), median(theirs), clearer, reaches, median(our_length),
                    median(their_length), shorter);
      md << buf;
    }
  }
  std::cout << md.str();
  if (!table.empty()) {
    std::ofstream t(table);
    t << md.str();
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("Clearance optimization benchmark on MotionBenchMaker problems");
  app.require_subcommand(1);
  RunOptions o;
  CLI::App* run_cmd = app.add_subcommand("run", "Plan, optimize and compare");
  run_cmd->add_option("--robot", o.urdf)->required();
  run_cmd->add_option("--srdf", o.srdf)->required();
  run_cmd->add_option("--problems", o.problems)->required();
  run_cmd->add_option("--out", o.out)->required();
  run_cmd->add_option("--time", o.time, "RRTConnect time limit, s");
  run_cmd->add_option("--optimize-time", o.optimize.time);
  run_cmd->add_option("--margin", o.optimize.margin);
  run_cmd->add_option("--length-weight", o.optimize.length_weight);
  run_cmd->add_option("--shard", o.shard);
  run_cmd->add_option("--per-family", o.per_family);
  run_cmd->add_option("--seed", o.seed);
  bool no_peers = false;
  run_cmd->add_flag("--no-peers", no_peers, "Skip RRT* and BIT*");
  std::vector<std::string> files;
  std::string table, title = "# Clearance optimization";
  CLI::App* sum_cmd = app.add_subcommand("summarize", "Tables from run CSVs");
  sum_cmd->add_option("files", files)->required();
  sum_cmd->add_option("--table", table);
  sum_cmd->add_option("--title", title);
  double margin = hullcheck::ClearanceOptimizationOptions{}.margin;
  sum_cmd->add_option("--margin", margin, "The margin the run optimised for, m");
  CLI11_PARSE(app, argc, argv);
  o.peers = !no_peers;
  try {
    if (*run_cmd) run(o);
    if (*sum_cmd) summarize(files, table, title, margin);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
