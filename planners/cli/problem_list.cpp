#include "problem_list.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <hullcheck/core/errors.hpp>
#include <regex>
#include <sstream>

namespace hullcheck::cli {
namespace fs = std::filesystem;

std::vector<ProblemFiles> find_problems(const std::vector<std::string>& sources) {
  std::vector<ProblemFiles> out;
  const std::regex scene_name("scene([0-9]+)\\.yaml");
  for (const std::string& source : sources) {
    std::error_code ec;
    if (fs::is_directory(source, ec)) {
      for (fs::recursive_directory_iterator it(source, ec), end; !ec && it != end;
           it.increment(ec)) {
        std::smatch m;
        const std::string file = it->path().filename().string();
        if (!it->is_regular_file(ec) || !std::regex_match(file, m, scene_name)) continue;
        const fs::path request = it->path().parent_path() / ("request" + m[1].str() + ".yaml");
        if (!fs::is_regular_file(request, ec)) {
          throw InputError("problems: " + it->path().string() + " has no " + request.string());
        }
        out.push_back({it->path().parent_path().filename().string() + "/" + m[1].str(),
                       it->path().string(), request.string()});
      }
    } else if (fs::is_regular_file(source, ec)) {
      std::ifstream in(source);
      std::string line;
      int number = 0;
      const fs::path base = fs::path(source).parent_path();
      while (std::getline(in, line)) {
        ++number;
        const std::string text = line.substr(0, line.find('#'));
        std::istringstream items(text);
        std::string scene, request, extra;
        if (!(items >> scene)) continue;  // blank or comment
        if (!(items >> request) || (items >> extra)) {
          throw InputError("problem list '" + source + "': line " + std::to_string(number) +
                           ": expected 'SCENE REQUEST'");
        }
        const auto resolve = [&](const std::string& p) {
          return fs::path(p).is_absolute() ? fs::path(p) : base / p;
        };
        out.push_back({fs::path(scene).stem().string() + "@" + std::to_string(number),
                       resolve(scene).string(), resolve(request).string()});
      }
    } else {
      throw InputError("problems: '" + source + "' is neither a folder nor a list file");
    }
  }
  if (out.empty()) throw InputError("problems: no sceneNNNN.yaml/requestNNNN.yaml pairs found");
  std::sort(out.begin(), out.end(),
            [](const ProblemFiles& a, const ProblemFiles& b) { return a.name < b.name; });
  return out;
}

std::vector<ProblemFiles> shard(const std::vector<ProblemFiles>& problems, int index, int count) {
  std::vector<ProblemFiles> out;
  for (std::size_t i = 0; i < problems.size(); ++i) {
    if (static_cast<int>(i % static_cast<std::size_t>(count)) == index) out.push_back(problems[i]);
  }
  return out;
}

void parse_shard(const std::string& text, int* index, int* count) {
  char slash = 0;
  std::istringstream in(text);
  std::string rest;
  if (!(in >> *index >> slash >> *count) || slash != '/' || (in >> rest) || *count < 1 ||
      *index < 0 || *index >= *count) {
    throw InputError("--shard '" + text + "': expected i/n with 0 <= i < n");
  }
}

}  // namespace hullcheck::cli
