#include "tuner/pareto.hpp"

#include <algorithm>

namespace bl::tuner {

bool dominates(const Objectives& a, const Objectives& b) {
  return a.time <= b.time && a.error <= b.error && (a.time < b.time || a.error < b.error);
}

std::vector<int> pareto_ranks(const std::vector<Objectives>& pts) {
  const int n = static_cast<int>(pts.size());
  std::vector<int> rank(n, -1), dominated_by(n, 0);
  std::vector<std::vector<int>> dominates_list(n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      if (i == j) continue;
      if (dominates(pts[i], pts[j]))
        dominates_list[i].push_back(j);
      else if (dominates(pts[j], pts[i]))
        ++dominated_by[i];
    }
  std::vector<int> current;
  for (int i = 0; i < n; ++i)
    if (dominated_by[i] == 0) current.push_back(i);
  for (int r = 0; !current.empty(); ++r) {
    std::vector<int> next;
    for (int i : current) {
      rank[i] = r;
      for (int j : dominates_list[i])
        if (--dominated_by[j] == 0) next.push_back(j);
    }
    current.swap(next);
  }
  return rank;
}

std::vector<int> pareto_front(const std::vector<Objectives>& pts) {
  std::vector<int> idx(pts.size());
  for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = static_cast<int>(i);
  std::stable_sort(idx.begin(), idx.end(), [&](int a, int b) {
    return pts[a].time != pts[b].time ? pts[a].time < pts[b].time : pts[a].error < pts[b].error;
  });
  std::vector<int> front;
  double best_error = 0;
  for (int i : idx) {
    // Sorted by time: a point is non-dominated iff its error beats every faster point's.
    if (front.empty() || pts[i].error < best_error) {
      front.push_back(i);
      best_error = pts[i].error;
    }
  }
  return front;
}

}  // namespace bl::tuner
