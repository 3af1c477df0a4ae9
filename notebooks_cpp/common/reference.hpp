// High-precision references for the notebooks, independent of the generated table: exact closed
// forms evaluated in 50- or 100-digit arithmetic (Boost.Multiprecision), and Boost.Math tanh_sinh
// quadrature split at every jump to cross-check those closed forms. Multiprecision stays inside
// reference.cpp (it costs seconds per translation unit to compile).
#pragma once

#include <string>

namespace nb::ref {

// A high-precision value as the unevaluated sum hi + lo of two doubles.
struct Exact {
  double hi;
  double lo;
};

// |v - r| / max(1, |r|), the table's error measure; +inf when v is NaN or inf and r is finite.
double rel_error(double v, Exact r);

// Gaussian N(0, s^2): fract, fract^2 (image sum over periods for s < 1/4, Fourier series beyond,
// both truncated below 1e-50), floor = x - fract. Pure power: E[(x + sZ)^n] by the moment sum.
Exact gauss_fract(double x, double s);
Exact gauss_fract_sq(double x, double s);
Exact gauss_floor(double x, double s);
Exact gauss_pow(double x, double s, int n);

// Box (half-width sqrt(3) s) and tent (half-width sqrt(6) s) of fract, from the exact first and
// second integrals at 100 digits (differences at tiny widths keep > 30 correct digits).
Exact box_fract(double x, double s);
Exact tent_fract(double x, double s);
Exact box_pow(double x, double s, int n);

// Compact box/tent of tan, tan^2, log, log^2 ("tan", "tan_sq", "log", "log_sq"; tent: "log"):
// half-width min(h, r/2), r the exact distance to the nearest singularity, exact antiderivatives at
// 100 digits.
Exact box_compact(const std::string& f, double x, double s);
Exact tent_compact(const std::string& f, double x, double s);

// Cross-checks by quadrature (tanh_sinh in 50 digits, split at the jumps): the absolute difference
// between the closed-form reference above and the integral of the kernel times f.
double check_gauss_fract(double x, double s);
double check_box_fract(double x, double s);
double check_tent_fract(double x, double s);
double check_box_compact(const std::string& f, double x, double s);

}  // namespace nb::ref
