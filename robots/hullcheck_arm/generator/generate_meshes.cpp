// Writes every collision mesh of the hullcheck_arm robot (robots/hullcheck_arm/meshes/).
//
//   g++ -std=c++17 -O2 -Wall -Wextra -Werror generate_meshes.cpp -o generate_meshes
//   ./generate_meshes ../meshes
//
// Standard library only. The output is deterministic: every coordinate is rounded to a grid of
// 1e-6 (micrometres for the files in metres) before it is written, and the text formats use a
// fixed number of decimals, so the files are byte-identical from run to run.
//
// Each mesh is one or more closed, consistently oriented (outward) triangle shells; the program
// checks this before writing. Shapes are surfaces of revolution (tubes with domes and fillets)
// and rounded boxes. link5_mm.stl is deliberately non-convex (a fork), and in millimetres.

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace {

constexpr double kPi = 3.14159265358979323846;

struct V3 {
  double x = 0, y = 0, z = 0;
};
V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V3 operator*(double s, V3 a) { return {s * a.x, s * a.y, s * a.z}; }
double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V3 cross(V3 a, V3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double norm(V3 a) { return std::sqrt(dot(a, a)); }

using Tri = std::array<std::uint32_t, 3>;

struct Mesh {
  std::vector<V3> v;
  std::vector<Tri> f;
  std::size_t shells = 0;

  void append(const Mesh& o) {
    const auto base = static_cast<std::uint32_t>(v.size());
    v.insert(v.end(), o.v.begin(), o.v.end());
    for (const Tri& t : o.f) f.push_back({t[0] + base, t[1] + base, t[2] + base});
    shells += o.shells;
  }
  double signed_volume() const {
    double vol = 0;
    for (const Tri& t : f) vol += dot(v[t[0]], cross(v[t[1]], v[t[2]]));
    return vol / 6.0;
  }
  void flip() {
    for (Tri& t : f) std::swap(t[1], t[2]);
  }
};

// A 3x3 rotation (row-major) and translation applied to every vertex.
struct Rigid {
  std::array<double, 9> r{1, 0, 0, 0, 1, 0, 0, 0, 1};
  V3 t;
  V3 apply(V3 p) const {
    return {r[0] * p.x + r[1] * p.y + r[2] * p.z + t.x, r[3] * p.x + r[4] * p.y + r[5] * p.z + t.y,
            r[6] * p.x + r[7] * p.y + r[8] * p.z + t.z};
  }
};
Rigid rot_x(double a, V3 t = {}) {
  const double c = std::cos(a), s = std::sin(a);
  Rigid g;
  g.r = {1, 0, 0, 0, c, -s, 0, s, c};
  g.t = t;
  return g;
}
Rigid translation(V3 t) {
  Rigid g;
  g.t = t;
  return g;
}
Mesh transformed(Mesh m, const Rigid& g) {
  for (V3& p : m.v) p = g.apply(p);
  return m;
}

// ---------------------------------------------------------------------------------------------
// Shapes

// Profile of a surface of revolution about z: points (r, z) from the bottom pole (r = 0) to the
// top pole (r = 0). Helper to build it from lines and arcs.
struct Profile {
  std::vector<std::pair<double, double>> pts;  // (r, z)
  void to(double r, double z) { pts.emplace_back(r, z); }
  // Straight segment from the last point to (r, z), with `steps` pieces.
  void line(double r, double z, int steps) {
    const auto [r0, z0] = pts.back();
    for (int i = 1; i <= steps; ++i) {
      const double s = static_cast<double>(i) / steps;
      to(r0 + s * (r - r0), z0 + s * (z - z0));
    }
  }
  // Arc about centre (cr, cz) with radius rad from angle a0 to a1 (radians, measured from +r
  // towards +z), excluding the first point, with `steps` pieces.
  void arc(double cr, double cz, double rad, double a0, double a1, int steps) {
    for (int i = 1; i <= steps; ++i) {
      const double a = a0 + (a1 - a0) * i / steps;
      double r = cr + rad * std::cos(a);
      if (std::fabs(r) < 1e-12) r = 0;
      to(r, cz + rad * std::sin(a));
    }
  }
};

Mesh revolve(const Profile& prof, int segments) {
  const auto& p = prof.pts;
  if (p.size() < 3 || p.front().first != 0.0 || p.back().first != 0.0)
    throw std::logic_error("profile must start and end on the axis");
  Mesh m;
  m.shells = 1;
  const std::size_t rings = p.size() - 2;
  m.v.push_back({0, 0, p.front().second});
  for (std::size_t i = 1; i + 1 < p.size(); ++i) {
    if (p[i].first <= 0) throw std::logic_error("profile touches the axis in the middle");
    for (int s = 0; s < segments; ++s) {
      const double a = 2 * kPi * s / segments;
      m.v.push_back({p[i].first * std::cos(a), p[i].first * std::sin(a), p[i].second});
    }
  }
  const auto top = static_cast<std::uint32_t>(m.v.size());
  m.v.push_back({0, 0, p.back().second});
  const auto seg = static_cast<std::uint32_t>(segments);
  auto ring = [&](std::size_t r, int s) {
    return static_cast<std::uint32_t>(1 + r * seg + static_cast<std::uint32_t>(s % segments));
  };
  for (int s = 0; s < segments; ++s) m.f.push_back({0, ring(0, s + 1), ring(0, s)});
  for (std::size_t r = 0; r + 1 < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      m.f.push_back({ring(r, s), ring(r, s + 1), ring(r + 1, s + 1)});
      m.f.push_back({ring(r, s), ring(r + 1, s + 1), ring(r + 1, s)});
    }
  for (int s = 0; s < segments; ++s)
    m.f.push_back({top, ring(rings - 1, s), ring(rings - 1, s + 1)});
  if (m.signed_volume() < 0) m.flip();
  return m;
}

// Tube of radius r about z from z0 (flat bottom with a fillet of radius fb) to z1, closed on top
// by a half sphere of radius r centred at z1.
Mesh domed_tube(double r, double z0, double z1, double fb, int segments, int body_steps) {
  Profile p;
  p.to(0, z0);
  p.line(r - fb, z0, 2);
  p.arc(r - fb, z0 + fb, fb, -kPi / 2, 0, 4);
  p.line(r, z1, body_steps);
  p.arc(0, z1, r, 0, kPi / 2, 10);
  return revolve(p, segments);
}

// Disc (short cylinder) about z between z0 and z1, radius r, both edges filleted with f.
Mesh filleted_disc(double r, double z0, double z1, double f, int segments) {
  Profile p;
  p.to(0, z0);
  p.line(r - f, z0, 3);
  p.arc(r - f, z0 + f, f, -kPi / 2, 0, 3);
  p.line(r, z1 - f, 1);
  p.arc(r - f, z1 - f, f, 0, kPi / 2, 3);
  p.line(0, z1, 3);
  return revolve(p, segments);
}

// Samples of one axis of a rounded box: -h .. h, with `arc` pieces in each rounded band
// (uniform in angle) and `flat` pieces on the flat part in between.
std::vector<double> box_axis(double h, double r, int arc, int flat) {
  if (!(r > 0 && r < h)) throw std::logic_error("rounded box needs 0 < radius < half extent");
  std::vector<double> out;
  for (int k = arc; k >= 1; --k) out.push_back(-((h - r) + r * std::tan(kPi / 4 * k / arc)));
  for (int k = 0; k <= flat; ++k) out.push_back(-(h - r) + 2 * (h - r) * k / flat);
  for (int k = 1; k <= arc; ++k) out.push_back((h - r) + r * std::tan(kPi / 4 * k / arc));
  out.front() = -h;  // exact ends (tan(pi/4) is not exactly 1)
  out.back() = h;
  return out;
}

// Box with half extents h, centred at the origin, edges and corners rounded with radius r
// (the Minkowski sum of a box and a ball), meshed as a welded cube grid.
Mesh rounded_box(V3 h, double r, int arc, int flat) {
  const std::array<std::vector<double>, 3> ax = {
      box_axis(h.x, r, arc, flat), box_axis(h.y, r, arc, flat), box_axis(h.z, r, arc, flat)};
  const std::array<double, 3> inner = {h.x - r, h.y - r, h.z - r};
  Mesh m;
  m.shells = 1;
  std::map<std::array<int, 3>, std::uint32_t> index;
  auto vertex = [&](std::array<int, 3> g) {
    auto it = index.find(g);
    if (it != index.end()) return it->second;
    std::array<double, 3> p{}, c{}, d{};
    for (int a = 0; a < 3; ++a) {
      p[a] = ax[a][static_cast<std::size_t>(g[a])];
      c[a] = std::max(-inner[a], std::min(inner[a], p[a]));
      d[a] = p[a] - c[a];
    }
    const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    const V3 q{c[0] + r * d[0] / len, c[1] + r * d[1] / len, c[2] + r * d[2] / len};
    const auto id = static_cast<std::uint32_t>(m.v.size());
    m.v.push_back(q);
    index.emplace(g, id);
    return id;
  };
  for (int a = 0; a < 3; ++a) {
    const int u = (a + 1) % 3, w = (a + 2) % 3;
    const int nu = static_cast<int>(ax[u].size()), nw = static_cast<int>(ax[w].size());
    for (int side = 0; side < 2; ++side) {
      const int fixed = side == 0 ? 0 : static_cast<int>(ax[a].size()) - 1;
      V3 normal;
      (a == 0 ? normal.x : a == 1 ? normal.y : normal.z) = side == 0 ? -1 : 1;
      for (int i = 0; i + 1 < nu; ++i)
        for (int j = 0; j + 1 < nw; ++j) {
          auto id = [&](int di, int dj) {
            std::array<int, 3> g{};
            g[static_cast<std::size_t>(a)] = fixed;
            g[static_cast<std::size_t>(u)] = i + di;
            g[static_cast<std::size_t>(w)] = j + dj;
            return vertex(g);
          };
          const std::uint32_t q00 = id(0, 0), q10 = id(1, 0), q11 = id(1, 1), q01 = id(0, 1);
          for (Tri t : {Tri{q00, q10, q11}, Tri{q00, q11, q01}}) {
            const V3 n = cross(m.v[t[1]] - m.v[t[0]], m.v[t[2]] - m.v[t[0]]);
            if (dot(n, normal) < 0) std::swap(t[1], t[2]);
            m.f.push_back(t);
          }
        }
    }
  }
  return m;
}

// ---------------------------------------------------------------------------------------------
// Checks and output

// Every shell closed and consistently oriented: each directed edge used once, its reverse once.
void check_closed(const Mesh& m, const std::string& name) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (const Tri& t : m.f) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[static_cast<std::size_t>(k)],
                          b = t[static_cast<std::size_t>((k + 1) % 3)];
      if (a == b) throw std::runtime_error(name + ": degenerate triangle");
      ++edges[{a, b}];
    }
    const double area2 = norm(cross(m.v[t[1]] - m.v[t[0]], m.v[t[2]] - m.v[t[0]]));
    if (!(area2 > 1e-14)) throw std::runtime_error(name + ": zero-area triangle");
  }
  for (const auto& [e, n] : edges) {
    auto rev = edges.find({e.second, e.first});
    if (n != 1 || rev == edges.end() || rev->second != 1)
      throw std::runtime_error(name + ": mesh is not a closed oriented surface");
  }
  if (!(m.signed_volume() > 0)) throw std::runtime_error(name + ": inward-facing mesh");
}

