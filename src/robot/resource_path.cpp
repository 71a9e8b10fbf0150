#include <cstdlib>
#include <filesystem>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/robot/resource_path.hpp>
#include <sstream>
#include <system_error>
#include <vector>

namespace hullcheck {
namespace {

namespace fs = std::filesystem;

bool is_file(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

bool is_dir(const fs::path& p) {
  std::error_code ec;
  return fs::is_directory(p, ec);
}

std::vector<std::string> split_path_list(const char* value) {
  std::vector<std::string> out;
  if (value == nullptr) return out;
  std::stringstream ss(value);
  std::string item;
  while (std::getline(ss, item, ':')) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

// A folder named `package` holding a package.xml, at most `depth` levels below `dir` (its
// children are 1 level below).
bool find_package_below(const fs::path& dir, const std::string& package, int depth,
                        fs::path* found) {
  if (depth < 1) return false;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (!it->is_directory(ec)) continue;
    const fs::path sub = it->path();
    if (sub.filename() == package && is_file(sub / "package.xml")) {
      *found = sub;
      return true;
    }
    if (find_package_below(sub, package, depth - 1, found)) return true;
  }
  return false;
}

// Records `folder / rel` as searched and returns true when it is an existing file.
bool try_candidate(const fs::path& folder, const std::string& rel, std::vector<std::string>* tried,
                   std::string* result) {
  const fs::path candidate = folder / rel;
  tried->push_back(candidate.lexically_normal().string());
  if (!is_file(candidate)) return false;
  *result = candidate.lexically_normal().string();
  return true;
}

[[noreturn]] void fail(const std::string& context, const std::string& uri, const std::string& why,
                       const std::vector<std::string>& tried) {
  std::ostringstream msg;
  msg << context << ": cannot resolve '" << uri << "': " << why;
  if (!tried.empty()) {
    msg << "; searched:";
    for (const std::string& t : tried) msg << "\n  " << t;
  }
  throw InputError(msg.str());
}

std::string resolve_package(const std::string& uri, const std::string& base_dir,
                            const PackageMap& packages, const std::string& context) {
  const std::string rest = uri.substr(std::string("package://").size());
  const std::size_t slash = rest.find('/');
  if (slash == std::string::npos || slash == 0 || slash + 1 == rest.size()) {
    fail(context, uri, "expected package://PACKAGE/RELATIVE_PATH", {});
  }
  const std::string package = rest.substr(0, slash);
  const std::string rel = rest.substr(slash + 1);
  std::vector<std::string> tried;
  std::string result;

  const auto mapped = packages.find(package);
  if (mapped != packages.end()) {
    if (try_candidate(mapped->second, rel, &tried, &result)) return result;
  } else {
    tried.push_back("package map: no entry for '" + package + "'");
  }

  const std::vector<std::string> ros_paths = split_path_list(std::getenv("ROS_PACKAGE_PATH"));
  if (ros_paths.empty()) tried.push_back("ROS_PACKAGE_PATH: not set");
  for (const std::string& dir : ros_paths) {
    const fs::path d(dir);
    if (is_dir(d / package) && try_candidate(d / package, rel, &tried, &result)) return result;
    if (d.filename() == package && try_candidate(d, rel, &tried, &result)) return result;
    fs::path below;
    if (find_package_below(d, package, 3, &below) && try_candidate(below, rel, &tried, &result)) {
      return result;
    }
    if (!is_dir(d / package)) tried.push_back((d / package).string() + " (no such folder)");
  }

  const std::vector<std::string> prefixes = split_path_list(std::getenv("AMENT_PREFIX_PATH"));
  if (prefixes.empty()) tried.push_back("AMENT_PREFIX_PATH: not set");
  for (const std::string& prefix : prefixes) {
    if (try_candidate(fs::path(prefix) / "share" / package, rel, &tried, &result)) return result;
  }

  std::error_code ec;
  fs::path up = fs::absolute(base_dir.empty() ? fs::path(".") : fs::path(base_dir), ec);
  up = up.lexically_normal();
  while (true) {
    if (!up.filename().empty() && up.filename() == package &&
        try_candidate(up, rel, &tried, &result)) {
      return result;
    }
    if (try_candidate(up / package, rel, &tried, &result)) return result;
    if (!up.has_parent_path() || up.parent_path() == up) break;
    up = up.parent_path();
  }
  fail(context, uri, "package '" + package + "' does not hold '" + rel + "' in any place searched",
       tried);
}

}  // namespace

std::string resolve_resource_path(const std::string& uri, const std::string& base_dir,
                                  const PackageMap& packages, const std::string& context) {
  if (uri.empty()) fail(context, uri, "empty file name", {});
  if (uri.rfind("package://", 0) == 0) return resolve_package(uri, base_dir, packages, context);
  std::vector<std::string> tried;
  std::string result;
  if (uri.rfind("file://", 0) == 0) {
    const fs::path path(uri.substr(std::string("file://").size()));
    if (is_file(path)) return path.lexically_normal().string();
    fail(context, uri, "no such file", {path.string()});
  }
  const fs::path p(uri);
  if (p.is_absolute()) {
    if (is_file(p)) return p.lexically_normal().string();
    fail(context, uri, "no such file", {p.string()});
  }
  if (try_candidate(base_dir.empty() ? fs::path(".") : fs::path(base_dir), uri, &tried, &result)) {
    return result;
  }
  fail(context, uri, "no such file (relative paths are taken against the URDF's folder)", tried);
}

}  // namespace hullcheck
