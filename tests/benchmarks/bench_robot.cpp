// Robot-model benchmarks (Release build): forward kinematics of hullcheck beside KDL's chain
// solver, self-collision check and minimum self-distance at random configurations, and URDF
// load time, for the project's own arm and every shared robot present.
//   build-bench/tests/benchmarks/bench_robot [google-benchmark flags]
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <hullcheck/scene.hpp>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/tree.hpp>
#include <kdl_parser/kdl_parser.hpp>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace {

struct RobotCase {
  std::string id;
  std::string urdf;
  std::string srdf;
};

std::vector<RobotCase> robot_cases() {
  const std::string own = HULLCHECK_ROBOTS_DIR "/hullcheck_arm";
  const char* env = std::getenv("HULLCHECK_SHARED_DIR");
  const std::string s = env != nullptr ? env : HULLCHECK_SHARED_DIR;
  std::vector<RobotCase> all = {
      {"hullcheck_arm", own + "/urdf/hullcheck_arm.urdf", own + "/srdf/hullcheck_arm.srdf"},
      {"panda", s + "/robots/panda/moveit_resources_panda_description/urdf/panda.urdf",
       s + "/robots/panda/srdf/panda.srdf"},
      {"ur5e", s + "/robots/ur5e/ur_description/urdf/ur5e.urdf", s + "/robots/ur5e/srdf/ur5e.srdf"},
      {"baxter", s + "/robots/baxter/example-robot-data/robots/baxter_description/urdf/baxter.urdf",
       ""},
      {"mbm_ur5", s + "/benchmarks/mbm/robots/ur5_robotiq85/ur5.urdf",
       s + "/benchmarks/mbm/robots/ur5_robotiq85/ur5.srdf"},
  };
  std::vector<RobotCase> present;
  for (const RobotCase& r : all) {
    if (std::filesystem::exists(r.urdf)) present.push_back(r);
  }
  return present;
}

// 256 random configurations within limits (continuous joints in [-pi, pi]).
std::vector<Eigen::VectorXd> random_configurations(const hullcheck::RobotModel& model) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::VectorXd lo = model.lower_limits(), hi = model.upper_limits();
  std::vector<Eigen::VectorXd> out;
  for (int k = 0; k < 256; ++k) {
    Eigen::VectorXd q(model.variable_count());
    for (int i = 0; i < q.size(); ++i) {
      const double a = std::isfinite(lo[i]) ? lo[i] : -M_PI;
      const double b = std::isfinite(hi[i]) ? hi[i] : M_PI;
      q[i] = a + (b - a) * unit(rng);
    }
    out.push_back(q);
  }
  return out;
}

