// Bad robot input: every case is an InputError whose message names the file, the element and
// the problem. Never a crash, never a silent wrong model.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/robot/robot_model.hpp>
#include <initializer_list>
#include <limits>
#include <random>
#include <string>

#include "robot_test_support.hpp"

namespace hullcheck {
namespace {

namespace fs = std::filesystem;

using test::expect_contains;
using test::input_error_of;
using test::TempDir;

// A URDF with one link `body` holding `collision` (a <collision> body or ""), joined to a root
// link by `joint` (a <joint> element or "" for a single-link robot).
std::string urdf_with(const std::string& collision, const std::string& joint = "",
                      const std::string& extra_links = "") {
  std::string xml = R"(<?xml version="1.0"?>
<robot name="probe">
  <link name="root">
    <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
  </link>
  <link name="body">
)";
  xml += collision;
  xml += "  </link>\n";
  xml += extra_links;
  if (joint.empty()) {
    xml += R"(  <joint name="hold" type="fixed"><parent link="root"/><child link="body"/></joint>
)";
  } else {
    xml += joint;
  }
  xml += "</robot>\n";
  return xml;
}

std::string mesh_collision(const std::string& uri) {
  return "    <collision><geometry><mesh filename=\"" + uri + "\"/></geometry></collision>\n";
}

const char* const kRevolute = R"(  <joint name="swing" type="revolute">
    <parent link="root"/><child link="body"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
)";

TEST(RobotErrors, MissingCollisionMeshNamesLinkUriAndPlacesSearched) {
  const TempDir dir("missing_mesh");
  const std::string xml = urdf_with(mesh_collision("meshes/nope.stl"));
  const std::string msg =
      input_error_of([&] { RobotModel::from_urdf_string(xml, dir.str(), {}, "probe.urdf"); });
  expect_contains(msg, {"probe.urdf", "link 'body'", "meshes/nope.stl",
                        (dir.path() / "meshes" / "nope.stl").lexically_normal().string()});
}

TEST(RobotErrors, MissingAbsoluteAndFileUriMeshes) {
  const TempDir dir("missing_abs");
  const std::string absolute = (dir.path() / "gone.stl").string();
  expect_contains(input_error_of([&] {
                    RobotModel::from_urdf_string(urdf_with(mesh_collision(absolute)), dir.str());
                  }),
                  {"link 'body'", absolute, "no such file"});
  expect_contains(input_error_of([&] {
                    RobotModel::from_urdf_string(urdf_with(mesh_collision("file://" + absolute)),
                                                 dir.str());
                  }),
                  {"link 'body'", "file://" + absolute, "no such file"});
}

TEST(RobotErrors, UnreadableMeshNamesLinkAndFile) {
  const TempDir dir("garbage_mesh");
  // 37 bytes: not "solid ..." (ASCII STL) and too short for a binary STL header.
  const fs::path garbage =
      dir.write("garbage.stl", "\x01\x02 this is not a mesh at all \xff\xfe\n");
  const std::string xml = urdf_with(mesh_collision("garbage.stl"));
  const std::string msg =
      input_error_of([&] { RobotModel::from_urdf_string(xml, dir.str(), {}, "probe.urdf"); });
  expect_contains(
      msg, {"probe.urdf", "link 'body'", garbage.lexically_normal().string(), "cannot be read"});
}

TEST(RobotErrors, EmptyMeshFileIsAnError) {
  const TempDir dir("empty_mesh");
  dir.write("empty.stl", "");
  const std::string msg = input_error_of(
      [&] { RobotModel::from_urdf_string(urdf_with(mesh_collision("empty.stl")), dir.str()); });
  expect_contains(msg, {"link 'body'", "empty.stl"});
}

TEST(RobotErrors, MeshWithNonFiniteVertex) {
  const TempDir dir("nan_mesh");
  dir.write("nan.stl",
            "solid bad\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n"
            "   vertex 1 0 0\n   vertex nan 1 0\n  endloop\n endfacet\nendsolid bad\n");
  const std::string msg = input_error_of(
      [&] { RobotModel::from_urdf_string(urdf_with(mesh_collision("nan.stl")), dir.str()); });
  expect_contains(msg, {"link 'body'", "nan.stl"});
}

