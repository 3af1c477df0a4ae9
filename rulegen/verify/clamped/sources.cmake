# blverify (tree plugin): verification of generated/bandlimit/rules_clamped.hpp (issue 3).
target_sources(blverify_tree PRIVATE ${CMAKE_CURRENT_LIST_DIR}/verify_clamped.cpp)