void set_per_item(benchmark::State& state, std::size_t per_iteration) {
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(per_iteration));
  state.counters["time_per_item"] = benchmark::Counter(
      static_cast<double>(state.iterations() * static_cast<std::int64_t>(per_iteration)),
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void fk_hullcheck(benchmark::State& state, const RobotCase& c) {
  const auto model = hullcheck::RobotModel::from_urdf_file(c.urdf);
  const std::vector<Eigen::VectorXd> qs = random_configurations(model);
  std::vector<Eigen::Isometry3d> poses(model.links().size());
  double sink = 0.0;
  for (auto _ : state) {
    for (const Eigen::VectorXd& q : qs) {
      model.compute_link_poses_unchecked(q.data(), poses.data());
      sink += poses.back().translation().x();
    }
  }
  benchmark::DoNotOptimize(sink);
  state.counters["links"] = static_cast<double>(model.links().size());
  set_per_item(state, qs.size());
}

// The same configurations kPoseBlockLanes at a time (compute_link_poses_block), per configuration.
void fk_hullcheck_block(benchmark::State& state, const RobotCase& c) {
  const auto model = hullcheck::RobotModel::from_urdf_file(c.urdf);
  const std::vector<Eigen::VectorXd> qs = random_configurations(model);
  constexpr int kLanes = hullcheck::kPoseBlockLanes;
  Eigen::MatrixXd columns(model.variable_count(), static_cast<Eigen::Index>(qs.size()));
  for (std::size_t k = 0; k < qs.size(); ++k) columns.col(static_cast<Eigen::Index>(k)) = qs[k];
  hullcheck::LinkPoseBlock block;
  double sink = 0.0;
  for (auto _ : state) {
    for (Eigen::Index first = 0; first < columns.cols(); first += kLanes) {
      const auto count = static_cast<int>(std::min<Eigen::Index>(kLanes, columns.cols() - first));
      model.compute_link_poses_block(columns.col(first).data(), columns.outerStride(), count,
                                     block);
      sink += block.values.back();
    }
  }
  benchmark::DoNotOptimize(sink);
  set_per_item(state, qs.size());
}

// KDL's recursive chain solver from the root to the link with the longest chain, writing the
// frame of every segment of that chain (fewer links than hullcheck's whole tree on branching
// robots).
void fk_kdl_chain(benchmark::State& state, const RobotCase& c) {
  const auto model = hullcheck::RobotModel::from_urdf_file(c.urdf);
  KDL::Tree tree;
  if (!kdl_parser::treeFromFile(c.urdf, tree)) {
    state.SkipWithError("kdl_parser failed");
    return;
  }
  // The longest chain from the root.
  KDL::Chain chain;
  for (const auto& entry : tree.getSegments()) {
    KDL::Chain candidate;
    tree.getChain(tree.getRootSegment()->first, entry.first, candidate);
    if (candidate.getNrOfSegments() > chain.getNrOfSegments()) chain = candidate;
  }
  KDL::ChainFkSolverPos_recursive solver(chain);
  // Chain joints in chain order, valued from hullcheck's configuration by name.
  std::vector<int> source;
  for (const KDL::Segment& s : chain.segments) {
    if (s.getJoint().getType() != KDL::Joint::None) {
      source.push_back(model.variable_index(s.getJoint().getName()));
    }
  }
  const std::vector<Eigen::VectorXd> qs = random_configurations(model);
  std::vector<KDL::JntArray> kdl_qs;
  for (const Eigen::VectorXd& q : qs) {
    KDL::JntArray a(static_cast<unsigned>(source.size()));
    for (std::size_t i = 0; i < source.size(); ++i)
      a(static_cast<unsigned>(i)) = source[i] >= 0 ? q[source[i]] : 0.0;
    kdl_qs.push_back(a);
  }
  std::vector<KDL::Frame> frames(chain.getNrOfSegments());
  double sink = 0.0;
  for (auto _ : state) {
    for (const KDL::JntArray& q : kdl_qs) {
      solver.JntToCart(q, frames);
      sink += frames.back().p.x();
    }
  }
  benchmark::DoNotOptimize(sink);
  state.counters["links"] = static_cast<double>(chain.getNrOfSegments());
  set_per_item(state, qs.size());
}

std::unique_ptr<hullcheck::CollisionChecker> make_checker(const RobotCase& c) {
  auto model =
      std::make_shared<const hullcheck::RobotModel>(hullcheck::RobotModel::from_urdf_file(c.urdf));
  const hullcheck::Srdf srdf =
      c.srdf.empty() ? hullcheck::Srdf{} : hullcheck::read_srdf_file(c.srdf);
  return std::make_unique<hullcheck::CollisionChecker>(
      model, hullcheck::AllowedCollisionMatrix::from_srdf(*model, srdf));
}

void self_collision(benchmark::State& state, const RobotCase& c) {
  auto checker = make_checker(c);
  const std::vector<Eigen::VectorXd> qs = random_configurations(checker->model());
  int colliding = 0;
  for (auto _ : state) {
    colliding = 0;
    for (const Eigen::VectorXd& q : qs) colliding += checker->is_valid(q) ? 0 : 1;
  }
  state.counters["colliding_fraction"] =
      static_cast<double>(colliding) / static_cast<double>(qs.size());
  state.counters["pairs"] = static_cast<double>(checker->checked_link_pairs().size());
  set_per_item(state, qs.size());
}

void self_distance(benchmark::State& state, const RobotCase& c) {
  auto checker = make_checker(c);
  const std::vector<Eigen::VectorXd> qs = random_configurations(checker->model());
  double sink = 0.0;
  int exact = 0;
  for (auto _ : state) {
    exact = 0;
    for (const Eigen::VectorXd& q : qs) {
      const hullcheck::ClearanceResult p = checker->clearance(q);
      sink += p.distance;
      exact += p.exact_queries;
    }
  }
  benchmark::DoNotOptimize(sink);
  state.counters["exact_queries"] = static_cast<double>(exact) / static_cast<double>(qs.size());
  set_per_item(state, qs.size());
}

void load(benchmark::State& state, const RobotCase& c) {
  for (auto _ : state) {
    benchmark::DoNotOptimize(hullcheck::RobotModel::from_urdf_file(c.urdf));
  }
}

}  // namespace

int main(int argc, char** argv) {
  for (const RobotCase& c : robot_cases()) {
    benchmark::RegisterBenchmark(("fk/hullcheck/" + c.id).c_str(), fk_hullcheck, c);
    benchmark::RegisterBenchmark(("fk/hullcheck_block/" + c.id).c_str(), fk_hullcheck_block, c);
    benchmark::RegisterBenchmark(("fk/kdl_chain/" + c.id).c_str(), fk_kdl_chain, c);
    benchmark::RegisterBenchmark(("self_collision/" + c.id).c_str(), self_collision, c);
    benchmark::RegisterBenchmark(("self_distance/" + c.id).c_str(), self_distance, c);
    benchmark::RegisterBenchmark(("load/" + c.id).c_str(), load, c)->Unit(benchmark::kMillisecond);
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
