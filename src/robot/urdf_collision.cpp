#include "urdf_collision.hpp"

#include <algorithm>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/robot/decomposition_cache.hpp>
#include <hullcheck/robot/length_checks.hpp>
#include <hullcheck/robot/mesh_file.hpp>
#include <tuple>
#include <utility>

#include "urdf_pose.hpp"

namespace hullcheck::detail {
namespace {

// The distinct points, in the order of their first occurrence. Mesh files repeat a vertex for
// every triangle using it (binary STL about 6 times), and qhull's time grows with its input,
// duplicates included: removing them first halves the hull time of a large STL.
std::vector<Eigen::Vector3d> distinct_points(const std::vector<Eigen::Vector3d>& points) {
  std::vector<std::size_t> order(points.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  const auto key = [&](std::size_t i) {
    return std::make_tuple(points[i].x(), points[i].y(), points[i].z(), i);
  };
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return key(a) < key(b); });
  std::vector<char> keep(points.size(), 0);
  for (std::size_t k = 0; k < order.size(); ++k) {
    keep[order[k]] = k == 0 || points[order[k]] != points[order[k - 1]];
  }
  std::vector<Eigen::Vector3d> out;
  out.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (keep[i]) out.push_back(points[i]);
  }
  return out;
}

// The URDF element name of a geometry type.
const char* geometry_tag(int type) {
  switch (type) {
    case urdf::Geometry::SPHERE:
      return "sphere";
    case urdf::Geometry::BOX:
      return "box";
    case urdf::Geometry::CYLINDER:
      return "cylinder";
    case urdf::Geometry::MESH:
      return "mesh";
    default:
      return "geometry";
  }
}

// Throws unless every vertex coordinate is within the loaders' length range (m).
void check_mesh_extent(const std::vector<Eigen::Vector3d>& vertices, const std::string& what) {
  for (const Eigen::Vector3d& v : vertices) {
    if (v.array().abs().maxCoeff() > kMaxLoadedLength) {
      check_lengths(v, what + ": vertex");
    }
  }
}

// Sets `out`'s unpadded shape and source from a sphere, box or cylinder after checking its
// dimensions; throws for any other geometry type (meshes are made elsewhere).
void set_primitive(const urdf::Geometry& g, const std::string& where, CollisionShape& out) {
  switch (g.type) {
    case urdf::Geometry::SPHERE: {
      const auto& s = static_cast<const urdf::Sphere&>(g);
      check_length(s.radius, where + ": <sphere radius>");
      out.unpadded = Sphere(s.radius);
      out.source = "sphere";
      break;
    }
    case urdf::Geometry::BOX: {
      const auto& b = static_cast<const urdf::Box&>(g);
      check_lengths(Eigen::Vector3d(b.dim.x, b.dim.y, b.dim.z), where + ": <box size>");
      out.unpadded = Box(b.dim.x, b.dim.y, b.dim.z);
      out.source = "box";
      break;
    }
    case urdf::Geometry::CYLINDER: {
      const auto& c = static_cast<const urdf::Cylinder&>(g);
      check_length(c.radius, where + ": <cylinder radius>");
      check_length(c.length, where + ": <cylinder length>");
      out.unpadded = Cylinder(c.radius, c.length);
      out.source = "cylinder";
      break;
    }
    default:
      throw InputError("unknown geometry type");
  }
}

}  // namespace

bool CollisionLoader::MeshKey::operator<(const MeshKey& o) const {
  return std::tie(path, sx, sy, sz) < std::tie(o.path, o.sx, o.sy, o.sz);
}

CollisionLoader::CollisionLoader(const std::string& source, const std::string& base_dir,
                                 const RobotLoadOptions& options)
    : source_(source), base_dir_(base_dir), options_(options) {}

std::vector<CollisionShape> CollisionLoader::link_shapes(const urdf::Link& link) {
  std::vector<CollisionShape> shapes;
  int element = 0;
  for (const urdf::CollisionSharedPtr& c : link.collision_array) {
    if (!c) continue;
    for (CollisionShape& shape : make_shapes(*c, link.name, element)) {
      shapes.push_back(std::move(shape));
    }
    ++element;
  }
  return shapes;
}

