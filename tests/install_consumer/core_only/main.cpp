// Smallest program using only an installed hullcheck::core; exits non-zero on a wrong answer.
#include <cmath>
#include <cstdio>
#include <hullcheck/core.hpp>

// The core layer must not put OMPL on a consumer's include path (Debian installs its headers
// under /usr/include/ompl-<version>, found only through OMPL's package config).
#if __has_include(<ompl/config.h>)
#error "hullcheck::core exposed OMPL's headers to its consumer"
#endif

int main() {
  Eigen::Isometry3d b = Eigen::Isometry3d::Identity();
  b.translation().x() = 3.0;
  const hullcheck::Shape sphere(hullcheck::Sphere(1.0));
  const hullcheck::Shape box(hullcheck::Box(2, 2, 2));
  const double d = hullcheck::distance(sphere, Eigen::Isometry3d::Identity(), box, b).distance;
  // The warm-started signed distance of the same pair, moved 0.5 m closer.
  hullcheck::WarmStart warm;
  hullcheck::signed_distance_below(sphere, Eigen::Isometry3d::Identity(), box, b, INFINITY, warm);
  b.translation().x() = 2.5;
  const double s = hullcheck::signed_distance_below(sphere, Eigen::Isometry3d::Identity(), box, b,
                                                    INFINITY, warm)
                       .signed_distance;
  std::printf("installed hullcheck::core: sphere-box distance %.12f (expected 1), %.12f (0.5)\n", d,
              s);
  return std::abs(d - 1.0) < 1e-12 && std::abs(s - 0.5) < 1e-12 ? 0 : 1;
}