TEST(RobotErrors, FlatMesh) {
  // Every vertex in the plane z = 0: no volume. Either a clear InputError naming the link and
  // file, or a valid (flat) shape; never a crash.
  const TempDir dir("flat_mesh");
  dir.write("flat.stl",
            "solid flat\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n"
            "   vertex 1 0 0\n   vertex 0 1 0\n  endloop\n endfacet\n"
            " facet normal 0 0 1\n  outer loop\n   vertex 1 0 0\n"
            "   vertex 1 1 0\n   vertex 0 1 0\n  endloop\n endfacet\nendsolid flat\n");
  try {
    const RobotModel model =
        RobotModel::from_urdf_string(urdf_with(mesh_collision("flat.stl")), dir.str());
    const CollisionShape& shape = model.link(model.link_index("body")).shapes.at(0);
    EXPECT_GT(shape.bounding_radius, 0.5);
  } catch (const InputError& e) {
    expect_contains(e.what(), {"link 'body'", "flat.stl"});
  }
}

TEST(RobotErrors, MalformedXml) {
  const std::string xml = "<robot name=\"probe\">\n  <link name=\"root\">\n</robot>\n";
  const std::string msg =
      input_error_of([&] { RobotModel::from_urdf_string(xml, ".", {}, "broken.urdf"); });
  expect_contains(msg, {"broken.urdf", "malformed"});
  // Not even XML.
  expect_contains(input_error_of([] { RobotModel::from_urdf_string("robot {}", ".", {}, "x"); }),
                  {"malformed"});
}

TEST(RobotErrors, NotAUrdf) {
  const std::string msg = input_error_of([] {
    RobotModel::from_urdf_string("<?xml version=\"1.0\"?>\n<model name=\"m\"/>\n", ".", {},
                                 "model.xml");
  });
  expect_contains(msg, {"model.xml", "<robot>"});
}

TEST(RobotErrors, RobotWithoutLinksCarriesUrdfdomReason) {
  const std::string msg = input_error_of(
      [] { RobotModel::from_urdf_string("<robot name=\"empty\"/>", ".", {}, "empty.urdf"); });
  expect_contains(msg, {"empty.urdf", "not a valid URDF"});
  EXPECT_EQ(msg.find("urdfdom gave no reason"), std::string::npos) << msg;
}

TEST(RobotErrors, UnknownPackageNamesPackage) {
  const TempDir dir("unknown_pkg");
  const std::string xml = urdf_with(mesh_collision("package://no_such_pkg/x.stl"));
  const std::string msg =
      input_error_of([&] { RobotModel::from_urdf_string(xml, dir.str(), {}, "probe.urdf"); });
  expect_contains(msg, {"probe.urdf", "link 'body'", "package://no_such_pkg/x.stl",
                        "package 'no_such_pkg'", "searched"});
}

TEST(RobotErrors, PackageMapIsUsedAndReportedWhenTheFileIsMissing) {
  const TempDir dir("pkg_map");
  fs::create_directories(dir.path() / "my_pkg");
  RobotLoadOptions options;
  options.packages["my_pkg"] = (dir.path() / "my_pkg").string();
  const std::string xml = urdf_with(mesh_collision("package://my_pkg/meshes/absent.stl"));
  const std::string msg =
      input_error_of([&] { RobotModel::from_urdf_string(xml, dir.str(), options, "probe.urdf"); });
  expect_contains(msg, {"package 'my_pkg'", "meshes/absent.stl",
                        (dir.path() / "my_pkg" / "meshes" / "absent.stl").string()});
}

TEST(RobotErrors, PackageMappedToAMissingFolderIsAnError) {
  const TempDir dir("pkg_missing");
  RobotLoadOptions options;
  options.packages["my_pkg"] = (dir.path() / "no_such_folder").string();
  const std::string xml = urdf_with("");
  const std::string msg =
      input_error_of([&] { RobotModel::from_urdf_string(xml, dir.str(), options, "probe.urdf"); });
  expect_contains(msg, {"probe.urdf", "package 'my_pkg'", (dir.path() / "no_such_folder").string(),
                        "not a folder"});
}

TEST(RobotErrors, RevoluteJointWithoutLimitCarriesUrdfdomReason) {
  const std::string joint = R"(  <joint name="elbow" type="revolute">
    <parent link="root"/><child link="body"/><axis xyz="0 0 1"/>
  </joint>
)";
  const std::string xml = urdf_with("", joint);
  const std::string msg =
      input_error_of([&] { RobotModel::from_urdf_string(xml, ".", {}, "probe.urdf"); });
  // urdfdom rejects the joint and says why through console_bridge; our message must carry that
  // reason, not a generic one.
  // (Only urdfdom's message names the joint: the model was never built.)
  expect_contains(msg, {"probe.urdf", "not a valid URDF", "elbow", "REVOLUTE", "limits"});
  EXPECT_EQ(msg.find("urdfdom gave no reason"), std::string::npos) << msg;
}

