// ns per call measured with std::chrono: the function runs over a fixed set of inputs, repeated
// until at least `min_seconds` have passed (so timer resolution and loop overhead stay negligible);
// the results are summed into a volatile sink so the calls cannot be optimized away.
#pragma once

#include <chrono>
#include <vector>

namespace nb {

template <class T, class F>
double ns_per_call(F&& f, const std::vector<T>& xs, double min_seconds = 0.02) {
  using clock = std::chrono::steady_clock;
  volatile T sink = T(0);
  long calls = 0;
  const auto t0 = clock::now();
  double elapsed = 0;
  do {
    T acc = T(0);
    for (const T x : xs) acc += f(x);
    sink = sink + acc;
    calls += static_cast<long>(xs.size());
    elapsed = std::chrono::duration<double>(clock::now() - t0).count();
  } while (elapsed < min_seconds);
  return 1e9 * elapsed / static_cast<double>(calls);
}

}  // namespace nb
