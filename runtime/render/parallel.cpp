#include "render/parallel.hpp"

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace bl::render {

int thread_count() {
  if (const char* e = std::getenv("BL_THREADS")) {
    const int n = std::atoi(e);
    if (n > 0) return n;
  }
  const unsigned n = std::thread::hardware_concurrency();
  return n ? static_cast<int>(n) : 1;
}

void parallel_rows(int rows, const std::function<void(int)>& row_fn, const std::string& label) {
  std::atomic<int> next{0}, done{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  const bool bar = !label.empty() && (isatty(2) || (std::getenv("BL_PROGRESS") && std::getenv("BL_PROGRESS")[0] == '1'));
  const auto start = std::chrono::steady_clock::now();
  auto work = [&] {
    for (int y; (y = next.fetch_add(1)) < rows;) {
      try {
        row_fn(y);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        next = rows;
      }
      done.fetch_add(1);
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < thread_count(); ++t) pool.emplace_back(work);
  if (bar) {
    std::thread progress([&] {
      while (done.load() < rows && !error) {
        const int d = done.load();
        const int w = 30, filled = rows ? w * d / rows : w;
        std::fprintf(stderr, "\r%s [%.*s%*s] %3d%%", label.c_str(), filled, "##############################",
                     w - filled, "", rows ? 100 * d / rows : 100);
        std::this_thread::sleep_for(std::chrono::milliseconds(200));
      }
    });
    work();
    for (auto& t : pool) t.join();
    progress.join();
  } else {
    work();
    for (auto& t : pool) t.join();
  }
  if (!label.empty()) {
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "%s%s: %d rows in %.2f s\n", bar ? "\r" : "", label.c_str(), rows, s);
  }
  if (error) std::rethrow_exception(error);
}

}  // namespace bl::render