double quantize(double x) {
  double q = std::round(x * 1e6) / 1e6;
  return q == 0 ? 0.0 : q;  // no negative zero
}

Mesh quantized(Mesh m) {
  for (V3& p : m.v) p = {quantize(p.x), quantize(p.y), quantize(p.z)};
  return m;
}

V3 unit_normal(const Mesh& m, const Tri& t) {
  const V3 n = cross(m.v[t[1]] - m.v[t[0]], m.v[t[2]] - m.v[t[0]]);
  const double len = norm(n);
  return (1.0 / len) * n;
}

std::string fixed6(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6f", x);
  return std::string(buf) == "-0.000000" ? std::string("0.000000") : std::string(buf);
}

void put_u32(std::string& out, std::uint32_t x) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((x >> (8 * i)) & 0xffu));
}
void put_f32(std::string& out, double x) {
  const float f = static_cast<float>(x);
  std::uint32_t bits = 0;
  static_assert(sizeof bits == sizeof f, "32-bit float expected");
  std::memcpy(&bits, &f, sizeof bits);
  put_u32(out, bits);
}

std::string binary_stl(const Mesh& m, const std::string& header) {
  std::string out = header.substr(0, 80);
  out.resize(80, ' ');
  put_u32(out, static_cast<std::uint32_t>(m.f.size()));
  for (const Tri& t : m.f) {
    const V3 n = unit_normal(m, t);
    put_f32(out, quantize(n.x));
    put_f32(out, quantize(n.y));
    put_f32(out, quantize(n.z));
    for (std::uint32_t i : t) {
      put_f32(out, m.v[i].x);
      put_f32(out, m.v[i].y);
      put_f32(out, m.v[i].z);
    }
    out.push_back('\0');  // attribute byte count
    out.push_back('\0');
  }
  return out;
}

