// Scenes and robots the scene tests load: MotionBenchMaker problems in ../shared (skipped
// cleanly when absent), the own arm, and sample-count scaling for sanitizer builds.
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <hullcheck/core/queries.hpp>
#include <hullcheck/robot.hpp>
#include <hullcheck/scene/planning_scene.hpp>
#include <memory>
#include <random>
#include <string>
#include <variant>
#include <vector>

#include "robot_test_support.hpp"

namespace hullcheck::test {

/// Sample counts are divided by this under AddressSanitizer (tests run ~10x slower there).
#if defined(__SANITIZE_ADDRESS__)
constexpr int kSanitizerDivisor = 10;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr int kSanitizerDivisor = 10;
#else
constexpr int kSanitizerDivisor = 1;
#endif
#else
constexpr int kSanitizerDivisor = 1;
#endif

/// `count` scaled for the build (at least 1); the environment variable `env`, when set, gives
/// the count instead (for long offline runs).
inline int sample_count(int count, const char* env = nullptr) {
  if (env != nullptr) {
    if (const char* value = std::getenv(env)) return std::max(1, std::atoi(value));
  }
  return std::max(1, count / kSanitizerDivisor);
}

/// A MotionBenchMaker robot: model files and its problem folders.
struct MbmRobot {
  std::string id;    // "panda" or "ur5"
  std::string urdf;  // benchmarks/mbm/robots/...
  std::string srdf;
  std::string folder;                 // benchmarks/mbm/<id>
  std::vector<std::string> families;  // e.g. "box_panda"
};

inline std::string mbm_dir() {
  const std::string s = shared_dir();
  return s.empty() ? std::string() : s + "/benchmarks/mbm";
}

inline std::vector<MbmRobot> mbm_robots();

/// Appends to the columns of q from `filled` on, up to its last column, pairs of states within a
/// hair of contact (both ends of a 40-step bisection between two of the first `states` columns
/// whose validity differs, 1e-12 of the segment apart); returns the columns filled. `Checker`:
/// anything with is_valid(q) (a CollisionChecker).
template <class Checker>
int append_near_contact_states(const Checker& checker, int states, int filled, int tries,
                               Eigen::MatrixXd& q) {
  for (int t = 0; filled + 2 <= q.cols() && t < tries; ++t) {
    const Eigen::VectorXd a = q.col(t % states), b = q.col((t * 7 + 3) % states);
    const bool va = checker.is_valid(a);
    if (va == checker.is_valid(b)) continue;
    double lo = 0.0, hi = 1.0;  // is_valid(a + lo (b - a)) == va, at hi the other
    for (int i = 0; i < 40; ++i) {
      const double mid = 0.5 * (lo + hi);
      (checker.is_valid(a + mid * (b - a)) == va ? lo : hi) = mid;
    }
    q.col(filled++) = a + lo * (b - a);
    q.col(filled++) = a + hi * (b - a);
  }
  return filled;
}

/// The MBM robot `id` ("panda", "ur5") when present: false when ../shared is absent.
inline bool find_mbm_robot(const std::string& id, MbmRobot* out) {
  for (const MbmRobot& r : mbm_robots()) {
    if (r.id == id) {
      *out = r;
      return true;
    }
  }
  return false;
}

/// The MBM robots whose model and problems are present (empty when ../shared is absent).
inline std::vector<MbmRobot> mbm_robots() {
  const std::string dir = mbm_dir();
  std::vector<MbmRobot> out;
  if (dir.empty()) return out;
  const char* const kFamilies[] = {
      "bookshelf_small", "bookshelf_tall",  "bookshelf_thin", "box", "cage",
      "table_pick",      "table_under_pick"};
  const std::vector<MbmRobot> all = {
      {"panda",
       dir + "/robots/panda_obj/panda.urdf",
       dir + "/robots/panda_obj/panda.srdf",
       dir + "/panda",
       {}},
      {"ur5",
       dir + "/robots/ur5_robotiq85/ur5.urdf",
       dir + "/robots/ur5_robotiq85/ur5.srdf",
       dir + "/ur5",
       {}},
  };
  for (MbmRobot r : all) {
    if (!std::filesystem::exists(r.urdf) || !std::filesystem::exists(r.srdf)) continue;
    for (const char* f : kFamilies) {
      const std::string family = std::string(f) + "_" + r.id;
      if (std::filesystem::is_directory(r.folder + "/" + family)) r.families.push_back(family);
    }
    if (!r.families.empty()) out.push_back(r);
  }
  return out;
}

/// "<folder>/<family>/sceneNNNN.yaml" (or request).
inline std::string mbm_file(const MbmRobot& robot, const std::string& family, const char* kind,
                            int number) {
  char name[32];
  std::snprintf(name, sizeof name, "%s%04d.yaml", kind, number);
  return robot.folder + "/" + family + "/" + name;
}

/// Models are loaded once per test binary (meshes take a moment).
inline std::shared_ptr<const RobotModel> cached_model(const std::string& urdf) {
  static std::vector<std::pair<std::string, std::shared_ptr<const RobotModel>>> cache;
  for (const auto& [path, model] : cache) {
    if (path == urdf) return model;
  }
  auto model = std::make_shared<const RobotModel>(RobotModel::from_urdf_file(urdf));
  cache.emplace_back(urdf, model);
  return model;
}

/// The own arm with its SRDF's collision matrix in its table-and-wall scene.
struct ArmInScene {
  std::shared_ptr<const RobotModel> model;
  AllowedCollisionMatrix matrix;
  PlanningScene scene;
};

inline ArmInScene arm_in_scene() {
  ArmInScene w;
  w.model = cached_model(own_arm().urdf);
  w.matrix = AllowedCollisionMatrix::from_srdf(*w.model, read_srdf_file(own_arm().srdf));
  w.scene = read_planning_scene(robots_dir() + "/hullcheck_arm/scenes/table_wall.yaml", *w.model);
  return w;
}

/// Minimum signed distance over every self pair `matrix` checks, each query cold: the brute
/// force a clearance search must equal. `status`: that pair's query status.
inline double brute_force_self_clearance(const RobotModel& model,
                                         const AllowedCollisionMatrix& matrix,
                                         const std::vector<Eigen::Isometry3d>& poses,
                                         Status* status = nullptr) {
  double best = INFINITY;
  const int n = static_cast<int>(model.links().size());
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) {
      if (matrix.allowed(a, b)) continue;
      for (const CollisionShape& sa : model.link(a).shapes) {
        for (const CollisionShape& sb : model.link(b).shapes) {
          const SignedDistanceResult r =
              signed_distance(sa.shape, poses[static_cast<std::size_t>(a)] * sa.origin, sb.shape,
                              poses[static_cast<std::size_t>(b)] * sb.origin);
          if (r.signed_distance < best) {
            best = r.signed_distance;
            if (status != nullptr) *status = r.status;
          }
        }
      }
    }
  }
  return best;
}

