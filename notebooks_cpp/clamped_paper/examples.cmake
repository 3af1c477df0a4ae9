# bl_clamped_examples: the clamped-domain paper's examples (notebooks_cpp/clamped_paper/examples/),
# shared by tests/clamped_paper_test.cpp and the clamped_paper notebook; included from both.
include_guard(GLOBAL)
add_library(bl_clamped_examples STATIC ${CMAKE_CURRENT_LIST_DIR}/examples/paper_rules.cpp
                                       ${CMAKE_CURRENT_LIST_DIR}/examples/paper_examples.cpp)
target_include_directories(bl_clamped_examples PUBLIC ${CMAKE_CURRENT_LIST_DIR}/examples)
target_link_libraries(bl_clamped_examples PUBLIC bandlimit::generated Boost::headers)
