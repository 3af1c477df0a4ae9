// The truncated Taylor series of Gaussian smoothing (Yang & Barnes eq. 4.7 in one dimension):
// f^(x, s) = sum_k s^(2k) / (2^k k!) f^(2k)(x), i.e. exp((s^2 / 2) d^2/dx^2) f, cut after K terms.
#pragma once

#include <vector>

namespace nb::taylor {

constexpr int kTerms = 10;                // the paper's 10 terms: k = 0..9
constexpr int kOrder = 2 * (kTerms - 1);  // so derivatives up to order 18

// f(x) = sin(x^2) + x^2 / 100 and its derivatives 0..kOrder at x (Boost autodiff, forward mode).
std::vector<double> derivatives(double x);

// The same derivatives from the exact recurrence d^n/dx^n e^(ix^2) = e^(ix^2) P_n(x),
// P_(n+1) = P_n' + 2ix P_n (complex polynomials), plus those of x^2 / 100: a check on autodiff.
std::vector<double> exact_derivatives(double x);

// sum_{k < terms} s^(2k) / (2^k k!) f^(2k)(x), from derivatives(x).
double truncated(const std::vector<double>& d, double s, int terms = kTerms);

// The same series applied to one frequency w: the gain of exp(iwx) is sum_{k < terms} (-s^2 w^2 / 2)^k / k!,
// a truncation of the Gaussian's exp(-s^2 w^2 / 2); it grows like a polynomial once s w > ~sqrt(2 terms).
double gain(double s, double w, int terms = kTerms);

}  // namespace nb::taylor
