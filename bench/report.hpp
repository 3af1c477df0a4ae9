// The summary's rows and the files made from them: <prefix>.csv (one row per registry entry) and
// <prefix>.md (how to reproduce, machine, per-family medians, full table, link to the plot).
#pragma once

#include <string>
#include <vector>

#include "machine.hpp"
#include "methods.hpp"

namespace blb {

struct Row {
  std::string name;    // "gaussian/fract"
  std::string kernel;  // "gaussian"
  std::string family;
  double ns[kNumMethods];   // median ns per call, double, indexed by Method
  double err[kNumMethods];  // RMS error; err[Smoothed] is NaN (the reference itself)
  double ref_rms;           // RMS of the exact smoothed values (scale of the errors)
  double f32_plain_ns, f32_smoothed_ns, f32_smoothed_err;
};

struct RunInfo {
  MachineInfo machine;
  int repetitions;
  double min_time_s;
  int inputs;
  int error_seeds;
  double wall_s;
  std::string command;  // how the summary was produced
  std::string prefix;   // the files written: prefix.{md,csv,png}
};

void write_csv(const std::string& path, const std::vector<Row>& rows);
void write_markdown(const std::string& path, const std::string& png_name,
                    const std::vector<Row>& rows, const RunInfo& info);

}  // namespace blb
