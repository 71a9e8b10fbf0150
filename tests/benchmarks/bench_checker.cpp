// Validity checks and clearance of the Panda on MotionBenchMaker scenes: hullcheck's
// CollisionChecker beside an FCL 0.7 checker on the same shapes (Release build).
//   bench_checker [--quick] [--scenes=N] [--states=N] [--table=FILE] [google-benchmark flags]
//
// The FCL checker (benchmark-only code, below) is what an FCL user writes: every robot
// collision shape (hulls as fcl::Convexd from ConvexHull::vertices()/triangles(), primitives as
// fcl::Boxd/Sphered/Cylinderd/Capsuled) is one CollisionObject in a
// DynamicAABBTreeCollisionManager, updated per state (setTransform, computeAABB, update());
// the obstacles are in a second, static manager. Validity: robot manager against obstacle
// manager, then the robot manager against itself, with a callback that skips the pairs the
// allowed-collision matrix allows (the SRDF's and the scene's, the same matrix hullcheck uses)
// and stops at the first collision. Clearance: the same two traversals with
// manager->distance and fcl::distance (GST_LIBCCD, enable_signed_distance) per pair, the
// running minimum passed back to the tree for pruning and a stop at the first penetration
// (FCL's default distance callback does the same). Forward kinematics is hullcheck's for both.
//
// Two state sets per scene: "random", uniform within the panda_arm joint limits (mostly
// colliding, so early exits dominate), and "line", evenly spaced on the straight joint-space
// segment from the request's start to its goal (mostly valid). Before timing, every state is
// checked by both checkers and disagreements are counted.
#include <benchmark/benchmark.h>
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <hullcheck/robot.hpp>
#include <hullcheck/scene/collision_checker.hpp>
#include <hullcheck/scene/motion_plan_request.hpp>
#include <hullcheck/scene/planning_scene.hpp>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using hullcheck::AllowedCollisionMatrix;
using hullcheck::CollisionChecker;
using hullcheck::PlanningScene;
using hullcheck::RobotModel;

// ---------------------------------------------------------------------------------------------
// FCL checker

std::shared_ptr<fcl::CollisionGeometryd> to_fcl(const hullcheck::Shape& shape) {
  if (shape.margin() != 0.0) {
    throw std::runtime_error("bench_checker: padded shapes have no FCL counterpart");
  }
  const hullcheck::Shape::Geometry& g = shape.geometry();
  if (const auto* box = std::get_if<hullcheck::Box>(&g)) {
    return std::make_shared<fcl::Boxd>(2.0 * box->half_extents);
  }
  if (const auto* sphere = std::get_if<hullcheck::Sphere>(&g)) {
    return std::make_shared<fcl::Sphered>(sphere->radius);
  }
  if (const auto* cylinder = std::get_if<hullcheck::Cylinder>(&g)) {
    return std::make_shared<fcl::Cylinderd>(cylinder->radius, 2.0 * cylinder->half_length);
  }
  if (const auto* capsule = std::get_if<hullcheck::Capsule>(&g)) {
    return std::make_shared<fcl::Capsuled>(capsule->radius, 2.0 * capsule->half_length);
  }
  const auto& hull = std::get<hullcheck::ConvexHull>(g);
  auto vertices = std::make_shared<std::vector<Eigen::Vector3d>>(hull.vertices());
  auto faces = std::make_shared<std::vector<int>>();
  faces->reserve(hull.triangles().size() * 4);
  for (const auto& t : hull.triangles()) faces->insert(faces->end(), {3, t[0], t[1], t[2]});
  // throw_if_invalid: a hull that is not watertight would make FCL fall back silently to a
  // linear-scan support function, and the comparison would not be what it claims.
  auto convex = std::make_shared<fcl::Convexd>(vertices, static_cast<int>(hull.triangles().size()),
                                               faces, /*throw_if_invalid=*/true);
  return convex;
}

