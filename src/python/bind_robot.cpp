// The robot layer in Python: RobotModel (URDF, joints, limits, forward kinematics), SRDF and
// planning groups.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <hullcheck/robot.hpp>

#include "arguments.hpp"
#include "bindings.hpp"

namespace hullcheck::python {
namespace {

RobotLoadOptions load_options(const std::map<std::string, std::string>& packages, double padding,
                              const std::map<std::string, double>& link_padding,
                              const std::string& mesh_geometry, double tolerance, int max_pieces,
                              const std::string& cache_dir, bool use_cache) {
  RobotLoadOptions o;
  o.packages = packages;
  o.default_padding = padding;
  o.link_padding = link_padding;
  if (mesh_geometry == "hull") {
    o.mesh_geometry = MeshGeometry::kHull;
  } else if (mesh_geometry == "decompose") {
    o.mesh_geometry = MeshGeometry::kDecompose;
  } else {
    throw InputError("mesh_geometry: expected 'decompose' or 'hull', got '" + mesh_geometry + "'");
  }
  o.decomposition.tolerance = tolerance;
  o.decomposition.max_pieces = max_pieces;
  o.decomposition_cache_dir = cache_dir;
  o.use_decomposition_cache = use_cache;
  return o;
}

// Every link's pose for each configuration: (links, 4, 4) or (N, links, 4, 4).
py::array forward_kinematics(const RobotModel& model, py::handle q, py::handle threads) {
  const Configurations c = configurations(q, "q", model.variable_count());
  const auto links = static_cast<py::ssize_t>(model.links().size());
  py::array_t<double> out = c.single ? py::array_t<double>({links, py::ssize_t{4}, py::ssize_t{4}})
                                     : py::array_t<double>({static_cast<py::ssize_t>(c.count),
                                                            links, py::ssize_t{4}, py::ssize_t{4}});
  double* data = out.mutable_data();
  const int n_threads = thread_count(threads, c.count);
  {
    py::gil_scoped_release release;
    parallel_chunks(c.count, n_threads, [&](Eigen::Index begin, Eigen::Index end) {
      std::vector<Eigen::Isometry3d> poses(model.links().size());
      for (Eigen::Index i = begin; i < end; ++i) {
        model.compute_link_poses_unchecked(c.data + i * c.dof, poses.data());
        double* o = data + i * links * 16;
        for (const Eigen::Isometry3d& p : poses) {
          for (int r = 0; r < 4; ++r) {
            for (int col = 0; col < 4; ++col) *o++ = p.matrix()(r, col);
          }
        }
      }
    });
  }
  return out;
}

std::vector<std::string> link_names(const RobotModel& model) {
  std::vector<std::string> names;
  for (const Link& l : model.links()) names.push_back(l.name);
  return names;
}

}  // namespace

void bind_robot(py::module_& m) {
  py::class_<Srdf>(m, "Srdf", "A MoveIt SRDF: planning groups, named states, disabled pairs.")
      .def_readonly("robot_name", &Srdf::robot_name)
      .def_property_readonly("group_names",
                             [](const Srdf& s) {
                               std::vector<std::string> names;
                               for (const SrdfGroup& g : s.groups) names.push_back(g.name);
                               return names;
                             })
      .def(
          "group_state_names",
          [](const Srdf& s, const std::string& group) {
            std::vector<std::string> names;
            for (const SrdfGroupState& g : s.group_states) {
              if (g.group == group) names.push_back(g.name);
            }
            return names;
          },
          py::arg("group"), "Names of the group's <group_state>s.")
      .def_property_readonly("disabled_collisions", [](const Srdf& s) {
        std::vector<std::tuple<std::string, std::string, std::string>> pairs;
        for (const SrdfLinkPair& p : s.disabled_collisions) {
          pairs.emplace_back(p.link1, p.link2, p.reason);
        }
        return pairs;
      });
  m.def("read_srdf", &read_srdf_file, py::arg("path"),
        "Parses an SRDF file (InputError naming the element on bad input).");
  m.def("parse_srdf", &parse_srdf, py::arg("xml"), py::arg("source_name") = "<srdf string>",
        "Parses SRDF text.");

  py::class_<RobotModel, std::shared_ptr<RobotModel>>(
      m, "RobotModel",
      "A robot loaded from URDF: links with convex collision shapes (meshes as convex pieces or "
      "one hull each) and forward kinematics. Poses are in the model frame (the URDF root "
      "link's); metres and radians. Configurations hold one value per active joint, in "
      "variable_names order. Immutable; thread-safe.")
      .def_static(
          "from_urdf",
          [](const std::string& path, const std::map<std::string, std::string>& packages,
             double padding, const std::map<std::string, double>& link_padding,
             const std::string& mesh_geometry, double tolerance, int max_pieces,
             const std::string& cache_dir, bool use_cache) {
            const RobotLoadOptions o = load_options(packages, padding, link_padding, mesh_geometry,
                                                    tolerance, max_pieces, cache_dir, use_cache);
            py::gil_scoped_release release;
            return std::make_shared<RobotModel>(RobotModel::from_urdf_file(path, o));
          },
          py::arg("path"), py::arg("packages") = std::map<std::string, std::string>{},
          py::arg("padding") = 0.0, py::arg("link_padding") = std::map<std::string, double>{},
          py::arg("mesh_geometry") = "decompose",
          py::arg("tolerance") = DecompositionOptions{}.tolerance,
          py::arg("max_pieces") = DecompositionOptions{}.max_pieces, py::arg("cache_dir") = "",
          py::arg("use_cache") = true,
          "Loads a URDF file. packages: {name: folder} for package:// URIs; padding (m) on every "
          "link, link_padding per link name; mesh_geometry 'decompose' (convex pieces within "
          "`tolerance` m of the mesh, at most max_pieces, cached in cache_dir or the default "
          "folder) or 'hull'. InputError naming the file, element and problem on bad input.")
      .def_static(
          "from_urdf_string",
          [](const std::string& xml, const std::string& base_dir,
             const std::map<std::string, std::string>& packages, double padding,
             const std::string& mesh_geometry) {
            const RobotLoadOptions o =
                load_options(packages, padding, {}, mesh_geometry, DecompositionOptions{}.tolerance,
                             DecompositionOptions{}.max_pieces, "", true);
            py::gil_scoped_release release;
            return std::make_shared<RobotModel>(RobotModel::from_urdf_string(xml, base_dir, o));
          },
          py::arg("xml"), py::arg("base_dir") = ".",
          py::arg("packages") = std::map<std::string, std::string>{}, py::arg("padding") = 0.0,
          py::arg("mesh_geometry") = "decompose",
          "Loads URDF text; relative mesh paths resolve against base_dir.")
      .def_property_readonly("name", &RobotModel::name)
      .def_property_readonly("variable_count", &RobotModel::variable_count)
      .def_property_readonly("variable_names", &RobotModel::variable_names,
                             "Active joints in configuration order.")
      .def_property_readonly("lower_limits", &RobotModel::lower_limits,
                             "Per configuration value, rad or m (-inf for continuous joints).")
      .def_property_readonly("upper_limits", &RobotModel::upper_limits)
      .def_property_readonly("link_names", &link_names, "Every link, in forward_kinematics order.")
      .def_property_readonly("joint_names",
                             [](const RobotModel& model) {
                               std::vector<std::string> names;
                               for (const Joint& j : model.joints()) names.push_back(j.name);
                               return names;
                             })
      .def_property_readonly(
          "links_with_geometry",
          [](const RobotModel& model) {
            std::vector<std::string> names;
            for (int l : model.links_with_geometry()) names.push_back(model.link(l).name);
            return names;
          },
          "Links that have collision shapes.")
      .def("default_configuration", &RobotModel::default_configuration,
           "Each value 0 when within its limits, else the middle of its range.")
      .def("variable_index", &RobotModel::variable_index, py::arg("name"),
           "Configuration index of an active joint; -1 when it is not one.")
      .def("link_index", &RobotModel::link_index, py::arg("name"))
      .def(
          "shape_count",
          [](const RobotModel& model, const std::string& link) {
            const int l = model.link_index(link);
            if (l < 0) throw InputError("link '" + link + "' is not a link of " + model.name());
            return model.link(l).shapes.size();
          },
          py::arg("link"), "Convex shapes of a link (pieces of decomposed meshes count each).")
      .def("forward_kinematics", &forward_kinematics, py::arg("q"), py::arg("threads") = 1,
           "Link poses (model frame <- link frame) as 4x4 matrices: q of shape (dof,) gives "
           "(links, 4, 4), (N, dof) gives (N, links, 4, 4). threads: 0 for every hardware "
           "thread. The GIL is released.");

  m.def(
      "group_variables",
      [](const RobotModel& model, const Srdf& srdf, const std::string& group) {
        return group_variables(model, srdf, group);
      },
      py::arg("model"), py::arg("srdf"), py::arg("group"),
      "Configuration indices of an SRDF group's active joints, in configuration order.");
  m.def(
      "group_state_configuration",
      [](const RobotModel& model, const Srdf& srdf, const std::string& group,
         const std::string& state, py::handle base) {
        const Eigen::VectorXd b =
            base.is_none()
                ? model.default_configuration()
                : Eigen::VectorXd(configurations(base, "base", model.variable_count()).row(0));
        return group_state_configuration(model, srdf, group, state, b);
      },
      py::arg("model"), py::arg("srdf"), py::arg("group"), py::arg("state"),
      py::arg("base") = py::none(),
      "A full configuration: `base` (default: the model's default) with the group state's "
      "values written in.");
}

}  // namespace hullcheck::python