std::string ascii_stl(const Mesh& m, const std::string& solid) {
  std::ostringstream s;
  s << "solid " << solid << "\n";
  for (const Tri& t : m.f) {
    const V3 n = unit_normal(m, t);
    s << "  facet normal " << fixed6(n.x) << ' ' << fixed6(n.y) << ' ' << fixed6(n.z) << "\n"
      << "    outer loop\n";
    for (std::uint32_t i : t)
      s << "      vertex " << fixed6(m.v[i].x) << ' ' << fixed6(m.v[i].y) << ' ' << fixed6(m.v[i].z)
        << "\n";
    s << "    endloop\n  endfacet\n";
  }
  s << "endsolid " << solid << "\n";
  return s.str();
}

std::string obj(const Mesh& m, const std::string& name, const std::string& comment) {
  std::ostringstream s;
  s << "# " << comment << "\n# " << m.v.size() << " vertices, " << m.f.size() << " triangles\n"
    << "o " << name << "\n";
  for (const V3& p : m.v)
    s << "v " << fixed6(p.x) << ' ' << fixed6(p.y) << ' ' << fixed6(p.z) << "\n";
  for (const Tri& t : m.f) s << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << "\n";
  return s.str();
}

enum class Format { kBinaryStl, kAsciiStl, kObj };

