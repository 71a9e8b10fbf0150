// Small helpers shared by the test files.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <string>

namespace hullcheck::test {

inline Eigen::Isometry3d translation(double x, double y, double z) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(x, y, z);
  return pose;
}

inline Eigen::Isometry3d random_pose(std::mt19937_64& rng, double spread) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::Quaterniond q(normal(rng), normal(rng), normal(rng), normal(rng));
  q.normalize();
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = q.toRotationMatrix();
  pose.translation() = spread * Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
  return pose;
}

/// Folder of the shared test data (../shared beside the checkout), or "" when absent.
inline std::string shared_dir() {
  if (const char* env = std::getenv("HULLCHECK_SHARED_DIR")) return env;
#ifdef HULLCHECK_SHARED_DIR
  return HULLCHECK_SHARED_DIR;
#else
  return "";
#endif
}

}  // namespace hullcheck::test
