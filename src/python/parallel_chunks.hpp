// parallel_chunks (arguments.hpp): contiguous chunks of a batch on plain threads.
#pragma once

#include <exception>
#include <thread>
#include <vector>

namespace hullcheck::python {

template <class Body>
void parallel_chunks(Eigen::Index count, int threads, const Body& body) {
  if (threads <= 1 || count <= 1) {
    body(Eigen::Index{0}, count);
    return;
  }
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(threads));
  std::vector<std::thread> workers;
  const auto chunk = [&](int k) {
    const Eigen::Index begin = count * k / threads, end = count * (k + 1) / threads;
    try {
      body(begin, end);
    } catch (...) {
      errors[static_cast<std::size_t>(k)] = std::current_exception();
    }
  };
  for (int k = 1; k < threads; ++k) workers.emplace_back(chunk, k);
  chunk(0);
  for (std::thread& w : workers) w.join();
  for (const std::exception_ptr& e : errors) {
    if (e) std::rethrow_exception(e);
  }
}

}  // namespace hullcheck::python
