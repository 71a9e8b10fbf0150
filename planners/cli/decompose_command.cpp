#include "decompose_command.hpp"

#include <tinyxml2.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

#include "robot_options.hpp"

namespace hullcheck::cli {

namespace {

namespace fs = std::filesystem;

// Writes the hull's triangles (outward for a 3D hull) as a binary STL, metres.
void write_binary_stl(const fs::path& path, const ConvexHull& hull) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw InputError("decompose: cannot write '" + path.string() + "'");
  char header[80] = "hullcheck convex piece";
  out.write(header, sizeof header);
  const auto count = static_cast<std::uint32_t>(hull.triangles().size());
  out.write(reinterpret_cast<const char*>(&count), sizeof count);
  const auto& v = hull.vertices();
  for (const auto& t : hull.triangles()) {
    const Eigen::Vector3d& a = v[static_cast<std::size_t>(t[0])];
    const Eigen::Vector3d& b = v[static_cast<std::size_t>(t[1])];
    const Eigen::Vector3d& c = v[static_cast<std::size_t>(t[2])];
    const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
    float values[12];
    for (int k = 0; k < 3; ++k) {
      values[k] = static_cast<float>(n[k]);
      values[3 + k] = static_cast<float>(a[k]);
      values[6 + k] = static_cast<float>(b[k]);
      values[9 + k] = static_cast<float>(c[k]);
    }
    out.write(reinterpret_cast<const char*>(values), sizeof values);
    const std::uint16_t attribute = 0;
    out.write(reinterpret_cast<const char*>(&attribute), sizeof attribute);
  }
  if (!out) throw InputError("decompose: write to '" + path.string() + "' failed");
}

// The URDF at `urdf` with every decomposed mesh <collision> replaced by one <collision> per
// piece (same origin, the piece's STL in `mesh_dir`, no scale: pieces are in metres), written
// to `out_path`. Returns the number of piece files written.
int write_pieces_urdf(const RobotModel& model, const std::string& urdf, const fs::path& out_path,
                      const fs::path& mesh_dir) {
  tinyxml2::XMLDocument doc;
  if (doc.LoadFile(urdf.c_str()) != tinyxml2::XML_SUCCESS) {
    throw InputError("URDF '" + urdf + "': cannot be read again: " + doc.ErrorStr());
  }
  tinyxml2::XMLElement* robot = doc.FirstChildElement("robot");
  if (robot == nullptr) throw InputError("URDF '" + urdf + "': no <robot> element");
  fs::create_directories(mesh_dir);
  const fs::path out_dir = fs::absolute(out_path).parent_path();
  int files = 0;
  for (tinyxml2::XMLElement* link = robot->FirstChildElement("link"); link != nullptr;
       link = link->NextSiblingElement("link")) {
    const char* name = link->Attribute("name");
    const int l = name == nullptr ? -1 : model.link_index(name);
    if (l < 0) continue;
    const std::vector<CollisionShape>& shapes = model.link(l).shapes;
    std::vector<tinyxml2::XMLElement*> collisions;
    for (tinyxml2::XMLElement* c = link->FirstChildElement("collision"); c != nullptr;
         c = c->NextSiblingElement("collision")) {
      collisions.push_back(c);
    }
    for (std::size_t e = 0; e < collisions.size(); ++e) {
      std::vector<const CollisionShape*> pieces;
      for (const CollisionShape& s : shapes) {
        if (s.element == static_cast<int>(e) && s.piece_count > 1) pieces.push_back(&s);
      }
      if (pieces.empty()) {
        // A primitive, or a mesh kept as one hull: unchanged, but a relative mesh path must
        // still lead to the same file from the new URDF's folder.
        tinyxml2::XMLElement* geometry = collisions[e]->FirstChildElement("geometry");
        tinyxml2::XMLElement* mesh =
            geometry == nullptr ? nullptr : geometry->FirstChildElement("mesh");
        const char* filename = mesh == nullptr ? nullptr : mesh->Attribute("filename");
        if (filename != nullptr && std::string(filename).find("://") == std::string::npos &&
            !fs::path(filename).is_absolute()) {
          const fs::path original = fs::absolute(fs::path(urdf).parent_path() / filename);
          mesh->SetAttribute(
              "filename", original.lexically_normal().lexically_relative(out_dir).string().c_str());
        }
        continue;
      }
      for (const CollisionShape* s : pieces) {
        const std::string file = std::string(name) + "_" + std::to_string(e) + "_piece" +
                                 std::to_string(s->piece) + ".stl";
        write_binary_stl(mesh_dir / file, std::get<ConvexHull>(s->unpadded.geometry()));
        ++files;
        auto* copy = collisions[e]->DeepClone(&doc)->ToElement();
        copy->SetAttribute("name",
                           (std::string(name) + "_piece" + std::to_string(s->piece)).c_str());
        tinyxml2::XMLElement* mesh = copy->FirstChildElement("geometry")->FirstChildElement("mesh");
        const fs::path target = fs::absolute(mesh_dir / file);
        mesh->SetAttribute("filename", target.lexically_relative(out_dir).string().c_str());
        mesh->DeleteAttribute("scale");
        link->InsertAfterChild(collisions[e], copy);
      }
      link->DeleteChild(collisions[e]);
    }
  }
  if (doc.SaveFile(out_path.string().c_str()) != tinyxml2::XML_SUCCESS) {
    throw InputError("decompose: cannot write '" + out_path.string() + "'");
  }
  return files;
}

}  // namespace

