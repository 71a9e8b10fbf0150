// Benchmark data sets and oracle answers.
#include "bench_data.hpp"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <atomic>
#include <cctype>
#include <filesystem>
#include <limits>
#include <oracles.hpp>
#include <random>
#include <thread>

namespace hullcheck::bench {

DataSet make_random_set(std::uint64_t seed, int count, int vertices) {
  DataSet set;
  set.name = "n=" + std::to_string(vertices);
  set.description = std::to_string(count) + " pairs of random hulls (oracle::make_hull_pairs, " +
                    std::to_string(vertices) + " vertices each, size 1, ~30% overlapping)";
  for (const oracle::HullPair& pair : oracle::make_hull_pairs(seed, count, vertices, 0.3, 1.0)) {
    Case c;
    c.a = make_hull_mesh(pair.a);
    c.b = make_hull_mesh(pair.b);
    c.pose_a = pair.pose_a;
    c.pose_b = pair.pose_b;
    set.cases.push_back(std::move(c));
  }
  return set;
}

namespace {

std::vector<Eigen::Vector3d> read_mesh_vertices(const std::string& path) {
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path, aiProcess_JoinIdenticalVertices);
  std::vector<Eigen::Vector3d> points;
  if (scene == nullptr) return points;
  // Collision STLs are a single mesh at the root; accumulate node transforms anyway.
  struct Item {
    const aiNode* node;
    aiMatrix4x4 transform;
  };
  std::vector<Item> stack{{scene->mRootNode, scene->mRootNode->mTransformation}};
  while (!stack.empty()) {
    const Item item = stack.back();
    stack.pop_back();
    for (unsigned k = 0; k < item.node->mNumMeshes; ++k) {
      const aiMesh* mesh = scene->mMeshes[item.node->mMeshes[k]];
      for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
        const aiVector3D p = item.transform * mesh->mVertices[v];
        points.emplace_back(p.x, p.y, p.z);
      }
    }
    for (unsigned k = 0; k < item.node->mNumChildren; ++k) {
      const aiNode* child = item.node->mChildren[k];
      stack.push_back({child, item.transform * child->mTransformation});
    }
  }
  return points;
}

Eigen::Matrix3d random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  Eigen::Quaterniond q(normal(rng), normal(rng), normal(rng), normal(rng));
  q.normalize();
  return q.toRotationMatrix();
}

Eigen::Vector3d random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  Eigen::Vector3d u;
  do {
    u = Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
  } while (u.norm() < 1e-6);
  return u.normalized();
}

double radius_about(const HullMesh& mesh, const Eigen::Vector3d& center) {
  double r = 0;
  for (const Eigen::Vector3d& v : mesh.vertices) r = std::max(r, (v - center).norm());
  return r;
}

}  // namespace

