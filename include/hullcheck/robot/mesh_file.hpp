// Reading the vertices of a mesh file (STL binary or ASCII, COLLADA, OBJ, ... via assimp).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace hullcheck {

/// Every vertex of every mesh in the file at `path`, in the file's model frame (node transforms
/// and COLLADA's <unit> applied; COLLADA's up-axis ignored, as ROS tools do), each multiplied
/// componentwise by `scale` (URDF's mesh scale; negative components mirror). Units are the
/// file's own, i.e. metres for URDF meshes. The extension's case does not matter.
/// Throws InputError naming the file and assimp's reason when the file cannot be read, holds
/// no vertices, or holds a non-finite coordinate. Thread-safe (one importer per call).
std::vector<Eigen::Vector3d> read_mesh_vertices(const std::string& path,
                                                const Eigen::Vector3d& scale);

}  // namespace hullcheck
