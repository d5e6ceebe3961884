#include "compiler/formats/pose_text.hpp"

#include <algorithm>
#include <sstream>

namespace seqc::compiler {
namespace {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::string line;
  std::istringstream in(text);
  while (std::getline(in, line)) lines.push_back(line);
  return lines;
}

bool is_top_key(const std::string& line, const std::string& key) {
  if (line.compare(0, key.size() + 1, key + ":") != 0) return false;
  const std::string rest = line.substr(key.size() + 1);
  const auto first = rest.find_first_not_of(" \t");
  return first == std::string::npos || rest[first] == '#';
}

bool top_key_inline(const std::string& line, const std::string& key) {
  return line.compare(0, key.size() + 1, key + ":") == 0 && !is_top_key(line, key);
}

// Lines after `start` that belong to its block: indented, blank or comment lines; the block's
// last entry line is the last indented non-comment line.
std::size_t block_end(const std::vector<std::string>& lines, std::size_t start) {
  std::size_t last = start;
  for (std::size_t i = start + 1; i < lines.size(); ++i) {
    const std::string& l = lines[i];
    const auto first = l.find_first_not_of(" \t");
    if (first == std::string::npos || l[first] == '#') continue;  // blank or comment
    if (first == 0) break;                                        // the next top-level key
    last = i;
  }
  return last;
}

std::string entry_name(const std::string& line) {
  const auto first = line.find_first_not_of(" \t");
  const auto colon = line.find(':', first);
  if (first == std::string::npos || colon == std::string::npos) return "";
  return line.substr(first, colon - first);
}

}  // namespace

std::string pose_line(const std::string& name,
                      const std::vector<std::pair<std::uint8_t, std::uint16_t>>& positions,
                      const compiler::RobotInfo& robot) {
  std::string out = name + ": {";
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const compiler::ServoInfo* s = robot.find_id(positions[i].first);
    const std::string servo = s != nullptr ? s->name : std::to_string(positions[i].first);
    out += (i ? ", " : "") + servo + ": " + std::to_string(positions[i].second);
  }
  return out + "}";
}

std::vector<std::string> pose_names(const std::string& text) {
  const std::vector<std::string> lines = lines_of(text);
  std::vector<std::string> names;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (!is_top_key(lines[i], "poses")) continue;
    // Entries are the block's lines at its first entry's indentation (deeper lines continue
    // an entry written over several lines).
    std::size_t entry_indent = std::string::npos;
    for (std::size_t j = i + 1; j <= block_end(lines, i); ++j) {
      const auto first = lines[j].find_first_not_of(" \t");
      if (first == std::string::npos || lines[j][first] == '#') continue;
      if (entry_indent == std::string::npos) entry_indent = first;
      if (first == entry_indent) names.push_back(entry_name(lines[j]));
    }
  }
  return names;
}

Result<std::string> add_pose(const std::string& text, const std::string& pose_line_text,
                             const std::string& name) {
  std::vector<std::string> lines = lines_of(text);
  for (const std::string& existing : pose_names(text)) {
    if (existing == name) return make_error("the file already has a pose named '" + name + "'");
  }
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (top_key_inline(lines[i], "poses")) {
      return make_error(
          "'poses:' is written on one line; make it a block (each pose on its own "
          "line) so seqc can add to it");
    }
    if (!is_top_key(lines[i], "poses")) continue;
    const std::size_t end = block_end(lines, i);
    std::string indent = "  ";
    // The first entry's indentation (a pose written over several lines has deeper lines).
    for (std::size_t j = i + 1; j <= end; ++j) {
      const auto first = lines[j].find_first_not_of(" \t");
      if (first != std::string::npos && lines[j][first] != '#') {
        indent = lines[j].substr(0, first);
        break;
      }
    }
    lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(end) + 1, indent + pose_line_text);
    std::string out;
    for (const std::string& l : lines) out += l + "\n";
    return out;
  }
  // No poses section: one, before the sequence.
  std::size_t at = lines.size();
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (is_top_key(lines[i], "sequence") || top_key_inline(lines[i], "sequence")) {
      at = i;
      break;
    }
  }
  lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(at), {"poses:", "  " + pose_line_text});
  std::string out;
  for (const std::string& l : lines) out += l + "\n";
  return out;
}

std::string next_pose_name(const std::string& text) {
  const std::vector<std::string> taken = compiler::pose_names(text);
  for (int n = 1;; ++n) {
    const std::string name = "pose" + std::to_string(n);
    if (std::find(taken.begin(), taken.end(), name) == taken.end()) return name;
  }
}

bool is_pose_name(const std::string& name) {
  if (name.empty() || (name[0] >= '0' && name[0] <= '9')) return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
  });
}

}  // namespace seqc::compiler
