# esif_add_test(<name> LABEL fast|slow SOURCES ... [LIBS ...])
# A GoogleTest executable beside the code it tests (framework/<layer>/tests,
# plugins/<name>/tests) or in tests/ (integration). Its tests are discovered
# by ctest with the label: "fast" (unit, seconds) or "slow" (whole replays).
# Every test can drive the host: it links esif::host, finds the esif binary
# and plugin folder through ESIF_BINARY / ESIF_PLUGIN_DIR, and builds after
# them (esif_all_plugins). Shared helpers are in tests/support.
include(GoogleTest)

set(ESIF_MRPT_DATASETS /usr/share/mrpt/datasets)

# esif_add_sdk_test(<name> LABEL fast|slow SOURCES ...)
# A unit test of the SDK: it links the SDK alone (what a plugin links) and
# sees the SDK's private headers (framework/sdk/src), so it tests the
# internals a plugin cannot reach without the host in between.
function(esif_add_sdk_test name)
  cmake_parse_arguments(ARG "" "LABEL" "SOURCES" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE esif::sdk GTest::gtest_main)
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests/support ${PROJECT_SOURCE_DIR}/framework/sdk/src)
  set_target_properties(${name} PROPERTIES BUILD_RPATH "${CMAKE_BINARY_DIR}/lib" UNITY_BUILD OFF)
  gtest_discover_tests(${name}
    WORKING_DIRECTORY ${CMAKE_BINARY_DIR}
    PROPERTIES LABELS ${ARG_LABEL}
    DISCOVERY_TIMEOUT 60)
endfunction()

function(esif_add_test name)
  cmake_parse_arguments(ARG "" "LABEL" "SOURCES;LIBS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  # The MRPT modules whose files tests read back (landmark and simple maps,
  # scenes, images, rawlogs; CLandmarksMap is in mrpt::vision).
  target_link_libraries(${name} PRIVATE esif::host GTest::gtest_main
    mrpt::maps mrpt::vision mrpt::opengl mrpt::img mrpt::io mrpt::poses ${ARG_LIBS})
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests/support ${PROJECT_SOURCE_DIR}/bench)
  target_compile_definitions(${name} PRIVATE
    ESIF_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    ESIF_BINARY="$<TARGET_FILE:esif>"
    ESIF_PLUGIN_DIR="${ESIF_PLUGIN_OUTPUT_DIR}"
    ESIF_MRPT_DATASETS="${ESIF_MRPT_DATASETS}")
  set_target_properties(${name} PROPERTIES BUILD_RPATH "${CMAKE_BINARY_DIR}/lib" UNITY_BUILD OFF)
  add_dependencies(${name} esif esif_all_plugins)
  gtest_discover_tests(${name}
    WORKING_DIRECTORY ${CMAKE_BINARY_DIR}
    PROPERTIES LABELS ${ARG_LABEL}
    DISCOVERY_TIMEOUT 60)
endfunction()