class FclChecker {
 public:
  // The robot, matrix (scene's link pairs included) and scene of `hc`; obstacle/link pairs the
  // scene allows are resolved here as CollisionChecker does.
  explicit FclChecker(const CollisionChecker& hc)
      : model_(&hc.model()), matrix_(hc.matrix()), link_poses_(hc.model().links().size()) {
    const PlanningScene& scene = hc.scene();
    const int n_links = static_cast<int>(model_->links().size());
    link_object_allowed_.assign(static_cast<std::size_t>(n_links),
                                std::vector<bool>(scene.obstacles.size(), false));
    for (const auto& [first, second] : scene.allowed_pairs) {
      const int la = model_->link_index(first);
      const int lb = model_->link_index(second);
      if ((la >= 0) == (lb >= 0)) continue;  // link/link pairs are in hc.matrix() already
      const int link = la >= 0 ? la : lb;
      const std::string& object = la >= 0 ? second : first;
      for (std::size_t o = 0; o < scene.obstacles.size(); ++o) {
        if (scene.obstacles[o].object == object) {
          link_object_allowed_[static_cast<std::size_t>(link)][o] = true;
        }
      }
    }
    // User data points into infos_, which is sized once and never reallocated.
    std::size_t robot_shapes = 0;
    for (const hullcheck::Link& link : model_->links()) robot_shapes += link.shapes.size();
    infos_.reserve(robot_shapes + scene.obstacles.size());
    for (int l = 0; l < n_links; ++l) {
      const hullcheck::Link& link = model_->link(l);
      first_object_.push_back(static_cast<int>(robot_.size()));
      for (const hullcheck::CollisionShape& cs : link.shapes) {
        robot_.push_back(std::make_unique<fcl::CollisionObjectd>(to_fcl(cs.shape)));
        origins_.push_back(cs.origin);
        infos_.push_back({l, -1});
        robot_.back()->setUserData(&infos_.back());
        robot_links_.push_back(l);
      }
    }
    for (std::size_t o = 0; o < scene.obstacles.size(); ++o) {
      const hullcheck::Obstacle& obstacle = scene.obstacles[o];
      obstacles_.push_back(
          std::make_unique<fcl::CollisionObjectd>(to_fcl(obstacle.shape), obstacle.pose));
      infos_.push_back({-1, static_cast<int>(o)});
      obstacles_.back()->setUserData(&infos_.back());
    }
    // Robot objects registered at the default configuration, then moved per state.
    place(model_->default_configuration());
    std::vector<fcl::CollisionObjectd*> robot, obstacles;
    for (auto& r : robot_) robot.push_back(r.get());
    for (auto& o : obstacles_) obstacles.push_back(o.get());
    robot_manager_.registerObjects(robot);
    robot_manager_.setup();
    obstacle_manager_.registerObjects(obstacles);
    obstacle_manager_.setup();
    for (int a = 0; a < n_links && !has_self_pairs_; ++a) {
      for (int b = a + 1; b < n_links; ++b) {
        if (!matrix_.allowed(a, b) && !model_->link(a).shapes.empty() &&
            !model_->link(b).shapes.empty()) {
          has_self_pairs_ = true;
          break;
        }
      }
    }
    collision_request_.num_max_contacts = 1;
    collision_request_.enable_contact = false;
    collision_request_.gjk_solver_type = fcl::GST_LIBCCD;
    distance_request_.enable_nearest_points = false;
    distance_request_.enable_signed_distance = true;
    distance_request_.gjk_solver_type = fcl::GST_LIBCCD;
  }

  bool is_valid(const Eigen::VectorXd& q) {
    place(q);
    robot_manager_.update();
    collision_ = false;
    robot_manager_.collide(&obstacle_manager_, this, &FclChecker::collide_callback);
    if (!collision_ && has_self_pairs_) {
      robot_manager_.collide(this, &FclChecker::collide_callback);
    }
    return !collision_;
  }

  double clearance(const Eigen::VectorXd& q) {
    place(q);
    robot_manager_.update();
    min_distance_ = std::numeric_limits<double>::max();
    robot_manager_.distance(&obstacle_manager_, this, &FclChecker::distance_callback);
    if (min_distance_ > 0.0 && has_self_pairs_) {
      robot_manager_.distance(this, &FclChecker::distance_callback);
    }
    return min_distance_;
  }

