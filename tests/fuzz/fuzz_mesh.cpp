// libFuzzer target: mesh bytes -> read_mesh (assimp) -> convex hull -> convex decomposition. The
// library reads meshes from files only, so the input goes to a per-process temp file whose
// extension follows the content: '<' first -> .dae, "solid" or binary bytes -> .stl, otherwise
// .obj.
#include <Eigen/Core>
#include <algorithm>
#include <cstring>
#include <hullcheck/core/convex_hull.hpp>
#include <hullcheck/robot/convex_decomposition.hpp>
#include <hullcheck/robot/mesh_file.hpp>
#include <string>
#include <vector>

#include "fuzz_support.hpp"

namespace {

// The extension URDF meshes of this content would carry.
const char* extension_for(const std::uint8_t* data, std::size_t size) {
  std::size_t i = 0;
  while (i < size && (data[i] == ' ' || data[i] == '\t' || data[i] == '\r' || data[i] == '\n')) {
    ++i;
  }
  if (i < size && data[i] == '<') return ".dae";
  if (size - i >= 5 && std::memcmp(data + i, "solid", 5) == 0) return ".stl";
  for (std::size_t k = 0; k < size && k < 256; ++k) {
    if (data[k] == 0 || data[k] >= 0x80) return ".stl";
  }
  return ".obj";
}

}  // namespace

// One input: a mesh file's bytes.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hullcheck;
  const std::string file = fuzz::temp_path(extension_for(data, size));
  fuzz::write_file(file, data, size);
  fuzz::expect_input_errors_only([&] {
    const TriangleMesh mesh = read_mesh(file, Eigen::Vector3d(1.0, 1.0, 1.0));
    const ConvexHull hull(mesh.vertices);
    // The decomposition at a tolerance of a quarter of the mesh's size and two pieces at most,
    // so that the fuzzer explores degenerate and broken triangle soups quickly (the work grows
    // as the hull's area over the tolerance squared: at 5% and 4 pieces, one input took over
    // 10 s in the -O0 fuzzing build, 7 ms in Release; regressions/mesh/timeout-*).
    DecompositionOptions options;
    options.tolerance = std::max(1e-6, 0.25 * hull.extent());
    options.max_pieces = 2;
    const ConvexDecomposition pieces = decompose_mesh(mesh, options);
    if (pieces.pieces.empty()) __builtin_trap();  // a mesh with vertices has a piece
  });
  std::remove(file.c_str());
  return 0;
}
