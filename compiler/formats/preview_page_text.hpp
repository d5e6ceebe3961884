// The preview page's fixed text, as written in compiler/formats/preview/: its skeleton, its style,
// its script and the studio's live script, byte for byte as they are on disk.
// compiler/CMakeLists.txt embeds them at build time (formats/preview/embed.cmake writes these
// functions into one generated source), so the page stays one self-contained file while its
// parts are ordinary files that an editor, a browser and a linter read; editing one rebuilds only
// the generated source. preview_html.cpp fills the skeleton; preview_html.hpp gives the page's
// contract.
#pragma once

#include <string_view>

namespace seqc::compiler {

// preview.html: the page with @title@ (twice), @style@, @end@, @audio@, @lanes@, @data@ and
// @script@ where preview_page() puts its parts.
std::string_view preview_skeleton();

// preview.css.
std::string_view preview_style();

// The script: clock.js, motion.js, kinematics.js and page.js, in that order, with one blank line
// between each; one classic script, strict by the directive that opens clock.js. Neither the
// style nor the script holds an end tag of its element (the build refuses them).
std::string_view preview_script();

// live.js: the studio's script (runtime/studio/server.hpp), which makes the page live. It runs
// after preview_script(), in a <script> of its own; it too holds no end tag of its element.
std::string_view preview_live_script();

}  // namespace seqc::compiler
