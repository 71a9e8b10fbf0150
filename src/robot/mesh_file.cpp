#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <cmath>
#include <hullcheck/errors.hpp>
#include <hullcheck/robot/mesh_file.hpp>

namespace hullcheck {
namespace {

void collect(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent,
             const Eigen::Vector3d& scale, std::vector<Eigen::Vector3d>* out) {
  const aiMatrix4x4 transform = parent * node.mTransformation;
  for (unsigned m = 0; m < node.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[m]];
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D p = transform * mesh.mVertices[v];
      out->emplace_back(scale.x() * p.x, scale.y() * p.y, scale.z() * p.z);
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) {
    collect(scene, *node.mChildren[c], transform, scale, out);
  }
}

}  // namespace

std::vector<Eigen::Vector3d> read_mesh_vertices(const std::string& path,
                                                const Eigen::Vector3d& scale) {
  if (!scale.allFinite()) {
    throw InputError("mesh '" + path + "': scale is not finite");
  }
  Assimp::Importer importer;
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  // Only vertices are needed: no triangulation, no normals, no vertex joining (the hull
  // computation handles duplicates).
  const aiScene* scene = importer.ReadFile(path, 0);
  if (scene == nullptr || scene->mRootNode == nullptr) {
    throw InputError("mesh '" + path + "': cannot be read: " + importer.GetErrorString());
  }
  std::vector<Eigen::Vector3d> vertices;
  std::size_t total = 0;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) total += scene->mMeshes[m]->mNumVertices;
  vertices.reserve(total);
  collect(*scene, *scene->mRootNode, aiMatrix4x4(), scale, &vertices);
  if (vertices.empty()) {
    throw InputError("mesh '" + path + "': holds no vertices");
  }
  for (const Eigen::Vector3d& v : vertices) {
    if (!v.allFinite()) throw InputError("mesh '" + path + "': has a non-finite vertex");
  }
  return vertices;
}

}  // namespace hullcheck