void add_decompose_command(CLI::App& app) {
  struct Settings {
    RobotOptions robot;
    std::string write_urdf;
    std::string mesh_dir;
  };
  auto settings = std::make_shared<Settings>();
  CLI::App* command = app.add_subcommand(
      "decompose",
      "Decompose the robot's collision meshes into convex pieces within --tolerance of each "
      "mesh, filling the cache so that later loads are quick; print the pieces per link");
  settings->robot.add_to(*command, false);
  command->add_option("--write-urdf", settings->write_urdf,
                      "Also write a URDF whose links use the convex pieces as separate meshes "
                      "(binary STL, metres), for other tools");
  command->add_option("--mesh-dir", settings->mesh_dir,
                      "Folder for the pieces' STL files (default: beside --write-urdf, "
                      "<name>_pieces)");
  command->callback([settings] {
    RobotOptions robot = settings->robot;
    robot.mesh_geometry = "decompose";
    const auto t0 = std::chrono::steady_clock::now();
    const std::shared_ptr<RobotModel> model = robot.load();
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    int meshes = 0, decomposed = 0, pieces = 0, over = 0;
    for (const Link& l : model->links()) {
      for (const CollisionShape& s : l.shapes) {
        if (s.mesh_vertex_count == 0 || s.piece > 0) continue;
        ++meshes;
        pieces += s.piece_count;
        decomposed += s.piece_count > 1 ? 1 : 0;
        const bool within = s.mesh_excess <= robot.tolerance;
        over += within ? 0 : 1;
        std::printf("  %-28s %-36s %3d piece%s  within %.2f mm%s\n", l.name.c_str(),
                    fs::path(s.source).filename().string().c_str(), s.piece_count,
                    s.piece_count == 1 ? " " : "s", 1e3 * s.mesh_excess,
                    within ? "" : "  (piece budget reached: above the tolerance)");
      }
    }
    const std::string cache = robot.no_cache            ? std::string("none")
                              : robot.cache_dir.empty() ? default_decomposition_cache_dir()
                                                        : robot.cache_dir;
    std::printf(
        "%s: %d meshes, %d decomposed, %d convex pieces in all (tolerance %.1f mm, %d above it); "
        "%.2f s; cache %s\n",
        model->name().c_str(), meshes, decomposed, pieces, 1e3 * robot.tolerance, over, seconds,
        cache.empty() ? "none (no HOME)" : cache.c_str());
    if (!settings->write_urdf.empty()) {
      const fs::path out(settings->write_urdf);
      const fs::path dir = settings->mesh_dir.empty()
                               ? fs::absolute(out).parent_path() / (out.stem().string() + "_pieces")
                               : fs::path(settings->mesh_dir);
      const int files = write_pieces_urdf(*model, robot.urdf, out, dir);
      std::printf("wrote %s (%d piece meshes in %s)\n", out.string().c_str(), files,
                  dir.string().c_str());
    }
  });
}

}  // namespace hullcheck::cli
