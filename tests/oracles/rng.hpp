// Random numbers for test data, identical on every platform (no std distributions, whose
// output is implementation-defined).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <random>

namespace hullcheck::oracle {

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : gen_(seed) {}
  std::uint64_t bits() { return gen_(); }
  /// Uniform in [0, 1).
  double uniform() { return static_cast<double>(gen_() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /// Uniform integer in [lo, hi] (inclusive).
  int integer(int lo, int hi) {
    return lo + static_cast<int>(gen_() % static_cast<std::uint64_t>(hi - lo + 1));
  }
  bool coin(double p = 0.5) { return uniform() < p; }
  /// Standard normal (Box-Muller).
  double normal() {
    const double u1 = 1.0 - uniform();  // (0, 1]
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
  }
  Eigen::Vector3d unit_vector() {
    for (;;) {
      const Eigen::Vector3d v(normal(), normal(), normal());
      const double length = v.norm();
      if (length > 1e-6) return v / length;
    }
  }
  /// Uniformly distributed rotation.
  Eigen::Quaterniond quaternion() {
    for (;;) {
      Eigen::Quaterniond q(normal(), normal(), normal(), normal());
      if (q.norm() > 1e-6) return q.normalized();
    }
  }
  Eigen::Matrix3d rotation() { return quaternion().toRotationMatrix(); }
  Eigen::Vector3d in_box(double half) {
    return Eigen::Vector3d(uniform(-half, half), uniform(-half, half), uniform(-half, half));
  }

 private:
  std::mt19937_64 gen_;
};

}  // namespace hullcheck::oracle
