# The language features of `seqc lsp` (features.hpp): inlay hints, hover, names, completion,
# code actions and the outline, each answered from the compiler's own reading of the file.
seqc_library(seqc_lsp_features
  SOURCES
    ${CMAKE_CURRENT_LIST_DIR}/analysis.cpp
    ${CMAKE_CURRENT_LIST_DIR}/features.cpp
    ${CMAKE_CURRENT_LIST_DIR}/inlay_hints.cpp
    ${CMAKE_CURRENT_LIST_DIR}/hover.cpp
    ${CMAKE_CURRENT_LIST_DIR}/names.cpp
    ${CMAKE_CURRENT_LIST_DIR}/completion.cpp
    ${CMAKE_CURRENT_LIST_DIR}/code_actions.cpp
    ${CMAKE_CURRENT_LIST_DIR}/symbols.cpp
  DEPS seqc_compiler seqc_base nlohmann_json::nlohmann_json)
