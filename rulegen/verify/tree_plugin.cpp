// blverify: the plugin's export table (compiled into each tree plugin with -fvisibility=hidden, so
// that its registry functions bind to its own tree, never to another plugin's or blverify's).
#include "clamped/verify_clamped.hpp"
#include "tree_api.hpp"

#ifndef BLVERIFY_TREE_HASH
#include "tree_hash_default.h"  // written by blverify_treehash for the plugin CMake builds
#endif

extern "C" __attribute__((visibility("default"))) const blv::TreeApi* blv_tree_api() {
  static const blv::TreeApi api{blv::kTreeAbi,       BLVERIFY_TREE_HASH,        &blv::registry_compiled_in,
                                &blv::load_registry, &blv::mp_registry_matches, &blv::mp_warm_up,
                                &blv::mp_check,      &blv::rules_compiled_in,   &blv::check_bivariate,
                                &blv::check_rule2,   &blv::clamped::run,        &blv::load_stats};
  return &api;
}
