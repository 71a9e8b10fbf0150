// The C++ side of tests/benchmarks/bench_python.py: validity of the same configurations, timed
// in C++ (a loop of CollisionChecker::is_valid, and is_valid_batch as the Python binding calls
// it), so that the binding's overhead is measured in the same run on the same states.
//   bench_python_reference URDF SRDF SCENE STATES.f64 DOF REPEATS [--tables]
// --tables: measure the self tables first (CollisionChecker::measure_self_tables, not timed).
// STATES.f64: N x DOF float64 values, row after row (numpy's tofile). Prints, best of REPEATS:
//   loop_ns_per_state X
//   batch_ns_per_state Y
//   valid Z          (valid states; the two ways must agree, else exit 3)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <hullcheck/scene.hpp>
#include <memory>
#include <string>
#include <vector>

using namespace hullcheck;

namespace {

template <class Body>
double best_ns_per_state(int repeats, Eigen::Index count, const Body& body) {
  double best = 1e300;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    body();
    const double ns =
        std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count();
    best = std::min(best, ns / static_cast<double>(count));
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) try {
  const bool tables = argc == 8 && std::string(argv[7]) == "--tables";
  if (argc != 7 && !tables) {
    std::fprintf(stderr, "usage: %s URDF SRDF SCENE STATES.f64 DOF REPEATS [--tables]\n", argv[0]);
    return 2;
  }
  auto model = std::make_shared<const RobotModel>(RobotModel::from_urdf_file(argv[1]));
  const Srdf srdf = read_srdf_file(argv[2]);
  const CollisionChecker checker(model, AllowedCollisionMatrix::from_srdf(*model, srdf),
                                 read_planning_scene(argv[3], *model));
  // --tables: the self blocks' distance tables measured first (once per model, not timed).
  if (tables) checker.measure_self_tables();
  const int dof = std::stoi(argv[5]), repeats = std::max(1, std::stoi(argv[6]));
  if (dof != model->variable_count()) {
    std::fprintf(stderr, "%s: DOF %d, the robot has %d values\n", argv[4], dof,
                 model->variable_count());
    return 2;
  }
  std::ifstream in(argv[4], std::ios::binary | std::ios::ate);
  const auto bytes = static_cast<std::size_t>(in.tellg());
  if (!in || bytes % (sizeof(double) * static_cast<std::size_t>(dof)) != 0) {
    std::fprintf(stderr, "%s: not a whole number of %d-value rows\n", argv[4], dof);
    return 2;
  }
  std::vector<double> values(bytes / sizeof(double));
  in.seekg(0);
  in.read(reinterpret_cast<char*>(values.data()), static_cast<std::streamsize>(bytes));
  const Eigen::Index count = static_cast<Eigen::Index>(values.size()) / dof;
  const Eigen::Map<const Eigen::MatrixXd> q(values.data(), dof, count);
  std::unique_ptr<bool[]> loop(new bool[static_cast<std::size_t>(count)]);
  std::unique_ptr<bool[]> batch(new bool[static_cast<std::size_t>(count)]);

  const double loop_ns = best_ns_per_state(repeats, count, [&] {
    for (Eigen::Index i = 0; i < count; ++i)
      loop[static_cast<std::size_t>(i)] = checker.is_valid(q.col(i));
  });
  const double batch_ns =
      best_ns_per_state(repeats, count, [&] { checker.is_valid_batch(q, batch.get()); });
  long valid = 0;
  for (Eigen::Index i = 0; i < count; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (loop[k] != batch[k]) {
      std::fprintf(stderr, "state %ld: is_valid %d, is_valid_batch %d\n", static_cast<long>(i),
                   loop[k], batch[k]);
      return 3;
    }
    valid += loop[k] ? 1 : 0;
  }
  std::printf("loop_ns_per_state %.3f\nbatch_ns_per_state %.3f\nvalid %ld\n", loop_ns, batch_ns,
              valid);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "error: %s\n", e.what());
  return 1;
}
