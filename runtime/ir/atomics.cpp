#include "ir/atomics.hpp"

#include <bandlimit/registry.hpp>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace bl::ir {
namespace {

// kAtomics ends with the pseudo-atomic "moment" (raw kernel moments), which is not a function.
int count_real() {
  int n = 0;
  for (const auto& a : bl::registry::kAtomics) {
    if (std::strcmp(a.name, "moment") == 0) break;
    ++n;
  }
  return n;
}

template <class T>
const std::vector<T (*)(T)>& plains() {
  static const std::vector<T (*)(T)> table = [] {
    std::vector<T (*)(T)> t(count_real(), nullptr);
    int n = 0;
    const auto* e = bl::registry::entries<T>(&n);
    for (int i = 0; i < n; ++i) {
      const int k = static_cast<int>(e[i].atomic - bl::registry::kAtomics);
      if (k < count_real() && !t[k]) t[k] = e[i].plain;
    }
    for (std::size_t k = 0; k < t.size(); ++k)
      if (!t[k])
        throw std::logic_error(std::string("generated registry has no plain function for ") +
                               bl::registry::kAtomics[k].name);
    return t;
  }();
  return table;
}

}  // namespace

int atomic_count() {
  static const int n = count_real();
  return n;
}

int atomic_index(const std::string& name) {
  for (int i = 0; i < atomic_count(); ++i)
    if (name == bl::registry::kAtomics[i].name) return i;
  return -1;
}

const char* atomic_name(int index) {
  if (index < 0 || index >= atomic_count()) throw std::out_of_range("atomic index " + std::to_string(index));
  return bl::registry::kAtomics[index].name;
}

void atomic_range(int index, double* lo, double* hi) {
  atomic_name(index);  // range check
  *lo = bl::registry::kAtomics[index].range_lo;
  *hi = bl::registry::kAtomics[index].range_hi;
}

bool atomic_indicator(int index) {
  atomic_name(index);  // range check
  return bl::registry::kAtomics[index].indicator;
}

double plain_atomic(int index, double x) {
  return plains<double>().at(index)(x);
}
float plain_atomic(int index, float x) {
  return plains<float>().at(index)(x);
}
PlainFloatFn plain_atomic_fn(int index) {
  return plains<float>().at(index);
}

}  // namespace bl::ir
