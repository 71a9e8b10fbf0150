#include "html_viewer.hpp"

#include <yaml-cpp/yaml.h>

#include <fstream>
#include <hullcheck/core/errors.hpp>
#include <sstream>

namespace hullcheck::cli {
namespace {

const char* const kThreeDir = "/usr/share/javascript/three";

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw InputError("viewer: cannot read '" + path +
                     "' (three.js: install Debian's libjs-three, scripts/install-deps.sh does)");
  }
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// JSON through yaml-cpp's emitter: flow style, keys double-quoted.
void key(YAML::Emitter& e, const char* name) { e << YAML::Key << YAML::DoubleQuoted << name; }

void emit_pose(YAML::Emitter& e, const Eigen::Isometry3d& pose) {
  e << YAML::BeginSeq;  // column-major 4x4, as THREE.Matrix4.fromArray expects
  for (int i = 0; i < 16; ++i) e << pose.matrix().data()[i];
  e << YAML::EndSeq;
}

void emit_shape(YAML::Emitter& e, const Shape& shape) {
  const Shape::Geometry& g = shape.geometry();
  e << YAML::BeginMap;
  if (const auto* box = std::get_if<Box>(&g)) {
    key(e, "type");
    e << YAML::DoubleQuoted << "box";
    key(e, "size");
    e << YAML::BeginSeq << 2 * box->half_extents.x() << 2 * box->half_extents.y()
      << 2 * box->half_extents.z() << YAML::EndSeq;
  } else if (const auto* sphere = std::get_if<Sphere>(&g)) {
    key(e, "type");
    e << YAML::DoubleQuoted << "sphere";
    key(e, "radius");
    e << sphere->radius;
  } else if (const auto* cylinder = std::get_if<Cylinder>(&g)) {
    key(e, "type");
    e << YAML::DoubleQuoted << "cylinder";
    key(e, "radius");
    e << cylinder->radius;
    key(e, "length");
    e << 2 * cylinder->half_length;
  } else if (const auto* capsule = std::get_if<Capsule>(&g)) {
    key(e, "type");
    e << YAML::DoubleQuoted << "capsule";
    key(e, "radius");
    e << capsule->radius;
    key(e, "length");
    e << 2 * capsule->half_length;
  } else {
    const auto& hull = std::get<ConvexHull>(g);
    key(e, "type");
    e << YAML::DoubleQuoted << "hull";
    key(e, "vertices");
    e << YAML::BeginSeq;
    for (const Eigen::Vector3d& v : hull.vertices()) e << v.x() << v.y() << v.z();
    e << YAML::EndSeq;
    key(e, "triangles");
    e << YAML::BeginSeq;
    for (const auto& t : hull.triangles()) e << t[0] << t[1] << t[2];
    e << YAML::EndSeq;
  }
  e << YAML::EndMap;
}

// Text for HTML element content.
std::string html_escaped(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// JSON made safe inside <script>: '<' occurs only in strings (names), where \u003c means the same.
std::string script_safe(const char* json) {
  std::string out;
  for (const char* c = json; *c; ++c) {
    if (*c == '<') {
      out += "\\u003c";
    } else {
      out += *c;
    }
  }
  return out;
}

const char* const kScript = R"JS(
const data = JSON.parse(document.getElementById('data').textContent);
const renderer = new THREE.WebGLRenderer({antialias: true});
renderer.setPixelRatio(window.devicePixelRatio);
document.body.appendChild(renderer.domElement);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0xf4f4f4);
const camera = new THREE.PerspectiveCamera(45, 1, 0.01, 100);
camera.up.set(0, 0, 1);  // z up, as in ROS
const controls = new THREE.OrbitControls(camera, renderer.domElement);
// A headlight (the directional light moves with the camera, so every view is lit) and ambient.
scene.add(new THREE.AmbientLight(0xffffff, 0.45));
const light = new THREE.DirectionalLight(0xffffff, 0.7);
light.position.set(0.5, 1, 0.2);  // camera frame: from above and a little to the right
light.target.position.set(0, 0, -1);
camera.add(light, light.target);
scene.add(camera);
function geometryOf(s) {
  if (s.type === 'box') return new THREE.BoxGeometry(s.size[0], s.size[1], s.size[2]);
  if (s.type === 'sphere') return new THREE.SphereGeometry(s.radius, 32, 16);
  if (s.type === 'cylinder' || s.type === 'capsule') {
    const g = new THREE.CylinderGeometry(s.radius, s.radius, s.length, 32);
    g.rotateX(Math.PI / 2);  // three.js cylinders run along y; ours along z
    return g;
  }
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.Float32BufferAttribute(s.vertices, 3));
  g.setIndex(s.triangles);
  g.computeVertexNormals();
  return g;
}
function meshOf(s, color, opacity) {
  const material = new THREE.MeshPhongMaterial({color: color, transparent: opacity < 1,
    opacity: opacity, flatShading: s.type === 'hull', side: THREE.DoubleSide});
  const group = new THREE.Group();
  group.add(new THREE.Mesh(geometryOf(s), material));
  if (s.type === 'capsule') {
    for (const z of [-s.length / 2, s.length / 2]) {
      const cap = new THREE.Mesh(new THREE.SphereGeometry(s.radius, 32, 16), material);
      cap.position.z = z;
      group.add(cap);
    }
  }
  return group;
}
function place(object, m) {
  object.matrixAutoUpdate = false;
  object.matrix.fromArray(m);
}
const world = new THREE.Group();
for (const o of data.obstacles) {
  const mesh = meshOf(o.shape, 0xc0504d, 0.55);
  place(mesh, o.pose);
  world.add(mesh);
}
scene.add(world);
const robot = new THREE.Group();
const links = data.links.map((link, i) => {
  const group = new THREE.Group();
  group.matrixAutoUpdate = false;
  for (const s of link.shapes) {
    const mesh = meshOf(s.shape, i % 2 ? 0x4f81bd : 0x8eb4e3, 1.0);
    place(mesh, s.origin);
    group.add(mesh);
  }
  robot.add(group);
  return group;
});
scene.add(robot);
const frames = data.frames;
const slider = document.getElementById('frame');
slider.max = Math.max(frames.length - 1, 0);
slider.disabled = frames.length < 2;
function show(k) {
  if (frames.length === 0) {
    document.getElementById('label').textContent = 'no states';
    return;
  }
  links.forEach((g, i) => g.matrix.fromArray(frames[k][i]));
  document.getElementById('label').textContent = 'state ' + (k + 1) + ' / ' + frames.length;
}
// Camera and floor grid fitted to the bounding box of the obstacles and of the robot along the
// whole path.
const box = new THREE.Box3().setFromObject(world);
const step = Math.max(1, Math.floor(frames.length / 30));
for (let k = 0; k < frames.length; k += step) {
  show(k);
  box.expandByObject(robot);
}
if (frames.length > 0) {
  show(frames.length - 1);
  box.expandByObject(robot);
}
if (box.isEmpty()) box.set(new THREE.Vector3(-0.5, -0.5, 0), new THREE.Vector3(0.5, 0.5, 1));
const center = box.getCenter(new THREE.Vector3());
const extent = Math.max(Math.abs(box.min.x), Math.abs(box.max.x),
                        Math.abs(box.min.y), Math.abs(box.max.y));