void write(const std::string& dir, const std::string& file, Format format, const Mesh& raw,
           const std::string& what) {
  const Mesh m = quantized(raw);
  check_closed(m, file);
  std::string data;
  switch (format) {
    case Format::kBinaryStl:
      data = binary_stl(m, "hullcheck_arm " + what + " (binary STL)");
      break;
    case Format::kAsciiStl:
      data = ascii_stl(m, "hullcheck_arm_" + file.substr(0, file.find('.')));
      break;
    case Format::kObj:
      data = obj(m, file.substr(0, file.find('.')), "hullcheck_arm " + what);
      break;
  }
  const std::string path = dir + "/" + file;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(data.data(), static_cast<std::streamsize>(data.size()));
  out.close();
  if (!out) throw std::runtime_error("cannot write " + path);
  std::cout << file << ": " << m.v.size() << " vertices, " << m.f.size() << " triangles, "
            << m.shells << (m.shells == 1 ? " shell" : " shells") << "\n";
}

// ---------------------------------------------------------------------------------------------
// The robot's meshes. Dimensions in metres, in each mesh's own frame (the URDF's <collision>
// <origin> places it in the link frame). See ../README.md.

// Base pedestal: tapered column, r 0.090 at the bottom to 0.075, 0.13 m tall, rounded top edge.
Mesh base_pedestal() {
  Profile p;
  p.to(0, 0);
  p.line(0.085, 0, 3);
  p.arc(0.085, 0.005, 0.005, -kPi / 2, 0, 4);
  p.line(0.075, 0.12, 12);
  p.arc(0.065, 0.12, 0.010, 0, kPi / 2, 6);
  p.line(0, 0.13, 4);
  return revolve(p, 64);
}

// Link 1: column r 0.07 from z 0.005 to the shoulder axis at z 0.19, domed on top.
Mesh link1() { return domed_tube(0.07, 0.005, 0.19, 0.008, 56, 10); }

