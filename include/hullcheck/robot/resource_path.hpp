// Resolution of URDF resource URIs (mesh file names) to files on disk.
#pragma once

#include <map>
#include <string>

namespace hullcheck {

/// Package name -> folder of that package (the folder holding its package.xml), given by the
/// caller; it takes precedence over the environment. Example: {"panda_description",
/// "/opt/robots/panda_description"}.
using PackageMap = std::map<std::string, std::string>;

/// Resolves a URDF resource URI to an existing file path.
///  - `package://PKG/REL`: PKG is looked up, in order, in `packages`, in every folder of
///    ROS_PACKAGE_PATH (as `DIR/PKG`, as `DIR` itself when its name is PKG, or as a folder named
///    PKG holding a package.xml up to 3 levels below DIR), in every prefix of AMENT_PREFIX_PATH
///    (as `PREFIX/share/PKG`), then in the folders above `base_dir` (as `UP/PKG`, or `UP` itself
///    when its name is PKG). The first folder found that holds REL wins.
///  - `file:///abs/path`: that absolute path.
///  - anything else: a path, relative paths taken against `base_dir` (the URDF's folder).
/// Throws InputError when no existing file is found, naming `context` (e.g. "link 'forearm'"),
/// the URI and every place searched. Reads the environment at each call; thread-safe as long
/// as nobody modifies the environment concurrently.
std::string resolve_resource_path(const std::string& uri, const std::string& base_dir,
                                  const PackageMap& packages, const std::string& context);

}  // namespace hullcheck
