// FclMeshModel: a URDF's link collision geometry as FCL 0.7 objects, for tests only.
//
// Built from the URDF file alone, independently of hullcheck's shapes: urdfdom parses the
// file, each <collision> element becomes one FCL geometry in its link's frame (the element's
// <origin> kept as the geometry's pose). Meshes are the triangle meshes themselves (not their
// hulls): assimp reads the file (aiProcess_Triangulate; COLLADA's up-axis ignored, as ROS tools
// do), node transforms and the URDF <mesh scale> are applied, and the triangles go into an
// fcl::BVHModel<fcl::OBBRSSd>. Boxes, spheres and cylinders are FCL's primitives. Only mesh
// paths are resolved with hullcheck (resolve_resource_path). Immutable once built; the BVHs
// are built once here and shared by every checker that uses the model.
#pragma once

#include <fcl/geometry/collision_geometry.h>

#include <Eigen/Geometry>
#include <cstddef>
#include <hullcheck/robot/resource_path.hpp>
#include <memory>
#include <string>
#include <vector>

namespace hullcheck::test {

/// One <collision> element of a link as an FCL geometry.
struct FclMeshElement {
  std::shared_ptr<fcl::CollisionGeometryd> geometry;         ///< Local AABB computed.
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();  ///< Link frame <- element frame.
  std::string source;         ///< "box", "sphere", "cylinder", or the resolved mesh path.
  std::size_t triangles = 0;  ///< Mesh triangles (0 for primitives).
};

/// The collision elements of one URDF link (none for a link without <collision>).
struct FclMeshLink {
  std::string name;
  std::vector<FclMeshElement> elements;
};

/// Every link of a URDF with its collision geometry in FCL's types.
class FclMeshModel {
 public:
  /// Reads `urdf_path`; mesh URIs resolve against its folder and `packages`. Throws
  /// std::runtime_error naming the file, link and problem when the URDF cannot be parsed, a
  /// mesh cannot be read or holds no triangle, or a geometry type is not supported.
  explicit FclMeshModel(const std::string& urdf_path, const PackageMap& packages = {});

  const std::string& source() const { return source_; }
  /// Every link of the URDF, sorted by name.
  const std::vector<FclMeshLink>& links() const { return links_; }
  /// Index into links() of the link called `name`, or -1.
  int link_index(const std::string& name) const;
  /// Sum of the mesh triangles over every element.
  std::size_t triangle_count() const;

 private:
  std::string source_;
  std::vector<FclMeshLink> links_;
};

}  // namespace hullcheck::test
