// The FCL mesh oracle's robot geometry, shared by the tests that use it.
#pragma once

#include <hullcheck/robot/resource_path.hpp>
#include <map>
#include <memory>
#include <string>

#include "fcl_mesh_model.hpp"

namespace hullcheck::test {

/// The meshes of a URDF, read once per test binary (the first `packages` given for it apply):
/// building the BVHs of the UR5's 100k triangles takes a moment.
inline std::shared_ptr<const FclMeshModel> cached_meshes(const std::string& urdf,
                                                         const PackageMap& packages = {}) {
  static std::map<std::string, std::shared_ptr<const FclMeshModel>> cache;
  auto& entry = cache[urdf];
  if (!entry) entry = std::make_shared<const FclMeshModel>(urdf, packages);
  return entry;
}

}  // namespace hullcheck::test
