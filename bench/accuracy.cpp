// RMS errors against the emitted smoothed function; see accuracy.hpp.
#include "accuracy.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

namespace blb {
namespace {

std::uint64_t fnv1a(const std::string& s) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (unsigned char c : s) h = (h ^ c) * 0x100000001b3ull;
  return h;
}

}  // namespace

template <class T>
double rms_error(const EntryView<T>& v, const EntryView<double>& ref,
                 const std::vector<Input<double>>& in, Method m) {
  if (std::is_same<T, double>::value && m == Method::Smoothed)
    return std::numeric_limits<double>::quiet_NaN();
  const int seeds = mc_samples(m) > 0 ? kErrorSeeds : 1;
  double sum = 0;
  long count = 0;
  for (int s = 0; s < seeds; ++s) {
    Rng rng{fnv1a(v.name) ^ (0xA11CE5EEDull * static_cast<std::uint64_t>(s + 1))};
    for (const auto& p : in) {
      const T x = static_cast<T>(p.x), sigma = static_cast<T>(p.sigma);
      const double r = ref.entry->smoothed(static_cast<double>(x), static_cast<double>(sigma));
      if (!std::isfinite(r)) continue;
      T value;
      switch (m) {
        case Method::Plain:
          value = eval_plain(v, x, sigma);
          break;
        case Method::Smoothed:
          value = eval_smoothed(v, x, sigma);
          break;
        default:
          value = eval_mc(v, x, sigma, mc_samples(m), rng);
          break;
      }
      const double d = static_cast<double>(value) - r;
      sum += d * d;
      ++count;
    }
  }
  return count ? std::sqrt(sum / count) : std::numeric_limits<double>::quiet_NaN();
}

template double rms_error<double>(const EntryView<double>&, const EntryView<double>&,
                                  const std::vector<Input<double>>&, Method);
template double rms_error<float>(const EntryView<float>&, const EntryView<double>&,
                                 const std::vector<Input<double>>&, Method);

double rms_reference(const EntryView<double>& ref, const std::vector<Input<double>>& in) {
  double sum = 0;
  long count = 0;
  for (const auto& p : in) {
    const double r = ref.entry->smoothed(p.x, p.sigma);
    if (!std::isfinite(r)) continue;
    sum += r * r;
    ++count;
  }
  return count ? std::sqrt(sum / count) : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace blb
