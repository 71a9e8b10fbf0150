#include "benchmark_command.hpp"

#include <ompl/tools/benchmark/Benchmark.h>
#include <ompl/util/Console.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <mutex>
#include <sstream>
#include <thread>

#include "number_options.hpp"
#include "planner_factory.hpp"
#include "problem.hpp"
#include "problem_list.hpp"

namespace hullcheck::cli {
namespace {

namespace ot = ::ompl::tools;

struct BenchmarkSettings {
  WorldOptions world;
  std::vector<std::string> problems;
  std::string planners = "RRTConnect";
  int runs = 1;
  double time = 10.0;
  double memory = 4096.0;
  int jobs = 1;
  std::string shard = "0/1";
  std::string log;
  bool simplify = false;
  bool discrete = false;
};

// ompl::tools::Benchmark whose recorded data can be merged across problems, so that one log
// (one experiment) holds every problem's runs; OMPL's own writer then writes it.
class MergedBenchmark : public ot::Benchmark {
 public:
  using ot::Benchmark::Benchmark;
  CompleteExperiment& data() { return exp_; }
};

std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

void merge(ot::Benchmark::CompleteExperiment& into, const ot::Benchmark::CompleteExperiment& from) {
  into.totalDuration += from.totalDuration;
  for (const auto& planner : from.planners) {
    auto it = std::find_if(into.planners.begin(), into.planners.end(),
                           [&](const auto& p) { return p.name == planner.name; });
    if (it == into.planners.end()) {
      into.planners.push_back(planner);
      continue;
    }
    it->runs.insert(it->runs.end(), planner.runs.begin(), planner.runs.end());
    it->runsProgressData.insert(it->runsProgressData.end(), planner.runsProgressData.begin(),
                                planner.runsProgressData.end());
  }
}

void run(const BenchmarkSettings& s) {
  ::ompl::msg::setLogLevel(::ompl::msg::LOG_ERROR);
  int shard_index = 0, shard_count = 1;
  parse_shard(s.shard, &shard_index, &shard_count);
  if (s.runs < 1 || s.jobs < 1 || !(s.time > 0.0)) {
    throw InputError("--runs and --jobs must be >= 1 and --time > 0");
  }
  const std::vector<std::string> planner_list = split_list(s.planners);
  if (planner_list.empty()) throw InputError("--planners: no planner named");
  const std::vector<ProblemFiles> problems =
      shard(find_problems(s.problems), shard_index, shard_count);
  if (s.discrete) {
    std::fprintf(stderr,
                 "warning: --discrete: motions are checked at sampled states only; solution "
                 "paths are not certified between them\n");
  }
  const LoadedWorld base = s.world.load();  // the robot and SRDF; scenes come per problem
  {
    // Fail on a bad planner name now, not in a worker thread.
    std::vector<int> all;
    for (int i = 0; i < base.model->variable_count(); ++i) all.push_back(i);
    PlanningSetup probe =
        make_planning_setup(base.checker, all, base.model->default_configuration());
    for (const std::string& p : planner_list) make_planner(p, probe.setup->getSpaceInformation());
  }
  // The self blocks' distance tables, once for the model: every problem's checker shares them
  // while base.checker lives.
  const auto tables_start = std::chrono::steady_clock::now();
  base.checker->measure_self_tables();
  std::fprintf(
      stderr, "benchmark: self-collision tables measured in %.2f s\n",
      std::chrono::duration<double>(std::chrono::steady_clock::now() - tables_start).count());
  std::fprintf(stderr,
               "benchmark: %zu problems (shard %d/%d), planners %s, %d run(s) each, "
               "%.1f s limit, %d job(s)\n",
               problems.size(), shard_index, shard_count, s.planners.c_str(), s.runs, s.time,
               s.jobs);

  std::mutex mutex;  // guards merged, skipped and the progress line
  ot::Benchmark::CompleteExperiment merged;
  bool have_merged = false;
  std::vector<std::string> skipped;
  std::atomic<std::size_t> next{0}, done{0};
  const auto t0 = std::chrono::steady_clock::now();
  std::string failure;

  const auto worker = [&] {
    for (std::size_t i; (i = next.fetch_add(1)) < problems.size();) {
      const ProblemFiles& problem = problems[i];
      try {
        auto model = base.model;
        auto checker = std::make_shared<const CollisionChecker>(
            model, AllowedCollisionMatrix::from_srdf(*model, base.srdf),
            read_planning_scene(problem.scene, *model));
        const MotionPlanRequest request = read_motion_plan_request(problem.request, *model);
        const std::vector<int> variables = request.group.empty()
                                               ? request.goal_variables
                                               : group_variables(*model, base.srdf, request.group);
        std::string invalid;
        for (const auto& [q, what] :
             {std::make_pair(request.start, "start"), std::make_pair(request.goal, "goal")}) {
          if (!checker->is_valid(q)) {
            invalid += std::string(invalid.empty() ? "" : "; ") + what +
                       " in collision: " + describe_pair(checker->clearance(q));
          }
        }
        if (!invalid.empty()) {
          std::lock_guard<std::mutex> lock(mutex);
          skipped.push_back(problem.name + " (" + invalid + ")");
        } else {
          PlanningSetup planning = make_planning_setup(
              checker, variables, request.start,
              s.discrete ? MotionChecking::kDiscrete : MotionChecking::kGuaranteed);
          auto& ss = *planning.setup;
          const auto si = ss.getSpaceInformation();
          ss.setStartAndGoalStates(planning.state(request.start), planning.state(request.goal));
          MergedBenchmark bench(ss, "hullcheck " + model->name());
          for (const std::string& p : planner_list) bench.addPlanner(make_planner(p, si));
          const auto validity = planning.validity;
          bench.setPreRunEvent(
              [validity](const ::ompl::base::PlannerPtr&) { validity->reset_check_count(); });
          bench.setPostRunEvent(
              [&, validity, i](const ::ompl::base::PlannerPtr&, ot::Benchmark::RunProperties& run) {
                run["problem INTEGER"] = std::to_string(i);
                run["validity checks INTEGER"] = std::to_string(validity->check_count());
                if (ss.haveExactSolutionPath()) {
                  double clearance = INFINITY;
                  const auto& path = ss.getSolutionPath();
                  for (std::size_t k = 0; k < path.getStateCount(); ++k) {
                    clearance = std::min(clearance, validity->clearance(path.getState(k)));
                  }
                  run["solution clearance REAL"] = std::to_string(clearance);
                }
              });
          ot::Benchmark::Request req(s.time, s.memory, static_cast<unsigned>(s.runs), 0.05,
                                     /*displayProgress=*/false, /*saveConsoleOutput=*/false,
                                     s.simplify);
          bench.benchmark(req);
          std::lock_guard<std::mutex> lock(mutex);
          if (!have_merged) {
            merged = bench.data();
            // ompl_benchmark_statistics keeps the last word of the name line: one token.
            merged.name =
                "hullcheck_" + model->name() + "_" + std::to_string(problems.size()) + "_problems";
            have_merged = true;
          } else {
            merge(merged, bench.data());
          }
        }
      } catch (const std::exception& e) {
        std::lock_guard<std::mutex> lock(mutex);
        if (failure.empty()) failure = problem.name + ": " + e.what();
        next = problems.size();  // stop the others
      }
      const std::size_t finished = ++done;
      std::lock_guard<std::mutex> lock(mutex);
      const double elapsed =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const double eta =
          elapsed / static_cast<double>(finished) * static_cast<double>(problems.size() - finished);
      std::fprintf(stderr, "\r[%zu/%zu problems] %.0f s elapsed, ETA %.0f s   ", finished,
                   problems.size(), elapsed, eta);
    }
  };
  std::vector<std::thread> threads;
  for (int j = 0; j < s.jobs; ++j) threads.emplace_back(worker);
  for (std::thread& t : threads) t.join();
  std::fprintf(stderr, "\n");
  if (!failure.empty()) throw InputError("benchmark stopped: " + failure);
  for (const std::string& k : skipped) {
    std::fprintf(stderr, "skipped (invalid start/goal): %s\n", k.c_str());
  }
  if (!have_merged) throw InputError("benchmark: no problem with a valid start and goal");
  merged.runCount = static_cast<unsigned>(merged.planners.front().runs.size());
  merged.parameters["problems INTEGER"] = std::to_string(problems.size());
  merged.parameters["skipped_invalid INTEGER"] = std::to_string(skipped.size());
  merged.parameters["jobs INTEGER"] = std::to_string(s.jobs);
  merged.parameters["shard VARCHAR(32)"] = s.shard;
  merged.parameters["motion_checking VARCHAR(32)"] = s.discrete ? "discrete" : "guaranteed";
  // Write with OMPL's writer: a Benchmark object that holds the merged data.
  {
    std::vector<int> all;
    for (int i = 0; i < base.model->variable_count(); ++i) all.push_back(i);
    PlanningSetup holder =
        make_planning_setup(base.checker, all, base.model->default_configuration());
    MergedBenchmark writer(*holder.setup, merged.name);
    writer.data() = merged;
    std::ostringstream text;
    writer.saveResultsToStream(text);
    std::string log = text.str();
    // Debian's OMPL 1.5.2 writes an empty version ("OMPL version "); Planner Arena shows it.
    const std::string blank = "OMPL version \n";
    if (log.rfind(blank, 0) == 0)
      log.replace(0, blank.size(), "OMPL version " HULLCHECK_OMPL_VERSION "\n");
    std::ofstream out(s.log);
    out << log;
    if (!out) throw InputError("--log '" + s.log + "': cannot write");
  }
  std::size_t solved = 0, total = 0;
  for (const auto& planner : merged.planners) {
    for (const auto& r : planner.runs) {
      ++total;
      const auto it = r.find("solved BOOLEAN");
      solved += it != r.end() && it->second == "1" ? 1 : 0;
    }
  }
  std::printf(
      "benchmark: %zu runs, %zu solved, %zu problems skipped (invalid start/goal); "
      "log written to %s\n(ompl_benchmark_statistics %s -d results.db)\n",
      total, solved, skipped.size(), s.log.c_str(), s.log.c_str());
}

}  // namespace

void add_benchmark_command(CLI::App& app) {
  auto s = std::make_shared<BenchmarkSettings>();
  CLI::App* command = app.add_subcommand(
      "benchmark",
      "Run OMPL's benchmark over MotionBenchMaker problems and write OMPL's benchmark log");
  s->world.robot.add_to(*command, true);
  command
      ->add_option("--problems", s->problems,
                   "Folders searched for sceneNNNN.yaml + requestNNNN.yaml, or list files of "
                   "'SCENE REQUEST' lines")
      ->required();
  command->add_option("--planners", s->planners, "Comma-separated planners (default RRTConnect)");
  command->add_option("--runs", s->runs, "Runs per planner and problem (default 1)")
      ->check(integer_in(1, 1000000));
  command->add_option("--time", s->time, "Time limit per run, s (default 10)")
      ->check(finite_in(0.0, 1e9, true));
  command->add_option("--memory", s->memory, "Memory limit per run, MB (default 4096)")
      ->check(finite_in(0.0, 1e12, true));
  command
      ->add_option("--jobs", s->jobs,
                   "Problems run in parallel threads (timings then share the cores)")
      ->check(integer_in(1, 1024));
  command->add_option("--shard", s->shard,
                      "Run shard i of n (every n-th problem from the i-th), e.g. 0/4");
  command->add_option("--log", s->log, "OMPL benchmark log to write")->required();
  command->add_flag("--simplify", s->simplify, "Let the benchmark simplify solutions");
  command->add_flag("--discrete", s->discrete, "Discrete motion checking instead of guaranteed");
  command->footer(
      "One log holds one experiment with every problem's runs (run property 'problem' gives "
      "the problem's index); turn it into a Planner Arena database with "
      "ompl_benchmark_statistics LOG -d DB. Problems whose start or goal is in collision are "
      "skipped and listed.");
  command->callback([s] { run(*s); });
}

}  // namespace hullcheck::cli
