# esif_add_plugin(<name> [LIBS <libs>...])
# Builds the filter plugin in the current folder as a MODULE library
# libesif_plugin_<name>.so in the folder the host scans (ESIF_PLUGIN_OUTPUT_DIR).
#
# Every *.cpp of the folder but register.cpp goes into an OBJECT library
# esif_plugin_<name>_objects, which the module and the plugin's unit tests both
# link, so no source is listed twice. register.cpp (the MRPT class
# registration that the host's loader relies on) goes into the module alone.
#
# Its unit tests, in tests/ of the folder, are added with it.
#
# A plugin links the SDK (esif::sdk) and the LIBS it names, nothing else of
# esif: no host header is on its include path, and plugins never depend on
# each other.
function(esif_add_plugin name)
  cmake_parse_arguments(ARG "" "" "LIBS" ${ARGN})
  set(target esif_plugin_${name})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cpp)
  list(REMOVE_ITEM sources ${CMAKE_CURRENT_SOURCE_DIR}/register.cpp)
  add_library(${target}_objects OBJECT ${sources})
  target_link_libraries(${target}_objects PUBLIC esif::sdk ${ARG_LIBS})
  target_include_directories(${target}_objects PUBLIC ${CMAKE_CURRENT_SOURCE_DIR})
  set_target_properties(${target}_objects PROPERTIES CXX_VISIBILITY_PRESET default)

  add_library(${target} MODULE ${CMAKE_CURRENT_SOURCE_DIR}/register.cpp)
  target_link_libraries(${target} PRIVATE ${target}_objects)
  set_target_properties(${target} PROPERTIES
    PREFIX "lib"
    LIBRARY_OUTPUT_DIRECTORY ${ESIF_PLUGIN_OUTPUT_DIR}
    BUILD_RPATH "$ORIGIN/.."
    CXX_VISIBILITY_PRESET default)
  add_dependencies(esif_all_plugins ${target})
  set_property(GLOBAL APPEND PROPERTY ESIF_PLUGIN_TARGETS ${target})
  if(BUILD_TESTING AND EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/tests/CMakeLists.txt)
    add_subdirectory(tests)
  endif()
endfunction()

# esif_add_plugin_cache(): after every esif_add_plugin, writes the cache that
# lets the launcher answer `esif plugins` without loading the host
# (framework/app/launcher/PluginCache.h). It is rebuilt whenever a plugin or
# an esif library is; a cache that is out of date anyway is not used.
function(esif_add_plugin_cache)
  get_property(plugins GLOBAL PROPERTY ESIF_PLUGIN_TARGETS)
  set(cache ${ESIF_PLUGIN_OUTPUT_DIR}/plugins.cache)
  add_custom_command(OUTPUT ${cache}
    COMMAND esif_query_plugins
    DEPENDS esif_query_plugins esif_app esif_host esif_render esif_formats esif_safeio esif_sdk ${plugins}
    COMMENT "Writing the plugin cache for esif plugins"
    VERBATIM)
  add_custom_target(esif_plugin_cache DEPENDS ${cache})
  add_dependencies(esif_all_plugins esif_plugin_cache)
endfunction()
