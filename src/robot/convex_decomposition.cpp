#include <algorithm>
#include <cmath>
#include <hullcheck/core/convex_hull.hpp>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/robot/convex_decomposition.hpp>
#include <limits>
#include <map>
#include <memory>
#include <queue>
#include <set>
#include <sstream>
#include <tuple>

#include "mesh_distance.hpp"

// Contents:
//   Cell, clip_triangle        - the boxes the mesh is cut into, a triangle's part in one
//   Piece, make_piece           - the mesh's part in a cell and its hull
//   measure                     - the proven tightness bound of a piece's hull
//   best_cut                    - choosing the plane that splits a piece
//   decompose_mesh              - the greedy loop

namespace hullcheck {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// An axis-aligned box of the mesh frame; the mesh is cut along its faces.
struct Cell {
  Eigen::Vector3d lo, hi;
  Eigen::Vector3d corner(int k) const {
    return {(k & 1) ? hi.x() : lo.x(), (k & 2) ? hi.y() : lo.y(), (k & 4) ? hi.z() : lo.z()};
  }
};

// Appends to `out` the corners of triangle (a, b, c) clipped to `cell` (Sutherland-Hodgman over
// the six faces; points computed on a face get that face's coordinate exactly). Returns false
// when nothing of the triangle is in the cell.
bool clip_triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                   const Cell& cell, std::vector<Eigen::Vector3d>* out) {
  // A triangle clipped by six planes has at most 9 corners.
  Eigen::Vector3d buffer[2][12];
  int count = 3;
  buffer[0][0] = a;
  buffer[0][1] = b;
  buffer[0][2] = c;
  int from = 0;
  for (int axis = 0; axis < 3; ++axis) {
    for (int side = 0; side < 2; ++side) {
      const double plane = side == 0 ? cell.lo[axis] : cell.hi[axis];
      const double sign = side == 0 ? 1.0 : -1.0;  // kept: sign * (x - plane) >= 0
      const Eigen::Vector3d* in = buffer[from];
      Eigen::Vector3d* kept = buffer[1 - from];
      int n = 0;
      for (int i = 0; i < count; ++i) {
        const Eigen::Vector3d& p = in[i];
        const Eigen::Vector3d& q = in[(i + 1) % count];
        const double sp = sign * (p[axis] - plane);
        const double sq = sign * (q[axis] - plane);
        if (sp >= 0.0) kept[n++] = p;
        if ((sp >= 0.0) != (sq >= 0.0) && sp != 0.0 && sq != 0.0) {
          Eigen::Vector3d x = p + (sp / (sp - sq)) * (q - p);
          x[axis] = plane;
          kept[n++] = x;
        }
      }
      count = n;
      from = 1 - from;
      if (count == 0) return false;
    }
  }
  for (int i = 0; i < count; ++i) out->push_back(buffer[from][i]);
  return true;
}

// Sorts and removes exact duplicates.
void make_distinct(std::vector<Eigen::Vector3d>* points) {
  const auto less = [](const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
    return std::tie(p.x(), p.y(), p.z()) < std::tie(q.x(), q.y(), q.z());
  };
  std::sort(points->begin(), points->end(), less);
  points->erase(std::unique(points->begin(), points->end()), points->end());
}

// The decomposition's view of the mesh: triangles as corners, the distance queries, and the
// inside flags of cell corners already asked for.
struct MeshView {
  const TriangleMesh& mesh;
  detail::MeshDistance distance;
  double tolerance;
  std::map<std::tuple<double, double, double>, bool> inside_cache;

  bool inside(const Eigen::Vector3d& p) {
    const auto key = std::make_tuple(p.x(), p.y(), p.z());
    const auto it = inside_cache.find(key);
    if (it != inside_cache.end()) return it->second;
    return inside_cache.emplace(key, distance.inside(p)).first->second;
  }
};

// The mesh's part in one cell: the triangles meeting it, and the points whose hull covers the
// solid within it (clipped triangles and the cell's corners inside the solid).
struct Piece {
  Cell cell;
  std::vector<Cell> merged_cells;  // cells of the pieces merged into this one
  std::vector<int> triangles;
  std::vector<Eigen::Vector3d> points;
  std::shared_ptr<ConvexHull> hull;
  double bound = 0.0;  // tightness bound; a lower bound > tolerance when `refuted`
  bool refuted = false;
  double volume = -1.0;  // hull volume, once computed
  int id = 0;            // unique per decomposition, for remembering failed merges
  Eigen::Vector3d witness = Eigen::Vector3d::Zero();  // the farthest surface point found
};

