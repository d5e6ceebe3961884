// The one rule for rewriting golden files: they are rewritten instead of compared when, and
// only when, the environment has SEQC_UPDATE_GOLDEN=1 (any other value compares as usual).
//
// Every golden is written through write_golden(), so no update goes unseen: a file whose
// content is already right is not touched (its timestamp stays, it is not mentioned), and every
// file that is created or rewritten is reported on stderr with its path, how many lines were
// added and removed, and the first lines that differ. Review every reported file by eye (and
// `git diff`) before committing it. `.ci/run` refuses to run with SEQC_UPDATE_GOLDEN set at
// all, so CI can never rewrite a golden and pass.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace seqc::testing {

inline bool updating_goldens() {
  const char* v = std::getenv("SEQC_UPDATE_GOLDEN");
  return v != nullptr && std::strcmp(v, "1") == 0;
}

// What an update changed, line by line (a line is what ends with '\n', or the unterminated
// rest). `first_removed` / `first_added` hold the first few lines of the first place where the
// two differ, so a report shows what changed without a diff tool.
struct GoldenDiff {
  std::size_t added = 0;
  std::size_t removed = 0;
  std::size_t first_line = 0;  // 1-based line number of the first difference (in the old file)
  std::vector<std::string> first_removed;
  std::vector<std::string> first_added;
};

inline std::vector<std::string> golden_lines(std::string_view text) {
  std::vector<std::string> lines;
  while (!text.empty()) {
    const std::size_t end = text.find('\n');
    if (end == std::string_view::npos) {
      lines.emplace_back(text);  // a last line without '\n' differs from one with it
      break;
    }
    lines.emplace_back(text.substr(0, end + 1));
    text.remove_prefix(end + 1);
  }
  return lines;
}

inline GoldenDiff golden_diff(std::string_view before, std::string_view after) {
  constexpr std::size_t kShown = 3;  // lines shown of each side at the first difference
  const std::vector<std::string> a = golden_lines(before);
  const std::vector<std::string> b = golden_lines(after);
  std::size_t prefix = 0;
  while (prefix < a.size() && prefix < b.size() && a[prefix] == b[prefix]) ++prefix;
  std::size_t suffix = 0;
  while (suffix < a.size() - prefix && suffix < b.size() - prefix &&
         a[a.size() - 1 - suffix] == b[b.size() - 1 - suffix]) {
    ++suffix;
  }
  const std::size_t n = a.size() - prefix - suffix;
  const std::size_t m = b.size() - prefix - suffix;
  // Lines kept in the changed middle: a longest common subsequence, so that one inserted line
  // counts as +1 rather than as every following line replaced. Goldens are small; past a few
  // million cells the middle is counted as wholly replaced instead.
  std::size_t common = 0;
  if (n > 0 && m > 0 && n * m <= 4'000'000) {
    std::vector<std::size_t> row(m + 1, 0);
    for (std::size_t i = 0; i < n; ++i) {
      std::size_t diagonal = 0;  // row[j] of the previous i
      for (std::size_t j = 0; j < m; ++j) {
        const std::size_t above = row[j + 1];
        row[j + 1] = a[prefix + i] == b[prefix + j] ? diagonal + 1 : std::max(row[j], above);
        diagonal = above;
      }
    }
    common = row[m];
  }
  GoldenDiff d;
  d.removed = n - common;
  d.added = m - common;
  d.first_line = prefix + 1;
  for (std::size_t i = 0; i < std::min(n, kShown); ++i) d.first_removed.push_back(a[prefix + i]);
  for (std::size_t j = 0; j < std::min(m, kShown); ++j) d.first_added.push_back(b[prefix + j]);
  return d;
}

enum class GoldenWrite { Unchanged, Created, Rewritten, Failed };

// Makes `path` hold `content`: a file that already holds it is left alone and nothing is said;
// otherwise the file (and its folder) is written and `report` gets its path and the diff.
inline GoldenWrite write_golden(const std::filesystem::path& path, std::string_view content,
                                std::ostream& report = std::cerr) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const bool existed = fs::exists(path, ec);
  std::string before;
  if (existed) {
    std::ifstream in(path, std::ios::binary);
    before.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    if (before == content) return GoldenWrite::Unchanged;
  }
  if (!path.parent_path().empty()) fs::create_directories(path.parent_path(), ec);
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    if (!out.flush()) {
      report << "golden NOT written: " << path.string() << ": cannot write\n";
      return GoldenWrite::Failed;
    }
  }
  const GoldenDiff d = golden_diff(before, content);
  std::ostringstream s;
  s << "golden " << (existed ? "rewritten" : "created") << ": " << path.string() << " (+" << d.added
    << " -" << d.removed << " lines)\n";
  if (existed) s << "  first difference at line " << d.first_line << ":\n";
  auto show = [&s](char sign, const std::string& line) {
    s << "  " << sign << ' ' << line;
    if (line.empty() || line.back() != '\n') s << "\n  \\ no newline at end of file\n";
  };
  for (const std::string& line : d.first_removed) show('-', line);
  for (const std::string& line : d.first_added) show('+', line);
  report << s.str() << std::flush;
  return existed ? GoldenWrite::Rewritten : GoldenWrite::Created;
}

}  // namespace seqc::testing