  // FCL's signed distance of the pair hullcheck reports as closest, at the poses of the last
  // query, the smaller over both argument orders (libccd's GJK distance depends on the order
  // and can stop early on large hulls; the broad phase passes the pair in either order).
  double pair_distance(const hullcheck::ClearanceResult& r) {
    fcl::CollisionObjectd* a =
        robot_[static_cast<std::size_t>(first_object_[static_cast<std::size_t>(r.link_a)] +
                                        r.shape_a)]
            .get();
    fcl::CollisionObjectd* b =
        r.self ? robot_[static_cast<std::size_t>(first_object_[static_cast<std::size_t>(r.link_b)] +
                                                 r.shape_b)]
                     .get()
               : obstacles_[static_cast<std::size_t>(r.obstacle)].get();
    fcl::DistanceResultd ab, ba;
    fcl::distance(a, b, distance_request_, ab);
    fcl::distance(b, a, distance_request_, ba);
    return std::min(ab.min_distance, ba.min_distance);
  }

 private:
  struct Info {
    int link;      // robot link, or -1 for an obstacle
    int obstacle;  // scene obstacle, or -1 for a robot shape
  };

  void place(const Eigen::VectorXd& q) {
    model_->compute_link_poses_unchecked(q.data(), link_poses_.data());
    for (std::size_t i = 0; i < robot_.size(); ++i) {
      robot_[i]->setTransform(link_poses_[static_cast<std::size_t>(robot_links_[i])] * origins_[i]);
      robot_[i]->computeAABB();
    }
  }

  bool allowed(const fcl::CollisionObjectd* o1, const fcl::CollisionObjectd* o2) const {
    const Info& a = *static_cast<const Info*>(o1->getUserData());
    const Info& b = *static_cast<const Info*>(o2->getUserData());
    if (a.link >= 0 && b.link >= 0) return matrix_.allowed(a.link, b.link);
    if (a.link >= 0 && b.obstacle >= 0) {
      return link_object_allowed_[static_cast<std::size_t>(a.link)]
                                 [static_cast<std::size_t>(b.obstacle)];
    }
    if (b.link >= 0 && a.obstacle >= 0) {
      return link_object_allowed_[static_cast<std::size_t>(b.link)]
                                 [static_cast<std::size_t>(a.obstacle)];
    }
    return true;  // obstacle/obstacle: never checked
  }

  static bool collide_callback(fcl::CollisionObjectd* o1, fcl::CollisionObjectd* o2, void* data) {
    auto& self = *static_cast<FclChecker*>(data);
    if (self.collision_) return true;
    if (self.allowed(o1, o2)) return false;
    self.collision_result_.clear();
    fcl::collide(o1, o2, self.collision_request_, self.collision_result_);
    self.collision_ = self.collision_result_.isCollision();
    return self.collision_;
  }

  static bool distance_callback(fcl::CollisionObjectd* o1, fcl::CollisionObjectd* o2, void* data,
                                double& dist) {
    auto& self = *static_cast<FclChecker*>(data);
    if (self.min_distance_ <= 0.0) {
      dist = self.min_distance_;
      return true;
    }
    if (!self.allowed(o1, o2)) {
      self.distance_result_.clear();
      fcl::distance(o1, o2, self.distance_request_, self.distance_result_);
      self.min_distance_ = std::min(self.min_distance_, self.distance_result_.min_distance);
    }
    dist = self.min_distance_;
    return self.min_distance_ <= 0.0;
  }

