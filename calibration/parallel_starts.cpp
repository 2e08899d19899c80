#include "calibration/parallel_starts.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <thread>
#include <vector>

namespace wl {

void run_starts(int count, int threads, const std::function<void(int)>& solve) {
  const int workers = std::min(count, std::max(1, threads));
  if (workers <= 1) {
    for (int s = 0; s < count; ++s) solve(s);
    return;
  }
  std::atomic<int> next{0};
  std::vector<std::exception_ptr> errors(workers);
  std::vector<std::thread> pool;
  for (int w = 0; w < workers; ++w)
    pool.emplace_back([&, w] {
      try {
        for (int s = next++; s < count; s = next++) solve(s);
      } catch (...) {
        errors[w] = std::current_exception();
        next = count;
      }
    });
  for (std::thread& t : pool) t.join();
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace wl
