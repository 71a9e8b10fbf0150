// Adversarial robot, mesh, scene and state input ("Truthful under attack"): each case must end
// quickly in one InputError whose message names the file, the element and the problem once;
// never a hang, a crash, unbounded memory or a silently wrong model.
#include <gtest/gtest.h>
#include <ompl/base/ScopedState.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <functional>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/ompl/joint_state_space.hpp>
#include <hullcheck/robot/allowed_collision_matrix.hpp>
#include <hullcheck/robot/mesh_file.hpp>
#include <hullcheck/robot/robot_model.hpp>
#include <hullcheck/robot/srdf.hpp>
#include <hullcheck/scene/collision_matrix_generation.hpp>
#include <hullcheck/scene/planning_scene.hpp>
#include <limits>
#include <memory>
#include <random>
#include <sstream>
#include <string>

#include "robot_test_support.hpp"

namespace hullcheck {
namespace {

using test::expect_contains;
using test::input_error_of;
using test::TempDir;

// Occurrences of `part` in `text`.
int count_of(const std::string& text, const std::string& part) {
  int n = 0;
  for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) {
    ++n;
  }
  return n;
}

std::string link(const std::string& name, const std::string& body = "") {
  return "  <link name=\"" + name + "\">" + body + "</link>\n";
}

std::string fixed_joint(const std::string& name, const std::string& parent,
                        const std::string& child) {
  return "  <joint name=\"" + name + "\" type=\"fixed\"><parent link=\"" + parent +
         "\"/><child link=\"" + child + "\"/></joint>\n";
}

std::string robot(const std::string& body) {
  return "<?xml version=\"1.0\"?>\n<robot name=\"probe\">\n" + body + "</robot>\n";
}

std::string load_error(const std::string& xml, const std::string& dir = ".") {
  return input_error_of([&] { RobotModel::from_urdf_string(xml, dir, {}, "probe.urdf"); });
}

// ---- 1. The joints must form one tree --------------------------------------------------------

TEST(InputHardening, CycleBelowTheRootIsRejectedNotWalkedForever) {
  // root -> a -> b -> c -> a: `a` is the child of two joints.
  const std::string xml = robot(link("root") + link("a") + link("b") + link("c") +
                                fixed_joint("root_a", "root", "a") + fixed_joint("a_b", "a", "b") +
                                fixed_joint("b_c", "b", "c") + fixed_joint("c_a", "c", "a"));
  const std::string msg = load_error(xml);
  expect_contains(msg, {"URDF 'probe.urdf'", "link 'a' is the child of two joints", "'root_a'",
                        "'c_a'", "tree"});
  EXPECT_EQ(count_of(msg, "URDF '"), 1) << msg;
}

TEST(InputHardening, LinkWithTwoParentJointsIsRejected) {
  // urdfdom keeps the last parent silently; the loader must not.
  const std::string xml =
      robot(link("root") + link("a") + link("b") + fixed_joint("root_a", "root", "a") +
            fixed_joint("root_b", "root", "b") + fixed_joint("a_b", "a", "b"));
  expect_contains(load_error(xml), {"link 'b' is the child of two joints", "'root_b'", "'a_b'"});
}

TEST(InputHardening, CycleDetachedFromTheRootIsRejectedNotDropped) {
  const std::string xml =
      robot(link("root") + link("a") + link("x") + link("y") + fixed_joint("root_a", "root", "a") +
            fixed_joint("x_y", "x", "y") + fixed_joint("y_x", "y", "x"));
  expect_contains(load_error(xml),
                  {"URDF 'probe.urdf'", "links 'x', 'y'", "not reachable from root link 'root'",
                   "'y_x', 'x_y'", "form a cycle"});
}

TEST(InputHardening, JointsFormingOnlyACycleHaveNoRoot) {
  const std::string xml =
      robot(link("a") + link("b") + fixed_joint("a_b", "a", "b") + fixed_joint("b_a", "b", "a"));
  expect_contains(load_error(xml), {"no root link", "'a_b', 'b_a'", "cycle"});
}

TEST(InputHardening, TwoRootLinksAreNamed) {
  const std::string xml =
      robot(link("root") + link("a") + link("lonely") + fixed_joint("root_a", "root", "a"));
  expect_contains(load_error(xml), {"2 root links", "'root', 'lonely'"});
}

TEST(InputHardening, JointToAnUndefinedLinkAndDuplicateNames) {
  expect_contains(
      load_error(robot(link("root") + link("a") + fixed_joint("root_typo", "root", "typo"))),
      {"joint 'root_typo'", "child link 'typo' is not defined"});
  expect_contains(load_error(robot(link("root") + link("root"))), {"link 'root' is defined twice"});
  expect_contains(load_error(robot(link("root") + link("a") + link("b") +
                                   fixed_joint("j", "root", "a") + fixed_joint("j", "root", "b"))),
                  {"joint 'j' is defined twice"});
}

TEST(InputHardening, MutatedUr5eWithADetachedCycleIsRejected) {
  const std::vector<test::RobotFile> robots = test::shared_robots();
  const auto ur5e = std::find_if(robots.begin(), robots.end(),
                                 [](const test::RobotFile& r) { return r.id == "ur5e"; });
  if (ur5e == robots.end()) GTEST_SKIP() << "no ../shared UR5e";
  std::ifstream in(ur5e->urdf);
  std::stringstream text;
  text << in.rdbuf();
  std::string xml = text.str();
  // The shoulder joint hangs the arm below its own last link: the arm becomes a cycle detached
  // from base_link (before the fix: 5 of 11 links loaded, no error).
  const std::size_t joint = xml.find("<joint name=\"shoulder_pan_joint\"");
  ASSERT_NE(joint, std::string::npos);
  const std::size_t parent = xml.find("<parent link=\"base_link\"/>", joint);
  ASSERT_NE(parent, std::string::npos);
  xml.replace(parent, std::strlen("<parent link=\"base_link\"/>"),
              "<parent link=\"wrist_3_link\"/>");
  const std::string dir = std::filesystem::path(ur5e->urdf).parent_path().string();
  expect_contains(load_error(xml, dir),
                  {"not reachable from root link", "'shoulder_link'", "form a cycle"});
}

// ---- 6. Sizes and positions beyond 1e6 m, errors that say where --------------------------------

std::string one_shape(const std::string& collision, const std::string& joint_origin = "") {
  return robot(link("root") + link("body", "<collision>" + collision + "</collision>") +
               "  <joint name=\"hold\" type=\"fixed\"><parent link=\"root\"/><child "
               "link=\"body\"/>" +
               joint_origin + "</joint>\n");
}

TEST(InputHardening, HugeBoxNamesFileLinkAndElement) {
  const std::string msg = load_error(one_shape("<geometry><box size=\"1e300 1 1\"/></geometry>"));
  expect_contains(
      msg, {"URDF 'probe.urdf'", "link 'body'", "<box size> x", "1e+300", "at most 1e+06 m"});
  EXPECT_EQ(count_of(msg, "URDF '"), 1) << msg;
  EXPECT_EQ(msg.find("range_check"), std::string::npos) << msg;
}

TEST(InputHardening, HugeCylinderSphereAndOriginsAreRejected) {
  expect_contains(
      load_error(one_shape("<geometry><cylinder radius=\"0.1\" length=\"2e6\"/></geometry>")),
      {"link 'body'", "<cylinder length>", "2e+06"});
  expect_contains(load_error(one_shape("<geometry><sphere radius=\"1e7\"/></geometry>")),
                  {"link 'body'", "<sphere radius>"});
  expect_contains(load_error(one_shape("<origin xyz=\"0 3e6 0\"/><geometry><sphere "
                                       "radius=\"1\"/></geometry>")),
                  {"link 'body'", "<collision><origin xyz> y", "3e+06"});
  expect_contains(load_error(one_shape("<geometry><sphere radius=\"1\"/></geometry>",
                                       "<origin xyz=\"0 0 -5e6\"/>")),
                  {"joint 'hold'", "<origin xyz> z", "-5e+06"});
}

TEST(InputHardening, HugeJointLimitsAndMimicCoefficientsAreRejected) {
  const std::string two_links = link("root") + link("body") + link("tip");
  const auto revolute = [](const std::string& name, const std::string& parent,
                           const std::string& child, const std::string& extra) {
    return "  <joint name=\"" + name + "\" type=\"revolute\"><parent link=\"" + parent +
           "\"/><child link=\"" + child + "\"/><axis xyz=\"0 0 1\"/>" + extra + "</joint>\n";
  };
  const std::string limit = "<limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/>";
  expect_contains(
      load_error(robot(two_links +
                       revolute("swing", "root", "body",
                                "<limit lower=\"-1\" upper=\"1e300\" effort=\"1\" "
                                "velocity=\"1\"/>") +
                       revolute("turn", "body", "tip", limit))),
      {"URDF 'probe.urdf'", "joint 'swing'", "<limit upper>", "at most 1e+06 rad", "1e+300"});
  expect_contains(
      load_error(robot(two_links + revolute("swing", "root", "body", limit) +
                       revolute("turn", "body", "tip",
                                limit + "<mimic joint=\"swing\" multiplier=\"1e300\"/>"))),
      {"joint 'turn'", "<mimic multiplier>", "at most 1e+06 in magnitude"});
}

TEST(InputHardening, MeshVertexBeyondTheRangeAfterScaleNamesMesh) {
  const TempDir dir("huge_vertex");
  dir.write("big.stl",
            "solid big\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n"
            "   vertex 1 0 0\n   vertex 0 1 0\n  endloop\n endfacet\nendsolid big\n");
  const std::string msg = load_error(
      one_shape("<geometry><mesh filename=\"big.stl\" scale=\"1 2e6 1\"/></geometry>"), dir.str());
  expect_contains(msg, {"link 'body'", "big.stl", "after <mesh scale>", "vertex y", "2e+06"});
}

std::string scene_with(const std::string& object) {
  return "name: probe\nworld:\n  collision_objects:\n" + object;
}

TEST(InputHardening, SceneErrorsCarryTheirPrefixOnce) {
  const RobotModel model = RobotModel::from_urdf_file(test::own_arm().urdf);
  const std::string wrong_count = scene_with(
      "    - id: o\n      primitives:\n        - {type: box, dimensions: [1, 1]}\n"
      "      primitive_poses:\n        - {position: [0, 0, 0]}\n");
  const std::string msg =
      input_error_of([&] { parse_planning_scene(wrong_count, model, "f.yaml"); });
  expect_contains(msg, {"scene 'f.yaml': object 'o': box needs 3 dimensions"});
  EXPECT_EQ(count_of(msg, "scene '"), 1) << msg;
  EXPECT_EQ(count_of(msg, "object '"), 1) << msg;
}

TEST(InputHardening, SceneSizesAndPositionsBeyondTheRangeAreRejected) {
  const RobotModel model = RobotModel::from_urdf_file(test::own_arm().urdf);
  const std::string huge_box = scene_with(
      "    - id: o\n      primitives:\n        - {type: box, dimensions: [1e300, 1, 1]}\n"
      "      primitive_poses:\n        - {position: [0, 0, 0]}\n");
  std::string msg = input_error_of([&] { parse_planning_scene(huge_box, model, "f.yaml"); });
  expect_contains(msg, {"scene 'f.yaml': object 'o': box dimension 0 is 1e+300"});
  EXPECT_EQ(count_of(msg, "scene '"), 1) << msg;
  const std::string far = scene_with(
      "    - id: o\n      primitives:\n        - {type: sphere, dimensions: [1]}\n"
      "      primitive_poses:\n        - {position: [0, 2e6, 0]}\n");
  expect_contains(input_error_of([&] { parse_planning_scene(far, model, "f.yaml"); }),
                  {"object 'o'", "primitive_poses[0].position", "2e+06"});
  const std::string nan_box = scene_with(
      "    - id: o\n      primitives:\n        - {type: box, dimensions: [1, .nan, 1]}\n"
      "      primitive_poses:\n        - {position: [0, 0, 0]}\n");
  expect_contains(input_error_of([&] { parse_planning_scene(nan_box, model, "f.yaml"); }),
                  {"object 'o'", "box dimension 1 is not finite"});
}

// ---- 3. Joint values in range before motion checks ------------------------------------------

TEST(InputHardening, JointRangesNameJointValueAndLimits) {
  const RobotModel model = RobotModel::from_urdf_file(test::own_arm().urdf);
  Eigen::VectorXd q = model.default_configuration();
  EXPECT_NO_THROW(model.check_joint_ranges(q));
  int bounded = -1;
  int continuous = -1;
  for (int i = 0; i < model.variable_count(); ++i) {
    const JointType type = model.joint(model.variable_joint(i)).type;
    if (type == JointType::kRevolute && bounded < 0) bounded = i;
    if (type == JointType::kContinuous && continuous < 0) continuous = i;
  }
  ASSERT_GE(bounded, 0);
  ASSERT_GE(continuous, 0);
  const Joint& j = model.joint(model.variable_joint(bounded));
  q[bounded] = j.upper + 0.5 * RobotModel::kLimitTolerance;  // slightly outside: accepted
  EXPECT_NO_THROW(model.check_joint_ranges(q));
  q[bounded] = 1e308;
  expect_contains(input_error_of([&] { model.check_joint_ranges(q); }),
                  {"joint '" + j.name + "'", "1e+308", "outside its limits"});
  q[bounded] = 0.0;
  q[continuous] = 1e7;
  expect_contains(
      input_error_of([&] { model.check_joint_ranges(q); }),
      {"joint '" + model.joint(model.variable_joint(continuous)).name + "'", "continuous"});
  q[continuous] = 50.0;  // several turns: fine
  EXPECT_NO_THROW(model.check_joint_ranges(q));
}

TEST(InputHardening, StateSpaceRejectsAValueFarOutsideTheLimits) {
  const auto model = std::make_shared<RobotModel>(RobotModel::from_urdf_file(test::own_arm().urdf));
  const Eigen::VectorXd base = model->default_configuration();
  JointStateSpace joints(model, test::all_variables(*model), base);
  ::ompl::base::ScopedState<> state(joints.space());
  Eigen::VectorXd q = base;
  q[0] = 1e308;
  expect_contains(input_error_of([&] { joints.from_configuration(q, state.get()); }),
                  {"joint '" + model->joint(model->variable_joint(0)).name + "'", "1e+308"});
}

// ---- 2. Bounded mesh reading -------------------------------------------------------------------

// Runs `f` in a child process whose address space is capped at `bytes`; returns the child's
// exit status: 0 when f threw InputError containing every part, 1 for another outcome, 2 when
// it ran out of memory (bad_alloc), or a signal number + 100.
int in_bounded_child(std::uint64_t bytes, const std::function<void()>& f,
                     std::initializer_list<std::string> parts) {
  const pid_t pid = fork();
  if (pid == 0) {
#if !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)
    // Not under the sanitizers: their shadow memory is reserved address space far beyond any
    // cap (the Release stage checks the bound, the sanitizer stages the outcome).
    rlimit limit{bytes, bytes};
    setrlimit(RLIMIT_AS, &limit);
#else
    (void)bytes;
#endif
    int code = 1;
    try {
      f();
    } catch (const InputError& e) {
      code = 0;
      for (const std::string& p : parts) {
        if (std::string(e.what()).find(p) == std::string::npos) code = 1;
      }
      if (code != 0) std::fprintf(stderr, "message: %s\n", e.what());
    } catch (const std::bad_alloc&) {
      code = 2;
    } catch (...) {
      code = 1;
    }
    _exit(code);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 100 + WTERMSIG(status);
}

std::string collada(const std::string& geometry_body, const std::string& extra = "") {
  return R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="meter" meter="1"/><up_axis>Z_UP</up_axis></asset>
  <library_geometries><geometry id="g"><mesh>
    <source id="p"><float_array id="pa" count="9">0 0 0 1 0 0 0 1 0</float_array>
      <technique_common><accessor source="#pa" count="3" stride="3">
        <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
      </accessor></technique_common></source>
    <vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
)" + geometry_body +
         R"(
  </mesh></geometry></library_geometries>
)" + extra +
         R"(
  <library_visual_scenes><visual_scene id="s"><node id="n"><instance_geometry url="#g"/></node>
  </visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
)";
}