  const RobotModel* model_;
  AllowedCollisionMatrix matrix_;
  std::vector<std::vector<bool>> link_object_allowed_;
  std::vector<Info> infos_;
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> robot_, obstacles_;
  std::vector<Eigen::Isometry3d> origins_;
  std::vector<int> robot_links_;
  std::vector<int> first_object_;  // per link: index of its first shape in robot_
  std::vector<Eigen::Isometry3d> link_poses_;
  fcl::DynamicAABBTreeCollisionManagerd robot_manager_, obstacle_manager_;
  bool has_self_pairs_ = false;
  fcl::CollisionRequestd collision_request_;
  fcl::CollisionResultd collision_result_;
  fcl::DistanceRequestd distance_request_;
  fcl::DistanceResultd distance_result_;
  bool collision_ = false;
  double min_distance_ = 0.0;
};

// ---------------------------------------------------------------------------------------------
// Data: per family, the first scenes with their checkers and states.

struct Options {
  bool quick = false;
  int scenes = 5;    // per family
  int states = 100;  // per scene and state set
  std::string table_file;
  std::string shared_dir;
};

const char* const kFamilies[] = {
    "bookshelf_small", "bookshelf_tall",  "bookshelf_thin", "box", "cage",
    "table_pick",      "table_under_pick"};
const char* const kSets[] = {"random", "line"};
constexpr int kSetCount = 2;

struct SceneCase {
  std::string name;
  std::unique_ptr<CollisionChecker> hc;
  std::unique_ptr<FclChecker> fcl;
  std::vector<Eigen::VectorXd> states[kSetCount];
};

struct Agreement {
  int states = 0;
  int valid_hc = 0;
  int valid_fcl = 0;
  int disagreements = 0;
  double disagreement_clearance = 0.0;  // largest |hullcheck clearance| at a disagreement
  double clearance_diff = 0.0;          // largest |hc - FCL| clearance where both are valid
  int fcl_lower = 0;       // both valid, FCL's clearance below hullcheck's by more than 1e-9 m
  int fcl_higher = 0;      // both valid, FCL's clearance above hullcheck's by more than 1e-9 m
  double pair_diff = 0.0;  // largest |hc - FCL on hullcheck's closest pair| at those states
  int clearance_sign = 0;  // states where hullcheck's clearance sign contradicts is_valid
};

struct Family {
  std::string name;
  std::vector<SceneCase> scenes;
  Agreement agreement[kSetCount];
  double obstacles = 0;  // mean per scene
  std::size_t states(int set) const {
    std::size_t n = 0;
    for (const SceneCase& s : scenes) n += s.states[set].size();
    return n;
  }
};

std::vector<Family> g_families;

// Timing entries filled by the reporter: CPU ns per state of each repetition.
enum Query { kHcValid, kFclValid, kHcClearance, kFclClearance, kQueryCount };
const char* const kQueryNames[] = {"hullcheck_is_valid", "fcl_collide", "hullcheck_clearance",
                                   "fcl_distance"};
struct Entry {
  int family, set, query;
  std::vector<double> ns;
  double median() const {
    if (ns.empty()) return std::nan("");
    std::vector<double> v = ns;
    std::sort(v.begin(), v.end());
    const std::size_t m = v.size() / 2;
    return v.size() % 2 == 1 ? v[m] : 0.5 * (v[m - 1] + v[m]);
  }
};
std::map<std::string, Entry> g_entries;

std::vector<Eigen::VectorXd> random_states(const RobotModel& model, const std::vector<int>& group,
                                           const Eigen::VectorXd& start, int count, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::VectorXd lo = model.lower_limits(), hi = model.upper_limits();
  std::vector<Eigen::VectorXd> out;
  for (int k = 0; k < count; ++k) {
    Eigen::VectorXd q = start;
    for (int v : group) q[v] = lo[v] + (hi[v] - lo[v]) * unit(rng);
    out.push_back(q);
  }
  return out;
}

std::vector<Eigen::VectorXd> line_states(const Eigen::VectorXd& start, const Eigen::VectorXd& goal,
                                         int count) {
  std::vector<Eigen::VectorXd> out;
  for (int k = 0; k < count; ++k) {
    const double t = count > 1 ? static_cast<double>(k) / (count - 1) : 0.0;
    out.push_back(start + t * (goal - start));
  }
  return out;
}