const gridSize = Math.max(2, 2 * Math.ceil(extent + 0.25));
const grid = new THREE.GridHelper(gridSize, gridSize <= 20 ? gridSize * 10 : gridSize,
                                  0xbbbbbb, 0xdddddd);
grid.rotation.x = Math.PI / 2;  // the z = 0 plane
scene.add(grid);
// Looking at the box's centre from the front right, above, just far enough to see all 8 corners.
const viewDirection = new THREE.Vector3(1, -1, 0.7).normalize();
function fitCamera() {
  const tanV = Math.tan(camera.fov * Math.PI / 360), tanH = tanV * camera.aspect;
  const right = new THREE.Vector3().crossVectors(camera.up, viewDirection).normalize();
  const up = new THREE.Vector3().crossVectors(viewDirection, right);
  let distance = 0.05;
  for (let i = 0; i < 8; ++i) {
    const c = new THREE.Vector3(i & 1 ? box.max.x : box.min.x, i & 2 ? box.max.y : box.min.y,
                                i & 4 ? box.max.z : box.min.z).sub(center);
    distance = Math.max(distance, c.dot(viewDirection) +
                        Math.max(Math.abs(c.dot(right)) / tanH, Math.abs(c.dot(up)) / tanV));
  }
  distance *= 1.05;
  const radius = Math.max(box.getSize(new THREE.Vector3()).length() / 2, 0.05);
  controls.target.copy(center);
  camera.position.copy(center).addScaledVector(viewDirection, distance);
  camera.near = distance / 100;
  camera.far = distance + 20 * radius;
  camera.updateProjectionMatrix();
  controls.update();
}
let playing = frames.length > 1;
document.getElementById('play').onclick = () => { playing = !playing; };
slider.oninput = () => { playing = false; show(+slider.value); };
renderer.domElement.ondblclick = fitCamera;
function resize() {
  const w = window.innerWidth, h = Math.max(window.innerHeight - 40, 1);
  renderer.setSize(w, h);
  camera.aspect = w / h;
  camera.updateProjectionMatrix();
}
window.addEventListener('resize', resize);
resize();
fitCamera();
let k = 0, last = 0;
function animate(t) {
  requestAnimationFrame(animate);
  if (playing && t - last > 40) {
    last = t;
    k = (k + 1) % frames.length;
    slider.value = k;
    show(k);
  }
  renderer.render(scene, camera);
}
show(0);
requestAnimationFrame(animate);
)JS";

}  // namespace

