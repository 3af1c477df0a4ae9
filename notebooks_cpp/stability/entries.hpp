// The entries of the stability notebook: for each, the emitted table function, the naive textbook
// form (common/naive.hpp) and the independent high-precision reference (common/reference.hpp), in
// float and double.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "reference.hpp"

namespace nbs {

struct Entry {
  std::string name;   // e.g. "gaussian fract"
  std::string naive;  // what the naive form is, in words
  std::vector<double> xs;
  std::function<double(double, double)> emitted_d, naive_d;
  std::function<float(float, float)> emitted_f, naive_f;
  std::function<nb::ref::Exact(double, double)> ref;
};

// Terms of the naive (Dorn et al.) Fourier series.
inline constexpr int kNaiveTerms = 16;

std::vector<Entry> entries();

}  // namespace nbs
