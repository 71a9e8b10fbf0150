// HullMesh from qhull (independent of hullcheck's own ConvexHull).
#include <libqhullcpp/Qhull.h>
#include <libqhullcpp/QhullFacet.h>
#include <libqhullcpp/QhullFacetList.h>
#include <libqhullcpp/QhullHyperplane.h>
#include <libqhullcpp/QhullPoint.h>
#include <libqhullcpp/QhullVertex.h>
#include <libqhullcpp/QhullVertexSet.h>

#include <algorithm>
#include <set>
#include <stdexcept>
#include <utility>

#include "peers.hpp"

namespace hullcheck::bench {

const char* to_string(Query q) {
  switch (q) {
    case Query::kIntersect:
      return "intersect";
    case Query::kDistance:
      return "distance";
    case Query::kPenetration:
      return "penetration";
    case Query::kSignedDistance:
      return "signed_distance";
  }
  return "?";
}

std::shared_ptr<const HullMesh> make_hull_mesh(const std::vector<Eigen::Vector3d>& points) {
  std::vector<double> coords;
  coords.reserve(points.size() * 3);
  for (const Eigen::Vector3d& p : points) {
    coords.insert(coords.end(), {p.x(), p.y(), p.z()});
  }
  orgQhull::Qhull qhull;
  try {
    qhull.runQhull("", 3, static_cast<int>(points.size()), coords.data(), "Qt");
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("qhull failed: ") + e.what());
  }

  auto mesh = std::make_shared<HullMesh>();
  // Map qhull point ids (input indices) to compact hull vertex indices.
  std::vector<int> index_of(points.size(), -1);
  auto vertex_index = [&](const orgQhull::QhullVertex& v) {
    const int id = v.point().id();
    if (index_of[static_cast<std::size_t>(id)] < 0) {
      index_of[static_cast<std::size_t>(id)] = static_cast<int>(mesh->vertices.size());
      mesh->vertices.push_back(points[static_cast<std::size_t>(id)]);
    }
    return index_of[static_cast<std::size_t>(id)];
  };
  for (const orgQhull::QhullFacet& facet : qhull.facetList()) {
    if (!facet.isGood()) continue;
    const orgQhull::QhullVertexSet vs = facet.vertices();
    if (vs.count() != 3) throw std::runtime_error("qhull returned a non-triangular facet");
    std::array<int, 3> t{vertex_index(vs[0]), vertex_index(vs[1]), vertex_index(vs[2])};
    const Eigen::Vector3d& p0 = mesh->vertices[static_cast<std::size_t>(t[0])];
    const Eigen::Vector3d& p1 = mesh->vertices[static_cast<std::size_t>(t[1])];
    const Eigen::Vector3d& p2 = mesh->vertices[static_cast<std::size_t>(t[2])];
    const double* n = facet.hyperplane().coordinates();
    const Eigen::Vector3d outward(n[0], n[1], n[2]);
    if ((p1 - p0).cross(p2 - p0).dot(outward) < 0) std::swap(t[1], t[2]);
    mesh->triangles.push_back(t);
  }
  if (mesh->triangles.size() < 4) throw std::runtime_error("qhull returned a degenerate hull");

  std::vector<std::set<int>> adjacency(mesh->vertices.size());
  for (const auto& t : mesh->triangles) {
    for (int k = 0; k < 3; ++k) {
      adjacency[static_cast<std::size_t>(t[static_cast<std::size_t>(k)])].insert(
          t[static_cast<std::size_t>((k + 1) % 3)]);
      adjacency[static_cast<std::size_t>(t[static_cast<std::size_t>((k + 1) % 3)])].insert(
          t[static_cast<std::size_t>(k)]);
    }
  }
  for (const auto& s : adjacency) mesh->neighbors.emplace_back(s.begin(), s.end());

  for (const Eigen::Vector3d& v : mesh->vertices) {
    mesh->centroid += v;
    mesh->extent = std::max(mesh->extent, v.norm());
  }
  mesh->centroid /= static_cast<double>(mesh->vertices.size());
  return mesh;
}

std::vector<std::unique_ptr<Impl>> make_peer_impls() {
  std::vector<std::unique_ptr<Impl>> peers;
  peers.push_back(make_libccd_gjk_impl());
  peers.push_back(make_libccd_mpr_impl());
  peers.push_back(make_fcl_libccd_impl());
  peers.push_back(make_fcl_indep_impl());
  peers.push_back(make_bullet_impl());
  return peers;
}

}  // namespace hullcheck::bench