std::vector<CollisionShape> CollisionLoader::make_shapes(const urdf::Collision& collision,
                                                         const std::string& link_name,
                                                         int element) {
  const std::string where = "URDF '" + source_ + "': link '" + link_name + "'";
  if (!collision.geometry) throw InputError(where + ": <collision> without <geometry>");
  CollisionShape out{Sphere(0.0),
                     Sphere(0.0),
                     Eigen::Isometry3d::Identity(),
                     Eigen::Vector3d::Zero(),
                     0.0,
                     std::string(),
                     0};
  out.element = element;
  out.origin = to_isometry(collision.origin);
  check_lengths(out.origin.translation(), where + ": <collision><origin xyz>");
  const urdf::Geometry& g = *collision.geometry;
  try {
    if (g.type == urdf::Geometry::MESH) {
      return mesh_pieces(static_cast<const urdf::Mesh&>(g), out, where);
    }
    set_primitive(g, where, out);
  } catch (const InputError& e) {
    // The loader's own errors carry the prefix already; the Shape constructors' get it once,
    // with the element.
    const std::string what = e.what();
    if (what.rfind("URDF '", 0) == 0) throw;
    throw InputError(where + ": <" + geometry_tag(g.type) + ">: " + what);
  }
  return {out};
}

std::vector<CollisionShape> CollisionLoader::mesh_pieces(const urdf::Mesh& m, CollisionShape& out,
                                                         const std::string& where) {
  const std::string path = resolve_resource_path(m.filename, base_dir_, options_.packages, where);
  const MeshShapes& mesh =
      mesh_shapes(path, Eigen::Vector3d(m.scale.x, m.scale.y, m.scale.z), where);
  out.mesh_vertex_count = mesh.vertex_count;
  out.mesh_excess = mesh.excess;
  out.source = path;
  out.piece_count = static_cast<int>(mesh.hulls.size());
  out.element_hull_unpadded = mesh.hull_of_pieces;
  std::vector<CollisionShape> pieces;
  for (std::size_t k = 0; k < mesh.hulls.size(); ++k) {
    out.unpadded = mesh.hulls[k];
    out.piece = static_cast<int>(k);
    pieces.push_back(out);
  }
  return pieces;
}

const CollisionLoader::MeshShapes& CollisionLoader::mesh_shapes(const std::string& path,
                                                                const Eigen::Vector3d& scale,
                                                                const std::string& where) {
  const MeshKey key{path, scale.x(), scale.y(), scale.z()};
  auto it = meshes_.find(key);
  if (it != meshes_.end()) return it->second;
  const std::string what = where + ": mesh '" + path + "' (after <mesh scale>)";
  MeshShapes shapes = options_.mesh_geometry == MeshGeometry::kHull
                          ? mesh_hull(path, scale, what)
                          : mesh_decomposition(path, scale, what);
  return meshes_.emplace(key, std::move(shapes)).first->second;
}

CollisionLoader::MeshShapes CollisionLoader::mesh_hull(const std::string& path,
                                                       const Eigen::Vector3d& scale,
                                                       const std::string& what) const {
  MeshShapes shapes{{}, nullptr, 0, -1.0};
  const std::vector<Eigen::Vector3d> vertices =
      read_mesh_vertices(path, scale, options_.mesh_limits);
  check_mesh_extent(vertices, what);
  shapes.hulls.emplace_back(distinct_points(vertices));
  shapes.vertex_count = vertices.size();
  return shapes;
}

CollisionLoader::MeshShapes CollisionLoader::mesh_decomposition(const std::string& path,
                                                                const Eigen::Vector3d& scale,
                                                                const std::string& what) const {
  MeshShapes shapes{{}, nullptr, 0, -1.0};
  const std::string cache_dir = !options_.use_decomposition_cache ? std::string()
                                : options_.decomposition_cache_dir.empty()
                                    ? default_decomposition_cache_dir()
                                    : options_.decomposition_cache_dir;
  const MeshDecomposition d = decompose_mesh_file(
      path, scale, options_.decomposition, options_.mesh_limits, cache_dir,
      [&](const TriangleMesh& mesh) { check_mesh_extent(mesh.vertices, what); });
  for (const auto& piece : d.decomposition.pieces) {
    check_mesh_extent(piece, what);  // a cached entry's points, checked like a mesh's
    shapes.hulls.emplace_back(piece);
  }
  shapes.vertex_count = d.vertex_count;
  shapes.excess = d.decomposition.bound;
  if (shapes.hulls.size() > 1) {
    std::vector<Eigen::Vector3d> all;
    for (const ConvexHull& h : shapes.hulls) {
      all.insert(all.end(), h.vertices().begin(), h.vertices().end());
    }
    shapes.hull_of_pieces = std::make_shared<const ConvexHull>(distinct_points(all));
  }
  return shapes;
}

}  // namespace hullcheck::detail