TEST(RobotErrors, PrismaticJointWithoutLimitCarriesUrdfdomReason) {
  const std::string joint = R"(  <joint name="slide" type="prismatic">
    <parent link="root"/><child link="body"/><axis xyz="1 0 0"/>
  </joint>
)";
  const std::string msg = input_error_of(
      [&] { RobotModel::from_urdf_string(urdf_with("", joint), ".", {}, "probe.urdf"); });
  expect_contains(msg, {"probe.urdf", "not a valid URDF", "slide", "PRISMATIC", "limits"});
}

TEST(RobotErrors, FloatingJointNotSupported) {
  const std::string joint = R"(  <joint name="free" type="floating">
    <parent link="root"/><child link="body"/>
  </joint>
)";
  const std::string msg = input_error_of(
      [&] { RobotModel::from_urdf_string(urdf_with("", joint), ".", {}, "probe.urdf"); });
  expect_contains(msg, {"probe.urdf", "joint 'free'", "floating", "not supported"});
}

TEST(RobotErrors, PlanarJointNotSupported) {
  const std::string joint = R"(  <joint name="table" type="planar">
    <parent link="root"/><child link="body"/><axis xyz="0 0 1"/>
  </joint>
)";
  const std::string msg = input_error_of(
      [&] { RobotModel::from_urdf_string(urdf_with("", joint), ".", {}, "probe.urdf"); });
  expect_contains(msg, {"probe.urdf", "joint 'table'", "planar", "not supported"});
}

TEST(RobotErrors, MimicOfUnknownJoint) {
  const std::string joint = R"(  <joint name="follower" type="revolute">
    <parent link="root"/><child link="body"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
    <mimic joint="ghost" multiplier="2" offset="0"/>
  </joint>
)";
  const std::string msg = input_error_of(
      [&] { RobotModel::from_urdf_string(urdf_with("", joint), ".", {}, "probe.urdf"); });
  expect_contains(msg, {"probe.urdf", "joint 'follower'", "ghost"});
}

TEST(RobotErrors, MimicCycle) {
  const std::string joints = R"(  <joint name="a" type="revolute">
    <parent link="root"/><child link="body"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
    <mimic joint="b"/>
  </joint>
  <joint name="b" type="revolute">
    <parent link="body"/><child link="tip"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
    <mimic joint="a"/>
  </joint>
)";
  const std::string msg = input_error_of([&] {
    RobotModel::from_urdf_string(urdf_with("", joints, "  <link name=\"tip\"/>\n"), ".", {},
                                 "probe.urdf");
  });
  expect_contains(msg, {"probe.urdf", "cycle"});
}

TEST(RobotErrors, LimitLowerAboveUpper) {
  const std::string joint = R"(  <joint name="inverted" type="revolute">
    <parent link="root"/><child link="body"/><axis xyz="0 0 1"/>
    <limit lower="1" upper="-1" effort="1" velocity="1"/>
  </joint>
)";
  const std::string msg = input_error_of(
      [&] { RobotModel::from_urdf_string(urdf_with("", joint), ".", {}, "probe.urdf"); });
  expect_contains(msg, {"probe.urdf", "inverted", "lower"});
}

TEST(RobotErrors, ZeroAxis) {
  const std::string joint = R"(  <joint name="noaxis" type="revolute">
    <parent link="root"/><child link="body"/><axis xyz="0 0 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
)";
  const std::string msg = input_error_of(
      [&] { RobotModel::from_urdf_string(urdf_with("", joint), ".", {}, "probe.urdf"); });
  expect_contains(msg, {"probe.urdf", "noaxis"});
}

TEST(RobotErrors, ConfigurationOfWrongLengthNamesExpectedCount) {
  const RobotModel model = RobotModel::from_urdf_string(urdf_with("", kRevolute), ".");
  ASSERT_EQ(model.variable_count(), 1);
  std::vector<Eigen::Isometry3d> poses;
  const std::string msg =
      input_error_of([&] { model.compute_link_poses(Eigen::VectorXd::Zero(3), poses); });
  expect_contains(msg, {"probe", "3 values", "expected 1", "swing"});
  expect_contains(input_error_of([&] { model.check_configuration(Eigen::VectorXd()); }),
                  {"0 values", "expected 1"});
}

