// Planning in Python as the command line does it: plan() runs one OMPL planner on a checker's
// robot and scene (certified motions by default), validate() checks every waypoint and every
// motion of a path. Both release the GIL while they work; results are plain dicts of numpy
// arrays, numbers and strings. benchmark() (hullcheck/planning.py) repeats plan().
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/util/Console.h>
#include <pybind11/stl.h>

#include <chrono>
#include <cmath>
#include <hullcheck/ompl.hpp>

#include "arguments.hpp"
#include "bindings.hpp"
#include "planner_factory.hpp"

namespace hullcheck::python {
namespace {

using Checker = std::shared_ptr<const CollisionChecker>;

/// The planned joints: None (every active joint), or a sequence of joint names or
/// configuration indices; InputError naming the unknown entry.
std::vector<int> planned_variables(const RobotModel& model, py::handle joints) {
  std::vector<int> variables;
  if (joints.is_none()) {
    for (int v = 0; v < model.variable_count(); ++v) variables.push_back(v);
    return variables;
  }
  if (py::isinstance<py::str>(joints) || !py::isinstance<py::sequence>(joints)) {
    throw InputError("joints: expected None or a list of joint names or indices");
  }
  for (py::handle item : joints) {
    int v = -1;
    if (py::isinstance<py::str>(item)) {
      const std::string name = item.cast<std::string>();
      v = model.variable_index(name);
      if (v < 0) {
        throw InputError("joints: '" + name + "' is not an active joint of robot '" + model.name() +
                         "'");
      }
    } else {
      v = item.cast<int>();
      if (v < 0 || v >= model.variable_count()) {
        throw InputError("joints: index " + std::to_string(v) + " is outside [0, " +
                         std::to_string(model.variable_count()) + ")");
      }
    }
    variables.push_back(v);
  }
  if (variables.empty()) throw InputError("joints: expected at least one joint");
  return variables;
}

/// "link_a - name_b (signed distance X m)".
std::string pair_text(const ClearanceResult& r) {
  return std::string(r.name_a) + " - " + std::string(r.name_b) + " (signed distance " +
         std::to_string(r.distance) + " m)";
}

/// The (K, dof) array of a list of configurations.
py::array_t<double> rows(const std::vector<Eigen::VectorXd>& states, int dof) {
  py::array_t<double> out({static_cast<py::ssize_t>(states.size()), static_cast<py::ssize_t>(dof)});
  double* o = out.mutable_data();
  for (const Eigen::VectorXd& q : states) {
    Eigen::Map<Eigen::VectorXd>(o, dof) = q;
    o += dof;
  }
  return out;
}

/// Everything plan() computes, filled with the GIL released.
struct PlanOutcome {
  std::string status, planner, invalid;
  bool solved = false;
  double time = 0.0, simplify_time = 0.0, length = 0.0, min_clearance = INFINITY;

