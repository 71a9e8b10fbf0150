// The collision shapes of URDF links: primitives, and meshes as one hull or convex pieces.
#pragma once

#include <urdf_model/link.h>

#include <Eigen/Core>
#include <cstddef>
#include <hullcheck/robot/robot_model.hpp>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace hullcheck::detail {

/// Makes the collision shapes of a URDF's links; reads (and decomposes) each mesh file once per
/// scale. Errors are InputErrors prefixed with "URDF '<source>': link '<name>'".
class CollisionLoader {
 public:
  /// `options` must outlive the loader.
  CollisionLoader(const std::string& source, const std::string& base_dir,
                  const RobotLoadOptions& options);

  /// The shapes of every <collision> element of `link`, in file order.
  std::vector<CollisionShape> link_shapes(const urdf::Link& link);

  /// The shapes of `link_name`'s <collision> element number `element`: one, or one per piece
  /// of a decomposed mesh.
  std::vector<CollisionShape> make_shapes(const urdf::Collision& collision,
                                          const std::string& link_name, int element);

 private:
  // A mesh file at one scale.
  struct MeshKey {
    std::string path;
    double sx, sy, sz;
    bool operator<(const MeshKey& o) const;
  };

  // A mesh file's convex shapes (one hull, or the pieces of its decomposition).
  struct MeshShapes {
    std::vector<ConvexHull> hulls;
    std::shared_ptr<const ConvexHull> hull_of_pieces;  // when there are several
    std::size_t vertex_count;
    double excess;  // CollisionShape::mesh_excess
  };

  // The shapes of a mesh element: `out` (origin and element set) once per convex piece.
  std::vector<CollisionShape> mesh_pieces(const urdf::Mesh& mesh, CollisionShape& out,
                                          const std::string& where);

  // The convex shapes of the mesh file at `path` scaled by `scale`, read (and decomposed) once
  // per file and scale.
  const MeshShapes& mesh_shapes(const std::string& path, const Eigen::Vector3d& scale,
                                const std::string& where);

  // The mesh file as one convex hull of its vertices (MeshGeometry::kHull); `what` prefixes
  // errors.
  MeshShapes mesh_hull(const std::string& path, const Eigen::Vector3d& scale,
                       const std::string& what) const;

  // The mesh file as the convex pieces of its (cached) decomposition, with the hull of all
  // pieces when there are several (MeshGeometry::kDecompose).
  MeshShapes mesh_decomposition(const std::string& path, const Eigen::Vector3d& scale,
                                const std::string& what) const;

  std::string source_;
  std::string base_dir_;
  const RobotLoadOptions& options_;
  std::map<MeshKey, MeshShapes> meshes_;
};

}  // namespace hullcheck::detail