TEST(RobotErrors, NonFiniteConfigurationNamesJoint) {
  const RobotModel model = RobotModel::from_urdf_string(urdf_with("", kRevolute), ".");
  std::vector<Eigen::Isometry3d> poses;
  Eigen::VectorXd q(1);
  q[0] = std::numeric_limits<double>::quiet_NaN();
  expect_contains(input_error_of([&] { model.compute_link_poses(q, poses); }),
                  {"probe", "joint 'swing'", "nan"});
  q[0] = std::numeric_limits<double>::infinity();
  expect_contains(input_error_of([&] { model.check_configuration(q); }), {"joint 'swing'", "inf"});
}

TEST(RobotErrors, BadPadding) {
  const std::string xml = urdf_with("", kRevolute);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const double bad : {-0.01, nan, std::numeric_limits<double>::infinity()}) {
    RobotLoadOptions by_default;
    by_default.default_padding = bad;
    expect_contains(
        input_error_of([&] { RobotModel::from_urdf_string(xml, ".", by_default, "probe.urdf"); }),
        {"probe.urdf", "padding"});
    RobotLoadOptions per_link;
    per_link.link_padding["body"] = bad;
    expect_contains(
        input_error_of([&] { RobotModel::from_urdf_string(xml, ".", per_link, "probe.urdf"); }),
        {"probe.urdf", "link 'body'", "padding"});
  }
  RobotModel model = RobotModel::from_urdf_string(xml, ".");
  expect_contains(input_error_of([&] { model.set_link_padding("body", -1.0); }),
                  {"link 'body'", "padding"});
  expect_contains(input_error_of([&] { model.set_default_padding(nan); }), {"padding"});
  // A failed set leaves the padding as it was.
  EXPECT_EQ(model.link(model.link_index("body")).padding, 0.0);
}

TEST(RobotErrors, PaddingForUnknownLink) {
  RobotLoadOptions options;
  options.link_padding["elbow_of_nobody"] = 0.01;
  const std::string msg = input_error_of(
      [&] { RobotModel::from_urdf_string(urdf_with("", kRevolute), ".", options, "probe.urdf"); });
  expect_contains(msg, {"probe.urdf", "elbow_of_nobody"});
  RobotModel model = RobotModel::from_urdf_string(urdf_with("", kRevolute), ".");
  expect_contains(input_error_of([&] { model.set_link_padding("elbow_of_nobody", 0.01); }),
                  {"elbow_of_nobody"});
}

TEST(RobotErrors, MissingUrdfFile) {
  const TempDir dir("missing_urdf");
  const std::string path = (dir.path() / "absent.urdf").string();
  expect_contains(input_error_of([&] { RobotModel::from_urdf_file(path); }), {path, "cannot open"});
}

TEST(RobotErrors, MissingVisualMeshIsNotAnError) {
  const TempDir dir("visual");
  const std::string collision = R"(    <visual>
      <geometry><mesh filename="package://nowhere_pkg/meshes/visual/body.dae"/></geometry>
    </visual>
    <visual><geometry><mesh filename="meshes/visual/also_missing.dae"/></geometry></visual>
    <collision><geometry><sphere radius="0.05"/></geometry></collision>
)";
  const fs::path file = dir.write("robot.urdf", urdf_with(collision, kRevolute));
  const RobotModel model = RobotModel::from_urdf_file(file.string());
  EXPECT_EQ(model.links().size(), 2u);
  EXPECT_EQ(model.link(model.link_index("body")).shapes.size(), 1u);
}

TEST(RobotErrors, RelativeMeshFromUrdfFileResolvesAgainstItsFolderAndErrorsNameTheFile) {
  const TempDir dir("urdf_file");
  const fs::path file =
      dir.write("urdf/robot.urdf", urdf_with(mesh_collision("../meshes/missing.stl")));
  const std::string msg = input_error_of([&] { RobotModel::from_urdf_file(file.string()); });
  expect_contains(msg, {file.string(), "link 'body'", "../meshes/missing.stl",
                        (dir.path() / "meshes" / "missing.stl").string()});
}

TEST(RobotErrors, OwnArmLoadsWithoutErrors) {
  // The counterpart of the failures above: the real file loads (visual meshes are absent).
  const RobotModel model = RobotModel::from_urdf_file(test::own_arm().urdf);
  EXPECT_EQ(model.variable_count(), 8);
}

}  // namespace
}  // namespace hullcheck
