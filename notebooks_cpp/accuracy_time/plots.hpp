// gnuplot scripts of the accuracy_time notebook.
#pragma once

#include <string>
#include <vector>

#include "bench_csv.hpp"
#include "families.hpp"
#include "suite.hpp"

namespace nb::acc {

// Every table entry: ns per call against relative RMS error (log-log), families coloured, one point
// per way (plain, MC-4/16/64, smoothed float); right panel: the family medians.
std::string entries_script(const std::string& png, const std::vector<EntryRow>& rows,
                           const std::vector<FamilyStats>& fams);

// Per scene: speed-up of the fastest front point at MSAA-16's error (model and evaluator); scenes
// that do not reach it: the speed-up at the highest MSAA level they reach (open points, labelled).
std::string speedup_script(const std::string& png, const Suite& s);

// Every scene's front normalized by its MSAA-16 (time / MSAA-16 time, error / MSAA-16 error), with
// each scene's MSAA 2..32 ladder in grey.
std::string fronts_script(const std::string& png, const Suite& s);

}  // namespace nb::acc
