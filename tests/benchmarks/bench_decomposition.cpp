// Convex decomposition against one hull per mesh (Release build): pieces per robot, load time
// (decomposing, from the cache, hulls), checker construction, and the cost per validity check
// and per clearance query on MotionBenchMaker states, both representations in the same run.
//   bench_decomposition [--quick] [--problems=N] [--table=FILE]
//
// States per problem: 32 evenly spaced on the straight joint-space segment from the request's
// start to its goal ("line": what planners mostly check, mostly valid) and 32 uniform within
// the joint limits ("random": mostly colliding). Each set is timed 3 times per representation,
// alternating, and the fastest run is kept (this machine drifts). Validity verdicts of the two
// are compared state by state: a state the hulls accept must be accepted by the pieces (the
// hull contains the pieces).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <hullcheck/robot.hpp>
#include <hullcheck/scene/collision_checker.hpp>
#include <hullcheck/scene/motion_plan_request.hpp>
#include <hullcheck/scene/planning_scene.hpp>
#include <iostream>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "benchmark_flags.hpp"

namespace {

using hullcheck::AllowedCollisionMatrix;
using hullcheck::CollisionChecker;
using hullcheck::MeshGeometry;
using hullcheck::RobotLoadOptions;
using hullcheck::RobotModel;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

struct RobotCase {
  std::string id, urdf, srdf, problems;
};

// One representation's figures for one robot.
struct Figures {
  std::size_t shapes = 0;
  int max_pieces = 1;
  double worst_bound = 0.0;  // largest decomposition bound, m
  double load_s = 0.0;       // from the cache for pieces
  double checker_s = 0.0;    // mean construction time per scene
  double valid_line_s = 0.0, valid_random_s = 0.0, clearance_line_s = 0.0;
  long line_states = 0, random_states = 0, line_valid = 0, random_valid = 0;
};

RobotLoadOptions options_for(MeshGeometry geometry, const std::string& cache) {
  RobotLoadOptions o;
  o.mesh_geometry = geometry;
  o.decomposition_cache_dir = cache;
  return o;
}

// Fastest of `runs` timings of f() (seconds).
template <class F>
double fastest(int runs, F f) {
  double best = INFINITY;
  for (int r = 0; r < runs; ++r) {
    const auto t = Clock::now();
    f();
    best = std::min(best, seconds_since(t));
  }
  return best;
}

void run_robot(const RobotCase& rc, int problems_per_family, std::ostream& table) {
  const std::string cache =
      (std::filesystem::temp_directory_path() / ("hullcheck_bench_cache_" + rc.id)).string();
  std::filesystem::remove_all(cache);
  // Decomposing (empty cache), then from the cache, then hulls: best of 3 for the last two.
  auto t = Clock::now();
  auto pieces = std::make_shared<const RobotModel>(
      RobotModel::from_urdf_file(rc.urdf, options_for(MeshGeometry::kDecompose, cache)));
  const double decompose_s = seconds_since(t);
  Figures f[2];  // 0: hull, 1: pieces
  std::shared_ptr<const RobotModel> hull;
  f[1].load_s = fastest(3, [&] {
    pieces = std::make_shared<const RobotModel>(
        RobotModel::from_urdf_file(rc.urdf, options_for(MeshGeometry::kDecompose, cache)));
  });
  f[0].load_s = fastest(3, [&] {
    hull = std::make_shared<const RobotModel>(
        RobotModel::from_urdf_file(rc.urdf, options_for(MeshGeometry::kHull, cache)));
  });
  const std::shared_ptr<const RobotModel> models[2] = {hull, pieces};
  for (int m = 0; m < 2; ++m) {
    for (const hullcheck::Link& l : models[m]->links()) {
      f[m].shapes += l.shapes.size();
      for (const hullcheck::CollisionShape& s : l.shapes) {
        f[m].max_pieces = std::max(f[m].max_pieces, s.piece_count);
        f[m].worst_bound = std::max(f[m].worst_bound, s.mesh_excess);
      }
    }
  }
  const hullcheck::Srdf srdf = hullcheck::read_srdf_file(rc.srdf);
  const AllowedCollisionMatrix matrix[2] = {AllowedCollisionMatrix::from_srdf(*hull, srdf),
                                            AllowedCollisionMatrix::from_srdf(*pieces, srdf)};
  long hull_only_rejects = 0, pieces_only_rejects = 0, scenes = 0;
  std::mt19937_64 rng(11);
  for (const auto& family : std::filesystem::directory_iterator(rc.problems)) {
    if (!family.is_directory()) continue;
    for (int number = 1; number <= problems_per_family; ++number) {
      char name[32];
      std::snprintf(name, sizeof name, "%04d.yaml", number);
      const std::string scene_file = (family.path() / ("scene" + std::string(name))).string();
      const std::string request_file = (family.path() / ("request" + std::string(name))).string();
      if (!std::filesystem::exists(scene_file)) continue;
      ++scenes;
      const hullcheck::PlanningScene scene = hullcheck::read_planning_scene(scene_file, *hull);
      const hullcheck::MotionPlanRequest request =
          hullcheck::read_motion_plan_request(request_file, *hull);
      std::vector<Eigen::VectorXd> line, random;
      for (int k = 0; k < 32; ++k) {
        line.push_back(request.start + (request.goal - request.start) * (k / 31.0));
      }
      const Eigen::VectorXd lo = hull->lower_limits(), hi = hull->upper_limits();
      for (int k = 0; k < 32; ++k) {
        Eigen::VectorXd q = request.start;
        for (int v : request.goal_variables) {
          const double a = std::isfinite(lo[v]) ? lo[v] : -M_PI;
          const double b = std::isfinite(hi[v]) ? hi[v] : M_PI;
          q[v] = std::uniform_real_distribution<double>(a, b)(rng);
        }
        random.push_back(q);
      }
      std::unique_ptr<CollisionChecker> checkers[2];
      for (int m = 0; m < 2; ++m) {
        f[m].checker_s += fastest(1, [&] {
          checkers[m] = std::make_unique<CollisionChecker>(models[m], matrix[m], scene);
        });
      }
      for (const auto* states : {&line, &random}) {
        for (const Eigen::VectorXd& q : *states) {
          const bool h = checkers[0]->is_valid(q), p = checkers[1]->is_valid(q);
          hull_only_rejects += !h && p;
          pieces_only_rejects += h && !p;
          const bool is_line = states == &line;
          f[0].line_valid += is_line && h;
          f[1].line_valid += is_line && p;
          f[0].random_valid += !is_line && h;
          f[1].random_valid += !is_line && p;
        }
      }
      for (int m = 0; m < 2; ++m) {
        f[m].line_states += static_cast<long>(line.size());
        f[m].random_states += static_cast<long>(random.size());
      }
      int sink = 0;
      double sink_distance = 0.0;
      for (int m = 0; m < 2; ++m) {
        const CollisionChecker& c = *checkers[m];
        f[m].valid_line_s += fastest(3, [&] {
          for (const Eigen::VectorXd& q : line) sink += c.is_valid(q);
        });
        f[m].valid_random_s += fastest(3, [&] {
          for (const Eigen::VectorXd& q : random) sink += c.is_valid(q);
        });
        f[m].clearance_line_s += fastest(3, [&] {
          for (const Eigen::VectorXd& q : line) sink_distance += c.clearance(q).distance;
        });
      }
      if (sink < 0 || std::isnan(sink_distance)) std::cerr << "";
    }
  }
  std::filesystem::remove_all(cache);
  const auto us = [](double s, long n) { return n > 0 ? 1e6 * s / static_cast<double>(n) : 0.0; };
  char row[1024];
  for (int m = 0; m < 2; ++m) {
    std::snprintf(row, sizeof row,
                  "| %s | %s | %zu (max %d per mesh) | %.1f mm | %.0f | %.2f | %ld / %ld | %.2f | "
                  "%ld / %ld | "
                  "%.2f | %.2f |\n",
                  rc.id.c_str(), m == 0 ? "hull" : "decompose", f[m].shapes, f[m].max_pieces,
                  m == 0 ? 0.0 : 1e3 * f[m].worst_bound, 1e3 * f[m].load_s,
                  1e3 * f[m].checker_s / static_cast<double>(scenes), f[m].line_valid,
                  f[m].line_states, us(f[m].valid_line_s, f[m].line_states), f[m].random_valid,
                  f[m].random_states, us(f[m].valid_random_s, f[m].random_states),
                  us(f[m].clearance_line_s, f[m].line_states));
    table << row;
  }
  std::snprintf(row, sizeof row,
                "| %s | decompose / hull | | | %.2f | | | **%.2f** | | **%.2f** | **%.2f** |\n",
                rc.id.c_str(), f[1].load_s / f[0].load_s, f[1].valid_line_s / f[0].valid_line_s,
                f[1].valid_random_s / f[0].valid_random_s,
                f[1].clearance_line_s / f[0].clearance_line_s);
  table << row;
  std::cerr << rc.id << ": decomposing every mesh (empty cache) took " << decompose_s
            << " s; states rejected by the hulls only: " << hull_only_rejects
            << ", by the pieces only: " << pieces_only_rejects << " (must be 0)\n";
  if (pieces_only_rejects != 0) throw std::runtime_error("pieces rejected a state hulls accept");
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  int problems = 5;
  std::string table_file;
  hullcheck::bench::take_program_flags(
      argc, argv, "bench_decomposition [--quick] [--problems=N] [--table=FILE]",
      [&](const std::string& arg) {
        if (arg == "--quick") return quick = true;
        if (arg.rfind("--problems=", 0) == 0) return (problems = std::stoi(arg.substr(11))) > 0;
        if (arg.rfind("--table=", 0) == 0) return !(table_file = arg.substr(8)).empty();
        return false;
      });
  if (quick) problems = 1;
  const std::string mbm = hullcheck::bench::shared_dir() + "/benchmarks/mbm";
  const std::vector<RobotCase> cases = {{"panda", mbm + "/robots/panda_obj/panda.urdf",
                                         mbm + "/robots/panda_obj/panda.srdf", mbm + "/panda"},
                                        {"ur5", mbm + "/robots/ur5_robotiq85/ur5.urdf",
                                         mbm + "/robots/ur5_robotiq85/ur5.srdf", mbm + "/ur5"}};
  std::ostringstream table;
  table << "| robot | shapes | count | pieces within (hull: not measured) | load (ms) | checker "
           "(ms) | line: valid | "
           "is_valid line (us) | random: valid | is_valid random (us) | clearance line (us) |\n"
           "|---|---|---|---|---|---|---|---|---|---|---|\n";
  try {
    for (const RobotCase& rc : cases) {
      if (!std::filesystem::exists(rc.urdf)) {
        std::cerr << rc.id << ": " << rc.urdf << " absent, skipped\n";
        continue;
      }
      run_robot(rc, problems, table);
    }
  } catch (const std::exception& e) {
    std::cerr << "bench_decomposition: " << e.what() << "\n";
    return 1;
  }
  std::cout << table.str();
  if (!table_file.empty()) std::ofstream(table_file) << table.str();
  return 0;
}
