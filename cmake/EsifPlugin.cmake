# esif_add_plugin(<name> SOURCES ...)
# Builds a filter plugin as a MODULE library libesif_plugin_<name>.so in the
# folder the host scans (ESIF_PLUGIN_OUTPUT_DIR). A plugin links the framework
# and nothing else of esif: plugins never depend on each other.
function(esif_add_plugin name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS" ${ARGN})
  set(target esif_plugin_${name})
  add_library(${target} MODULE ${ARG_SOURCES})
  target_link_libraries(${target} PRIVATE esif::framework ${ARG_LIBS})
  target_include_directories(${target} PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  set_target_properties(${target} PROPERTIES
    PREFIX "lib"
    LIBRARY_OUTPUT_DIRECTORY ${ESIF_PLUGIN_OUTPUT_DIR}
    BUILD_RPATH "$ORIGIN/.."
    CXX_VISIBILITY_PRESET default)
  set_property(GLOBAL APPEND PROPERTY ESIF_PLUGIN_TARGETS ${target})
endfunction()
