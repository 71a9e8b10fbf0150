// Small helpers shared by the test files.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <hullcheck/core/errors.hpp>
#include <initializer_list>
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

// A fresh folder under the system temp folder, removed with everything in it at scope exit.
class TempDir {
 public:
  explicit TempDir(const std::string& tag = "test") {
    std::random_device device;
    const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
    path_ = std::filesystem::temp_directory_path() /
            ("hullcheck_" + tag + "_" + std::to_string(stamp) + "_" + std::to_string(device()));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::string str() const { return path_.string(); }
  std::filesystem::path write(const std::string& name, const std::string& bytes) const {
    const std::filesystem::path p = path_ / name;
    std::filesystem::create_directories(p.parent_path());
    std::ofstream out(p, std::ios::binary);
    out << bytes;
    return p;
  }

 private:
  std::filesystem::path path_;
};

// Runs `f`, expects an InputError, and returns its message ("" and a failure otherwise).
inline std::string input_error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected InputError, got another exception: " << e.what();
    return "";
  }
  ADD_FAILURE() << "expected InputError, nothing was thrown";
  return "";
}

inline void expect_contains(const std::string& message, std::initializer_list<std::string> parts) {
  for (const std::string& part : parts) {
    EXPECT_NE(message.find(part), std::string::npos) << "message lacks '" << part << "':\n"
                                                     << message;
  }
}

}  // namespace hullcheck::test