DataSet make_robot_set(const std::string& shared_dir, std::uint64_t seed, int count) {
  namespace fs = std::filesystem;
  DataSet set;
  set.name = "robots";
  std::vector<std::string> files;
  for (const char* robot : {"panda", "ur5e", "abb_irb2400"}) {
    const fs::path root = fs::path(shared_dir) / "robots" / robot;
    std::error_code ec;
    if (!fs::is_directory(root, ec)) continue;
    for (fs::recursive_directory_iterator it(root, ec), end; it != end && !ec; it.increment(ec)) {
      if (!it->is_regular_file()) continue;
      std::string ext = it->path().extension().string();
      std::transform(ext.begin(), ext.end(), ext.begin(),
                     [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
      if (ext == ".stl" && it->path().parent_path().filename() == "collision") {
        files.push_back(it->path().string());
      }
    }
  }
  std::sort(files.begin(), files.end());
  std::vector<std::shared_ptr<const HullMesh>> meshes;
  std::size_t total_vertices = 0, min_vertices = std::numeric_limits<std::size_t>::max(),
              max_vertices = 0;
  for (const std::string& file : files) {
    const std::vector<Eigen::Vector3d> points = read_mesh_vertices(file);
    if (points.size() < 4) continue;
    try {
      meshes.push_back(make_hull_mesh(points));
    } catch (const std::exception&) {
      continue;  // flat or unreadable mesh: not a benchmark case
    }
    const std::size_t n = meshes.back()->vertices.size();
    total_vertices += n;
    min_vertices = std::min(min_vertices, n);
    max_vertices = std::max(max_vertices, n);
  }
  if (meshes.empty() || count <= 0) return set;

  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<std::size_t> pick(0, meshes.size() - 1);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const int overlapping = (3 * count + 5) / 10;
  int attempts = 0;
  while (static_cast<int>(set.cases.size()) < count && attempts++ < 20 * count) {
    Case c;
    c.a = meshes[pick(rng)];
    c.b = meshes[pick(rng)];
    // Both centroids at the origin first, then B moved along u.
    c.pose_a.linear() = random_rotation(rng);
    c.pose_a.translation() = -(c.pose_a.linear() * c.a->centroid);
    c.pose_b.linear() = random_rotation(rng);
    c.pose_b.translation() = -(c.pose_b.linear() * c.b->centroid);
    const Eigen::Vector3d u = random_unit(rng);
    const oracle::Interval interval =
        oracle::overlap_interval(oracle::transformed(c.a->vertices, c.pose_a),
                                 oracle::transformed(c.b->vertices, c.pose_b), u);
    if (interval.empty()) continue;
    const double size =
        std::max(radius_about(*c.a, c.a->centroid), radius_about(*c.b, c.b->centroid));
    const bool overlap = static_cast<int>(set.cases.size()) < overlapping;
    const double t = overlap
                         ? interval.lo + (0.05 + 0.9 * uniform(rng)) * (interval.hi - interval.lo)
                         : interval.hi + (0.01 + 0.99 * uniform(rng)) * size;
    c.pose_b.translation() += t * u;
    set.cases.push_back(std::move(c));
  }
  // Interleave overlapping and separated pairs (the first `overlapping` are overlapping).
  std::shuffle(set.cases.begin(), set.cases.end(), rng);
  set.description =
      std::to_string(set.cases.size()) + " random pairs of " + std::to_string(meshes.size()) +
      " robot collision-mesh hulls (panda, ur5e, abb_irb2400; " + std::to_string(min_vertices) +
      ".." + std::to_string(max_vertices) + " hull vertices, mean " +
      std::to_string(total_vertices / meshes.size()) + "), ~30% overlapping";
  return set;
}

std::vector<Truth> compute_truth(const std::vector<Case>& cases, unsigned threads) {
  std::vector<Truth> truth(cases.size());
  std::atomic<std::size_t> next{0};
  auto work = [&] {
    for (std::size_t i = next++; i < cases.size(); i = next++) {
      const Case& c = cases[i];
      Truth& t = truth[i];
      t.world_a = oracle::transformed(c.a->vertices, c.pose_a);
      t.world_b = oracle::transformed(c.b->vertices, c.pose_b);
      t.scale = std::max(c.a->extent, c.b->extent);
      const oracle::Distance d = oracle::brute_force_distance(t.world_a, t.world_b);
      t.overlapping = d.overlapping;
      t.distance = d.overlapping ? 0.0 : d.distance;
      if (d.overlapping) {
        const oracle::Penetration p = oracle::minkowski_penetration(t.world_a, t.world_b);
        t.depth = p.depth;
      }
    }
  };
  std::vector<std::thread> pool;
  for (unsigned k = 1; k < std::max(1u, threads); ++k) pool.emplace_back(work);
  work();
  for (std::thread& th : pool) th.join();
  return truth;
}

namespace {
// Closest point on triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5).
Eigen::Vector3d closest_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                    const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  }
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}
}  // namespace

double point_hull_distance(const Eigen::Vector3d& world_point, const HullMesh& mesh,
                           const Eigen::Isometry3d& pose) {
  const Eigen::Vector3d p = pose.inverse() * world_point;
  bool inside = true;
  double best = std::numeric_limits<double>::infinity();
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.vertices[static_cast<std::size_t>(t[0])];
    const Eigen::Vector3d& b = mesh.vertices[static_cast<std::size_t>(t[1])];
    const Eigen::Vector3d& c = mesh.vertices[static_cast<std::size_t>(t[2])];
    const Eigen::Vector3d n = (b - a).cross(c - a);
    if (n.dot(p - a) > 0) inside = false;
    best = std::min(best, (closest_on_triangle(p, a, b, c) - p).norm());
  }
  return inside ? 0.0 : best;
}

double depth_along(const Truth& truth, const Eigen::Vector3d& normal) {
  double max_a = -std::numeric_limits<double>::infinity();
  double min_b = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& a : truth.world_a) max_a = std::max(max_a, a.dot(normal));
  for (const Eigen::Vector3d& b : truth.world_b) min_b = std::min(min_b, b.dot(normal));
  return max_a - min_b;
}

}  // namespace hullcheck::bench
