// The scene layer in Python: MoveIt scenes and requests, and CollisionChecker with its batch
// entry points over (N, dof) arrays (validity, clearance with pairs and witnesses, clearance
// gradients), run with the GIL released on an optional number of threads.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <hullcheck/scene.hpp>
#include <limits>

#include "arguments.hpp"
#include "bindings.hpp"

namespace hullcheck::python {
namespace {

/// A ClearanceResult that owns its names (the C++ one views the checker's strings).
struct Clearance {
  double distance = 0.0;
  bool self_collision = false;
  std::string name_a, name_b;
  Eigen::Vector3d point_a{0, 0, 0}, point_b{0, 0, 0}, normal{0, 0, 0};
  Status status = Status::kConverged;
};

Clearance owned(const ClearanceResult& r) {
  return Clearance{
      r.distance, r.self,  std::string(r.name_a), std::string(r.name_b), r.point_a, r.point_b,
      r.normal,   r.status};
}

std::shared_ptr<const CollisionChecker> make_checker(std::shared_ptr<RobotModel> model,
                                                     py::handle srdf, py::handle scene) {
  if (!model) throw InputError("model: expected a RobotModel, got None");
  Srdf parsed;
  if (py::isinstance<py::str>(srdf)) {
    parsed = read_srdf_file(srdf.cast<std::string>());
  } else if (!srdf.is_none()) {
    parsed = srdf.cast<Srdf>();
  }
  PlanningScene world;
  if (py::isinstance<py::str>(scene)) {
    world = read_planning_scene(scene.cast<std::string>(), *model);
  } else if (!scene.is_none()) {
    world = scene.cast<PlanningScene>();
  }
  AllowedCollisionMatrix acm = srdf.is_none() ? AllowedCollisionMatrix::from_adjacency(*model)
                                              : AllowedCollisionMatrix::from_srdf(*model, parsed);
  py::gil_scoped_release release;
  return std::make_shared<const CollisionChecker>(std::move(model), std::move(acm),
                                                  std::move(world));
}

py::object is_valid(const CollisionChecker& checker, py::handle q, py::handle threads) {
  const Configurations c = configurations(q, "q", checker.model().variable_count());
  if (c.single) {
    py::gil_scoped_release release;
    const bool valid = checker.is_valid(c.row(0));
    py::gil_scoped_acquire acquire;
    return py::bool_(valid);
  }
  py::array_t<bool> out(static_cast<py::ssize_t>(c.count));
  bool* valid = out.mutable_data();
  const int n_threads = thread_count(threads, c.count);
  {
    py::gil_scoped_release release;
    parallel_chunks(c.count, n_threads, [&](Eigen::Index begin, Eigen::Index end) {
      const Eigen::Map<const Eigen::MatrixXd> block(c.data + begin * c.dof, c.dof, end - begin);
      checker.is_valid_batch(block, valid + begin);
    });
  }
  return std::move(out);
}

py::object clearance_lower_bound(const CollisionChecker& checker, py::handle q, double exact_below,
                                 py::handle threads) {
  const Configurations c = configurations(q, "q", checker.model().variable_count());
  py::array_t<double> out(static_cast<py::ssize_t>(c.count));
  double* lower = out.mutable_data();
  const int n_threads = thread_count(threads, c.count);
  {
    py::gil_scoped_release release;
    parallel_chunks(c.count, n_threads, [&](Eigen::Index begin, Eigen::Index end) {
      const Eigen::Map<const Eigen::MatrixXd> block(c.data + begin * c.dof, c.dof, end - begin);
      checker.clearance_lower_bound_batch(block, exact_below, lower + begin);
    });
  }
  if (c.single) return py::float_(lower[0]);
  return std::move(out);
}

py::object clearance(const CollisionChecker& checker, py::handle q, py::handle threads,
                     const std::string& scope_name, double below) {
  const ClearanceScope scope = clearance_scope(scope_name);
  const Configurations c = configurations(q, "q", checker.model().variable_count());
  if (c.single) {
    ClearanceResult r;
    {
      py::gil_scoped_release release;
      r = checker.clearance(c.row(0), scope, below);
    }
    return py::cast(owned(r));
  }
  const auto n = static_cast<py::ssize_t>(c.count);
  py::array_t<double> distance(n), point_a({n, py::ssize_t{3}}), point_b({n, py::ssize_t{3}}),
      normal({n, py::ssize_t{3}});
  py::array_t<bool> self(n);
  std::vector<std::string_view> name_a(static_cast<std::size_t>(n)),
      name_b(static_cast<std::size_t>(n));
  double *d = distance.mutable_data(), *pa = point_a.mutable_data(), *pb = point_b.mutable_data(),
         *nm = normal.mutable_data();
  bool* s = self.mutable_data();
  const int n_threads = thread_count(threads, c.count);
  {
    py::gil_scoped_release release;
    parallel_chunks(c.count, n_threads, [&](Eigen::Index begin, Eigen::Index end) {
      for (Eigen::Index i = begin; i < end; ++i) {
        const ClearanceResult r = checker.clearance(c.row(i), scope, below);
        d[i] = r.distance;
        s[i] = r.self;
        for (int k = 0; k < 3; ++k) {
          pa[3 * i + k] = r.point_a[k];
          pb[3 * i + k] = r.point_b[k];
          nm[3 * i + k] = r.normal[k];
        }
        name_a[static_cast<std::size_t>(i)] = r.name_a;
        name_b[static_cast<std::size_t>(i)] = r.name_b;
      }
    });
  }
  py::list names_a(n), names_b(n);
  for (py::ssize_t i = 0; i < n; ++i) {
    names_a[static_cast<std::size_t>(i)] = py::str(name_a[static_cast<std::size_t>(i)].data(),
                                                   name_a[static_cast<std::size_t>(i)].size());
    names_b[static_cast<std::size_t>(i)] = py::str(name_b[static_cast<std::size_t>(i)].data(),
                                                   name_b[static_cast<std::size_t>(i)].size());
  }
  py::dict out;
  out["distance"] = distance;
  out["self_collision"] = self;
  out["name_a"] = names_a;
  out["name_b"] = names_b;
  out["point_a"] = point_a;
  out["point_b"] = point_b;
  out["normal"] = normal;
  return std::move(out);
}

py::object gradient(const CollisionChecker& checker, py::handle q, py::handle threads,
                    const std::string& scope_name) {
  const ClearanceScope scope = clearance_scope(scope_name);
  const RobotModel& model = checker.model();
  const int dof = model.variable_count();
  const Configurations c = configurations(q, "q", dof);
  py::array_t<double> out =
      c.single
          ? py::array_t<double>(dof)
          : py::array_t<double>({static_cast<py::ssize_t>(c.count), static_cast<py::ssize_t>(dof)});
  double* g = out.mutable_data();
  const int n_threads = thread_count(threads, c.count);
  {
    py::gil_scoped_release release;
    parallel_chunks(c.count, n_threads, [&](Eigen::Index begin, Eigen::Index end) {
      std::vector<Eigen::Isometry3d> poses(model.links().size());
      for (Eigen::Index i = begin; i < end; ++i) {
        model.compute_link_poses_unchecked(c.data + i * dof, poses.data());
        const Eigen::VectorXd row =
            clearance_gradient(model, poses, checker.clearance_at(poses, scope));
        Eigen::Map<Eigen::VectorXd>(g + i * dof, dof) = row;
      }
    });
  }
  return std::move(out);
}

MotionCheckResult check_motion(const CollisionChecker& checker, py::handle q0, py::handle q1,
                               double min_clearance, double resolution, int max_states,
                               bool locate_contact) {
  const int dof = checker.model().variable_count();
  const Configurations a = configurations(q0, "q0", dof), b = configurations(q1, "q1", dof);
  if (!a.single || !b.single) {
    throw InputError("q0, q1: expected one configuration each, shape (" + std::to_string(dof) +
                     ",)");
  }
  MotionCheckOptions options;
  options.min_clearance = min_clearance;
  options.resolution = resolution;
  options.max_states = max_states;
  options.locate_contact = locate_contact;
  py::gil_scoped_release release;
  return checker.check_motion(a.row(0), b.row(0), options);
}

const char* verdict_name(MotionVerdict v) {
  switch (v) {
    case MotionVerdict::kFree:
      return "free";
    case MotionVerdict::kContact:
      return "contact";
    case MotionVerdict::kNearContact:
      return "near_contact";
    case MotionVerdict::kStateBudget:
      return "state_budget";
  }
  return "?";
}

}  // namespace

void bind_scene(py::module_& m) {
  py::class_<Obstacle>(m, "Obstacle", "A static convex obstacle, posed in the model frame.")
      .def_readonly("name", &Obstacle::name)
      .def_readonly("object", &Obstacle::object)
      .def_readonly("shape", &Obstacle::shape)
      .def_property_readonly("pose",
                             [](const Obstacle& o) { return Eigen::Matrix4d(o.pose.matrix()); })
      .def_readonly("source", &Obstacle::source);
  py::class_<PlanningScene>(m, "PlanningScene", "Static obstacles and the scene's allowed pairs.")
      .def(py::init<>())
      .def_readonly("name", &PlanningScene::name)
      .def_readonly("obstacles", &PlanningScene::obstacles)
      .def_readonly("allowed_pairs", &PlanningScene::allowed_pairs)
      .def_property_readonly("robot_joint_values", [](const PlanningScene& s) {
        return std::map<std::string, double>(s.robot_joint_values.begin(),
                                             s.robot_joint_values.end());
      });
  m.def("read_planning_scene", &read_planning_scene, py::arg("path"), py::arg("model"),
        "Reads a MoveIt PlanningScene YAML file (obstacles in the model frame, metres).");
  m.def("parse_planning_scene", &parse_planning_scene, py::arg("yaml"), py::arg("model"),
        py::arg("source_name") = "<scene string>", "The same from YAML text.");

  py::class_<MotionPlanRequest>(m, "MotionPlanRequest",
                                "Start and joint-space goal (full configurations) of a problem.")
      .def_readonly("group", &MotionPlanRequest::group)
      .def_readonly("start", &MotionPlanRequest::start)
      .def_readonly("goal", &MotionPlanRequest::goal)
      .def_readonly("goal_variables", &MotionPlanRequest::goal_variables)
      .def_readonly("allowed_planning_time", &MotionPlanRequest::allowed_planning_time);
  m.def("read_motion_plan_request", &read_motion_plan_request, py::arg("path"), py::arg("model"),
        "Reads a MoveIt MotionPlanRequest YAML file.");

  py::class_<Clearance>(m, "Clearance",
                        "The closest (or deepest) checked pair at a configuration: signed "
                        "distance (m, < 0 overlapping), names, witnesses (model frame).")
      .def_readonly("distance", &Clearance::distance)
      .def_readonly("self_collision", &Clearance::self_collision,
                    "True: robot against robot; False: robot against an obstacle.")
      .def_readonly("name_a", &Clearance::name_a, "Link of A.")
      .def_readonly("name_b", &Clearance::name_b, "Link (self) or obstacle of B.")
      .def_readonly("point_a", &Clearance::point_a)
      .def_readonly("point_b", &Clearance::point_b)
      .def_readonly("normal", &Clearance::normal, "Unit, from A to B.")
      .def_readonly("status", &Clearance::status)
      .def("__repr__", [](const Clearance& c) {
        return "Clearance(" + c.name_a + " - " + c.name_b +
               ", distance=" + std::to_string(c.distance) + ")";
      });

  py::class_<MotionCheckResult>(m, "MotionCheck", "Result of CollisionChecker.check_motion.")
      .def_property_readonly(
          "verdict", [](const MotionCheckResult& r) { return verdict_name(r.verdict); },
          "'free', 'contact', 'near_contact' or 'state_budget'.")
      .def_property_readonly("free", &MotionCheckResult::free)
      .def_readonly("last_free", &MotionCheckResult::last_free,
                    "[0, last_free] of the motion is proven free.")
      .def_readonly("contact", &MotionCheckResult::contact,
                    "Fraction of the first contact found (1 when free).")
      .def_readonly("states", &MotionCheckResult::states)
      .def_readonly("exact_queries", &MotionCheckResult::exact_queries);

  py::class_<CollisionChecker, std::shared_ptr<CollisionChecker>>(
      m, "CollisionChecker",
      "Checks configurations of a robot against its enabled self pairs (the SRDF's collision "
      "matrix, else adjacency) and a static scene's obstacles. Batch methods take q of shape "
      "(dof,) or (N, dof), release the GIL and split N over `threads` (0: every hardware "
      "thread). Thread-safe.")
      .def(py::init([](std::shared_ptr<RobotModel> model, py::handle srdf, py::handle scene) {
             return std::const_pointer_cast<CollisionChecker>(make_checker(model, srdf, scene));
           }),
           py::arg("model"), py::arg("srdf") = py::none(), py::arg("scene") = py::none(),
           "srdf: an SRDF path or Srdf (None: adjacent links allowed only); scene: a MoveIt "
           "scene YAML path or PlanningScene (None: no obstacles).")
      .def_property_readonly(
          "model",
          // RobotModel is immutable from Python: sharing it without const is safe.
          [](const CollisionChecker& c) {
            return std::const_pointer_cast<RobotModel>(c.shared_model());
          },
          "The robot model (shared with the checker).")
      .def_property_readonly("scene", &CollisionChecker::scene)
      .def("is_valid", &is_valid, py::arg("q"), py::arg("threads") = 1,
           "True when no checked pair overlaps: a bool for q (dof,), a bool array (N,) for "
           "(N, dof) (blocks vectorised across configurations, identical verdicts).")
      .def("clearance", &clearance, py::arg("q"), py::arg("threads") = 1, py::arg("scope") = "all",
           py::arg("below") = std::numeric_limits<double>::infinity(),
           "Minimum signed distance over the checked pairs, m, with the pair and witnesses: a "
           "Clearance for q (dof,); for (N, dof) a dict of arrays 'distance' (N,), "
           "'self_collision' (N,), 'point_a', 'point_b', 'normal' (N, 3) and lists 'name_a', "
           "'name_b'. scope: 'all', 'obstacles' (robot-obstacle pairs only) or 'self' (self "
           "pairs only); inf when the scope has no pair. below (m): a cap for callers needing "
           "only clearances under it: the same answer below it, inf (no pair) at or above it, "
           "faster far from contact.")
      .def("clearance_lower_bound", &clearance_lower_bound, py::arg("q"),
           py::arg("exact_below") = 0.0, py::arg("threads") = 1,
           "Lower bounds on clearance() over every checked pair, m: a float for q (dof,), an "
           "array (N,) for (N, dof). Exact (clearance()'s value) wherever the bound is below "
           "max(exact_below, 0); elsewhere a bound from covering spheres, vectorised across "
           "blocks of configurations, never above the clearance. A value above r proves the "
           "configuration r clear.")
      .def("clearance_gradient", &gradient, py::arg("q"), py::arg("threads") = 1,
           py::arg("scope") = "all",
           "d(clearance)/dq of the closest pair in `scope` (m/rad or m/m), witnesses and normal "
           "held fixed: (dof,) or (N, dof). Moving q along it increases that pair's distance.")
      .def("check_motion", &check_motion, py::arg("q0"), py::arg("q1"),
           py::arg("min_clearance") = MotionCheckOptions{}.min_clearance,
           py::arg("resolution") = MotionCheckOptions{}.resolution,
           py::arg("max_states") = MotionCheckOptions{}.max_states,
           py::arg("locate_contact") = true,
           "Proves the straight joint-space motion q0 -> q1 free everywhere (not at samples), "
           "or finds its first contact (within `resolution` m of travel).")
      .def(
          "measure_self_tables",
          [](const CollisionChecker& c, const py::object& threads) {
            const int n = thread_count(threads, std::numeric_limits<int>::max());
            py::gil_scoped_release release;
            c.measure_self_tables(n);
          },
          py::arg("threads") = 0,
          "Measures the self-collision distance tables once per model (faster checks after), "
          "on `threads` threads (0: one per hardware thread).")
      .def(
          "checked_link_pairs",
          [](const CollisionChecker& c) {
            std::vector<std::pair<std::string, std::string>> out;
            for (const auto& [a, b] : c.checked_link_pairs()) {
              out.emplace_back(c.model().link(a).name, c.model().link(b).name);
            }
            return out;
          },
          "The robot's link pairs that are checked (names).");
}

}  // namespace hullcheck::python
