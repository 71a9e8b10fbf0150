// Poses: X-Y-Z angles (Casalino eq. 38) and validation of poses given to queries.
#include <gtest/gtest.h>

#include <hullcheck/core.hpp>

#include "test_support.hpp"

namespace hullcheck {
namespace {

TEST(Pose, XyzAnglesAreRxRyRz) {
  const double gx = 0.3, gy = -1.1, gz = 2.0;
  Eigen::Matrix3d rx, ry, rz;
  rx << 1, 0, 0, 0, std::cos(gx), -std::sin(gx), 0, std::sin(gx), std::cos(gx);
  ry << std::cos(gy), 0, std::sin(gy), 0, 1, 0, -std::sin(gy), 0, std::cos(gy);
  rz << std::cos(gz), -std::sin(gz), 0, std::sin(gz), std::cos(gz), 0, 0, 0, 1;
  EXPECT_TRUE(rotation_from_xyz_angles(gx, gy, gz).isApprox(rx * ry * rz, 1e-15));
  const Eigen::Isometry3d pose = pose_from_xyz_angles({1, 2, 3}, {gx, gy, gz});
  EXPECT_TRUE(pose.linear().isApprox(rx * ry * rz, 1e-15));
  EXPECT_TRUE(pose.translation().isApprox(Eigen::Vector3d(1, 2, 3)));
}

TEST(Pose, NonFiniteOrNonRigidPosesAreRejected) {
  Eigen::Isometry3d nan_pose = Eigen::Isometry3d::Identity();
  nan_pose.translation().x() = std::nan("");
  Eigen::Isometry3d scaled = Eigen::Isometry3d::Identity();
  scaled.linear() *= 2.0;
  Eigen::Isometry3d mirrored = Eigen::Isometry3d::Identity();
  mirrored.linear()(2, 2) = -1.0;
  const Eigen::Isometry3d id = Eigen::Isometry3d::Identity();
  const Shape s = Sphere(1.0);
  EXPECT_THROW(intersect(s, nan_pose, s, id), InputError);
  EXPECT_THROW(distance(s, id, s, nan_pose), InputError);
  EXPECT_THROW(penetration(s, id, s, nan_pose), InputError);
  EXPECT_THROW(signed_distance(s, nan_pose, s, id), InputError);
  EXPECT_THROW(validate_pose(scaled, "scaled"), InputError);
  EXPECT_THROW(validate_pose(mirrored, "mirrored"), InputError);
  EXPECT_NO_THROW(validate_pose(pose_from_xyz_angles({1, 2, 3}, {0.1, 0.2, 0.3}), "rigid"));
  ProximityPair pair;
  EXPECT_THROW(pair.set_shape_a(s, scaled), InputError);
  EXPECT_THROW(pair.set_shape_b(s, mirrored), InputError);
  EXPECT_THROW(pair.set_pose_a(nan_pose), InputError);
  EXPECT_THROW(pose_from_xyz_angles({0, 0, 0}, {0, INFINITY, 0}), InputError);
  try {
    distance(s, id, s, nan_pose);
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("pose_b"), std::string::npos) << e.what();
  }
}

TEST(Primitives, NegativeOrNonFiniteSizesAreRejected) {
  EXPECT_THROW(Sphere(-1.0), InputError);
  EXPECT_THROW(Sphere(std::nan("")), InputError);
  EXPECT_THROW(Box(1, -1, 1), InputError);
  EXPECT_THROW(Capsule(1, INFINITY), InputError);
  EXPECT_THROW(Cylinder(-0.1, 1), InputError);
  EXPECT_THROW(Shape(Sphere(1.0)).inflated(-0.1), InputError);
}

}  // namespace
}  // namespace hullcheck
