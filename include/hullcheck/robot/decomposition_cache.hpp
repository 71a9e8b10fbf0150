// Convex decompositions of mesh files, cached on disk by content, scale and parameters.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <hullcheck/robot/convex_decomposition.hpp>
#include <hullcheck/robot/mesh_file.hpp>
#include <string>

namespace hullcheck {

/// The default cache folder: $HULLCHECK_CACHE_DIR when set, else $XDG_CACHE_HOME/hullcheck,
/// else $HOME/.cache/hullcheck; empty (no caching) when none of them is set.
std::string default_decomposition_cache_dir();

/// A mesh file's decomposition and where it came from.
struct MeshDecomposition {
  ConvexDecomposition decomposition;
  std::size_t vertex_count = 0;  ///< Vertices of the mesh file (read_mesh's count).
  bool from_cache = false;       ///< Read from the cache instead of computed.
};

/// decompose_mesh(read_mesh(path, scale, limits), options), through the cache folder
/// `cache_dir` (empty: no cache). Entries are keyed by the file's size and 64-bit FNV-1a hash of
/// its bytes, the scale, the options and the format version, and hold those values, verified on
/// reading (two different files of one size and hash, odds about 2^-64, are not told apart;
/// a cache folder is trusted like the mesh files themselves). A cache hit reads the
/// mesh file's bytes (for the hash) and the entry only, not the mesh. An entry that cannot be
/// parsed or checked is recomputed and rewritten; a folder that cannot be created or written
/// only means no caching (never an error). Entries are written to a temporary file and renamed,
/// so concurrent loaders never read half an entry. Throws InputError as read_mesh and
/// decompose_mesh do (the message names the file). Thread-safe.
/// `check_mesh`, when given, is called with the mesh read (on a cache miss) before it is
/// decomposed, to throw the caller's own errors (the loader's vertex range message).
MeshDecomposition decompose_mesh_file(
    const std::string& path, const Eigen::Vector3d& scale, const DecompositionOptions& options,
    const MeshLimits& limits, const std::string& cache_dir,
    const std::function<void(const TriangleMesh&)>& check_mesh = nullptr);

}  // namespace hullcheck