// Points of the mesh's part in `cell`, from the candidate triangles `triangles`; the triangles
// that meet the cell into `kept` when not null.
std::vector<Eigen::Vector3d> cell_points(MeshView& view, const std::vector<int>& triangles,
                                         const Cell& cell, std::vector<int>* kept,
                                         bool with_corners = true) {
  std::vector<Eigen::Vector3d> points;
  const TriangleMesh& m = view.mesh;
  for (int t : triangles) {
    const auto& tri = m.triangles[static_cast<std::size_t>(t)];
    if (clip_triangle(m.vertices[tri[0]], m.vertices[tri[1]], m.vertices[tri[2]], cell, &points) &&
        kept != nullptr) {
      kept->push_back(t);
    }
  }
  for (int k = 0; with_corners && k < 8; ++k) {
    const Eigen::Vector3d corner = cell.corner(k);
    if (view.inside(corner)) points.push_back(corner);
  }
  make_distinct(&points);
  return points;
}

// Whether triangle (a, b, c) lies in one face plane of the piece's cells (exactly: the clipped
// points carry the face coordinates exactly).
bool on_cell_face(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                  const Piece& piece) {
  const auto on = [&](const Cell& cell) {
    for (int axis = 0; axis < 3; ++axis) {
      for (double plane : {cell.lo[axis], cell.hi[axis]}) {
        if (a[axis] == plane && b[axis] == plane && c[axis] == plane) return true;
      }
    }
    return false;
  };
  return on(piece.cell) || std::any_of(piece.merged_cells.begin(), piece.merged_cells.end(), on);
}

// The tightness bound of `piece`'s hull (see decompose_mesh): sets piece.bound, and
// piece.refuted with piece.witness when some surface point is farther than the tolerance.
// With `stop_early`, returns at the first such point (the bound is then only a lower bound).
void measure(MeshView& view, Piece* piece, bool stop_early) {
  const ConvexHull& hull = *piece->hull;
  const std::vector<Eigen::Vector3d>& v = hull.vertices();
  std::vector<std::array<int, 3>> facets = hull.triangles();
  if (hull.dimension() == 1) facets.push_back({0, 1, 1});
  if (hull.dimension() == 0) facets.push_back({0, 0, 0});
  const double tol = view.tolerance;
  const double r_min = tol / 64.0;  // below this, a part is not subdivided further
  // Work bound: past this many parts, no part is subdivided (each still bounds its own
  // points, so the result stays a bound, only a looser one). Reached only when the tolerance
  // is tiny against the hull's size.
  constexpr long kMaxParts = 1L << 18;
  long parts = 0;
  // A part of a facet, with what its parent's centre told about its neighbourhood: the ball
  // of radius `ball_radius` about `ball_centre` is inside the solid (or outside it, by
  // `ball_inside`), since the ball does not reach the surface (for a closed mesh).
  struct Part {
    Eigen::Vector3d a, b, c;
    Eigen::Vector3d ball_centre;
    double ball_radius;
    bool ball_inside;
  };
  std::vector<Part> stack;
  double bound = 0.0;
  double worst = -1.0;  // largest distance of a refuting point
  const bool coarse = !stop_early && piece->refuted;
  piece->refuted = false;
  for (const auto& f : facets) {
    const Eigen::Vector3d& fa = v[static_cast<std::size_t>(f[0])];
    const Eigen::Vector3d& fb = v[static_cast<std::size_t>(f[1])];
    const Eigen::Vector3d& fc = v[static_cast<std::size_t>(f[2])];
    const bool face = on_cell_face(fa, fb, fc, *piece);
    stack.push_back({fa, fb, fc, fa, -1.0, false});
    while (!stack.empty()) {
      const Part p = stack.back();
      stack.pop_back();
      const Eigen::Vector3d c = (p.a + p.b + p.c) / 3.0;
      const double r = std::max({(p.a - c).norm(), (p.b - c).norm(), (p.c - c).norm()});
      const detail::MeshDistance::Nearest near = view.distance.nearest(c);
      const double d = near.distance;
      // Two bounds on the part's distance to the surface: d is 1-Lipschitz (d + r), and the
      // distance to the one triangle nearest c is convex, so at most its largest corner value.
      double part_bound = d + r;
      if (part_bound > tol) {
        part_bound =
            std::min(part_bound, std::max({view.distance.triangle_distance(p.a, near.triangle),
                                           view.distance.triangle_distance(p.b, near.triangle),
                                           view.distance.triangle_distance(p.c, near.triangle)}));
      }
      bool refutes = false;
      bool inside = false;
      if (part_bound > tol) {
        // Only points on a cell face can be inside the solid: elsewhere a hull boundary point
        // is not interior to the solid (the solid's part in the cells is inside the hull).
        if (face) {
          inside =
              (c - p.ball_centre).norm() < p.ball_radius ? p.ball_inside : view.distance.inside(c);
        }
        if (inside) {
          part_bound = std::max(0.0, r - d);  // the ball of radius d about c is in the solid
        } else {
          refutes = d > tol;
        }
      }
      if (refutes) {
        piece->refuted = true;
        if (d > worst) {
          worst = d;
          piece->witness = c;
        }
        if (stop_early) {
          piece->bound = d;
          return;
        }
      }
      // Parts of a piece already refuted only need a bound near their distance (half the
      // tolerance, or 2% of d): precision about the tolerance no longer matters there.
      const double r_stop = coarse ? std::max(0.5 * tol, 0.02 * d) : r_min;
      if (part_bound <= tol || r <= r_stop || ++parts > kMaxParts) {
        bound = std::max(bound, part_bound);
        continue;
      }
      const Eigen::Vector3d ab = (p.a + p.b) / 2.0, bc = (p.b + p.c) / 2.0, ca = (p.c + p.a) / 2.0;
      stack.push_back({p.a, ab, ca, c, d, inside});
      stack.push_back({ab, p.b, bc, c, d, inside});
      stack.push_back({ca, bc, p.c, c, d, inside});
      stack.push_back({ab, bc, ca, c, d, inside});
    }
  }
  piece->bound = bound;
}