void write_html_viewer(const std::string& file, const std::string& title, const RobotModel& model,
                       const PlanningScene& scene,
                       const std::vector<Eigen::VectorXd>& configurations) {
  const std::string three = read_file(std::string(kThreeDir) + "/three.min.js");
  const std::string orbit =
      read_file(std::string(kThreeDir) + "/examples/js/controls/OrbitControls.js");
  YAML::Emitter e;
  e.SetDoublePrecision(7);
  e << YAML::Flow << YAML::BeginMap;
  key(e, "links");
  e << YAML::BeginSeq;
  for (const Link& link : model.links()) {
    e << YAML::BeginMap;
    key(e, "name");
    e << YAML::DoubleQuoted << link.name;
    key(e, "shapes");
    e << YAML::BeginSeq;
    for (const CollisionShape& s : link.shapes) {
      e << YAML::BeginMap;
      key(e, "origin");
      emit_pose(e, s.origin);
      key(e, "shape");
      emit_shape(e, s.unpadded);
      e << YAML::EndMap;
    }
    e << YAML::EndSeq << YAML::EndMap;
  }
  e << YAML::EndSeq;
  key(e, "obstacles");
  e << YAML::BeginSeq;
  for (const Obstacle& o : scene.obstacles) {
    e << YAML::BeginMap;
    key(e, "name");
    e << YAML::DoubleQuoted << o.name;
    key(e, "pose");
    emit_pose(e, o.pose);
    key(e, "shape");
    emit_shape(e, o.shape);
    e << YAML::EndMap;
  }
  e << YAML::EndSeq;
  key(e, "frames");
  e << YAML::BeginSeq;
  std::vector<Eigen::Isometry3d> poses;
  for (const Eigen::VectorXd& q : configurations) {
    model.compute_link_poses(q, poses);
    e << YAML::BeginSeq;
    for (const Eigen::Isometry3d& p : poses) emit_pose(e, p);
    e << YAML::EndSeq;
  }
  e << YAML::EndSeq << YAML::EndMap;

  const std::string heading = html_escaped(title);
  std::ofstream out(file);
  if (!out) throw InputError("viewer '" + file + "': cannot write");
  out << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" << heading
      << "</title>\n<style>body{margin:0;font-family:sans-serif}"
         "#bar{height:40px;display:flex;align-items:center;gap:12px;padding:0 12px}"
         "#frame{flex:1}canvas{display:block}</style></head>\n<body>\n<div id=\"bar\">"
         "<button id=\"play\">play / pause</button>"
         "<input id=\"frame\" type=\"range\" min=\"0\" value=\"0\"><span id=\"label\"></span>"
         "<span title=\"drag: rotate, right-drag: pan, wheel: zoom, double-click: fit the view\">"
      << heading << "</span></div>\n<script id=\"data\" type=\"application/json\">"
      << script_safe(e.c_str()) << "</script>\n<script>\n"
      << three << "\n</script>\n<script>\n"
      << orbit << "\n</script>\n<script>" << kScript << "</script>\n</body></html>\n";
  if (!out) throw InputError("viewer '" + file + "': write failed");
}

}  // namespace hullcheck::cli
