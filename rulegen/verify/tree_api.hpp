// blverify: the part of blverify that includes a generated tree (registry, 50-digit instantiation,
// rules) lives in a plugin, one per tree: built by CMake for the project's generated/, or compiled
// at run time for any other tree (tree_loader.cpp). This is the table the plugin exports.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "reference_mp.hpp"
#include "registry_view.hpp"
#include "rules_check.hpp"

namespace blv {

// Bumped whenever TreeApi or the types it passes change (a cached plugin of another ABI is rebuilt).
constexpr int kTreeAbi = 3;

struct TreeApi {
  int abi;
  const char* tree_hash;  // tree_hash() of the tree it was compiled from
  bool (*registry_compiled_in)();
  std::vector<EntryView> (*load_registry)(std::string* error);
  bool (*mp_registry_matches)(const std::vector<EntryView>& entries, std::string* error);
  void (*mp_warm_up)();
  MpResult (*mp_check)(int index, const Spec& spec, double x, double sigma);
  bool (*rules_compiled_in)();
  std::vector<RuleCheck> (*check_bivariate)();
  std::vector<RuleCheck> (*check_rule2)();
  int (*clamped_run)(const std::string& manifest_path, bool record, std::FILE* out);
  std::vector<StatView> (*load_stats)(std::string* error);
};

}  // namespace blv

// The plugin's only exported symbol.
extern "C" const blv::TreeApi* blv_tree_api();
