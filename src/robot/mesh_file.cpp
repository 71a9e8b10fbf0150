#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <tinyxml2.h>

#include <algorithm>
#include <assimp/IOStream.hpp>
#include <assimp/IOSystem.hpp>
#include <assimp/Importer.hpp>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/robot/mesh_file.hpp>
#include <limits>
#include <map>
#include <string_view>
#include <unordered_set>
#include <utility>

namespace hullcheck {
namespace {

// Conservative peak bytes of reading a mesh (assimp's structures and hullcheck's copies) per
// byte of the file, beyond declared counts. Measured: an OBJ of line elements ("l 1 2", the
// densest) peaks at 37 bytes per file byte, a binary STL at 7.3.
constexpr std::uint64_t kBytesPerTextByte = 64;
constexpr std::uint64_t kBytesPerBinaryStlByte = 12;
// Bytes per declared array element (stored as 8-byte values or indices) and per primitive
// point (its vertex, normal and index entries in assimp's mesh).
constexpr std::uint64_t kBytesPerElement = 8;
constexpr std::uint64_t kBytesPerPoint = 64;
// Largest COLLADA <input offset> (real files use a handful of inputs per primitive).
constexpr std::uint64_t kMaxInputOffset = 63;
// Deepest node hierarchy after instancing (assimp walks it recursively).
constexpr std::size_t kMaxNodeDepth = 256;

[[noreturn]] void fail(const std::string& path, const std::string& problem) {
  throw InputError("mesh '" + path + "': " + problem);
}

// Throws "mesh 'p': <what> N exceeds the limit L (MeshLimits::<name>)" when count > limit.
void check_limit(const std::string& path, const std::string& what, std::uint64_t count,
                 std::uint64_t limit, const char* name) {
  if (count <= limit) return;
  fail(path, what + " " + std::to_string(count) + " exceeds the limit " + std::to_string(limit) +
                 " (MeshLimits::" + name + ")");
}

// a * b, saturating instead of overflowing.
std::uint64_t mul_sat(std::uint64_t a, std::uint64_t b) {
  if (a != 0 && b > std::numeric_limits<std::uint64_t>::max() / a) {
    return std::numeric_limits<std::uint64_t>::max();
  }
  return a * b;
}

std::uint64_t add_sat(std::uint64_t a, std::uint64_t b) {
  return b > std::numeric_limits<std::uint64_t>::max() - a
             ? std::numeric_limits<std::uint64_t>::max()
             : a + b;
}

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  if (!ext.empty()) ext.erase(0, 1);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

// The whole file, after checking its size against the limit.
std::string read_bounded(const std::string& path, const MeshLimits& limits) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) fail(path, "cannot be read: " + ec.message());
  check_limit(path, "file size (bytes)", size, limits.max_file_bytes, "max_file_bytes");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot be read: cannot open the file");
  std::string bytes(static_cast<std::size_t>(size), '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(size));
  if (static_cast<std::uintmax_t>(in.gcount()) != size) {
    fail(path, "cannot be read: the file changed while it was read");
  }
  return bytes;
}

// Binary STL: the declared facet count must fit the file and the limits (ASCII STL declares
// nothing: its memory is bounded through the file size).
void check_stl(const std::string& path, const std::string& bytes, const MeshLimits& limits) {
  if (bytes.size() < 84 || bytes.compare(0, 5, "solid") == 0) return;
  std::uint32_t facets = 0;
  std::memcpy(&facets, bytes.data() + 80, sizeof facets);
  const std::uint64_t room = (bytes.size() - 84) / 50;
  if (facets > room) {
    fail(path, "binary STL declares " + std::to_string(facets) + " facets, but its " +
                   std::to_string(bytes.size()) + " bytes hold at most " + std::to_string(room));
  }
  check_limit(path, "face count", facets, limits.max_faces, "max_faces");
  check_limit(path, "vertex count", 3ull * facets, limits.max_vertices, "max_vertices");
}

// An unsigned integer attribute (or `fallback` when absent); throws when it is not one.
std::uint64_t count_attribute(const std::string& path, const tinyxml2::XMLElement& e,
                              const char* name, std::uint64_t fallback) {
  const char* text = e.Attribute(name);
  if (text == nullptr) return fallback;
  std::uint64_t value = 0;
  if (!tinyxml2::XMLUtil::ToUnsigned64(text, &value) || text[0] == '-') {
    fail(path, std::string("<") + e.Name() + " " + name + "=\"" + text +
                   "\"> is not a non-negative integer");
  }
  return value;
}

// Sum of the whitespace-separated integers of a COLLADA <vcount>, <p> or <v> (saturating);
// throws when the text holds anything else (assimp reads such a token as a huge index).
std::uint64_t integer_list_sum(const std::string& path, const tinyxml2::XMLElement& e) {
  const char* text = e.GetText();
  std::uint64_t sum = 0;
  for (const char* p = text == nullptr ? "" : text; *p != '\0';) {
    if (std::isspace(static_cast<unsigned char>(*p))) {
      ++p;
      continue;
    }
    std::uint64_t value = 0;
    const char* start = p;
    while (std::isdigit(static_cast<unsigned char>(*p))) {
      value = add_sat(mul_sat(value, 10), static_cast<std::uint64_t>(*p - '0'));
      ++p;
    }
    if (p == start) {
      fail(path,
           "<" + std::string(e.Name()) + "> holds something other than non-negative integers");
    }
    sum = add_sat(sum, value);
  }
  return sum;
}

// The id attributes of a COLLADA document, from one walk: every element's (for <input source>
// references) and the <node> elements by id (for <instance_node url>; the first of a repeated id).
struct ColladaIds {
  std::unordered_set<std::string> all;
  std::map<std::string, const tinyxml2::XMLElement*> nodes;
};

ColladaIds collada_ids(const tinyxml2::XMLDocument& doc) {
  ColladaIds ids;
  std::vector<const tinyxml2::XMLElement*> todo{doc.RootElement()};
  while (!todo.empty()) {
    const tinyxml2::XMLElement* e = todo.back();
    todo.pop_back();
    if (const char* id = e->Attribute("id")) {
      ids.all.emplace(id);
      if (std::strcmp(e->Name(), "node") == 0) ids.nodes.emplace(id, e);
    }
    for (const tinyxml2::XMLElement* c = e->FirstChildElement(); c != nullptr;
         c = c->NextSiblingElement()) {
      todo.push_back(c);
    }
  }
  return ids;
}

// An <input>'s source must name an element of the file ("#id"), and index lists (<p>, <v>)
// must hold non-negative integers only: assimp 5.2 sizes its arrays from what it reads there
// even when the source is missing (a 5 KB file made it allocate 2.4 GB).
void check_references(const std::string& path, const tinyxml2::XMLElement& e,
                      const std::unordered_set<std::string>& ids) {
  const std::string_view name = e.Name();
  if (name == "input") {
    const char* source = e.Attribute("source");
    if (source != nullptr && (source[0] != '#' || ids.count(source + 1) == 0)) {
      fail(path, std::string("<input source=\"") + source + "\"> names no element of the file");
    }
  } else if (name == "p" || name == "v") {
    integer_list_sum(path, e);
  }
}

// What the declared counts of a COLLADA document let assimp allocate, estimated from above.
struct ColladaBudget {
  std::uint64_t bytes = 0;   // estimated memory
  std::uint64_t points = 0;  // primitive points (index tuples)
  std::uint64_t faces = 0;   // declared primitives
};

bool is_primitive(std::string_view name) {
  return name == "triangles" || name == "polylist" || name == "polygons" || name == "lines" ||
         name == "linestrips" || name == "tristrips" || name == "trifans";
}

// Adds one element's declared counts to the budget; every count must be backed by the file's
// bytes (an element of a count needs at least one byte of the file).
void add_declared(const std::string& path, const tinyxml2::XMLElement& e, std::uint64_t file_bytes,
                  ColladaBudget& budget) {
  const std::uint64_t count = count_attribute(path, e, "count", 0);
  const std::uint64_t stride = count_attribute(path, e, "stride", 1);
  const std::uint64_t offset =
      std::strcmp(e.Name(), "input") == 0 ? count_attribute(path, e, "offset", 0) : 0;
  if (offset > kMaxInputOffset) {
    fail(path, "<" + std::string(e.Name()) + " offset=\"" + std::to_string(offset) +
                   "\"> is above " + std::to_string(kMaxInputOffset));
  }
  std::uint64_t elements = mul_sat(count, stride);
  const std::string_view name = e.Name();
  if (is_primitive(name)) {
    std::uint64_t inputs = 1;
    for (const tinyxml2::XMLElement* in = e.FirstChildElement("input"); in != nullptr;
         in = in->NextSiblingElement("input")) {
      inputs = std::max(inputs, count_attribute(path, *in, "offset", 0) + 1);
    }
    const tinyxml2::XMLElement* vcount = e.FirstChildElement("vcount");
    const std::uint64_t points = vcount != nullptr ? integer_list_sum(path, *vcount)
                                                   : mul_sat(count, name == "lines" ? 2 : 3);
    elements = std::max(elements, points);
    budget.points = add_sat(budget.points, points);
    budget.faces = add_sat(budget.faces, count);
    budget.bytes =
        add_sat(budget.bytes, mul_sat(points, inputs * kBytesPerElement + kBytesPerPoint));
  } else {
    budget.bytes = add_sat(budget.bytes, mul_sat(elements, kBytesPerElement));
  }
  if (elements > file_bytes) {
    fail(path, "<" + std::string(name) + "> declares " + std::to_string(elements) +
                   " elements, more than the file's " + std::to_string(file_bytes) +
                   " bytes can hold");
  }
}

// The node count and depth of the COLLADA scene after <instance_node> expansion, saturating at
// the limits; throws on an instancing cycle.
class NodeExpansion {
 public:
  // `nodes_by_id`: the document's <node> elements by id (ColladaIds::nodes).
  NodeExpansion(const std::string& path,
                const std::map<std::string, const tinyxml2::XMLElement*>& nodes_by_id,
                const MeshLimits& limits)
      : path_(path), limits_(limits), by_id_(nodes_by_id) {}

