# Every dependency comes from a Debian 12 package (scripts/install-deps.sh installs them). A
# missing one stops the configure step with the package that provides it, not CMake's generic
# "could not find a package configuration file".

# seqc_find(Name debian-package [find_package arguments...])
macro(seqc_find name debian_package)
  find_package(${name} ${ARGN} QUIET)
  if(NOT ${name}_FOUND)
    message(FATAL_ERROR
      "seqc needs ${name}, which is missing. On Debian or Ubuntu install it with:\n"
      "  sudo apt-get install ${debian_package}\n"
      "(scripts/install-deps.sh installs everything seqc builds and tests with.)")
  endif()
endmacro()

seqc_find(yaml-cpp libyaml-cpp-dev)
seqc_find(CLI11 libcli11-dev)
seqc_find(fmt libfmt-dev)
seqc_find(SQLite3 libsqlite3-dev)  # .d6a action files are SQLite databases
seqc_find(Threads libc6-dev)
seqc_find(PkgConfig pkg-config)
pkg_check_modules(HIDAPI QUIET IMPORTED_TARGET hidapi-hidraw)
if(NOT HIDAPI_FOUND)
  message(FATAL_ERROR
    "seqc needs hidapi (hidapi-hidraw), which is missing. On Debian or Ubuntu install it with:\n"
    "  sudo apt-get install libhidapi-dev")
endif()
# Audio files for `seqc beats` (LGPL, linked dynamically).
pkg_check_modules(SNDFILE QUIET IMPORTED_TARGET sndfile)
if(NOT SNDFILE_FOUND)
  message(FATAL_ERROR
    "seqc needs libsndfile (sndfile), which is missing. On Debian or Ubuntu install it with:\n"
    "  sudo apt-get install libsndfile1-dev")
endif()
# Playing a song with the robot (`seqc play --music`; LGPL, linked dynamically).
pkg_check_modules(PULSE_SIMPLE QUIET IMPORTED_TARGET libpulse-simple libpulse)
if(NOT PULSE_SIMPLE_FOUND)
  message(FATAL_ERROR
    "seqc needs libpulse (libpulse-simple), which is missing. On Debian or Ubuntu install it with:\n"
    "  sudo apt-get install libpulse-dev")
endif()

# JSON for the language server's messages (MIT, header-only).
seqc_find(nlohmann_json nlohmann-json3-dev)
# The studio's local web server (MIT; Debian builds it as a shared library).
pkg_check_modules(HTTPLIB QUIET IMPORTED_TARGET cpp-httplib)
if(NOT HTTPLIB_FOUND)
  message(FATAL_ERROR
    "seqc needs cpp-httplib, which is missing. On Debian or Ubuntu install it with:\n"
    "  sudo apt-get install libcpp-httplib-dev")
endif()

# GoogleTest only for the tests: `-DBUILD_TESTING=OFF` builds the tool without it.
if(BUILD_TESTING)
  find_package(GTest QUIET)
  if(NOT GTest_FOUND)
    message(FATAL_ERROR
      "seqc's tests need GoogleTest, which is missing. Install it with:\n"
      "  sudo apt-get install libgtest-dev libgmock-dev\n"
      "or build the tool alone with -DBUILD_TESTING=OFF.")
  endif()
  include(GoogleTest)
endif()