/// The same over every robot shape against every obstacle of `scene` (for scenes that allow
/// no robot-obstacle pair).
inline double brute_force_obstacle_clearance(const RobotModel& model, const PlanningScene& scene,
                                             const std::vector<Eigen::Isometry3d>& poses) {
  double best = INFINITY;
  for (std::size_t l = 0; l < model.links().size(); ++l) {
    for (const CollisionShape& sa : model.link(static_cast<int>(l)).shapes) {
      for (const Obstacle& o : scene.obstacles) {
        best = std::min(
            best, signed_distance(sa.shape, poses[l] * sa.origin, o.shape, o.pose).signed_distance);
      }
    }
  }
  return best;
}

/// Points of a shape (its local frame) whose motion bounds its other points': hull vertices,
/// box corners, cylinder rims (16 points each), sphere poles, capsule cap poles; with padding,
/// each pushed out by the margin along the axes.
inline std::vector<Eigen::Vector3d> shape_points(const Shape& shape) {
  std::vector<Eigen::Vector3d> out;
  const Shape::Geometry& g = shape.geometry();
  const Eigen::Vector3d axes[] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                  {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
  if (const auto* box = std::get_if<Box>(&g)) {
    for (int c = 0; c < 8; ++c) {
      out.emplace_back((c & 1 ? 1 : -1) * box->half_extents.x(),
                       (c & 2 ? 1 : -1) * box->half_extents.y(),
                       (c & 4 ? 1 : -1) * box->half_extents.z());
    }
  } else if (const auto* sphere = std::get_if<Sphere>(&g)) {
    for (const auto& a : axes) out.push_back(sphere->radius * a);
  } else if (const auto* cyl = std::get_if<Cylinder>(&g)) {
    for (int i = 0; i < 16; ++i) {
      const double a = 2 * M_PI * i / 16;
      for (const double z : {-cyl->half_length, cyl->half_length}) {
        out.emplace_back(cyl->radius * std::cos(a), cyl->radius * std::sin(a), z);
      }
    }
  } else if (const auto* cap = std::get_if<Capsule>(&g)) {
    for (const auto& a : axes) {
      out.push_back(cap->radius * a + Eigen::Vector3d(0, 0, cap->half_length));
      out.push_back(cap->radius * a - Eigen::Vector3d(0, 0, cap->half_length));
    }
  } else {
    out = std::get<ConvexHull>(g).vertices();
  }
  if (shape.margin() > 0) {  // padding: the points pushed out along the axes
    const std::size_t n = out.size();
    for (std::size_t i = 0; i < n; ++i) {
      for (const auto& a : axes) out.push_back(out[i] + shape.margin() * a);
    }
  }
  return out;
}

}  // namespace hullcheck::test