  // Expanded node count of every <node> tree under `root`.
  std::uint64_t count_under(const tinyxml2::XMLElement* root) {
    std::uint64_t total = 0;
    std::vector<const tinyxml2::XMLElement*> todo{root};
    while (!todo.empty()) {
      const tinyxml2::XMLElement* e = todo.back();
      todo.pop_back();
      for (const tinyxml2::XMLElement* c = e->FirstChildElement(); c != nullptr;
           c = c->NextSiblingElement()) {
        if (std::strcmp(c->Name(), "node") == 0) {
          total = add_sat(total, expanded(c, 1).count);
        } else {
          todo.push_back(c);
        }
      }
    }
    return total;
  }

 private:
  // Node count and height (1 for a leaf) of the subtree of `node` after instancing.
  struct Subtree {
    std::uint64_t count = 0;
    std::size_t height = 0;
  };

  void check_depth(std::size_t depth) const {
    if (depth <= kMaxNodeDepth) return;
    fail(path_, "node hierarchy (with <instance_node>) is deeper than " +
                    std::to_string(kMaxNodeDepth) + " levels");
  }

  // The subtree of `node`, which sits at `depth` in the expanded tree (memoised: a node
  // instanced in many places is counted once per place but expanded once).
  Subtree expanded(const tinyxml2::XMLElement* node, std::size_t depth) {
    check_depth(depth);
    const auto memo = memo_.find(node);
    if (memo != memo_.end()) {
      if (memo->second.height == 0) fail(path_, "<instance_node> references form a cycle");
      check_depth(depth + memo->second.height - 1);
      return memo->second;
    }
    memo_[node] = Subtree{};  // height 0: in progress
    Subtree out{1, 1};
    const auto add = [&](const tinyxml2::XMLElement* child) {
      const Subtree sub = expanded(child, depth + 1);
      out.count = add_sat(out.count, sub.count);
      out.height = std::max(out.height, sub.height + 1);
    };
    for (const tinyxml2::XMLElement* c = node->FirstChildElement(); c != nullptr;
         c = c->NextSiblingElement()) {
      if (std::strcmp(c->Name(), "node") == 0) {
        add(c);
      } else if (std::strcmp(c->Name(), "instance_node") == 0) {
        const char* url = c->Attribute("url");
        const auto target = url != nullptr && url[0] == '#' ? by_id_.find(url + 1) : by_id_.end();
        if (target != by_id_.end()) add(target->second);
      }
      if (out.count > limits_.max_nodes) break;
    }
    memo_[node] = out;
    return out;
  }

