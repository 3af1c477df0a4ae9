// docs/accuracy_cost.csv (written by bench_table --summary): one row per registry entry with ns per
// call and RMS error of the plain function, the smoothed entry and Monte Carlo with 4/16/64 samples.
#pragma once

#include <string>
#include <vector>

namespace nb::acc {

struct EntryRow {
  std::string entry, kernel, family;
  double plain_ns, smoothed_ns, mc_ns[3];  // MC with 4, 16, 64 samples
  double err_plain, err_mc[3];             // absolute RMS against the double smoothed entry
  double ref_rms;                          // RMS of the exact smoothed values (the error scale)
  double f32_smoothed_ns, f32_smoothed_err;
};

inline constexpr int kMcSamples[3] = {4, 16, 64};

// Throws std::runtime_error naming the path when the file is missing or a row is malformed.
std::vector<EntryRow> read_accuracy_csv(const std::string& path);

}  // namespace nb::acc
