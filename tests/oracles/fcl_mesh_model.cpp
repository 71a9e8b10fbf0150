#include "fcl_mesh_model.hpp"

#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/OBBRSS.h>
#include <urdf_parser/urdf_parser.h>

#include <assimp/Importer.hpp>
#include <filesystem>
#include <stdexcept>
#include <utility>

namespace hullcheck::test {
namespace {

// A 4x4 assimp matrix in double.
Eigen::Matrix4d to_eigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d out;
  for (unsigned r = 0; r < 4; ++r) {
    for (unsigned c = 0; c < 4; ++c) out(r, c) = static_cast<double>(m[r][c]);
  }
  return out;
}

// Vertices and triangles gathered from an assimp scene, in the file's model frame.
struct TriangleSoup {
  std::vector<fcl::Vector3d> vertices;
  std::vector<fcl::Triangle> triangles;
};

// Appends the triangles of `node` and its children, with the composed node transforms and
// then the URDF scale applied to every vertex. Points and lines (fewer than 3 indices) are not
// surface and are skipped.
void collect(const aiScene& scene, const aiNode& node, const Eigen::Matrix4d& parent,
             const Eigen::Vector3d& scale, TriangleSoup* out) {
  const Eigen::Matrix4d transform = parent * to_eigen(node.mTransformation);
  for (unsigned k = 0; k < node.mNumMeshes; ++k) {
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[k]];
    const std::size_t first = out->vertices.size();
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D& p = mesh.mVertices[v];
      const Eigen::Vector4d h(p.x, p.y, p.z, 1.0);
      out->vertices.push_back(scale.cwiseProduct((transform * h).head<3>()));
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;
      out->triangles.emplace_back(first + face.mIndices[0], first + face.mIndices[1],
                                  first + face.mIndices[2]);
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) {
    collect(scene, *node.mChildren[c], transform, scale, out);
  }
}

// The triangle mesh of one file as an OBBRSS BVH.
std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> read_mesh(const std::string& path,
                                                       const Eigen::Vector3d& scale,
                                                       std::size_t* triangles) {
  Assimp::Importer importer;
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate);
  if (scene == nullptr || scene->mRootNode == nullptr) {
    throw std::runtime_error("FclMeshModel: cannot read " + path + ": " +
                             importer.GetErrorString());
  }
  TriangleSoup soup;
  collect(*scene, *scene->mRootNode, Eigen::Matrix4d::Identity(), scale, &soup);
  if (soup.triangles.empty()) throw std::runtime_error("FclMeshModel: no triangle in " + path);
  auto bvh = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  if (bvh->beginModel(static_cast<int>(soup.triangles.size()),
                      static_cast<int>(soup.vertices.size())) != fcl::BVH_OK ||
      bvh->addSubModel(soup.vertices, soup.triangles) != fcl::BVH_OK ||
      bvh->endModel() != fcl::BVH_OK) {
    throw std::runtime_error("FclMeshModel: FCL rejects the BVH of " + path);
  }
  *triangles = soup.triangles.size();
  return bvh;
}

// URDF <origin> as an isometry.
Eigen::Isometry3d to_isometry(const urdf::Pose& pose) {
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() =
      Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z)
          .normalized()
          .toRotationMatrix();
  out.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  return out;
}

// One <collision> element as an FCL geometry; `base_dir` and `packages` resolve mesh URIs.
FclMeshElement to_element(const urdf::Collision& collision, const std::string& link,
                          const std::string& base_dir, const PackageMap& packages) {
  FclMeshElement e;
  e.origin = to_isometry(collision.origin);
  const urdf::Geometry* g = collision.geometry.get();
  if (g == nullptr) throw std::runtime_error("FclMeshModel: link " + link + ": no geometry");
  switch (g->type) {
    case urdf::Geometry::BOX: {
      const auto& box = static_cast<const urdf::Box&>(*g);
      e.geometry = std::make_shared<fcl::Boxd>(box.dim.x, box.dim.y, box.dim.z);
      e.source = "box";
      break;
    }
    case urdf::Geometry::SPHERE:
      e.geometry = std::make_shared<fcl::Sphered>(static_cast<const urdf::Sphere&>(*g).radius);
      e.source = "sphere";
      break;
    case urdf::Geometry::CYLINDER: {
      const auto& cylinder = static_cast<const urdf::Cylinder&>(*g);
      e.geometry = std::make_shared<fcl::Cylinderd>(cylinder.radius, cylinder.length);
      e.source = "cylinder";
      break;
    }
    case urdf::Geometry::MESH: {
      const auto& mesh = static_cast<const urdf::Mesh&>(*g);
      e.source = resolve_resource_path(mesh.filename, base_dir, packages, "link '" + link + "'");
      e.geometry = read_mesh(e.source, Eigen::Vector3d(mesh.scale.x, mesh.scale.y, mesh.scale.z),
                             &e.triangles);
      break;
    }
    default:
      throw std::runtime_error("FclMeshModel: link " + link + ": unsupported geometry type");
  }
  e.geometry->computeLocalAABB();
  return e;
}

}  // namespace

FclMeshModel::FclMeshModel(const std::string& urdf_path, const PackageMap& packages)
    : source_(urdf_path) {
  const urdf::ModelInterfaceSharedPtr urdf = urdf::parseURDFFile(urdf_path);
  if (!urdf) throw std::runtime_error("FclMeshModel: cannot parse " + urdf_path);
  const std::string base_dir = std::filesystem::path(urdf_path).parent_path().string();
  for (const auto& [name, link] : urdf->links_) {
    FclMeshLink out;
    out.name = name;
    for (const urdf::CollisionSharedPtr& c : link->collision_array) {
      if (c) out.elements.push_back(to_element(*c, name, base_dir, packages));
    }
    links_.push_back(std::move(out));
  }
}

int FclMeshModel::link_index(const std::string& name) const {
  for (std::size_t i = 0; i < links_.size(); ++i) {
    if (links_[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

std::size_t FclMeshModel::triangle_count() const {
  std::size_t n = 0;
  for (const FclMeshLink& l : links_) {
    for (const FclMeshElement& e : l.elements) n += e.triangles;
  }
  return n;
}

}  // namespace hullcheck::test