  const std::string& path_;
  const MeshLimits& limits_;
  const std::map<std::string, const tinyxml2::XMLElement*>& by_id_;
  std::map<const tinyxml2::XMLElement*, Subtree> memo_;
};

// COLLADA: every declared count is backed by the file and within the limits, the estimated
// memory is within the limit, and node instancing stays bounded and acyclic.
void check_collada(const std::string& path, const std::string& bytes, const MeshLimits& limits) {
  tinyxml2::XMLDocument doc;
  if (doc.Parse(bytes.data(), bytes.size()) != tinyxml2::XML_SUCCESS) {
    fail(path, std::string("malformed COLLADA XML: ") + doc.ErrorStr());
  }
  if (doc.RootElement() == nullptr) fail(path, "COLLADA file without a root element");
  ColladaBudget budget;
  budget.bytes = mul_sat(bytes.size(), kBytesPerTextByte);
  const ColladaIds ids = collada_ids(doc);
  std::vector<const tinyxml2::XMLElement*> todo{doc.RootElement()};
  while (!todo.empty()) {
    const tinyxml2::XMLElement* e = todo.back();
    todo.pop_back();
    add_declared(path, *e, bytes.size(), budget);
    check_references(path, *e, ids.all);
    for (const tinyxml2::XMLElement* c = e->FirstChildElement(); c != nullptr;
         c = c->NextSiblingElement()) {
      todo.push_back(c);
    }
  }
  check_limit(path, "declared face count", budget.faces, limits.max_faces, "max_faces");
  check_limit(path, "declared primitive point count", budget.points, limits.max_vertices,
              "max_vertices");
  check_limit(path, "estimated memory (bytes) for the declared counts", budget.bytes,
              limits.max_memory_bytes, "max_memory_bytes");
  NodeExpansion nodes(path, ids.nodes, limits);
  check_limit(path, "node count after <instance_node> expansion",
              nodes.count_under(doc.RootElement()), limits.max_nodes, "max_nodes");
}

// Checks a file of a vetted format before assimp reads it; throws for other formats unless
// the limits allow them.
void vet(const std::string& path, const std::string& ext, const std::string& bytes,
         const MeshLimits& limits) {
  if (ext == "stl") {
    check_stl(path, bytes, limits);
  } else if (ext == "dae") {
    check_collada(path, bytes, limits);
  } else if (ext != "obj" && limits.vetted_formats_only) {
    fail(path, "format '." + ext +
                   "' is not accepted: only STL, OBJ and COLLADA (.dae) meshes are checked "
                   "against MeshLimits (set MeshLimits::vetted_formats_only = false to read "
                   "other formats without those checks)");
  }
  if (ext == "stl" || ext == "obj" || ext == "dae") {
    const bool binary_stl = ext == "stl" && bytes.compare(0, 5, "solid") != 0;
    check_limit(path, "estimated memory (bytes) for the file size",
                mul_sat(bytes.size(), binary_stl ? kBytesPerBinaryStlByte : kBytesPerTextByte),
                limits.max_memory_bytes, "max_memory_bytes");
  }
}

// Vertex and face counts of the imported scene, node instances included.
void check_scene_counts(const std::string& path, const aiScene& scene, const MeshLimits& limits) {
  std::uint64_t faces = 0;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) faces += scene.mMeshes[m]->mNumFaces;
  check_limit(path, "face count", faces, limits.max_faces, "max_faces");
  std::uint64_t vertices = 0;
  std::uint64_t nodes = 0;
  std::vector<const aiNode*> todo{scene.mRootNode};
  while (!todo.empty()) {
    const aiNode* node = todo.back();
    todo.pop_back();
    check_limit(path, "node count", ++nodes, limits.max_nodes, "max_nodes");
    for (unsigned m = 0; m < node->mNumMeshes; ++m) {
      vertices += scene.mMeshes[node->mMeshes[m]]->mNumVertices;
    }
    check_limit(path, "vertex count", vertices, limits.max_vertices, "max_vertices");
    for (unsigned c = 0; c < node->mNumChildren; ++c) todo.push_back(node->mChildren[c]);
  }
}

