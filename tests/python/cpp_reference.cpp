// The C++ answers the Python tests compare the bindings with (tests/python/test_against_cpp.py):
// reads a robot, its SRDF and a scene, then configurations from stdin (one per line, values
// separated by spaces) and prints for each, through the C++ API alone:
//   valid <0|1>
//   clearance <distance> <self 0|1> <name_a> <name_b> <point_a xyz> <point_b xyz> <normal xyz>
//   gradient <dof values>
//   link <name> <the 12 values of the 3x4 pose, row-major>   (every link)
// Numbers with 17 significant digits, so that equal doubles print equal.
//   hullcheck_python_reference URDF SRDF SCENE < configurations
#include <cstdio>
#include <hullcheck/scene.hpp>
#include <iostream>
#include <sstream>

using namespace hullcheck;

int main(int argc, char** argv) try {
  if (argc != 4) {
    std::fprintf(stderr, "usage: %s URDF SRDF SCENE < configurations\n", argv[0]);
    return 2;
  }
  auto model = std::make_shared<const RobotModel>(RobotModel::from_urdf_file(argv[1]));
  const Srdf srdf = read_srdf_file(argv[2]);
  const CollisionChecker checker(model, AllowedCollisionMatrix::from_srdf(*model, srdf),
                                 read_planning_scene(argv[3], *model));
  std::string line;
  std::vector<Eigen::Isometry3d> poses(model->links().size());
  while (std::getline(std::cin, line)) {
    std::istringstream in(line);
    Eigen::VectorXd q(model->variable_count());
    for (Eigen::Index i = 0; i < q.size(); ++i) in >> q[i];
    if (!in) continue;
    std::printf("valid %d\n", checker.is_valid(q) ? 1 : 0);
    const ClearanceResult r = checker.clearance(q);
    std::printf("clearance %.17g %d %s %s", r.distance, r.self ? 1 : 0,
                std::string(r.name_a).c_str(), std::string(r.name_b).c_str());
    for (const Eigen::Vector3d* v : {&r.point_a, &r.point_b, &r.normal}) {
      std::printf(" %.17g %.17g %.17g", (*v)[0], (*v)[1], (*v)[2]);
    }
    model->compute_link_poses(q, poses);
    const Eigen::VectorXd g = clearance_gradient(*model, poses, checker.clearance_at(poses));
    std::printf("\ngradient");
    for (Eigen::Index i = 0; i < g.size(); ++i) std::printf(" %.17g", g[i]);
    std::printf("\n");
    for (std::size_t l = 0; l < poses.size(); ++l) {
      std::printf("link %s", model->link(static_cast<int>(l)).name.c_str());
      for (int row = 0; row < 3; ++row) {
        for (int col = 0; col < 4; ++col) std::printf(" %.17g", poses[l].matrix()(row, col));
      }
      std::printf("\n");
    }
  }
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "error: %s\n", e.what());
  return 1;
}
