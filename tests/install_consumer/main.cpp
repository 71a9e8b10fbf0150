// Smallest program using an installed hullcheck; exits non-zero on a wrong answer.
#include <cmath>
#include <cstdio>
#include <hullcheck/core.hpp>
#include <hullcheck/hullcheck.hpp>
#include <memory>

int main() {
  Eigen::Isometry3d b = Eigen::Isometry3d::Identity();
  b.translation().x() = 3.0;
  const double d = hullcheck::distance(hullcheck::Sphere(1.0), Eigen::Isometry3d::Identity(),
                                       hullcheck::Box(2, 2, 2), b)
                       .distance;
  std::printf("installed hullcheck: sphere-box distance %.12f (expected 1)\n", d);

  // Two unit boxes, the second on a prismatic joint along x starting 2 m away; a third link
  // keeps them from being adjacent.
  const char* urdf = R"(<robot name="slider">
    <link name="a"><collision><geometry><box size="1 1 1"/></geometry></collision></link>
    <link name="middle"/>
    <link name="b"><collision><geometry><box size="1 1 1"/></geometry></collision></link>
    <joint name="fix" type="fixed"><parent link="a"/><child link="middle"/></joint>
    <joint name="slide" type="prismatic"><parent link="middle"/><child link="b"/>
      <origin xyz="2 0 0"/><axis xyz="1 0 0"/><limit lower="-2" upper="2" effort="1" velocity="1"/>
    </joint></robot>)";
  auto model =
      std::make_shared<hullcheck::RobotModel>(hullcheck::RobotModel::from_urdf_string(urdf, "."));
  hullcheck::AllowedCollisionMatrix acm(static_cast<int>(model->links().size()));
  const hullcheck::CollisionChecker checker(model, acm);  // no scene: self-collision only
  Eigen::VectorXd q(1);
  q[0] = 0.5;
  const double gap = checker.clearance(q).distance;
  std::printf("installed hullcheck: robot self distance %.12f (expected 1.5)\n", gap);
  return std::abs(d - 1.0) < 1e-12 && std::abs(gap - 1.5) < 1e-12 ? 0 : 1;
}