// An IOSystem that opens no file: assimp reads the checked bytes from memory only, never a
// further file a mesh names (an OBJ's material library, a COLLADA's external reference).
class NoFilesIOSystem : public Assimp::IOSystem {
 public:
  bool Exists(const char* /*file*/) const override { return false; }
  char getOsSeparator() const override { return '/'; }
  Assimp::IOStream* Open(const char* /*file*/, const char* /*mode*/) override { return nullptr; }
  void Close(Assimp::IOStream* stream) override { delete stream; }
};

// Appends every mesh instance below `node` to `out` (vertices transformed to the file's model
// frame and scaled; faces as fans, reversed when `mirror`); triangles only when `with_faces`.
void collect(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent,
             const Eigen::Vector3d& scale, bool with_faces, bool mirror, TriangleMesh* out) {
  const aiMatrix4x4 transform = parent * node.mTransformation;
  for (unsigned m = 0; m < node.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[m]];
    const auto first = static_cast<std::uint32_t>(out->vertices.size());
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D p = transform * mesh.mVertices[v];
      out->vertices.emplace_back(scale.x() * p.x, scale.y() * p.y, scale.z() * p.z);
    }
    if (!with_faces) continue;
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      for (unsigned k = 2; k < face.mNumIndices; ++k) {
        std::array<std::uint32_t, 3> t{first + face.mIndices[0], first + face.mIndices[k - 1],
                                       first + face.mIndices[k]};
        if (mirror) std::swap(t[1], t[2]);
        out->triangles.push_back(t);
      }
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) {
    collect(scene, *node.mChildren[c], transform, scale, with_faces, mirror, out);
  }
}

