#include "validate_command.hpp"

#include <ompl/util/Console.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "clearance_plot.hpp"
#include "exit_codes.hpp"
#include "html_viewer.hpp"
#include "path_file.hpp"
#include "problem.hpp"

namespace hullcheck::cli {
namespace {

struct ValidateSettings {
  WorldOptions world;
  std::string request;
  std::string path;
  std::string plot;
  std::string viewer;
  int samples_per_motion = 20;
};

// The values of the joints the path does not move: those the path file holds (as planning held
// them); for the others, the request's start state with --request (as `plan --request` plans
// from it), else the scene's robot state, else the default configuration. A held value that
// the request's start contradicts is an error: the path was not planned for that request.
Eigen::VectorXd held_configuration(const ValidateSettings& s, const LoadedWorld& world,
                                   const JointPath& path) {
  const RobotModel& model = *world.model;
  Eigen::VectorXd base = model.default_configuration();
  if (!s.request.empty()) {
    base = read_motion_plan_request(s.request, model).start;
  } else {
    for (const auto& [name, value] : world.checker->scene().robot_joint_values) {
      const int v = model.variable_index(name);
      if (v >= 0) base[v] = value;
    }
  }
  for (const auto& [name, value] : path.held) {
    const int v = model.variable_index(name);
    if (v < 0) {
      throw InputError("path '" + s.path + "': held joint '" + name +
                       "' is not an active joint of robot '" + model.name() + "'");
    }
    if (!s.request.empty() && std::abs(base[v] - value) > 1e-9) {
      throw InputError("path '" + s.path + "' holds '" + name + "' at " + std::to_string(value) +
                       ", request '" + s.request + "' starts it at " + std::to_string(base[v]) +
                       ": the path was not planned for this request");
    }
    base[v] = value;
  }
  return base;
}

void run(const ValidateSettings& s) {
  ::ompl::msg::setLogLevel(::ompl::msg::LOG_WARN);
  const LoadedWorld world = s.world.load();
  const RobotModel& model = *world.model;
  const JointPath path = read_joint_path(s.path);
  std::vector<int> variables;
  for (const std::string& name : path.joint_names) {
    const int v = model.variable_index(name);
    if (v < 0) {
      throw InputError("path '" + s.path + "': '" + name + "' is not an active joint of robot '" +
                       model.name() + "'");
    }
    variables.push_back(v);
  }
  const Eigen::VectorXd base = held_configuration(s, world, path);
  const auto full = [&](const Eigen::VectorXd& row) {
    Eigen::VectorXd q = base;
    for (std::size_t k = 0; k < variables.size(); ++k)
      q[variables[k]] = row[static_cast<Eigen::Index>(k)];
    return q;
  };
  // Every waypoint within its joints' ranges before any motion is checked: a value far
  // outside would make the motion checks crawl.
  for (std::size_t i = 0; i < path.waypoints.size(); ++i) {
    try {
      for (std::size_t k = 0; k < variables.size(); ++k) {
        model.check_joint_range(variables[k], path.waypoints[i][static_cast<Eigen::Index>(k)]);
      }
    } catch (const InputError& e) {
      throw InputError("path '" + s.path + "': waypoint " + std::to_string(i) + ": " + e.what());
    }
  }
  PlanningSetup planning = make_planning_setup(world.checker, variables, base);
  const auto si = planning.setup->getSpaceInformation();
  si->setup();

  bool valid = true;
  std::printf("%4s  %-8s %12s  %s\n", "#", "state", "clearance", "closest pair");
  std::vector<ClearanceSample> profile;
  std::vector<Eigen::VectorXd> frames;
  double position = 0.0;
  ::ompl::base::ScopedState<> from(si), to(si), mid(si);
  for (std::size_t i = 0; i < path.waypoints.size(); ++i) {
    const Eigen::VectorXd q = full(path.waypoints[i]);
    const bool ok = world.checker->is_valid(q);
    const ClearanceResult r = world.checker->clearance(q);
    valid = valid && ok;
    std::printf("%4zu  %-8s %12.6f  %s - %s\n", i, ok ? "valid" : "INVALID", r.distance,
                std::string(r.name_a).c_str(), std::string(r.name_b).c_str());
    profile.push_back({position, r.distance, true});
    frames.push_back(q);
    if (i + 1 == path.waypoints.size()) break;
    planning.joints->from_configuration(q, from.get());
    planning.joints->from_configuration(full(path.waypoints[i + 1]), to.get());
    std::pair<::ompl::base::State*, double> last(nullptr, 0.0);
    if (!si->getMotionValidator()->checkMotion(from.get(), to.get(), last)) {
      valid = false;
      std::printf("      motion %zu -> %zu: INVALID after %.1f%% of it\n", i, i + 1,
                  100.0 * last.second);
    }
    const double segment = si->distance(from.get(), to.get());
    for (int k = 1; k < s.samples_per_motion; ++k) {
      const double t = static_cast<double>(k) / s.samples_per_motion;
      si->getStateSpace()->interpolate(from.get(), to.get(), t, mid.get());
      profile.push_back({position + t * segment, planning.validity->clearance(mid.get()), false});
      frames.push_back(planning.configuration(mid.get()));
    }
    position += segment;
  }
  std::printf("path %s: %zu waypoints, %zu motions checked (guaranteed mode)\n",
              valid ? "VALID" : "INVALID", path.waypoints.size(), path.waypoints.size() - 1);
  // Minimum clearance per scope over the sampled states (waypoints and the profile's states
  // between them): the obstacle clearance is not hidden by a self pair that stays close.
  std::printf("min clearance over %zu states (waypoints and %d per motion):\n", frames.size(),
              s.samples_per_motion - 1);
  for (const auto& [scope, name] : {std::pair{ClearanceScope::kObstacles, "obstacles"},
                                    std::pair{ClearanceScope::kSelf, "self"}}) {
    ClearanceResult closest;
    for (const Eigen::VectorXd& q : frames) {
      const ClearanceResult r = world.checker->clearance(q, scope);
      if (r.distance < closest.distance) closest = r;
    }
    if (std::isinf(closest.distance)) {
      std::printf("  %-9s none checked\n", name);
    } else {
      std::printf("  %-9s %.6f m  %s - %s\n", name, closest.distance,
                  std::string(closest.name_a).c_str(), std::string(closest.name_b).c_str());
    }
  }
  if (!s.plot.empty()) {
    write_clearance_svg(s.plot, "clearance along " + s.path, profile);
    std::printf("clearance profile written to %s\n", s.plot.c_str());
  }
  if (!s.viewer.empty()) {
    write_html_viewer(s.viewer, "hullcheck validate: " + s.path, model, world.checker->scene(),
                      frames);
    std::printf("viewer written to %s\n", s.viewer.c_str());
  }
  if (!valid) throw ExitWith{kExitInvalidProblem};
}

}  // namespace

void add_validate_command(CLI::App& app) {
  auto s = std::make_shared<ValidateSettings>();
  CLI::App* command = app.add_subcommand(
      "validate",
      "Check every waypoint and every motion of a path (guaranteed mode): validity, clearance, "
      "closest pair");
  s->world.add_to(*command, true);
  command->add_option("--path", s->path, "Path file (CSV with a joint-name header, or .json)")
      ->required();
  command->add_option("--request", s->request,
                      "MotionPlanRequest the path was planned for: its start state gives the "
                      "joints the path neither moves nor holds (default: the scene's robot state)");
  command->add_option("--plot", s->plot, "Write the clearance profile as an SVG plot");
  command->add_option("--viewer", s->viewer,
                      "Write a self-contained HTML page animating the path in 3D");
  command->footer("Exit status: 0 valid, 1 bad input, 2 the path is invalid.");
  command->callback([s] { run(*s); });
}

}  // namespace hullcheck::cli
