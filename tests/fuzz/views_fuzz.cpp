// Fuzz target: what `seqc plot` and `seqc preview` make of a file, held in memory (main.yaml,
// as check_fuzz serves it). Any name, pose or section a file holds reaches these documents, so
// the invariants are the escaping's: the SVG holds no character XML 1.0 forbids, and the
// preview page's data island holds nothing the HTML tokenizer could take for the end of its
// <script> element or the start of a comment ("</", "<!--"), and the page has exactly the
// page's own two <script> elements.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "compiler/compile.hpp"
#include "compiler/formats/program_views.hpp"
#include "tests/fuzz/fuzz_check.hpp"
#include "tests/fuzz/memory_files.hpp"

namespace {

// XML 1.0's Char production, bytewise: C0 controls other than tab, LF and CR are not allowed.
bool xml_chars_only(std::string_view text) {
  for (unsigned char c : text) {
    if (c < 0x20 && c != '\t' && c != '\n' && c != '\r') return false;
  }
  return true;
}

std::size_t count(std::string_view text, std::string_view what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string_view::npos;
       at = text.find(what, at + 1)) {
    ++n;
  }
  return n;
}

void check_page(const std::string& page) {
  FUZZ_CHECK(count(page, "<script") == 2);
  const std::string_view open = "<script id=\"seqc-data\" type=\"application/json\">";
  const std::size_t from = page.find(open);
  FUZZ_CHECK(from != std::string::npos);
  const std::size_t body = from + open.size();
  const std::size_t to = page.find("</script>", body);
  FUZZ_CHECK(to != std::string::npos);
  const std::string_view island = std::string_view(page).substr(body, to - body);
  FUZZ_CHECK(island.find("</") == std::string_view::npos);
  FUZZ_CHECK(island.find("<!--") == std::string_view::npos);
  FUZZ_CHECK(xml_chars_only(island));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  seqc::fuzz::MemoryFiles files(text);
  const seqc::compiler::CompileOutput out = seqc::compiler::compile_file("main.yaml", files, {});
  if (!out.program) return 0;
  const std::string svg = seqc::compiler::plot_program(*out.program, {});
  FUZZ_CHECK(xml_chars_only(svg));
  FUZZ_CHECK(count(svg, "<script") == 0);
  // As `seqc preview main.yaml` makes it, and as a show makes it with the file's own text as
  // the performer's name (a show's names come from a file too).
  const double end = static_cast<double>(seqc::compiler::length_ms(*out.program));
  const auto part = seqc::compiler::preview_part(*out.program, "main.yaml", end);
  FUZZ_CHECK(part.has_value());
  const std::string single = seqc::compiler::preview_page("main.yaml", {""}, {*part}, end);
  const std::string show = seqc::compiler::preview_show(
      {{&*out.program, text.substr(0, 64), text.substr(0, 64)}}, text.substr(0, 64), "show");
  for (const std::string& page : {single, show}) check_page(page);
  return 0;
}