void check_agreement(Family& f) {
  for (int set = 0; set < kSetCount; ++set) {
    Agreement& a = f.agreement[set];
    for (SceneCase& s : f.scenes) {
      for (const Eigen::VectorXd& q : s.states[set]) {
        const bool hc_valid = s.hc->is_valid(q);
        const bool fcl_valid = s.fcl->is_valid(q);
        const hullcheck::ClearanceResult hc_result = s.hc->clearance(q);
        const double hc_clearance = hc_result.distance;
        ++a.states;
        a.valid_hc += hc_valid ? 1 : 0;
        a.valid_fcl += fcl_valid ? 1 : 0;
        if ((hc_clearance > 0.0) != hc_valid) ++a.clearance_sign;
        if (hc_valid != fcl_valid) {
          ++a.disagreements;
          a.disagreement_clearance = std::max(a.disagreement_clearance, std::abs(hc_clearance));
          std::fprintf(stderr, "disagreement: %s %s: hullcheck %s (clearance %.3g), FCL %s\n",
                       s.name.c_str(), kSets[set], hc_valid ? "valid" : "colliding", hc_clearance,
                       fcl_valid ? "valid" : "colliding");
        } else if (hc_valid) {
          const double fcl_clearance = s.fcl->clearance(q);
          const double diff = fcl_clearance - hc_clearance;
          a.clearance_diff = std::max(a.clearance_diff, std::abs(diff));
          if (std::abs(diff) > 1e-9) {
            ++(diff < 0.0 ? a.fcl_lower : a.fcl_higher);
            a.pair_diff =
                std::max(a.pair_diff, std::abs(s.fcl->pair_distance(hc_result) - hc_clearance));
          }
        }
      }
    }
  }
}

void load(const Options& o) {
  const std::string mbm = o.shared_dir + "/benchmarks/mbm";
  const std::string robot_dir = mbm + "/robots/panda_obj";
  auto model =
      std::make_shared<const RobotModel>(RobotModel::from_urdf_file(robot_dir + "/panda.urdf"));
  const hullcheck::Srdf srdf = hullcheck::read_srdf_file(robot_dir + "/panda.srdf");
  const AllowedCollisionMatrix matrix = AllowedCollisionMatrix::from_srdf(*model, srdf);
  const std::vector<int> group = hullcheck::group_variables(*model, srdf, "panda_arm");
  for (int fi = 0; fi < static_cast<int>(std::size(kFamilies)); ++fi) {
    Family f;
    f.name = kFamilies[fi];
    const std::string dir = mbm + "/panda/" + f.name + "_panda";
    for (int k = 1; k <= o.scenes; ++k) {
      char id[16];
      std::snprintf(id, sizeof id, "%04d", k);
      const std::string scene_path = dir + "/scene" + id + ".yaml";
      const std::string request_path = dir + "/request" + id + ".yaml";
      if (!std::filesystem::exists(scene_path) || !std::filesystem::exists(request_path)) break;
      SceneCase s;
      s.name = f.name + "/" + id;
      s.hc = std::make_unique<CollisionChecker>(model, matrix,
                                                hullcheck::read_planning_scene(scene_path, *model));
      s.fcl = std::make_unique<FclChecker>(*s.hc);
      const hullcheck::MotionPlanRequest request =
          hullcheck::read_motion_plan_request(request_path, *model);
      s.states[0] = random_states(*model, group, request.start, o.states,
                                  static_cast<unsigned>(1000 * fi + k));
      s.states[1] = line_states(request.start, request.goal, o.states);
      f.obstacles += static_cast<double>(s.hc->scene().obstacles.size());
      f.scenes.push_back(std::move(s));
    }
    if (f.scenes.empty()) continue;
    f.obstacles /= static_cast<double>(f.scenes.size());
    check_agreement(f);
    g_families.push_back(std::move(f));
  }
}

// ---------------------------------------------------------------------------------------------
// Benchmarks

