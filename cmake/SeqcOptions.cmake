# Warnings, sanitizers and the helper every seqc target uses.

add_library(seqc_warnings INTERFACE)
target_compile_options(seqc_warnings INTERFACE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                                               -Wno-sign-conversion)
# GCC 12 (Debian 12's compiler) reports -Wrestrict inside libstdc++'s own
# operator+(const char*, std::string&&) whenever the optimiser inlines it: a known false
# positive of that release, gone in GCC 13. It fires at whichever concatenations the inliner
# happens to pick, so rewriting call sites only moves it; it is switched off for GCC 12 alone.
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_GREATER_EQUAL 12
   AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
  target_compile_options(seqc_warnings INTERFACE -Wno-restrict)
endif()
if(SEQC_WERROR)
  target_compile_options(seqc_warnings INTERFACE -Werror)
endif()

if(SEQC_SANITIZE)
  # -fno-sanitize-recover makes any UBSan report fatal, so ctest fails on it.
  add_compile_options(-fsanitize=address,undefined -fno-sanitize-recover=all
                      -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined)
endif()

# seqc_library(name SOURCES ... DEPS ...): a static library rooted at the repository, so
# headers are included as "protocol/..." or "compiler/...".
function(seqc_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(${name} STATIC ${ARG_SOURCES})
  target_include_directories(${name} PUBLIC ${PROJECT_SOURCE_DIR})
  target_link_libraries(${name} PUBLIC ${ARG_DEPS} PRIVATE seqc_warnings ${ARG_PRIVATE_DEPS})
endfunction()

# seqc_test(name SOURCES ... DEPS ...): a GoogleTest executable registered with ctest.
function(seqc_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gtest_main seqc_warnings)
  # Test files are compiled eight to a unit: most of a test file's compile time is GoogleTest's
  # and the project's headers, parsed once per unit instead of once per file.
  set_target_properties(${name} PROPERTIES UNITY_BUILD ${SEQC_UNITY_TESTS} UNITY_BUILD_BATCH_SIZE 8)
  target_compile_definitions(${name} PRIVATE SEQC_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
                                             SEQC_BINARY_DIR="${PROJECT_BINARY_DIR}")
  gtest_discover_tests(${name} DISCOVERY_MODE PRE_TEST
                       PROPERTIES ENVIRONMENT "SEQC_SOURCE_DIR=${PROJECT_SOURCE_DIR}")
endfunction()

# seqc_binary_test(name SOURCES ... DEPS ...): a seqc_test that runs the built `seqc` (its path
# in SEQC_BIN), so it is built first.
function(seqc_binary_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  seqc_test(${name} SOURCES ${ARG_SOURCES} DEPS ${ARG_DEPS})
  target_compile_definitions(${name} PRIVATE SEQC_BIN="$<TARGET_FILE:seqc>")
  add_dependencies(${name} seqc)
endfunction()
