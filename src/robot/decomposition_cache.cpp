#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/core/limits.hpp>
#include <hullcheck/robot/decomposition_cache.hpp>
#include <sstream>
#include <thread>

namespace hullcheck {

namespace {

// Bumped whenever decompose_mesh's output for the same input can change.
constexpr int kFormatVersion = 1;
constexpr const char* kMagic = "hullcheck-decomposition";

// 64-bit FNV-1a.
std::uint64_t fnv1a(const void* data, std::size_t size,
                    std::uint64_t hash = 0xcbf29ce484222325ull) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) {
    hash ^= bytes[i];
    hash *= 0x100000001b3ull;
  }
  return hash;
}

std::string hex(std::uint64_t v) {
  char buffer[17];
  std::snprintf(buffer, sizeof buffer, "%016llx", static_cast<unsigned long long>(v));
  return buffer;
}

// Doubles as C99 hexadecimal floats: exact round trip.
std::string hexfloat(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%a", v);
  return buffer;
}

// The mesh file's bytes, within the mesh limits' file size.
std::string read_bytes(const std::string& path, const MeshLimits& limits) {
  std::error_code error;
  const auto size = std::filesystem::file_size(path, error);
  if (error) throw InputError("mesh '" + path + "': cannot be read: " + error.message());
  if (size > limits.max_file_bytes) {
    throw InputError(
        "mesh '" + path + "': file size " + std::to_string(size) +
        " bytes exceeds the limit max_file_bytes = " + std::to_string(limits.max_file_bytes));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("mesh '" + path + "': cannot be opened");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// What an entry must hold to be used: the key's values.
struct EntryKey {
  std::uint64_t content;
  std::uint64_t size;
  Eigen::Vector3d scale;
  DecompositionOptions options;
};

std::string header(const EntryKey& key) {
  std::ostringstream out;
  out << kMagic << ' ' << kFormatVersion << '\n'
      << "content " << hex(key.content) << ' ' << key.size << '\n'
      << "scale " << hexfloat(key.scale.x()) << ' ' << hexfloat(key.scale.y()) << ' '
      << hexfloat(key.scale.z()) << '\n'
      << "tolerance " << hexfloat(key.options.tolerance) << '\n'
      << "max_pieces " << key.options.max_pieces << '\n';
  return out.str();
}

std::string entry_name(const EntryKey& key) {
  const std::string h = header(key);
  return hex(fnv1a(h.data(), h.size())) + ".hcd";
}

// Parses a cache entry; false when it is not a valid entry for `key`.
bool parse_entry(const std::string& text, const EntryKey& key, MeshDecomposition* out) {
  const std::string expected = header(key);
  if (text.compare(0, expected.size(), expected) != 0) return false;
  std::istringstream in(text.substr(expected.size()));
  std::string word;
  std::size_t vertex_count = 0, pieces = 0;
  std::string bound_text;
  if (!(in >> word >> vertex_count) || word != "vertex_count") return false;
  if (!(in >> word >> bound_text) || word != "bound") return false;
  if (!(in >> word >> pieces) || word != "pieces") return false;
  if (pieces < 1 || pieces > static_cast<std::size_t>(key.options.max_pieces)) return false;
  const auto number = [](const std::string& s, double* v) {
    char* end = nullptr;
    *v = std::strtod(s.c_str(), &end);
    return end != s.c_str() && *end == '\0' && std::isfinite(*v);
  };
  double bound = 0.0;
  if (!number(bound_text, &bound) || bound < 0.0) return false;
  MeshDecomposition result;
  result.vertex_count = vertex_count;
  result.decomposition.bound = bound;
  result.decomposition.within_tolerance = bound <= key.options.tolerance;
  std::size_t total = 0;
  for (std::size_t p = 0; p < pieces; ++p) {
    std::size_t count = 0;
    if (!(in >> word >> count) || word != "piece" || count < 1) return false;
    total += count;
    if (total > 8 * vertex_count + 8 * pieces) return false;  // more than the mesh can give
    std::vector<Eigen::Vector3d> points(count);
    for (Eigen::Vector3d& point : points) {
      for (int k = 0; k < 3; ++k) {
        std::string s;
        if (!(in >> s) || !number(s, &point[k]) || std::abs(point[k]) > kMaxLength) return false;
      }
    }
    result.decomposition.pieces.push_back(std::move(points));
  }
  if (!(in >> word) || word != "end") return false;
  result.from_cache = true;
  *out = std::move(result);
  return true;
}

std::string format_entry(const EntryKey& key, const MeshDecomposition& d) {
  std::ostringstream out;
  out << header(key) << "vertex_count " << d.vertex_count << '\n'
      << "bound " << hexfloat(d.decomposition.bound) << '\n'
      << "pieces " << d.decomposition.pieces.size() << '\n';
  for (const auto& piece : d.decomposition.pieces) {
    out << "piece " << piece.size() << '\n';
    for (const Eigen::Vector3d& p : piece) {
      out << hexfloat(p.x()) << ' ' << hexfloat(p.y()) << ' ' << hexfloat(p.z()) << '\n';
    }
  }
  out << "end\n";
  return out.str();
}

// Writes the entry through a temporary file and a rename; failures are ignored (no caching).
void store(const std::filesystem::path& file, const std::string& text) {
  std::error_code error;
  std::filesystem::create_directories(file.parent_path(), error);
  if (error) return;
  std::ostringstream suffix;
  suffix << ".tmp." << ::getpid() << '.' << std::this_thread::get_id();
  const std::filesystem::path temporary = file.string() + suffix.str();
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) return;
    out << text;
    if (!out.flush()) {
      out.close();
      std::filesystem::remove(temporary, error);
      return;
    }
  }
  std::filesystem::rename(temporary, file, error);
  if (error) std::filesystem::remove(temporary, error);
}

}  // namespace