// A cut of a piece's cell: the plane x[axis] = position.
struct Cut {
  int axis = -1;
  double position = 0.0;
};

// The plane that splits `piece` into the two parts of least total hull volume, among the planes
// through the piece's farthest surface point and 1 and 2 tolerances beside it (7 evenly spaced
// positions per axis when no point refuted the piece). No cut (axis -1) when every axis of the
// piece is thinner than half the tolerance.
Cut best_cut(MeshView& view, const Piece& piece) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(kInf), hi = -lo;
  for (const Eigen::Vector3d& p : piece.points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  Cut best;
  double best_volume = kInf;
  for (int axis = 0; axis < 3; ++axis) {
    const double extent = hi[axis] - lo[axis];
    if (!(extent >= 0.5 * view.tolerance)) continue;
    std::vector<double> positions;
    if (piece.refuted) {
      // Through the farthest point found and beside it: the cut goes where the hull bridges a
      // concavity (cutting elsewhere spends pieces on parts that needed none).
      for (int k = -2; k <= 2; ++k) {
        const double x = piece.witness[axis] + k * view.tolerance;
        if (x > lo[axis] && x < hi[axis]) positions.push_back(x);
      }
    } else {
      for (int k = 1; k < 8; ++k) positions.push_back(lo[axis] + extent * k / 8.0);
    }
    for (double position : positions) {
      Cell left = piece.cell, right = piece.cell;
      left.hi[axis] = position;
      right.lo[axis] = position;
      const double left_volume =
          convex_hull_volume(cell_points(view, piece.triangles, left, nullptr));
      const double right_volume =
          convex_hull_volume(cell_points(view, piece.triangles, right, nullptr));
      // A cut leaving one side flat (only points on the plane) gains nothing and would make a
      // flat piece (qhull's joggled fallback gives flat sets a tiny volume, hence the margin).
      const double thin = 1e-9 * (hi - lo).prod();
      if (!(left_volume > thin) || !(right_volume > thin)) continue;
      const double volume = left_volume + right_volume;
      if (volume < best_volume) {
        best_volume = volume;
        best = {axis, position};
      }
    }
  }
  return best;
}

