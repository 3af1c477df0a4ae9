// blverify: the one-pass stat entries ({E f, Var f}, rulegen/emit_stat_pairs.hpp) against the
// quadrature references of their f and f^2 entries (RefEngine, as for every entry) on f's grid. The
// mean is held to the entries' bounds (double 1e-9, float 2e-5, relative to max(1, |E f|)); the
// variance E f^2 - (E f)^2 to the same bounds relative to max(1, E f^2): it is a difference of two
// such values, which is what a stat entry can promise. Float is compared at the float-rounded inputs.
#pragma once

#include <cstdio>
#include <vector>

#include "registry_view.hpp"
#include "verify_entry.hpp"

namespace blv {

// Prints one line per stat entry; returns 1 when one fails (or names an f / f^2 entry the registry
// lacks), else 0.
int run_stat_checks(const std::vector<EntryView>& entries, const std::vector<StatView>& stats,
                    const VerifyOptions& opt, std::FILE* out);

}  // namespace blv
