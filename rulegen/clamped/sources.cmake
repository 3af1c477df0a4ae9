# Clamped-domain rules (derivatives, Rule 1, Rule 3, bimodal, compact): sources of `rulegen` (library bl_rulegen).
target_sources(bl_rulegen PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/derivatives.cpp
  ${CMAKE_CURRENT_LIST_DIR}/emit_derivatives.cpp
  ${CMAKE_CURRENT_LIST_DIR}/emit_rules.cpp
  ${CMAKE_CURRENT_LIST_DIR}/emit_clamped.cpp)
target_include_directories(bl_rulegen PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
find_package(nlohmann_json REQUIRED)
target_link_libraries(bl_rulegen PRIVATE nlohmann_json::nlohmann_json)