std::string default_decomposition_cache_dir() {
  if (const char* dir = std::getenv("HULLCHECK_CACHE_DIR"); dir != nullptr && *dir != '\0') {
    return dir;
  }
  if (const char* dir = std::getenv("XDG_CACHE_HOME"); dir != nullptr && *dir != '\0') {
    return std::string(dir) + "/hullcheck";
  }
  if (const char* dir = std::getenv("HOME"); dir != nullptr && *dir != '\0') {
    return std::string(dir) + "/.cache/hullcheck";
  }
  return "";
}

MeshDecomposition decompose_mesh_file(const std::string& path, const Eigen::Vector3d& scale,
                                      const DecompositionOptions& options, const MeshLimits& limits,
                                      const std::string& cache_dir,
                                      const std::function<void(const TriangleMesh&)>& check_mesh) {
  if (!scale.allFinite()) throw InputError("mesh '" + path + "': scale is not finite");
  std::filesystem::path file;
  EntryKey key{0, 0, scale, options};
  if (!cache_dir.empty()) {
    const std::string bytes = read_bytes(path, limits);
    key.content = fnv1a(bytes.data(), bytes.size());
    key.size = bytes.size();
    file = std::filesystem::path(cache_dir) / "decompositions" / entry_name(key);
    std::ifstream in(file, std::ios::binary);
    if (in) {
      std::ostringstream text;
      text << in.rdbuf();
      MeshDecomposition cached;
      if (parse_entry(text.str(), key, &cached) && cached.vertex_count <= limits.max_vertices) {
        return cached;
      }
    }
  }
  MeshDecomposition result;
  const TriangleMesh mesh = read_mesh(path, scale, limits);
  result.vertex_count = mesh.vertices.size();
  if (check_mesh) check_mesh(mesh);
  try {
    result.decomposition = decompose_mesh(mesh, options);
  } catch (const InputError& e) {
    throw InputError("mesh '" + path + "': " + e.what());
  }
  if (!file.empty()) store(file, format_entry(key, result));
  return result;
}

}  // namespace hullcheck
