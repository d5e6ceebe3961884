# seqc_studio: the web server that serves the live preview page of one file, watches the files
# it read and passes the page's playhead to a PlayheadSink (server.hpp, watcher.hpp). cpp-httplib
# and nlohmann-json stay inside it.
seqc_library(seqc_studio
  SOURCES
    ${CMAKE_CURRENT_LIST_DIR}/server.cpp
    ${CMAKE_CURRENT_LIST_DIR}/watcher.cpp
  DEPS seqc_compiler seqc_base Threads::Threads
  PRIVATE_DEPS PkgConfig::HTTPLIB nlohmann_json::nlohmann_json)