// The piece of `cell` from the candidate triangles, its hull and (early-stopping) measure.
// Null when the cell holds no point of the solid.
std::unique_ptr<Piece> make_piece(MeshView& view, const std::vector<int>& triangles,
                                  const Cell& cell) {
  auto piece = std::make_unique<Piece>();
  piece->cell = cell;
  piece->points = cell_points(view, triangles, cell, &piece->triangles);
  if (piece->points.empty()) return nullptr;
  piece->hull = std::make_shared<ConvexHull>(piece->points);
  measure(view, piece.get(), true);
  return piece;
}

// Whether two boxes meet (share at least a point).
bool touching(const Cell& a, const Cell& b) {
  return (a.lo.array() <= b.hi.array()).all() && (b.lo.array() <= a.hi.array()).all();
}

bool adjacent(const Piece& a, const Piece& b) {
  std::vector<const Cell*> ca{&a.cell}, cb{&b.cell};
  for (const Cell& c : a.merged_cells) ca.push_back(&c);
  for (const Cell& c : b.merged_cells) cb.push_back(&c);
  for (const Cell* x : ca) {
    for (const Cell* y : cb) {
      if (touching(*x, *y)) return true;
    }
  }
  return false;
}

// Greedy merging of pieces within tolerance: of the adjacent pairs not tried yet, the one whose
// joint hull adds the least volume is tried; the merged piece (hull of both point sets, so it
// covers both) replaces the two when its measure is within tolerance. The cuts are chosen one
// piece at a time, so they also cut parts that needed no cut; this undoes most of those.
void merge_pieces(MeshView& view, std::vector<std::unique_ptr<Piece>>* pieces, int* next_id) {
  std::set<std::pair<int, int>> tried;
  std::map<std::pair<int, int>, double> joint_volume;
  const auto good = [&](const Piece& p) { return !p.refuted && p.bound <= view.tolerance; };
  for (auto& p : *pieces) {
    if (p->volume < 0.0) p->volume = convex_hull_volume(p->points);
  }
  const auto joined = [](const Piece& a, const Piece& b) {
    std::vector<Eigen::Vector3d> points = a.points;
    points.insert(points.end(), b.points.begin(), b.points.end());
    make_distinct(&points);
    return points;
  };
  for (;;) {
    double best = kInf;
    std::size_t bi = 0, bj = 0;
    for (std::size_t i = 0; i < pieces->size(); ++i) {
      const Piece& a = *(*pieces)[i];
      if (!good(a)) continue;
      for (std::size_t j = i + 1; j < pieces->size(); ++j) {
        const Piece& b = *(*pieces)[j];
        const std::pair<int, int> key{std::min(a.id, b.id), std::max(a.id, b.id)};
        if (!good(b) || tried.count(key) != 0 || !adjacent(a, b)) continue;
        auto it = joint_volume.find(key);
        if (it == joint_volume.end()) {
          it = joint_volume.emplace(key, convex_hull_volume(joined(a, b))).first;
        }
        const double added = it->second - a.volume - b.volume;
        if (added < best) {
          best = added;
          bi = i;
          bj = j;
        }
      }
    }
    if (best == kInf) return;
    Piece& a = *(*pieces)[bi];
    Piece& b = *(*pieces)[bj];
    tried.insert({std::min(a.id, b.id), std::max(a.id, b.id)});
    auto merged = std::make_unique<Piece>();
    merged->cell = a.cell;
    merged->merged_cells = a.merged_cells;
    merged->merged_cells.push_back(b.cell);
    merged->merged_cells.insert(merged->merged_cells.end(), b.merged_cells.begin(),
                                b.merged_cells.end());
    merged->triangles = a.triangles;
    merged->triangles.insert(merged->triangles.end(), b.triangles.begin(), b.triangles.end());
    std::sort(merged->triangles.begin(), merged->triangles.end());
    merged->triangles.erase(std::unique(merged->triangles.begin(), merged->triangles.end()),
                            merged->triangles.end());
    merged->points = joined(a, b);
    merged->hull = std::make_shared<ConvexHull>(merged->points);
    measure(view, merged.get(), true);
    if (!good(*merged)) continue;
    merged->volume = convex_hull_volume(merged->points);
    merged->id = (*next_id)++;
    (*pieces)[bi] = std::move(merged);
    pieces->erase(pieces->begin() + static_cast<std::ptrdiff_t>(bj));
  }
}