const char* const kTriangle =
    R"(<triangles count="1"><input semantic="VERTEX" source="#v" offset="0"/><p>0 1 2</p></triangles>)";

constexpr std::uint64_t kChildMemory = 1ull << 30;  // the reading must fit in 1 GiB

TEST(InputHardening, SmallColladaLoadsWithinTheBound) {
  const TempDir dir("dae_ok");
  const std::string path = dir.write("ok.dae", collada(kTriangle)).string();
  EXPECT_EQ(read_mesh_vertices(path, Eigen::Vector3d::Ones()).size(), 3u);
  EXPECT_EQ(in_bounded_child(kChildMemory,
                             [&] {
                               read_mesh_vertices(path, Eigen::Vector3d::Ones());
                               throw InputError("done");
                             },
                             {"done"}),
            0);
}

TEST(InputHardening, ColladaDeclaringHugeCountsFailsFastWithBoundedMemory) {
  const TempDir dir("dae_bomb");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"triangles.dae",
       R"(<triangles count="1000000000"><input semantic="VERTEX" source="#v" offset="0"/><p>0 1 2</p></triangles>)"},
      {"offset.dae",
       R"(<triangles count="1"><input semantic="VERTEX" source="#v" offset="100000"/><p>0 1 2</p></triangles>)"},
      {"vcount.dae",
       R"(<polylist count="2"><input semantic="VERTEX" source="#v" offset="0"/><vcount>3 4000000000</vcount><p>0 1 2</p></polylist>)"},
  };
  for (const auto& [name, body] : cases) {
    SCOPED_TRACE(name);
    const std::string path = dir.write(name, collada(body)).string();
    const std::string msg =
        input_error_of([&] { read_mesh_vertices(path, Eigen::Vector3d::Ones()); });
    expect_contains(msg, {"mesh '" + path + "'"});
    EXPECT_EQ(in_bounded_child(kChildMemory,
                               [&] { read_mesh_vertices(path, Eigen::Vector3d::Ones()); }, {name}),
              0);
  }
  std::string text = collada(kTriangle);
  text.replace(text.find("count=\"9\""), 9, "count=\"900000000\"");
  const std::string arrays = dir.write("array.dae", text).string();
  expect_contains(input_error_of([&] { read_mesh_vertices(arrays, Eigen::Vector3d::Ones()); }),
                  {"<float_array> declares 900000000 elements", "bytes can hold"});
}

TEST(InputHardening, ColladaIndexListsAndInputSourcesAreChecked) {
  // The fuzzer's finding, reduced: a <p> token that is not an integer with an input whose
  // source is missing made assimp allocate 2.4 GB for a 5 KB file.
  const TempDir dir("dae_refs");
  const std::string token =
      dir.write(
             "token.dae",
             collada(
                 R"(<polylist count="1"><input semantic="VERTEX" source="#v" offset="0"/><vcount>3</vcount><p>0 '5 2</p></polylist>)"))
          .string();
  expect_contains(input_error_of([&] { read_mesh_vertices(token, Eigen::Vector3d::Ones()); }),
                  {"mesh '" + token + "'", "<p> holds something other than non-negative integers"});
  const std::string missing =
      dir.write(
             "missing.dae",
             collada(
                 R"(<polylist count="1"><input semantic="VERTEX" source="#v" offset="0"/><input semantic="NORMAL" source="#normals" offset="1"/><vcount>3</vcount><p>0 0 1 0 2 0</p></polylist>)"))
          .string();
  expect_contains(input_error_of([&] { read_mesh_vertices(missing, Eigen::Vector3d::Ones()); }),
                  {"<input source=\"#normals\"> names no element of the file"});
  const std::filesystem::path found =
      std::filesystem::path(HULLCHECK_ROBOTS_DIR) / ".." /
      "tests/fuzz/regressions/mesh/oom-assimp-collada-bad-polylist-index.dae";
  EXPECT_EQ(in_bounded_child(kChildMemory,
                             [&] { read_mesh_vertices(found.string(), Eigen::Vector3d::Ones()); },
                             {"holds something other than non-negative integers"}),
            0);
}

TEST(InputHardening, ColladaNodeInstancingIsBoundedAndAcyclic) {
  const TempDir dir("dae_nodes");
  // Ten levels, each instancing the previous one ten times: 10^10 nodes from 3 KB.
  std::string library = "<library_nodes>\n<node id=\"l0\"><instance_geometry url=\"#g\"/></node>\n";
  for (int level = 1; level <= 10; ++level) {
    library += "<node id=\"l" + std::to_string(level) + "\">";
    for (int k = 0; k < 10; ++k) {
      library += "<instance_node url=\"#l" + std::to_string(level - 1) + "\"/>";
    }
    library += "</node>\n";
  }
  library += "</library_nodes>\n";
  std::string bomb = collada(kTriangle, library);
  bomb.replace(bomb.find("<instance_geometry url=\"#g\"/></node>\n  </visual_scene>"),
               std::strlen("<instance_geometry url=\"#g\"/>"), "<instance_node url=\"#l10\"/>");
  const std::string path = dir.write("bomb.dae", bomb).string();
  EXPECT_EQ(
      in_bounded_child(
          kChildMemory, [&] { read_mesh_vertices(path, Eigen::Vector3d::Ones()); },
          {"bomb.dae", "node count after <instance_node> expansion", "MeshLimits::max_nodes"}),
      0);
  const std::string cycle =
      collada(kTriangle,
              "<library_nodes><node id=\"a\"><instance_node url=\"#b\"/></node>"
              "<node id=\"b\"><instance_node url=\"#a\"/></node></library_nodes>");
  std::string looped = cycle;
  looped.replace(looped.find("<instance_geometry url=\"#g\"/></node>\n  </visual_scene>"),
                 std::strlen("<instance_geometry url=\"#g\"/>"), "<instance_node url=\"#a\"/>");
  const std::string loop_path = dir.write("loop.dae", looped).string();
  expect_contains(input_error_of([&] { read_mesh_vertices(loop_path, Eigen::Vector3d::Ones()); }),
                  {"loop.dae", "<instance_node> references form a cycle"});
}

TEST(InputHardening, ColladaNodeDepthIsBoundedAlsoWhereANodeIsInstancedTwice) {
  // c0 -> c1 -> ... -> c199 through <instance_node>: 200 levels. Instanced near the top it
  // fits the 256-level bound; instanced again below 80 nested nodes it does not (assimp walks
  // the hierarchy recursively).
  std::string library = "<library_nodes>\n";
  for (int i = 0; i < 200; ++i) {
    library += "<node id=\"c" + std::to_string(i) + "\">" +
               (i + 1 < 200 ? "<instance_node url=\"#c" + std::to_string(i + 1) + "\"/>"
                            : "<instance_geometry url=\"#g\"/>") +
               "</node>\n";
  }
  library += "</library_nodes>\n";
  std::string nested;
  for (int i = 0; i < 80; ++i) nested += "<node>";
  nested += "<instance_node url=\"#c0\"/>";
  for (int i = 0; i < 80; ++i) nested += "</node>";
  std::string text = collada(kTriangle, library);
  const std::string scene_node = "<node id=\"n\"><instance_geometry url=\"#g\"/></node>";
  const TempDir dir("dae_depth");
  std::string shallow = text;
  shallow.replace(shallow.find(scene_node), scene_node.size(),
                  "<node><instance_node url=\"#c0\"/></node>");
  const std::string ok = dir.write("shallow.dae", shallow).string();
  EXPECT_EQ(read_mesh_vertices(ok, Eigen::Vector3d::Ones()).size(), 3u);
  text.replace(text.find(scene_node), scene_node.size(),
               "<node><instance_node url=\"#c0\"/></node>" + nested);
  const std::string deep = dir.write("deep.dae", text).string();
  expect_contains(input_error_of([&] { read_mesh_vertices(deep, Eigen::Vector3d::Ones()); }),
                  {"deep.dae", "deeper than 256 levels"});
}

TEST(InputHardening, BinaryStlDeclaringMoreFacetsThanItHolds) {
  const TempDir dir("stl_bomb");
  std::string bytes(84 + 50, '\0');
  const std::uint32_t facets = 4000000000u;
  std::memcpy(&bytes[80], &facets, sizeof facets);
  const std::string path = dir.write("bomb.stl", bytes).string();
  EXPECT_EQ(
      in_bounded_child(kChildMemory, [&] { read_mesh_vertices(path, Eigen::Vector3d::Ones()); },
                       {"bomb.stl", "declares 4000000000 facets", "hold at most 1"}),
      0);
}

TEST(InputHardening, MeshLimitsAreConfigurable) {
  const TempDir dir("mesh_limits");
  const std::string obj = dir.write("quad.obj",
                                    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\n"
                                    "f 1 2 3\nf 1 3 4\nf 1 2 5\n")
                              .string();
  EXPECT_GE(read_mesh_vertices(obj, Eigen::Vector3d::Ones()).size(), 5u);
  MeshLimits small;
  small.max_file_bytes = 16;
  expect_contains(
      input_error_of([&] { read_mesh_vertices(obj, Eigen::Vector3d::Ones(), small); }),
      {"quad.obj", "file size (bytes)", "exceeds the limit 16", "MeshLimits::max_file_bytes"});
  small = MeshLimits{};
  small.max_vertices = 4;
  expect_contains(input_error_of([&] { read_mesh_vertices(obj, Eigen::Vector3d::Ones(), small); }),
                  {"quad.obj", "vertex count", "MeshLimits::max_vertices"});
  small = MeshLimits{};
  small.max_faces = 2;
  expect_contains(input_error_of([&] { read_mesh_vertices(obj, Eigen::Vector3d::Ones(), small); }),
                  {"quad.obj", "face count 3 exceeds the limit 2", "MeshLimits::max_faces"});
  small = MeshLimits{};
  small.max_memory_bytes = 1000;  // the file's ~60 bytes make an estimate of 64 x its size
  expect_contains(input_error_of([&] { read_mesh_vertices(obj, Eigen::Vector3d::Ones(), small); }),
                  {"quad.obj", "estimated memory (bytes) for the file size",
                   "exceeds the limit 1000", "MeshLimits::max_memory_bytes"});
  // Through the robot loader: RobotLoadOptions::mesh_limits.
  RobotLoadOptions options;
  options.mesh_limits.max_file_bytes = 16;
  const std::string xml = one_shape("<geometry><mesh filename=\"quad.obj\"/></geometry>");
  expect_contains(
      input_error_of([&] { RobotModel::from_urdf_string(xml, dir.str(), options, "probe.urdf"); }),
      {"URDF 'probe.urdf'", "link 'body'", "quad.obj", "max_file_bytes"});
}

TEST(InputHardening, UnvettedFormatsAreRejectedUnlessAllowed) {
  const TempDir dir("ply");
  const std::string ply = dir.write("t.ply",
                                    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                                    "property float y\nproperty float z\nelement face 1\n"
                                    "property list uchar int vertex_indices\nend_header\n"
                                    "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
                              .string();
  expect_contains(input_error_of([&] { read_mesh_vertices(ply, Eigen::Vector3d::Ones()); }),
                  {"t.ply", "format '.ply' is not accepted", "vetted_formats_only"});
  MeshLimits open;
  open.vetted_formats_only = false;
  EXPECT_EQ(read_mesh_vertices(ply, Eigen::Vector3d::Ones(), open).size(), 3u);
}

// ---- 4. Collision matrices linear in the links -------------------------------------------------

namespace matrix {

// A random tree of `n` links: link i's parent is a random earlier link; each link has geometry
// with probability 1/2; each joint is fixed with probability 1/3, else revolute.
std::string random_tree(int n, std::mt19937_64& rng) {
  std::string body;
  std::uniform_int_distribution<int> coin(0, 5);
  for (int i = 0; i < n; ++i) {
    const std::string geometry =
        coin(rng) < 3 ? "<collision><geometry><sphere radius=\"0.01\"/></geometry></collision>"
                      : "";
    body += link("l" + std::to_string(i), geometry);
  }
  for (int i = 1; i < n; ++i) {
    const int parent = std::uniform_int_distribution<int>(0, i - 1)(rng);
    const bool fixed = coin(rng) < 2;
    body += "  <joint name=\"j" + std::to_string(i) + "\" type=\"" +
            (fixed ? "fixed" : "revolute") + "\"><parent link=\"l" + std::to_string(parent) +
            "\"/><child link=\"l" + std::to_string(i) + "\"/><origin xyz=\"0 0 1\"/>" +
            (fixed ? ""
                   : "<axis xyz=\"0 0 1\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" "
                     "velocity=\"1\"/>") +
            "</joint>\n";
  }
  return robot(body);
}

// MoveIt's definition, by brute force: joined = joint neighbours, closed under "two neighbours
// of a link without geometry are joined"; adjacent = joined or in one rigid body.
std::vector<std::vector<bool>> brute_force_adjacency(const RobotModel& model) {
  const std::size_t n = model.links().size();
  std::vector<std::vector<bool>> joined(n, std::vector<bool>(n, false));
  for (const Joint& j : model.joints()) {
    joined[static_cast<std::size_t>(j.parent_link)][static_cast<std::size_t>(j.child_link)] = true;
    joined[static_cast<std::size_t>(j.child_link)][static_cast<std::size_t>(j.parent_link)] = true;
  }
  for (bool changed = true; changed;) {
    changed = false;
    for (std::size_t l = 0; l < n; ++l) {
      if (!model.links()[l].shapes.empty()) continue;
      for (std::size_t a = 0; a < n; ++a) {
        for (std::size_t b = 0; b < n; ++b) {
          if (a == b || a == l || b == l || !joined[l][a] || !joined[l][b] || joined[a][b]) {
            continue;
          }
          joined[a][b] = joined[b][a] = changed = true;
        }
      }
    }
  }
  std::vector<int> body(n);
  for (std::size_t l = 0; l < n; ++l) {
    const int j = model.links()[l].parent_joint;
    body[l] = j >= 0 && model.joint(j).type == JointType::kFixed
                  ? body[static_cast<std::size_t>(model.joint(j).parent_link)]
                  : static_cast<int>(l);
  }
  for (std::size_t a = 0; a < n; ++a) {
    for (std::size_t b = 0; b < n; ++b)
      joined[a][b] = a != b && (joined[a][b] || body[a] == body[b]);
  }
  return joined;
}

}  // namespace matrix

TEST(InputHardening, AdjacencyInClosedFormMatchesMoveItsFixpoint) {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 60; ++trial) {
    const int n = 2 + trial % 14;
    const RobotModel model =
        RobotModel::from_urdf_string(matrix::random_tree(n, rng), ".", {}, "tree.urdf");
    const auto expected = matrix::brute_force_adjacency(model);
    const AllowedCollisionMatrix acm = AllowedCollisionMatrix::from_adjacency(model);
    std::int64_t pairs = 0;
    for (int a = 0; a < n; ++a) {
      for (int b = 0; b < n; ++b) {
        ASSERT_EQ(acm.allowed(a, b),
                  a == b || expected[static_cast<std::size_t>(a)][static_cast<std::size_t>(b)])
            << "trial " << trial << " pair " << a << ", " << b;
        if (a < b && acm.allowed(a, b)) ++pairs;
      }
    }
    EXPECT_EQ(acm.allowed_pair_count(), pairs) << "trial " << trial;
  }
}

TEST(InputHardening, CollisionMatrixOfALongChainIsLinear) {
  // 20000 links, every 100th with geometry, the rest bare: MoveIt's rule joins all the bare
  // links with each other (2e8 pairs); the matrix must not store them one by one.
  constexpr int kLinks = 20000;
  std::string body;
  for (int i = 0; i < kLinks; ++i) {
    body += link(
        "l" + std::to_string(i),
        i % 100 == 0 ? "<collision><geometry><sphere radius=\"0.1\"/></geometry></collision>" : "");
  }
  for (int i = 1; i < kLinks; ++i) {
    body += "  <joint name=\"j" + std::to_string(i) + "\" type=\"" +
            (i % 2 ? "revolute" : "fixed") + "\"><parent link=\"l" + std::to_string(i - 1) +
            "\"/><child link=\"l" + std::to_string(i) + "\"/><origin xyz=\"0 0 1\"/>" +
            (i % 2 ? "<axis xyz=\"1 0 0\"/><limit lower=\"-0.01\" upper=\"0.01\" effort=\"1\" "
                     "velocity=\"1\"/>"
                   : "") +
            "</joint>\n";
  }
  const RobotModel model = RobotModel::from_urdf_string(robot(body), ".", {}, "chain.urdf");
  ASSERT_EQ(model.links().size(), static_cast<std::size_t>(kLinks));
  const AllowedCollisionMatrix acm = AllowedCollisionMatrix::from_adjacency(model);
  EXPECT_TRUE(acm.allowed(1, 99));    // bare to bare through bare links
  EXPECT_TRUE(acm.allowed(0, 100));   // neighbouring solids through bare links
  EXPECT_FALSE(acm.allowed(0, 200));  // the solid link 100 is in between
  EXPECT_FALSE(acm.allowed(1, kLinks - 1));
  // 199 cliques of 99 bare links and their two solid neighbours, and the last 99 bare links
  // with one solid: 1e6 pairs, counted, not stored.
  EXPECT_EQ(acm.allowed_pair_count(), 199 * (101 * 100 / 2) + 100 * 99 / 2);
  CollisionMatrixOptions options;
  options.samples = 20;
  const GeneratedCollisionMatrix generated = generate_collision_matrix(model, options);
  EXPECT_EQ(generated.adjacent, 199);
  EXPECT_EQ(generated.never + generated.adjacent + generated.always + generated.default_pose +
                generated.checked,
            200 * 199 / 2);
  const Srdf srdf = collision_matrix_to_srdf(model, generated.matrix);
  EXPECT_EQ(srdf.disabled_collisions.size(), static_cast<std::size_t>(200 * 199 / 2));
}

}  // namespace
}  // namespace hullcheck