  ClearanceResult closest;
  std::vector<Eigen::VectorXd> path;
  unsigned long state_checks = 0, motion_checks = 0;
};

PlanOutcome run_plan(const Checker& checker, const std::vector<int>& variables,
                     const Eigen::VectorXd& start, const Eigen::VectorXd& goal,
                     const std::string& planner, const std::string& objective, double time,
                     bool simplify, bool discrete) {
  PlanOutcome out;
  for (const auto& [q, what] : {std::pair{&start, "start"}, std::pair{&goal, "goal"}}) {
    if (!checker->is_valid(*q)) {
      out.status = std::string("invalid ") + what;
      out.invalid =
          std::string(what) + " state is in collision: " + pair_text(checker->clearance(*q));
      return out;
    }
  }
  PlanningSetup planning =
      make_planning_setup(checker, variables, start,
                          discrete ? MotionChecking::kDiscrete : MotionChecking::kGuaranteed);
  ::ompl::geometric::SimpleSetup& ss = *planning.setup;
  const auto si = ss.getSpaceInformation();
  ss.setStartAndGoalStates(planning.state(start), planning.state(goal));
  ss.setOptimizationObjective(cli::make_objective(objective, si));
  ss.setPlanner(cli::make_planner(planner, si));
  ss.setup();
  out.planner = ss.getPlanner()->getName();
  const auto t0 = std::chrono::steady_clock::now();
  const ::ompl::base::PlannerStatus status =
      ss.solve(::ompl::base::timedPlannerTerminationCondition(time));
  out.time = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  out.status = status.asString();
  out.solved = status == ::ompl::base::PlannerStatus::EXACT_SOLUTION;
  out.state_checks = planning.validity->check_count();
  if (const auto guaranteed =
          std::dynamic_pointer_cast<GuaranteedMotionValidator>(si->getMotionValidator())) {
    out.motion_checks = guaranteed->valid_motion_count() + guaranteed->invalid_motion_count();
  }
  if (!out.solved) return out;
  ::ompl::geometric::PathGeometric& path = ss.getSolutionPath();
  if (simplify) {
    const auto t1 = std::chrono::steady_clock::now();
    simplify_with_objective(si, path, ss.getOptimizationObjective(), 1.0,
                            ss.getProblemDefinition()->getGoal());
    out.simplify_time =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  }
  out.length = path.length();
  for (std::size_t i = 0; i < path.getStateCount(); ++i) {
    out.path.push_back(planning.configuration(path.getState(i)));
    const ClearanceResult r = planning.validity->closest(path.getState(i));
    if (r.distance < out.min_clearance) {
      out.min_clearance = r.distance;
      out.closest = r;
    }
  }
  return out;
}

py::dict plan(const Checker& checker, py::handle start, py::handle goal, py::handle joints,
              const std::string& planner, const std::string& objective, double time, bool simplify,
              bool discrete, bool verbose) {
  if (!checker) throw InputError("checker: expected a CollisionChecker, got None");
  const RobotModel& model = checker->model();
  const int dof = model.variable_count();
  const Configurations s = configurations(start, "start", dof),
                       g = configurations(goal, "goal", dof);
  if (!s.single || !g.single) {
    throw InputError("start, goal: expected one configuration each, shape (" + std::to_string(dof) +
                     ",)");
  }
  if (!(time > 0.0) || !std::isfinite(time)) {
    throw InputError("time: expected a finite number of seconds > 0, got " + std::to_string(time));
  }
  const std::vector<int> variables = planned_variables(model, joints);
  const Eigen::VectorXd q0 = s.row(0), q1 = g.row(0);
  PlanOutcome out;
  {
    py::gil_scoped_release release;
    ::ompl::msg::setLogLevel(verbose ? ::ompl::msg::LOG_INFO : ::ompl::msg::LOG_WARN);
    out = run_plan(checker, variables, q0, q1, planner, objective, time, simplify, discrete);
  }
  py::dict d;
  d["solved"] = out.solved;
  d["status"] = out.status;
  d["message"] = out.invalid;
  d["planner"] = out.planner;
  d["time"] = out.time;
  d["simplify_time"] = out.simplify_time;
  d["path"] = rows(out.path, dof);
  d["length"] = out.solved ? out.length : NAN;
  d["min_clearance"] = out.solved ? out.min_clearance : NAN;
  d["closest_pair"] =
      out.solved ? py::make_tuple(std::string(out.closest.name_a), std::string(out.closest.name_b))
                 : py::object(py::none());
  d["state_checks"] = out.state_checks;
  d["motion_checks"] = out.motion_checks;
  d["certified"] = !discrete;
  return d;
}

py::dict validate(const Checker& checker, py::handle path, double min_clearance,
                  double resolution) {
  if (!checker) throw InputError("checker: expected a CollisionChecker, got None");
  const RobotModel& model = checker->model();
  const Configurations c = configurations(path, "path", model.variable_count());
  if (c.single || c.count < 1) {
    throw InputError("path: expected shape (K, " + std::to_string(c.dof) + ") with K >= 1, got " +
                     shape_text(c.array));
  }
  // Every waypoint within its joints' ranges before any motion is checked (a value far outside
  // would make the motion checks crawl).
  for (Eigen::Index i = 0; i < c.count; ++i) {
    try {
      model.check_joint_ranges(c.row(i));
    } catch (const InputError& e) {
      throw InputError("path: waypoint " + std::to_string(i) + ": " + e.what());
    }
  }
  MotionCheckOptions options;
  options.min_clearance = min_clearance;
  options.resolution = resolution;
  hullcheck::validate(options, "validate: ");
  const auto k = static_cast<py::ssize_t>(c.count);
  py::array_t<bool> state_valid(k), motion_free(std::max<py::ssize_t>(0, k - 1));
  py::array_t<double> clearance(k), contact(std::max<py::ssize_t>(0, k - 1)), obstacle_clearance(k),
      self_clearance(k);
  std::vector<ClearanceResult> closest(static_cast<std::size_t>(k));
  bool *sv = state_valid.mutable_data(), *mf = motion_free.mutable_data();
  double *cl = clearance.mutable_data(), *ct = contact.mutable_data(),
         *oc = obstacle_clearance.mutable_data(), *sc = self_clearance.mutable_data();
  bool valid = true;
  {
    py::gil_scoped_release release;
    for (Eigen::Index i = 0; i < c.count; ++i) {
      sv[i] = checker->is_valid(c.row(i));
      closest[static_cast<std::size_t>(i)] = checker->clearance(c.row(i));
      cl[i] = closest[static_cast<std::size_t>(i)].distance;
      oc[i] = checker->clearance(c.row(i), ClearanceScope::kObstacles).distance;
      sc[i] = checker->clearance(c.row(i), ClearanceScope::kSelf).distance;
      valid = valid && sv[i];
      if (i + 1 == c.count) break;
      const MotionCheckResult m = checker->check_motion(c.row(i), c.row(i + 1), options);
      mf[i] = m.free();
      ct[i] = m.free() ? 1.0 : m.contact;
      valid = valid && mf[i];
    }
  }
  py::list names_a, names_b;
  for (const ClearanceResult& r : closest) {
    names_a.append(std::string(r.name_a));
    names_b.append(std::string(r.name_b));
  }
  py::dict d;
  d["valid"] = valid;
  d["state_valid"] = state_valid;
  d["clearance"] = clearance;
  d["obstacle_clearance"] = obstacle_clearance;
  d["self_clearance"] = self_clearance;
  d["name_a"] = names_a;
  d["name_b"] = names_b;
  d["motion_free"] = motion_free;
  d["contact"] = contact;
  return d;
}

/// The OMPL path of the full configurations `c` in `planning`'s space; InputError when a
/// row moves a joint that is not planned (the space holds those at the first row's values).
::ompl::geometric::PathGeometric to_ompl_path(const PlanningSetup& planning,
                                              const Configurations& c,
                                              const std::vector<int>& variables) {
  const RobotModel& model = planning.validity->collision_checker().model();
  std::vector<bool> planned(static_cast<std::size_t>(c.dof), false);
  for (int v : variables) planned[static_cast<std::size_t>(v)] = true;
  ::ompl::geometric::PathGeometric path(planning.setup->getSpaceInformation());
  for (Eigen::Index i = 0; i < c.count; ++i) {
    for (int v = 0; v < c.dof; ++v) {
      if (!planned[static_cast<std::size_t>(v)] && c.row(i)[v] != c.row(0)[v]) {
        throw InputError("path: waypoint " + std::to_string(i) + " moves joint '" +
                         model.variable_names()[static_cast<std::size_t>(v)] +
                         "', which is not among the optimized joints");
      }
    }
    path.append(planning.state(c.row(i)).get());
  }
  return path;
}

py::dict optimize_clearance(const Checker& checker, py::handle path, py::handle joints,
                            double margin, double length_weight, double time,
                            const std::string& scope_name) {
  if (!checker) throw InputError("checker: expected a CollisionChecker, got None");
  const RobotModel& model = checker->model();
  const Configurations c = configurations(path, "path", model.variable_count());
  if (c.single || c.count < 2) {
    throw InputError("path: expected shape (K, " + std::to_string(c.dof) + ") with K >= 2, got " +
                     shape_text(c.array));
  }
  ClearanceOptimizationOptions options;
  options.margin = margin;
  options.length_weight = length_weight;
  options.time = time;
  const std::vector<int> variables = planned_variables(model, joints);
  PlanningSetup planning = make_planning_setup(checker, variables, c.row(0));
  const auto si = planning.setup->getSpaceInformation();
  si->setup();
  ::ompl::geometric::PathGeometric ompl_path = to_ompl_path(planning, c, variables);
  std::vector<Eigen::VectorXd> states;
  ClearanceOptimizationResult result;
  std::size_t scope_pairs = 0;
  if (scope_name != "auto" && scope_name != "all" && scope_name != "obstacles" &&
      scope_name != "self") {
    throw InputError("scope: expected 'auto', 'all', 'obstacles' or 'self', got '" + scope_name +
                     "'");
  }
  if (!(margin > 0.0) || !std::isfinite(margin)) {
    throw InputError("margin: expected a finite distance > 0 m, got " + std::to_string(margin));
  }
  {
    py::gil_scoped_release release;
    // Obstacles and the self pairs the joints can move and clear of the margin, or a fixed
    // scope by name.
    auto scope = std::make_shared<PairScope>(
        scope_name == "auto" ? optimization_scope(*checker, variables, c.row(0), margin)
                             : checker->pair_scope(clearance_scope(scope_name)));
    scope_pairs = scope->self_link_pairs().size();
    planning.validity->set_clearance_scope(scope);
    // The optimizer keeps a valid path valid: it must start from one.
    const std::size_t count = ompl_path.getStateCount();
    for (std::size_t i = 0; i < count; ++i) {
      const bool state_free = si->isValid(ompl_path.getState(i));
      if (state_free &&
          (i + 1 == count || si->checkMotion(ompl_path.getState(i), ompl_path.getState(i + 1)))) {
        continue;
      }
      throw InputError("path: " +
                       (state_free ? "motion " + std::to_string(i) + " -> " +
                                         std::to_string(i + 1) + " is not free"
                                   : "waypoint " + std::to_string(i) + " is in collision") +
                       "; optimize_clearance takes a valid path (see validate)");
    }
    result = hullcheck::optimize_clearance(si, *planning.validity, ompl_path, options);
    for (std::size_t i = 0; i < ompl_path.getStateCount(); ++i) {
      states.push_back(planning.configuration(ompl_path.getState(i)));
    }
  }
  py::dict d;
  d["path"] = rows(states, c.dof);
  d["changed"] = result.changed;
  d["cost_before"] = result.cost_before;
  d["cost"] = result.cost_after;
  d["length_before"] = result.length_before;
  d["length"] = result.length_after;
  d["min_clearance_before"] = result.min_clearance_before;
  d["min_clearance"] = result.min_clearance_after;
  d["self_pairs"] = scope_pairs;
  d["rounds"] = result.rounds;
  d["moves"] = result.moves;
  d["refined"] = result.refined;
  d["seconds"] = result.seconds;
  return d;
}

}  // namespace

void bind_planning(py::module_& m) {
  m.def("plan", &plan, py::arg("checker"), py::arg("start"), py::arg("goal"),
        py::arg("joints") = py::none(), py::arg("planner") = "RRTConnect",
        py::arg("objective") = "length", py::arg("time") = 10.0, py::arg("simplify") = false,
        py::arg("discrete") = false, py::arg("verbose") = false,
        R"(Plans from `start` to `goal` (full configurations, shape (dof,)) with an OMPL planner.

joints: the planned joints (names or configuration indices; None: every active joint); the
others stay at their values in `start`. planner: an OMPL geometric planner by name
('RRTConnect', 'RRT*', 'BIT*', 'PRM*', 'KPIECE1', ...). objective: 'length', 'clearance',
'clearance-cost' or 'length+clearance'. time: seconds. simplify: objective-aware shortcuts
after solving (up to 1 s). discrete: check motions at OMPL's sampled states instead of
certifying them (faster; the path is NOT certified between states). The GIL is released.

Returns a dict: 'solved' (bool), 'status' (OMPL's status, or 'invalid start' / 'invalid
goal' with 'message' naming the colliding pair), 'planner', 'time' and 'simplify_time' (s),
'path' (K, dof) full configurations, 'length' (OMPL's metric of the planned joints: Euclidean
over the bounded joints plus the wrapped angle of each continuous one), 'min_clearance' (m, over
waypoints) and 'closest_pair' (names), 'state_checks', 'motion_checks', 'certified'.)");
  m.def("validate", &validate, py::arg("checker"), py::arg("path"),
        py::arg("min_clearance") = MotionCheckOptions{}.min_clearance,
        py::arg("resolution") = MotionCheckOptions{}.resolution,
        R"(Checks a path (K, dof) of full configurations: every waypoint and every straight
motion between consecutive waypoints (certified everywhere, CollisionChecker.check_motion with
min_clearance and resolution in m). InputError when a waypoint is outside its joint ranges.

Returns a dict: 'valid' (bool), 'state_valid' (K,) bool, 'clearance' (K,) m with the closest
pair's names 'name_a', 'name_b' (lists), 'obstacle_clearance' and 'self_clearance' (K,) m (the
minimum over robot-obstacle pairs and over self pairs; inf without any), 'motion_free' (K-1,) bool and 'contact' (K-1,): the
fraction of each motion at its first contact (1.0 when free).)");
  m.def("optimize_clearance", &optimize_clearance, py::arg("checker"), py::arg("path"),
        py::arg("joints") = py::none(), py::arg("margin") = ClearanceOptimizationOptions{}.margin,
        py::arg("length_weight") = ClearanceOptimizationOptions{}.length_weight,
        py::arg("time") = ClearanceOptimizationOptions{}.time, py::arg("scope") = "auto",
        R"(Optimizes a valid path (K >= 2, dof) of full configurations for clearance with
hullcheck's optimizer (C++ optimize_clearance): the cost is the path's joint-space length times
length_weight plus, along the path, max(0, margin - d) / margin for the clearance d (m) over the
scope's pairs; waypoints move along exact signed-distance gradients, interleaved with shortcuts,
every motion certified. The result is never costlier than the input and never uncertified; start
and goal never move. joints: the joints that may move (None: every active joint; a joint not
listed must hold one value along the path). margin: m, > 0. length_weight: >= 0. time: s, the
budget (the optimizer stops earlier when a round changes nothing). scope: 'auto' (obstacles and
the self pairs those joints move and can take clear of the margin, approaching_self_pairs),
'all', 'obstacles' or 'self'. InputError when the path is not valid or an option is bad. The GIL
is released.

Returns a dict: 'path' (K', dof), 'changed' (bool: False when the input is returned), 'cost_before'
and 'cost', 'length_before' and 'length' (joint-space), 'min_clearance_before' and
'min_clearance' (m, the scope's minimum over the waypoints), 'self_pairs' (self link pairs in
the scope), 'rounds', 'moves' (accepted waypoint moves), 'refined' (waypoints added where
motions dipped below the margin), 'seconds'.)");
}

}  // namespace hullcheck::python
