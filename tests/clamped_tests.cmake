# Clamped-domain rules (issue 3): generated/bandlimit/rules_clamped.hpp and bandlimit_clamped.glsl.
add_executable(clamped_test clamped_deriv_test.cpp)
target_link_libraries(clamped_test PRIVATE bandlimit::generated Boost::headers GTest::gtest_main)
add_test(NAME clamped_test COMMAND clamped_test)
add_test(NAME glsl_validate_clamped
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/glsl_validate_clamped.sh ${GLSLANG_VALIDATOR}
          ${PROJECT_SOURCE_DIR}/generated/bandlimit.glsl ${PROJECT_SOURCE_DIR}/generated/bandlimit_clamped.glsl)

# The clamped-domain paper's analytic examples (the library the clamped_paper notebook reports from).
include(${PROJECT_SOURCE_DIR}/notebooks_cpp/clamped_paper/examples.cmake)
add_executable(clamped_paper_test clamped_paper_test.cpp)
target_link_libraries(clamped_paper_test PRIVATE bl_clamped_examples GTest::gtest_main)
add_test(NAME clamped_paper_test COMMAND clamped_paper_test)
