// Demo of the proximity core: every query on every kind of shape, the cached pair with warm
// start, and a quick throughput measurement. Run: scripts/demo.sh
#include <chrono>
#include <cstdio>
#include <hullcheck/core.hpp>
#include <random>
#include <string>
#include <vector>

namespace {

using hullcheck::Shape;

/// A hull of `n` points on an ellipsoid with semi-axes (a, b, c), like a coarse link mesh.
hullcheck::ConvexHull ellipsoid(int n, double a, double b, double c, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d p = Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
    points.emplace_back(a * p.x(), b * p.y(), c * p.z());
  }
  return hullcheck::ConvexHull(points);
}

void print_vector(const char* name, const Eigen::Vector3d& v) {
  std::printf("%s (%+.6f, %+.6f, %+.6f)", name, v.x(), v.y(), v.z());
}

void report(const std::string& name, const Shape& a, const Eigen::Isometry3d& pa, const Shape& b,
            const Eigen::Isometry3d& pb) {
  const bool hit = hullcheck::intersect(a, pa, b, pb);
  const hullcheck::SignedDistanceResult s = hullcheck::signed_distance(a, pa, b, pb);
  std::printf("%-28s %-9s signed distance %+.9f m  ", name.c_str(), hit ? "COLLIDING" : "free",
              s.signed_distance);
  print_vector("normal", s.normal);
  std::printf("\n%-38s", "");
  print_vector("point on A", s.point_a);
  std::printf("  ");
  print_vector("point on B", s.point_b);
  std::printf("  [%s, %d iterations, %d in EPA]\n", hullcheck::to_string(s.status), s.iterations,
              s.epa_iterations);
}

}  // namespace

int main() {
  const hullcheck::ConvexHull link = ellipsoid(400, 0.30, 0.12, 0.10, 1);
  std::printf("hullcheck proximity demo\nhull of 400 points: %zu vertices, %zu triangles\n\n",
              link.vertex_count(), link.triangles().size());
  const Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
  auto at = [](double x, double y, double z, double gx = 0, double gy = 0, double gz = 0) {
    return hullcheck::pose_from_xyz_angles({x, y, z}, {gx, gy, gz});
  };
  report("hull vs box (apart)", link, origin, hullcheck::Box(0.2, 0.2, 0.2), at(0.55, 0.05, 0));
  report("hull vs box (overlap)", link, origin, hullcheck::Box(0.2, 0.2, 0.2),
         at(0.35, 0, 0, 0, 0, 0.6));
  report("hull vs sphere", link, origin, hullcheck::Sphere(0.05), at(0, 0.2, 0.05));
  report("hull vs cylinder", link, origin, hullcheck::Cylinder(0.05, 0.4),
         at(0.1, 0.1, 0.3, 1.2, 0, 0));
  report("capsule vs capsule (cross)", hullcheck::Capsule(0.04, 0.5), at(0, 0, 0, 0, M_PI / 2, 0),
         hullcheck::Capsule(0.04, 0.5), at(0, 0, 0.07, M_PI / 2, 0, 0));
  report("padded hull (2 cm) vs hull", Shape(link).inflated(0.02), origin, link,
         at(0.0, 0.25, 0, 0, 0, 0.3));

  // The cached pair: B slides through A in steps of 1% of its size, warm-started.
  std::printf("\nProximityPair: box sliding through the hull, 1 cm steps (warm start)\n");
  hullcheck::ProximityPair pair;
  pair.set_shape_a(link);
  pair.set_shape_b(hullcheck::Box(0.1, 0.1, 0.1), at(0.6, 0.02, 0.01));
  long warm = 0, cold = 0;
  for (int step = 0; step <= 60; ++step) {
    const Eigen::Isometry3d pose = at(0.6 - 0.01 * step, 0.02, 0.01, 0, 0, 0.01 * step);
    pair.set_pose_b(pose);
    const double sd = pair.signed_distance().signed_distance;
    warm += pair.last_iterations();
    cold +=
        hullcheck::signed_distance(link, origin, hullcheck::Box(0.1, 0.1, 0.1), pose).iterations;
    if (step % 10 == 0) {
      std::printf("  x = %.2f m  signed distance %+.6f m  colliding %s\n", 0.6 - 0.01 * step, sd,
                  pair.in_collision() ? "yes" : "no");
    }
  }
  std::printf("  GJK+EPA iterations over 61 steps: warm %ld, cold %ld\n", warm, cold);

  // Throughput on random poses (a quick figure; the benchmarks in tests/benchmarks are the
  // reference measurements).
  const hullcheck::ConvexHull other = ellipsoid(400, 0.2, 0.2, 0.1, 2);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.6, 0.6), angle(-3.14, 3.14);
  std::vector<Eigen::Isometry3d> poses;
  for (int i = 0; i < 1000; ++i)
    poses.push_back(at(u(rng), u(rng), u(rng), angle(rng), angle(rng), angle(rng)));
  int colliding = 0;
  const auto start = std::chrono::steady_clock::now();
  for (int round = 0; round < 20; ++round) {
    for (const auto& pose : poses) colliding += hullcheck::intersect(link, origin, other, pose);
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf(
      "\nintersect on 20000 random poses of two 400-point hulls: %.0f ns per query (%d "
      "colliding)\n",
      1e9 * seconds / 20000.0, colliding);
  return 0;
}
