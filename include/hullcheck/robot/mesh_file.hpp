// Reading the vertices of a mesh file (STL binary or ASCII, COLLADA, OBJ; other formats assimp
// reads on request, see MeshLimits), with bounded resources.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace hullcheck {

/// Resource limits for reading one mesh file; a file beyond any of them is rejected with
/// InputError before (or, for counts only known after parsing, right after) assimp reads it.
///
/// The memory bound: the file is checked against `max_file_bytes` before it is read, and the
/// counts a format declares (binary STL's facet count, COLLADA's array,
/// primitive and accessor counts, vertex-count lists, input offsets and node instancing) are
/// checked against the file's size and these limits before assimp allocates for them, so a
/// small file cannot make assimp allocate for a huge declared count. OBJ and ASCII STL declare
/// no counts: the peak memory is proportional to the file size, estimated as 64 bytes per byte
/// of a text file and 12 per byte of a binary STL (measured worst cases: 37 and 7.3), and that
/// estimate must stay within `max_memory_bytes` too (by default: text meshes up to 32 MiB,
/// binary STL up to 170 MiB). Other formats (PLY, FBX, 3DS, glTF, ...) have declared counts
/// hullcheck does not vet and are rejected unless `vetted_formats_only` is false.
struct MeshLimits {
  /// Largest file size, bytes (default 256 MiB).
  std::uint64_t max_file_bytes = 256ull << 20;
  /// Largest total vertex count over every mesh instance of the file (default 8 million).
  std::size_t max_vertices = 8'000'000;
  /// Largest total face (triangle or polygon) count over the file's meshes (default 8 million).
  std::size_t max_faces = 8'000'000;
  /// Largest number of scene nodes after COLLADA's node instancing (default 100000).
  std::size_t max_nodes = 100'000;
  /// Largest memory, bytes, assimp may need for the counts a file declares, estimated
  /// conservatively from them (default 2 GiB).
  std::uint64_t max_memory_bytes = 2ull << 30;
  /// Accept only the formats whose declared counts are checked: STL, OBJ, COLLADA (.dae).
  bool vetted_formats_only = true;
};

/// Every vertex of every mesh in the file at `path`, in the file's model frame (node transforms
/// and COLLADA's <unit> applied; COLLADA's up-axis ignored, as ROS tools do), each multiplied
/// componentwise by `scale` (URDF's mesh scale; negative components mirror). Units are the
/// file's own, i.e. metres for URDF meshes. The extension's case does not matter; the format is
/// chosen by the extension.
/// Throws InputError naming the file and the problem when the file cannot be read, exceeds
/// `limits` (the message names the limit and the count), is of an unvetted format, holds no
/// vertices, or holds a non-finite coordinate. Thread-safe (one importer per call).
std::vector<Eigen::Vector3d> read_mesh_vertices(const std::string& path,
                                                const Eigen::Vector3d& scale,
                                                const MeshLimits& limits = {});

/// A triangle mesh: vertices (m) and triangles as indices into them. Orientation is the file's;
/// nothing requires the mesh to be closed or consistently oriented.
struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

/// The vertices of read_mesh_vertices (same order, same checks and errors) with the file's faces
/// as triangles: a polygon of n >= 3 corners becomes a fan of n - 2 triangles from its first
/// corner; point and line faces add no triangle. A mirroring scale (an odd number of negative
/// components) reverses each triangle's corner order, so that orientation is kept.
TriangleMesh read_mesh(const std::string& path, const Eigen::Vector3d& scale,
                       const MeshLimits& limits = {});

}  // namespace hullcheck
