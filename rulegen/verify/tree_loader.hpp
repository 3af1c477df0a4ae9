// blverify: selects the tree plugin for --generated DIR (tree_api.hpp). The registry functions of
// registry_view.hpp, reference_mp.hpp, rules_check.hpp and clamped/verify_clamped.hpp, as blverify
// calls them, forward to the loaded plugin.
#pragma once

#include <string>

namespace blv {

// Loads the plugin for the tree in dir: the one CMake built, when its tree hash is dir's, else one
// compiled at run time with the system compiler (cached by tree hash under $BLVERIFY_CACHE, or
// $XDG_CACHE_HOME/bandlimit/blverify, or ~/.cache/bandlimit/blverify). Progress to stderr. False,
// with *error, when dir has no tree or the compilation fails.
bool load_tree(const std::string& dir, std::string* error);

}  // namespace blv
