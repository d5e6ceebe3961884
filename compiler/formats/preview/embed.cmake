# Writes OUT, the C++ source behind compiler/formats/preview_page_text.hpp, from the page's files
# in DIR: preview.html, preview.css and the script files SCRIPTS (a comma-separated list, in the
# order the page runs them), joined with one blank line between each, and LIVE, the studio's
# script. Run at build time by compiler/CMakeLists.txt:
#   cmake -DDIR=<this folder> -DSCRIPTS=clock.js,motion.js,... -DLIVE=live.js -DOUT=<file.cpp>
#         -P embed.cmake
#
# Each text becomes a char array of its bytes, not a string literal: the bytes go into the page
# exactly as they are on disk (no escaping, no delimiter to collide with), and no compiler's limit
# on a string literal's length applies.
foreach(var DIR SCRIPTS LIVE OUT)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "embed.cmake: -D${var}=... is missing")
  endif()
endforeach()

# `text` as the body of a char array's initializer, twelve bytes to a line, ending in the 0 that
# makes it a C string too.
function(char_array out text_hex)
  string(REGEX REPLACE "([0-9a-f][0-9a-f])" "'\\\\x\\1'," body "${text_hex}")
  string(REPEAT "'\\\\x[0-9a-f][0-9a-f]'," 12 line)
  string(REGEX REPLACE "(${line})" "\\1\n    " body "${body}")
  set(${out} "{\n    ${body}0}" PARENT_SCOPE)
endfunction()

file(READ ${DIR}/preview.html skeleton_hex HEX)
file(READ ${DIR}/preview.css style_hex HEX)
file(READ ${DIR}/preview.css style)
set(script_hex "")
set(script "")
string(REPLACE "," ", " script_names "${SCRIPTS}")
string(REPLACE "," ";" SCRIPTS "${SCRIPTS}")
foreach(name IN LISTS SCRIPTS)
  file(READ ${DIR}/${name} hex HEX)
  file(READ ${DIR}/${name} text)
  if(NOT script_hex STREQUAL "")
    string(APPEND script_hex "0a")
  endif()
  string(APPEND script_hex "${hex}")
  string(APPEND script "${text}")
endforeach()

file(READ ${DIR}/${LIVE} live_hex HEX)
file(READ ${DIR}/${LIVE} live)

# The page inlines them all: none may end its own element early.
string(TOLOWER "${style}" style)
string(TOLOWER "${script}" script)
if(style MATCHES "</style")
  message(FATAL_ERROR "embed.cmake: preview.css holds </style, which would end the page's <style>")
endif()
string(TOLOWER "${live}" live)
if(script MATCHES "</script" OR live MATCHES "</script")
  message(FATAL_ERROR "embed.cmake: a script file holds </script, which would end the page's <script>")
endif()

char_array(skeleton_array "${skeleton_hex}")
char_array(style_array "${style_hex}")
char_array(script_array "${script_hex}")
char_array(live_array "${live_hex}")
file(WRITE ${OUT} "// Generated at build time by compiler/formats/preview/embed.cmake from the files beside it
// (preview.html, preview.css, ${script_names} and ${LIVE}). Edit those, not this.
#include \"compiler/formats/preview_page_text.hpp\"

namespace seqc::compiler {
namespace {

constexpr char kSkeleton[] = ${skeleton_array};
constexpr char kStyle[] = ${style_array};
constexpr char kScript[] = ${script_array};
constexpr char kLive[] = ${live_array};

}  // namespace

std::string_view preview_skeleton() { return {kSkeleton, sizeof kSkeleton - 1}; }
std::string_view preview_style() { return {kStyle, sizeof kStyle - 1}; }
std::string_view preview_script() { return {kScript, sizeof kScript - 1}; }
std::string_view preview_live_script() { return {kLive, sizeof kLive - 1}; }

}  // namespace seqc::compiler
")
