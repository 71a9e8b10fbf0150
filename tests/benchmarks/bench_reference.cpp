// hullcheck alone on the cases for which Coal's timings are quoted in the proximity-core issue
// (Coal is not packaged in Debian, so it cannot run beside us): signed distance between
// separated hulls of 8, 130 and 2050 vertices, and the boolean test on the same hulls at
// separated and at overlapping poses. Release build:
//   build-bench/tests/benchmarks/bench_reference [google-benchmark flags]
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <hullcheck/core.hpp>
#include <vector>

#include "oracles.hpp"
#include "rng.hpp"

namespace {

struct PosedPairs {
  hullcheck::ConvexHull a, b;
  std::vector<Eigen::Isometry3d> poses_b;  // A at the identity
};

/// Hulls of `vertices` points on random ellipsoids; B placed in a random direction with its
/// bounding ball `gap` x (sum of the radii) beyond A's (gap > 0: provably apart) or inside.
PosedPairs make_pairs(int vertices, double gap_lo, double gap_hi, std::uint64_t seed) {
  PosedPairs p{hullcheck::ConvexHull(hullcheck::oracle::random_hull_points(seed, vertices)),
               hullcheck::ConvexHull(hullcheck::oracle::random_hull_points(seed + 1, vertices)),
               {}};
  const double reach = p.a.extent() + p.b.extent();
  hullcheck::oracle::Rng rng(seed + 2);
  for (int i = 0; i < 256; ++i) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = rng.rotation();
    pose.translation() = rng.unit_vector() * reach * (1.0 + rng.uniform(gap_lo, gap_hi));
    p.poses_b.push_back(pose);
  }
  return p;
}

template <class Query>
void run(benchmark::State& state, const PosedPairs& pairs, Query query) {
  const Eigen::Isometry3d identity = Eigen::Isometry3d::Identity();
  const hullcheck::Shape a = pairs.a, b = pairs.b;
  double sink = 0.0;
  for (auto _ : state) {
    for (const auto& pose : pairs.poses_b) sink += query(a, identity, b, pose);
  }
  benchmark::DoNotOptimize(sink);
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(pairs.poses_b.size()));
  // Seconds per query (printed with an SI prefix: "195n" is 195 ns).
  state.counters["time_per_query"] = benchmark::Counter(
      static_cast<double>(state.iterations() * static_cast<std::int64_t>(pairs.poses_b.size())),
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

double signed_distance(const hullcheck::Shape& a, const Eigen::Isometry3d& pa,
                       const hullcheck::Shape& b, const Eigen::Isometry3d& pb) {
  return hullcheck::signed_distance(a, pa, b, pb).signed_distance;
}

double intersect(const hullcheck::Shape& a, const Eigen::Isometry3d& pa, const hullcheck::Shape& b,
                 const Eigen::Isometry3d& pb) {
  return hullcheck::intersect(a, pa, b, pb) ? 1.0 : 0.0;
}

}  // namespace

int main(int argc, char** argv) {
  static std::vector<PosedPairs> separated, near, overlapping;
  for (int vertices : {8, 130, 2050}) {
    separated.push_back(make_pairs(vertices, 0.0, 0.5, 100 + vertices));
    // Near: bounding balls overlap by up to half; the hulls themselves may or may not.
    near.push_back(make_pairs(vertices, -0.5, 0.0, 200 + vertices));
    overlapping.push_back(make_pairs(vertices, -1.0, -0.8, 300 + vertices));
  }
  for (std::size_t k = 0; k < separated.size(); ++k) {
    const std::string n = std::to_string(separated[k].a.vertex_count());
    benchmark::RegisterBenchmark(
        ("signed_distance/separated/" + n).c_str(),
        [k](benchmark::State& s) { run(s, separated[k], signed_distance); });
    benchmark::RegisterBenchmark(("intersect/separated/" + n).c_str(),
                                 [k](benchmark::State& s) { run(s, separated[k], intersect); });
    benchmark::RegisterBenchmark(("intersect/near/" + n).c_str(),
                                 [k](benchmark::State& s) { run(s, near[k], intersect); });
    benchmark::RegisterBenchmark(("intersect/overlapping/" + n).c_str(),
                                 [k](benchmark::State& s) { run(s, overlapping[k], intersect); });
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