// read_mesh and read_mesh_vertices: the vetted import, with or without the faces.
TriangleMesh import_mesh(const std::string& path, const Eigen::Vector3d& scale,
                         const MeshLimits& limits, bool with_faces) {
  if (!scale.allFinite()) {
    throw InputError("mesh '" + path + "': scale is not finite");
  }
  const std::string bytes = read_bounded(path, limits);
  const std::string ext = lower_extension(path);
  vet(path, ext, bytes, limits);
  Assimp::Importer importer;
  importer.SetIOHandler(new NoFilesIOSystem);  // the importer owns it
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  // No triangulation, no normals, no vertex joining (the hull computation handles duplicates;
  // faces become fans here). The structure is validated (indices in range). Read from the
  // checked bytes, the format chosen by the extension.
  const aiScene* scene = importer.ReadFileFromMemory(bytes.data(), bytes.size(),
                                                     aiProcess_ValidateDataStructure, ext.c_str());
  if (scene == nullptr || scene->mRootNode == nullptr) {
    throw InputError("mesh '" + path + "': cannot be read: " + importer.GetErrorString());
  }
  check_scene_counts(path, *scene, limits);
  TriangleMesh mesh;
  std::size_t total = 0;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) total += scene->mMeshes[m]->mNumVertices;
  mesh.vertices.reserve(total);
  const bool mirror = (scale.array() < 0.0).count() % 2 == 1;
  collect(*scene, *scene->mRootNode, aiMatrix4x4(), scale, with_faces, mirror, &mesh);
  if (mesh.vertices.empty()) {
    throw InputError("mesh '" + path + "': holds no vertices");
  }
  for (const Eigen::Vector3d& v : mesh.vertices) {
    if (!v.allFinite()) throw InputError("mesh '" + path + "': has a non-finite vertex");
  }
  return mesh;
}

}  // namespace

std::vector<Eigen::Vector3d> read_mesh_vertices(const std::string& path,
                                                const Eigen::Vector3d& scale,
                                                const MeshLimits& limits) {
  return import_mesh(path, scale, limits, false).vertices;
}

TriangleMesh read_mesh(const std::string& path, const Eigen::Vector3d& scale,
                       const MeshLimits& limits) {
  return import_mesh(path, scale, limits, true);
}

}  // namespace hullcheck
