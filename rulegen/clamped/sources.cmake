# Clamped-domain rules (derivatives, Rule 1, Rule 3, bimodal, compact): sources of `rulegen`.
target_sources(rulegen PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/derivatives.cpp
  ${CMAKE_CURRENT_LIST_DIR}/emit_derivatives.cpp
  ${CMAKE_CURRENT_LIST_DIR}/emit_rules.cpp
  ${CMAKE_CURRENT_LIST_DIR}/emit_clamped.cpp)
target_include_directories(rulegen PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
find_package(nlohmann_json REQUIRED)
target_link_libraries(rulegen PRIVATE nlohmann_json::nlohmann_json)