// Link 2 (upper arm, lower half): tube r 0.06 along +z from the shoulder to joint 3 (z 0.2),
// domed on top. Placed in link 2 with a rotation (link 2's "up" is its -y axis).
Mesh link2() { return domed_tube(0.06, -0.02, 0.20, 0.006, 48, 10); }

// Link 3 (upper arm, upper half): tube r 0.06 from z -0.11 to the elbow axis at z 0.2, domed.
Mesh link3() { return domed_tube(0.06, -0.11, 0.20, 0.008, 32, 8); }

// Link 4 (forearm, lower half): tube r 0.055 from the elbow (z 0) to joint 5 (z 0.2), domed.
Mesh link4() { return domed_tube(0.055, 0.0, 0.20, 0.006, 48, 10); }

// Link 5 (forearm, upper half + wrist fork), NON-CONVEX: a column (r 0.055) carrying a yoke
// whose two prongs straddle link 6 on either side of the joint 6 axis (y axis at z 0.19). The
// gap between the prongs (|y| < 0.045 above z 0.11) lies inside the convex hull only.
// Authored in metres here, written in millimetres.
Mesh link5_fork() {
  Mesh m;
  {
    Profile p;  // column, chamfered into the yoke at the top
    p.to(0, -0.10);
    p.line(0.050, -0.10, 3);
    p.arc(0.050, -0.095, 0.005, -kPi / 2, 0, 4);
    p.line(0.055, 0.07, 12);
    p.line(0.045, 0.09, 2);
    p.line(0, 0.09, 3);
    m.append(revolve(p, 40));
  }
  m.append(
      transformed(rounded_box({0.045, 0.065, 0.015}, 0.006, 2, 3), translation({0, 0, 0.095})));
  for (double side : {1.0, -1.0}) {
    m.append(transformed(rounded_box({0.045, 0.010, 0.055}, 0.004, 2, 3),
                         translation({0, side * 0.055, 0.135})));
    // Round boss about the joint 6 axis (y): a disc about z rotated onto y.
    const double y0 = side > 0 ? 0.045 : -0.065;
    m.append(transformed(filleted_disc(0.045, y0, y0 + 0.020, 0.003, 32),
                         rot_x(-kPi / 2, {0, 0, 0.19})));
  }
  for (V3& q : m.v) q = 1000.0 * q;  // millimetres
  return m;
}

// Gripper housing on the tool flange: rounded box 0.06 x 0.14 x 0.063 (z 0.012 .. 0.075).
Mesh gripper_housing() {
  return transformed(rounded_box({0.030, 0.070, 0.0315}, 0.008, 4, 5), translation({0, 0, 0.0435}));
}

// Finger: rounded block x +-0.011, y 0 .. 0.016 (y = 0 is the gripping face), z 0 .. 0.052,
// tapering towards the tip (narrower in x, thinner in y) with the gripping face kept in place.
Mesh finger() {
  Mesh m =
      transformed(rounded_box({0.011, 0.008, 0.026}, 0.002, 3, 4), translation({0, 0.008, 0.026}));
  for (V3& q : m.v) {
    const double s = q.z / 0.052;
    q.x *= 1.0 - 0.25 * s;
    q.y *= 1.0 - 0.35 * s;
  }
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: " << argv[0] << " OUTPUT_DIR\n";
    return 2;
  }
  const std::string dir = argv[1];
  try {
    write(dir, "base_pedestal.stl", Format::kBinaryStl, base_pedestal(), "base pedestal, metres");
    write(dir, "link1.stl", Format::kBinaryStl, link1(), "link1, metres");
    write(dir, "link2.obj", Format::kObj, link2(), "link2 collision mesh, metres");
    write(dir, "link3.STL", Format::kAsciiStl, link3(), "link3, metres");
    write(dir, "link4.stl", Format::kBinaryStl, link4(), "link4, metres");
    write(dir, "link5_mm.stl", Format::kBinaryStl, link5_fork(), "link5 fork, MILLIMETRES");
    write(dir, "gripper_housing.stl", Format::kBinaryStl, gripper_housing(),
          "gripper housing, metres");
    write(dir, "finger.stl", Format::kBinaryStl, finger(), "finger, metres");
  } catch (const std::exception& e) {
    std::cerr << "generate_meshes: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