void run(benchmark::State& state, int family, int set, int query) {
  const Family& f = g_families[static_cast<std::size_t>(family)];
  double sink = 0.0;
  for (auto _ : state) {
    for (const SceneCase& s : f.scenes) {
      for (const Eigen::VectorXd& q : s.states[set]) {
        switch (query) {
          case kHcValid:
            sink += s.hc->is_valid(q) ? 1.0 : 0.0;
            break;
          case kFclValid:
            sink += s.fcl->is_valid(q) ? 1.0 : 0.0;
            break;
          case kHcClearance:
            sink += s.hc->clearance(q).distance;
            break;
          default:
            sink += s.fcl->clearance(q);
            break;
        }
      }
    }
  }
  benchmark::DoNotOptimize(sink);
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(f.states(set)));
}

class CollectingReporter : public benchmark::ConsoleReporter {
 public:
  CollectingReporter() : ConsoleReporter(isatty(fileno(stdout)) != 0 ? OO_Defaults : OO_Tabular) {}
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      if (run.error_occurred || run.iterations == 0 || run.run_type != Run::RT_Iteration) continue;
      auto it = g_entries.find(run.run_name.function_name);
      if (it == g_entries.end()) continue;
      Entry& e = it->second;
      const double states =
          static_cast<double>(g_families[static_cast<std::size_t>(e.family)].states(e.set));
      e.ns.push_back(run.cpu_accumulated_time * 1e9 /
                     (static_cast<double>(run.iterations) * states));
    }
    ConsoleReporter::ReportRuns(runs);
  }
};

// ---------------------------------------------------------------------------------------------
// Table

std::string fmt(double v, int precision) {
  if (std::isnan(v)) return "—";
  std::ostringstream s;
  s << std::fixed << std::setprecision(precision) << v;
  return s.str();
}

std::string fmt_ns(double ns) {
  if (std::isnan(ns)) return "—";
  return fmt(ns, ns < 100 ? 1 : 0);
}

std::string fmt_g(double v) {
  std::ostringstream s;
  s << std::setprecision(2) << v;
  return s.str();
}

double median_ns(int family, int set, int query) {
  for (const auto& [name, e] : g_entries) {
    if (e.family == family && e.set == set && e.query == query) return e.median();
  }
  return std::nan("");
}

