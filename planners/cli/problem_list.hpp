// Finding MotionBenchMaker problems (scene + request pairs) on disk.
#pragma once

#include <string>
#include <vector>

namespace hullcheck::cli {

/// One planning problem: a PlanningScene YAML and a MotionPlanRequest YAML.
struct ProblemFiles {
  std::string name;  ///< "<folder>/<NNNN>", e.g. "box_panda/0001".
  std::string scene;
  std::string request;
};

/// The problems named by `sources`, sorted by name: a folder is searched recursively for
/// sceneNNNN.yaml files with a requestNNNN.yaml beside them; a file lists one problem per line
/// as "SCENE REQUEST" (paths relative to the list's folder; '#' starts a comment). Throws
/// InputError for a missing source, a malformed list line, a scene without its request, or
/// when nothing is found.
std::vector<ProblemFiles> find_problems(const std::vector<std::string>& sources);

/// Keeps the problems of shard `index` of `count` (every count-th problem, starting at index);
/// "i/n" text form parsed by parse_shard (0 <= i < n), which throws InputError otherwise.
std::vector<ProblemFiles> shard(const std::vector<ProblemFiles>& problems, int index, int count);
void parse_shard(const std::string& text, int* index, int* count);

}  // namespace hullcheck::cli