void check_options(const TriangleMesh& mesh, const DecompositionOptions& options) {
  std::ostringstream msg;
  if (!std::isfinite(options.tolerance) || options.tolerance < 1e-6) {
    msg << "decomposition tolerance must be finite and at least 1e-6 m (got " << options.tolerance
        << ")";
  } else if (options.max_pieces < 1 || options.max_pieces > 1024) {
    msg << "decomposition max_pieces must be within 1..1024 (got " << options.max_pieces << ")";
  } else {
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      for (std::uint32_t i : mesh.triangles[t]) {
        if (i >= mesh.vertices.size()) {
          msg << "triangle " << t << " refers to vertex " << i << " of " << mesh.vertices.size();
          break;
        }
      }
      if (!msg.str().empty()) break;
    }
  }
  if (!msg.str().empty()) throw InputError(msg.str());
}

}  // namespace

ConvexDecomposition decompose_mesh(const TriangleMesh& mesh, const DecompositionOptions& options) {
  check_options(mesh, options);
  ConvexDecomposition result;
  if (mesh.vertices.empty()) throw InputError("decomposition of a mesh without vertices");
  if (mesh.triangles.empty()) {
    result.pieces.push_back(mesh.vertices);
    make_distinct(&result.pieces.back());
    return result;
  }
  MeshView view{mesh, detail::MeshDistance(mesh), options.tolerance, {}};
  Cell root{Eigen::Vector3d::Constant(kInf), Eigen::Vector3d::Constant(-kInf)};
  for (const Eigen::Vector3d& p : mesh.vertices) {
    root.lo = root.lo.cwiseMin(p);
    root.hi = root.hi.cwiseMax(p);
  }
  std::vector<int> all(mesh.triangles.size());
  for (std::size_t t = 0; t < all.size(); ++t) all[t] = static_cast<int>(t);

  // Pieces in a max-heap on their bound; a refuted piece's bound is a lower bound above the
  // tolerance, so it comes before every proven one. Split until every piece is within
  // tolerance or the budget is spent, merge what can be merged, and split again with the
  // budget that freed (a few rounds at most).
  std::vector<std::unique_ptr<Piece>> pieces;
  const auto worse = [](const std::unique_ptr<Piece>& a, const std::unique_ptr<Piece>& b) {
    return a->bound < b->bound;
  };
  int next_id = 0;
  if (auto root_piece = make_piece(view, all, root)) {
    root_piece->id = next_id++;
    pieces.push_back(std::move(root_piece));
  }
  std::vector<std::unique_ptr<Piece>> done;  // pieces that cannot be split
  for (int round = 0; round < 4; ++round) {
    std::make_heap(pieces.begin(), pieces.end(), worse);
    bool split_any = false;
    while (!pieces.empty() && static_cast<int>(pieces.size() + done.size()) < options.max_pieces) {
      std::pop_heap(pieces.begin(), pieces.end(), worse);
      std::unique_ptr<Piece> piece = std::move(pieces.back());
      pieces.pop_back();
      if (!piece->refuted && piece->bound <= options.tolerance) {
        pieces.push_back(std::move(piece));  // the worst is within tolerance: all are
        std::push_heap(pieces.begin(), pieces.end(), worse);
        break;
      }
      const Cut cut = best_cut(view, *piece);
      if (cut.axis < 0) {
        done.push_back(std::move(piece));
        continue;
      }
      split_any = true;
      Cell left = piece->cell, right = piece->cell;
      left.hi[cut.axis] = cut.position;
      right.lo[cut.axis] = cut.position;
      for (const Cell& cell : {left, right}) {
        if (auto child = make_piece(view, piece->triangles, cell)) {
          child->id = next_id++;
          pieces.push_back(std::move(child));
          std::push_heap(pieces.begin(), pieces.end(), worse);
        }
      }
    }
    if (!split_any) break;
    const std::size_t before = pieces.size();
    merge_pieces(view, &pieces, &next_id);
    if (pieces.size() == before) break;
  }
  for (auto& p : done) pieces.push_back(std::move(p));
  for (auto& piece : pieces) {
    if (piece->refuted) measure(view, piece.get(), false);  // its full bound, not a lower one
    result.bound = std::max(result.bound, piece->bound);
    result.pieces.push_back(piece->hull->vertices());
  }
  result.within_tolerance = result.bound <= options.tolerance;
  return result;
}

}  // namespace hullcheck