void print_table(std::ostream& out, const Options& o, const std::string& command) {
  const RobotModel& model = g_families.front().scenes.front().hc->model();
  std::size_t shapes = 0;
  for (const hullcheck::Link& l : model.links()) shapes += l.shapes.size();
  out << "# Validity and clearance on MotionBenchMaker Panda scenes: hullcheck vs FCL\n\n";
  out << "Command: `" << command << "`"
      << (o.quick ? " (quick mode: few states, short runs; not for reporting)" : "") << "\n\n";
  out << "Robot: `benchmarks/mbm/robots/panda_obj/panda.urdf` (" << shapes
      << " collision shapes as convex hulls of the OBJ meshes, no padding), its SRDF's "
         "allowed-collision matrix plus each scene's. Scenes: the first "
      << o.scenes << " of each family (boxes and cylinders). States per scene: " << o.states
      << " random (uniform within the panda_arm limits) and " << o.states
      << " line (evenly spaced on the joint-space segment from the request's start to its "
         "goal, both included).\n\n";
  out << "Time: CPU ns per state, forward kinematics included, median over the repetitions of "
         "one run (each repetition loops over every state of the family). hullcheck: "
         "`CollisionChecker::is_valid` / `clearance` (exact signed distance of the closest or "
         "deepest checked pair). FCL 0.7: robot shapes in a `DynamicAABBTreeCollisionManager` "
         "(setTransform + computeAABB + update() per state), obstacles in a static one; "
         "`collide` robot/obstacles then robot/self with the allowed-collision matrix in the "
         "callback, stopping at the first collision; `distance` the same with `fcl::distance` "
         "per pair (GST_LIBCCD, signed), stopping at the first penetration as FCL's default "
         "callback does (hullcheck's clearance finds the deepest). Speed-up: FCL time / "
         "hullcheck time. clr/valid: hullcheck clearance time / hullcheck is_valid time. "
         "valid: fraction of states hullcheck calls valid. disagree: states where the two "
         "checkers' validity differs.\n";
  for (int set = 0; set < kSetCount; ++set) {
    out << "\n## " << (set == 0 ? "Random states" : "Line states (start to goal)") << "\n\n";
    out << "| family | obstacles | states | valid | hullcheck is_valid ns | FCL collide ns | "
           "speed-up | hullcheck clearance ns | FCL distance ns | speed-up | clr/valid | "
           "disagree |\n";
    out << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    double sum[kQueryCount] = {0, 0, 0, 0};
    int states = 0, valid = 0, disagree = 0;
    for (std::size_t fi = 0; fi < g_families.size(); ++fi) {
      const Family& f = g_families[fi];
      const Agreement& a = f.agreement[set];
      double ns[kQueryCount];
      for (int q = 0; q < kQueryCount; ++q) {
        ns[q] = median_ns(static_cast<int>(fi), set, q);
        sum[q] += ns[q] * a.states;
      }
      states += a.states;
      valid += a.valid_hc;
      disagree += a.disagreements;
      out << "| " << f.name << " | " << fmt(f.obstacles, 1) << " | " << a.states << " | "
          << fmt(static_cast<double>(a.valid_hc) / a.states, 2) << " | " << fmt_ns(ns[kHcValid])
          << " | " << fmt_ns(ns[kFclValid]) << " | " << fmt(ns[kFclValid] / ns[kHcValid], 1)
          << " | " << fmt_ns(ns[kHcClearance]) << " | " << fmt_ns(ns[kFclClearance]) << " | "
          << fmt(ns[kFclClearance] / ns[kHcClearance], 1) << " | "
          << fmt(ns[kHcClearance] / ns[kHcValid], 2) << " | " << a.disagreements << " |\n";
    }
    double mean[kQueryCount];
    for (int q = 0; q < kQueryCount; ++q) mean[q] = sum[q] / states;
    out << "| **all** | | " << states << " | " << fmt(static_cast<double>(valid) / states, 2)
        << " | " << fmt_ns(mean[kHcValid]) << " | " << fmt_ns(mean[kFclValid]) << " | "
        << fmt(mean[kFclValid] / mean[kHcValid], 1) << " | " << fmt_ns(mean[kHcClearance]) << " | "
        << fmt_ns(mean[kFclClearance]) << " | " << fmt(mean[kFclClearance] / mean[kHcClearance], 1)
        << " | " << fmt(mean[kHcClearance] / mean[kHcValid], 2) << " | " << disagree << " |\n";
  }
  out << "\n## Agreement\n\n";
  out << "Every state of both sets checked by both checkers before timing. valid: states each "
         "checker calls valid. Where both call a state valid: max |Δ|, the largest difference "
         "of the two clearances (m); FCL lower / higher, states where FCL's clearance is below / "
         "above hullcheck's by more than 1e-9 m; max |Δ pair|, at those states the largest "
         "difference between hullcheck's clearance and FCL's distance of the pair hullcheck "
         "reports as closest (`fcl::distance`, the smaller over both argument orders). FCL 0.7's "
         "libccd GJK distance depends on the argument order and can stop early: on the Panda's "
         "link5/link7 hulls the order the broad phase passes gives up to several mm too much. "
         "sign: states where hullcheck's clearance sign contradicts its own is_valid.\n\n";
  out << "| family | set | states | valid hullcheck | valid FCL | disagree | max |Δ| m | FCL "
         "lower | FCL higher | max |Δ pair| m | sign |\n";
  out << "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const Family& f : g_families) {
    for (int set = 0; set < kSetCount; ++set) {
      const Agreement& a = f.agreement[set];
      out << "| " << f.name << " | " << kSets[set] << " | " << a.states << " | " << a.valid_hc
          << " | " << a.valid_fcl << " | " << a.disagreements;
      if (a.disagreements > 0) out << " (|clearance| ≤ " << fmt_g(a.disagreement_clearance) << ")";
      out << " | " << fmt_g(a.clearance_diff) << " | " << a.fcl_lower << " | " << a.fcl_higher
          << " | " << fmt_g(a.pair_diff) << " | " << a.clearance_sign << " |\n";
    }
  }
}

