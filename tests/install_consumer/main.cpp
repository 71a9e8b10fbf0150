// Smallest program using an installed hullcheck; exits non-zero on a wrong answer.
#include <cstdio>
#include <hullcheck/hullcheck.hpp>

int main() {
  Eigen::Isometry3d b = Eigen::Isometry3d::Identity();
  b.translation().x() = 3.0;
  const double d = hullcheck::distance(hullcheck::Sphere(1.0), Eigen::Isometry3d::Identity(),
                                       hullcheck::Box(2, 2, 2), b)
                       .distance;
  std::printf("installed hullcheck: sphere-box distance %.12f (expected 1)\n", d);
  return std::abs(d - 1.0) < 1e-12 ? 0 : 1;
}
