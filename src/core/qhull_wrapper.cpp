#include "qhull_wrapper.hpp"

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace hullcheck::detail {

namespace {

/// Collects qhull's error output in memory.
class MemoryStream {
 public:
  MemoryStream() : file_(open_memstream(&buffer_, &size_)) {}
  ~MemoryStream() {
    if (file_ != nullptr) std::fclose(file_);
    std::free(buffer_);
  }
  MemoryStream(const MemoryStream&) = delete;
  MemoryStream& operator=(const MemoryStream&) = delete;
  FILE* file() const { return file_; }
  std::string text() {
    if (file_ != nullptr) std::fflush(file_);
    return buffer_ != nullptr ? std::string(buffer_, size_) : std::string();
  }

 private:
  char* buffer_ = nullptr;
  std::size_t size_ = 0;
  FILE* file_;
};

bool try_qhull(int dim, std::vector<double>& coords, const char* options, QhullOutput& out,
               std::string& error) {
  MemoryStream errors;
  qhT qh_storage;
  qhT* qh = &qh_storage;
  qh_zero(qh, errors.file());
  std::string command = std::string("qhull ") + options;
  const int count = static_cast<int>(coords.size()) / dim;
  const int exit_code =
      qh_new_qhull(qh, dim, count, coords.data(), False, command.data(), nullptr, errors.file());
  if (exit_code == 0) {
    out.vertex_ids.clear();
    out.facets.clear();
    vertexT* vertex;
    FORALLvertices { out.vertex_ids.push_back(qh_pointid(qh, vertex->point)); }
    facetT* facet;
    FORALLfacets {
      std::array<int, 3> ids{-1, -1, -1};
      int k = 0;
      vertexT** vertexp;
      FOREACHvertex_(facet->vertices) {
        if (k < 3) ids[k] = qh_pointid(qh, vertex->point);
        ++k;
      }
      if (dim == 3 && k == 3) {
        // Make the triangle counter-clockwise seen from outside (along facet->normal).
        const double* p0 = coords.data() + 3 * ids[0];
        const double* p1 = coords.data() + 3 * ids[1];
        const double* p2 = coords.data() + 3 * ids[2];
        const double e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
        const double e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
        const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                             e1[0] * e2[1] - e1[1] * e2[0]};
        if (n[0] * facet->normal[0] + n[1] * facet->normal[1] + n[2] * facet->normal[2] < 0) {
          std::swap(ids[1], ids[2]);
        }
      }
      out.facets.push_back(ids);
    }
  } else {
    error = errors.text();
  }
  qh_freeqhull(qh, !qh_ALL);
  int current_long = 0, total_long = 0;
  qh_memfreeshort(qh, &current_long, &total_long);
  return exit_code == 0;
}

}  // namespace

QhullOutput run_qhull(int dim, const std::vector<double>& coords) {
  std::vector<double> work = coords;  // qhull may scale its input in place
  QhullOutput out;
  std::string error;
  if (try_qhull(dim, work, "Qt", out, error)) return out;
  work = coords;
  std::string joggle_error;
  if (try_qhull(dim, work, "QJ", out, joggle_error)) return out;
  throw std::runtime_error("qhull failed: " + error + joggle_error);
}

}  // namespace hullcheck::detail