Options parse_options(int& argc, char** argv) {
  Options o;
  const char* env = std::getenv("HULLCHECK_SHARED_DIR");
  o.shared_dir = env != nullptr && *env != '\0' ? env : HULLCHECK_SHARED_DIR;
  int kept = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--quick") {
      o.quick = true;
      o.scenes = 1;
      o.states = 8;
    } else if (arg.rfind("--scenes=", 0) == 0) {
      o.scenes = std::atoi(arg.c_str() + 9);
    } else if (arg.rfind("--states=", 0) == 0) {
      o.states = std::atoi(arg.c_str() + 9);
    } else if (arg.rfind("--table=", 0) == 0) {
      o.table_file = arg.substr(8);
    } else if (arg == "--help" || arg == "-h") {
      std::cout << "bench_checker [--quick] [--scenes=N] [--states=N] [--table=FILE] "
                   "[benchmark flags]\n  HULLCHECK_SHARED_DIR: directory with benchmarks/mbm "
                   "(default "
                << HULLCHECK_SHARED_DIR << ")\n";
      std::exit(0);
    } else {
      argv[kept++] = argv[i];
    }
  }
  argc = kept;
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  std::string command = "bench_checker";
  for (int i = 1; i < argc; ++i) command += std::string(" ") + argv[i];
  Options options = parse_options(argc, argv);
  // Defaults unless the caller chose: quick mode runs each benchmark for ~1 ms; a full run
  // repeats each 5 times (0.2 s each) and reports the median.
  std::vector<char*> args(argv, argv + argc);
  static char quick_min_time[] = "--benchmark_min_time=0.001";
  static char full_min_time[] = "--benchmark_min_time=0.2";
  static char full_repetitions[] = "--benchmark_repetitions=5";
  bool has_min_time = false, has_repetitions = false;
  for (int i = 1; i < argc; ++i) {
    has_min_time |= std::strncmp(argv[i], "--benchmark_min_time", 20) == 0;
    has_repetitions |= std::strncmp(argv[i], "--benchmark_repetitions", 23) == 0;
  }
  if (!has_min_time) args.push_back(options.quick ? quick_min_time : full_min_time);
  if (!options.quick && !has_repetitions) args.push_back(full_repetitions);
  int bench_argc = static_cast<int>(args.size());
  benchmark::Initialize(&bench_argc, args.data());
  if (benchmark::ReportUnrecognizedArguments(bench_argc, args.data())) return 1;

  if (!std::filesystem::exists(options.shared_dir +
                               "/benchmarks/mbm/robots/panda_obj/panda.urdf")) {
    std::cout << "bench_checker: no MotionBenchMaker Panda data under " << options.shared_dir
              << "/benchmarks/mbm; nothing to run\n";
    return 0;
  }
  load(options);
  for (int fi = 0; fi < static_cast<int>(g_families.size()); ++fi) {
    for (int set = 0; set < kSetCount; ++set) {
      for (int q = 0; q < kQueryCount; ++q) {
        const std::string name = std::string(kQueryNames[q]) + "/" +
                                 g_families[static_cast<std::size_t>(fi)].name + "/" + kSets[set];
        g_entries[name] = Entry{fi, set, q, {}};
        benchmark::RegisterBenchmark(name.c_str(), run, fi, set, q);
      }
    }
  }
  CollectingReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();

  std::ostringstream table;
  print_table(table, options, command);
  std::cout << "\n" << table.str();
  if (!options.table_file.empty()) {
    std::ofstream file(options.table_file);
    file << table.str();
    if (!file) {
      std::cerr << "bench_checker: cannot write " << options.table_file << "\n";
      return 1;
    }
  }
  int disagreements = 0;
  for (const Family& f : g_families) {
    for (const Agreement& a : f.agreement) disagreements += a.disagreements;
  }
  return disagreements == 0 ? 0 : 3;
}
