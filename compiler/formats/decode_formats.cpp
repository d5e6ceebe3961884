#include "compiler/formats/decode_formats.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <functional>
#include <map>
#include <optional>
#include <sstream>
#include <vector>

#include "base/terminal_text.hpp"
#include "protocol/dialects.hpp"
#include "protocol/lsc/lsc_stream.hpp"
#include "protocol/raspblock/raspblock.hpp"

namespace seqc::compiler {
namespace {

std::vector<std::string> split_lines(std::string_view text) {
  std::vector<std::string> out;
  std::istringstream in{std::string(text)};
  for (std::string l; std::getline(in, l);) {
    if (!l.empty() && l.back() == '\r') l.pop_back();
    out.push_back(std::move(l));
  }
  return out;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

// A line without its '#' comment and, for the Raspblock's timed listing, without the leading
// "<N> ms" column.
std::string hex_part(std::string_view line) {
  std::string_view s = trim(line.substr(0, line.find('#')));
  const std::size_t ms = s.find(" ms ");
  if (ms != std::string_view::npos &&
      s.substr(0, ms).find_first_not_of("0123456789 ") == std::string_view::npos) {
    s = trim(s.substr(ms + 4));
  }
  return std::string(s);
}

// At most this much of a line that is not hex is quoted: a binary file is one long "line".
constexpr std::size_t kQuotedLine = 60;

Bytes hex_bytes(std::string_view text, std::vector<std::string>& errors) {
  Bytes out;
  std::size_t number = 0;
  for (const std::string& line : split_lines(text)) {
    ++number;
    auto bytes = parse_hex(hex_part(line));
    if (!bytes) {
      const auto shorten = [](const std::string& t) {
        return t.size() > kQuotedLine ? t.substr(0, kQuotedLine) + "..." : t;
      };
      errors.push_back("line " + std::to_string(number) + ": " +
                       terminal_safe(bytes.error().message) + " in '" +
                       terminal_safe(shorten(line)) + "'");
      continue;
    }
    out.insert(out.end(), bytes->begin(), bytes->end());
  }
  return out;
}

bool is_trace_line(std::string_view line) { return trim(line).starts_with("t="); }

// One line of a trace (docs/trace.md): its time ("t=..."), its direction ('>' sent, '<'
// received, '#' a note) and what follows; nullopt for a line that is none.
struct TraceLine {
  std::string time;
  char direction = '#';
  std::string_view rest;
};
std::optional<TraceLine> split_trace_line(std::string_view line) {
  const std::string_view l = trim(line);
  if (!is_trace_line(l)) return std::nullopt;
  const std::size_t dir = l.find_first_of("<>#");
  if (dir == std::string_view::npos) return std::nullopt;
  return TraceLine{std::string(l.substr(0, l.find(' '))), l[dir], trim(l.substr(dir + 1))};
}
constexpr std::string_view kRecordHeader = "time_s,status,bytes,message";
// `seqc emulate raspblock --record`: the car board's state, one line per change.
constexpr std::string_view kCarRecordHeader = "time_s,field,previous,value";

// Describes every whole frame in `bytes` as `describe` says; frames that do not decode, and
// bytes outside frames, are issues.
struct FrameText {
  std::vector<std::string> messages;
  std::vector<std::string> problems;
};
FrameText describe_frames(lsc::FrameDecoder& frames, ByteView bytes,
                          const std::function<Result<std::string>(const lsc::Frame&)>& describe) {
  FrameText out;
  const std::size_t skipped = frames.skipped_bytes();
  frames.feed(bytes);
  while (auto f = frames.next()) {
    auto text = describe(*f);
    if (text) {
      out.messages.push_back(*text);
    } else {
      out.problems.push_back(text.error().message);
    }
  }
  if (frames.skipped_bytes() != skipped) {
    out.problems.push_back(
        fmt::format("{} byte(s) are not part of any frame", frames.skipped_bytes() - skipped));
  }
  return out;
}

using Describe = std::function<Result<std::string>(const lsc::Frame&)>;
// A frame described as the row's request (`sent`) or reply.
Describe describer(const Dialect& dialect, bool sent) {
  const auto describe = sent ? dialect.describe_request : dialect.describe_reply;
  return [describe](const lsc::Frame& f) -> Result<std::string> {
    if (describe == nullptr) return make_error("the board sends nothing");
    return describe(Unit{f.cmd, f.data});
  };
}

class TextTable {
 public:
  void row(const std::string& text) { out_.table += text + "\n"; }
  void issue(const std::string& where, const std::string& message) {
    out_.table += "! " + where + ": " + message + "\n";
    out_.issues.push_back(where + ": " + message);
  }
  DecodeResult finish(const std::string& summary) {
    out_.table += fmt::format("# {}, {} issue(s)\n", summary, out_.issues.size());
    return std::move(out_);
  }
  DecodeResult& result() { return out_; }

 private:
  DecodeResult out_;
};

// A trace's Raspblock packets: the car answers nothing, so only what was written ("> ").
DecodeResult decode_raspblock_trace(const std::vector<std::string>& lines, const Dialect& dialect) {
  TextTable t;
  t.row(fmt::format("# trace, {} packets", dialect.name));
  raspblock::PacketDecoder packets;
  std::size_t n = 0;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::optional<TraceLine> line = split_trace_line(lines[i]);
    if (!line) continue;
    const std::string& time = line->time;
    const std::string_view rest = line->rest;
    if (line->direction != '>') {
      t.row(time + " " + line->direction + " " + std::string(rest));
      continue;
    }
    auto bytes = parse_hex(rest);
    if (!bytes) {
      t.issue(fmt::format("line {}", i + 1), bytes.error().message);
      continue;
    }
    packets.feed(*bytes);
    while (auto p = packets.next()) {
      ++n;
      if (*p) {
        t.row(time + " > " + raspblock::describe(**p));
      } else {
        t.issue(fmt::format("line {}", i + 1), p->error().message);
      }
    }
  }
  if (packets.skipped_bytes() > 0) {
    t.issue("input", fmt::format("{} byte(s) are not part of any packet", packets.skipped_bytes()));
  }
  return t.finish(fmt::format("{} packet(s)", n));
}

// The dialect a trace's "# dialect: NAME" line names (seqc writes its row's name there,
// protocol/dialects.hpp), or "" for a trace without one (traces written before it, or by hand).
std::string trace_dialect(const std::vector<std::string>& lines) {
  constexpr std::string_view kDialect = "# dialect:";
  for (const std::string& l : lines) {
    const std::string_view s = trim(l);
    if (s.starts_with(kDialect)) return std::string(trim(s.substr(kDialect.size())));
    if (is_trace_line(s)) break;  // the header comes first
  }
  return "";
}

DecodeResult decode_trace(std::string_view text) {
  const std::vector<std::string> lines = split_lines(text);
  const std::string header = trace_dialect(lines);
  const Dialect* named = dialect_named(header);
  if (named != nullptr && named->framing == Framing::Packets) {
    return decode_raspblock_trace(lines, *named);
  }
  Bytes all;
  for (const std::string& l : lines) {
    if (!is_trace_line(l)) continue;
    const std::size_t dir = l.find_first_of("<>");
    if (dir == std::string::npos) continue;
    if (auto b = parse_hex(trim(std::string_view(l).substr(dir + 1)))) {
      all.insert(all.end(), b->begin(), b->end());
    }
  }
  // The header's dialect when it names one; else the one the frames show (an LSC-6 download),
  // and the frames' first dialect for a name no row has.
  const Dialect& dialect = named != nullptr ? *named
                           : header.empty() ? sniff_dialect(all, Framing::Frames)
                                            : *all_dialects().front();
  TextTable t;
  t.row(fmt::format("# trace, {} dialect", dialect.name));
  lsc::FrameDecoder sent, received;
  const Describe req = describer(dialect, true), rep = describer(dialect, false);
  std::size_t n = 0;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::optional<TraceLine> line = split_trace_line(lines[i]);
    if (!line) continue;
    const std::string& time = line->time;
    const std::string_view rest = line->rest;
    if (line->direction == '#') {
      t.row(time + " # " + std::string(rest));
      continue;
    }
    if (rest == "hang-up") {
      t.row(time + " < hang-up");
      continue;
    }
    auto bytes = parse_hex(rest);
    if (!bytes) {
      t.issue(fmt::format("line {}", i + 1), bytes.error().message);
      continue;
    }
    const bool out = line->direction == '>';
    FrameText ft = describe_frames(out ? sent : received, *bytes, out ? req : rep);
    for (const std::string& m : ft.messages) {
      ++n;
      t.row(time + (out ? " > " : " < ") + m);
    }
    for (const std::string& p : ft.problems) t.issue(fmt::format("line {}", i + 1), p);
  }
  return t.finish(fmt::format("{} frame(s)", n));
}

// The first three fields of a record line (time, status, bytes: none holds a comma).
struct RecordLine {
  std::string time, status, bytes;
};
std::optional<RecordLine> record_fields(const std::string& l) {
  const std::size_t a = l.find(',');
  const std::size_t b = a == std::string::npos ? a : l.find(',', a + 1);
  const std::size_t c = b == std::string::npos ? b : l.find(',', b + 1);
  if (c == std::string::npos) return std::nullopt;
  return RecordLine{l.substr(0, a), l.substr(a + 1, b - a - 1), l.substr(b + 1, c - b - 1)};
}

// Why a record line's bytes had no effect, from its status ("" for ok): `dropped:<reason>` is
// a frame the emulator dropped on purpose, `unframed` bytes it could not frame; `busy` and
// `fault` are how records marked drops before they carried a reason.
std::string record_problem(std::string_view status) {
  if (status == "ok") return "";
  if (status.starts_with("dropped:")) {
    return "dropped by the emulator (" + std::string(status.substr(8)) + ")";
  }
  if (status == "busy" || status == "fault") {
    return "dropped by the emulator (" + std::string(status) + ")";
  }
  if (status == "unframed") return "not a frame: the emulator ignored these bytes";
  return "unknown status '" + std::string(status) + "'";
}

DecodeResult decode_record(std::string_view text) {
  const std::vector<std::string> lines = split_lines(text);
  Bytes all;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const auto f = record_fields(lines[i]);
    if (!f) continue;
    if (auto bytes = parse_hex(f->bytes)) all.insert(all.end(), bytes->begin(), bytes->end());
  }
  const Dialect& dialect = sniff_dialect(all, Framing::Frames);
  TextTable t;
  t.row(fmt::format("# emulator record, {} dialect", dialect.name));
  const Describe req = describer(dialect, true);
  std::size_t n = 0;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    if (trim(lines[i]).empty()) continue;
    const auto f = record_fields(lines[i]);
    if (!f) {
      t.issue(fmt::format("line {}", i + 1), "not a record line (time_s,status,bytes,message)");
      continue;
    }
    auto bytes = parse_hex(f->bytes);
    if (!bytes) {
      t.issue(fmt::format("line {}", i + 1), bytes.error().message);
      continue;
    }
    ++n;
    lsc::FrameDecoder frames;
    FrameText ft = describe_frames(frames, *bytes, req);
    std::string what = ft.messages.empty() ? to_hex(*bytes) : ft.messages.front();
    if (ft.messages.empty() && !ft.problems.empty()) what += " (" + ft.problems.front() + ")";
    t.row(fmt::format("{} {:<8} {}", f->time, f->status, what));
    if (const std::string problem = record_problem(f->status); !problem.empty()) {
      t.issue(fmt::format("line {}", i + 1), problem);
    }
  }
  return t.finish(fmt::format("{} record(s)", n));
}

std::optional<int> whole_number(std::string_view s) {
  int v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size()) return std::nullopt;
  return v;
}

// The car record holds each change with the value it replaced, so a record that was cut,
// merged or edited shows: a `previous` that is not the field's last value, or time running
// backwards, is an issue.
DecodeResult decode_car_record(std::string_view text) {
  const std::vector<std::string> lines = split_lines(text);
  TextTable t;
  t.row("# Raspblock emulator record: each change of the board's state");
  std::map<std::string, int, std::less<>> last;
  double last_time = 0;
  std::size_t n = 0;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    if (trim(lines[i]).empty()) continue;
    const std::string where = fmt::format("line {}", i + 1);
    std::vector<std::string_view> f;
    std::string_view rest = lines[i];
    for (std::size_t comma; (comma = rest.find(',')) != std::string_view::npos;) {
      f.push_back(rest.substr(0, comma));
      rest.remove_prefix(comma + 1);
    }
    f.push_back(rest);
    int value = 0, previous = 0;
    bool well_formed = f.size() == 4;
    if (well_formed) {
      const auto v = whole_number(f[3]);
      const auto p = f[2].empty() ? std::optional<int>(0) : whole_number(f[2]);
      well_formed = v.has_value() && p.has_value();
      value = v.value_or(0);
      previous = p.value_or(0);
    }
    char* end = nullptr;
    const std::string time(f[0]);
    const double seconds = std::strtod(time.c_str(), &end);
    if (!well_formed || end == time.c_str() || *end != '\0') {
      t.issue(where, "not a record line (time_s,field,previous,value)");
      continue;
    }
    ++n;
    const bool has_previous = !f[2].empty();
    const std::string field(f[1]);
    t.row(has_previous ? fmt::format("{} {:<18} {} -> {}", time, field, previous, value)
                       : fmt::format("{} {:<18} = {}", time, field, value));
    if (seconds < last_time) {
      t.issue(where, fmt::format("time runs backwards ({} after {:.6f})", time, last_time));
    }
    last_time = std::max(last_time, seconds);
    const auto known = last.find(field);
    if (known == last.end() && has_previous) {
      t.issue(where, fmt::format("{} had no value before, yet the record says it was {}", field,
                                 previous));
    } else if (known != last.end() && !has_previous) {
      t.issue(where, fmt::format("{} was {}, yet the record gives no previous value", field,
                                 known->second));
    } else if (known != last.end() && previous != known->second) {
      t.issue(where, fmt::format("{} was {}, not {}", field, known->second, previous));
    }
    last[field] = value;
  }
  return t.finish(fmt::format("{} change(s)", n));
}

DecodeResult decode_raspblock(std::string_view text) {
  TextTable t;
  t.row(fmt::format("{:<7} {:>8}  {}", "packet", "time_ms", "message"));
  raspblock::PacketDecoder packets;
  std::size_t n = 0;
  for (const std::string& line : split_lines(text)) {
    const std::string_view s = trim(std::string_view(line).substr(0, line.find('#')));
    std::string time = "-";
    const std::size_t ms = s.find(" ms ");
    if (ms != std::string_view::npos) time = std::string(trim(s.substr(0, ms)));
    auto bytes = parse_hex(hex_part(line));
    if (!bytes) {
      t.issue("line", bytes.error().message);
      continue;
    }
    packets.feed(*bytes);
    while (auto p = packets.next()) {
      ++n;
      if (*p) {
        t.row(fmt::format("{:<7} {:>8}  {}", n, time, raspblock::describe(**p)));
      } else {
        t.issue(fmt::format("packet {}", n), p->error().message);
      }
    }
  }
  if (packets.skipped_bytes() > 0) {
    t.issue("input", fmt::format("{} byte(s) are not part of any packet", packets.skipped_bytes()));
  }
  return t.finish(fmt::format("Raspblock: {} packet(s)", n));
}

constexpr DecodeFormat kFormats[] = {DecodeFormat::Auto,  DecodeFormat::Hex,
                                     DecodeFormat::Lsc6,  DecodeFormat::Raspblock,
                                     DecodeFormat::Trace, DecodeFormat::Record};

}  // namespace

const Dialect* dialect_of(DecodeFormat format) {
  switch (format) {
    case DecodeFormat::Hex:
      return &kXarmDialect;
    case DecodeFormat::Lsc6:
      return &kLsc6Dialect;
    case DecodeFormat::Raspblock:
      return &kRaspblockDialect;
    default:
      return nullptr;
  }
}

std::vector<std::string> decode_format_names() {
  std::vector<std::string> names{"auto"};
  for (const Dialect* d : all_dialects()) names.emplace_back(d->decode_name);
  names.emplace_back("trace");
  names.emplace_back("record");
  return names;
}

Result<DecodeFormat> parse_decode_format(std::string_view name) {
  for (DecodeFormat f : kFormats) {
    if (name == to_string(f)) return f;
  }
  const std::vector<std::string> names = decode_format_names();
  std::string expected;
  for (std::size_t i = 0; i < names.size(); ++i) {
    expected += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
  }
  return make_error("unknown format '" + std::string(name) + "'; expected " + expected);
}

std::string_view to_string(DecodeFormat format) {
  if (const Dialect* d = dialect_of(format)) return d->decode_name;
  switch (format) {
    case DecodeFormat::Auto:
      return "auto";
    case DecodeFormat::Trace:
      return "trace";
    case DecodeFormat::Record:
      return "record";
    default:
      return "?";
  }
}

DecodeFormat detect_format(std::string_view text) {
  const std::vector<std::string> lines = split_lines(text);
  for (const std::string& l : lines) {
    if (l == kRecordHeader || l == kCarRecordHeader) return DecodeFormat::Record;
    if (is_trace_line(l)) return DecodeFormat::Trace;
  }
  std::vector<std::string> errors;
  const Bytes bytes = hex_bytes(text, errors);
  const Dialect& dialect = sniff_dialect(bytes);
  for (DecodeFormat f : kFormats) {
    if (dialect_of(f) == &dialect) return f;
  }
  return DecodeFormat::Hex;
}

DecodeResult decode_text(std::string_view text, DecodeFormat format) {
  if (format == DecodeFormat::Auto) format = detect_format(text);
  switch (format) {
    case DecodeFormat::Trace:
      return decode_trace(text);
    case DecodeFormat::Record:
      for (const std::string& l : split_lines(text)) {
        if (trim(l).empty()) continue;
        return l == kCarRecordHeader ? decode_car_record(text) : decode_record(text);
      }
      return decode_record(text);
    case DecodeFormat::Raspblock:
      return decode_raspblock(text);
    default:
      break;
  }
  std::vector<std::string> errors;
  const Bytes bytes = hex_bytes(text, errors);
  DecodeResult r = format == DecodeFormat::Lsc6 ? decode_lsc6_frames(bytes) : decode_frames(bytes);
  if (errors.empty()) return r;
  // The lines that are not hex are issues like the frames': listed before the summary, which
  // is the table's last line, and counted in it.
  std::string lines;
  for (const std::string& e : errors) {
    lines += "! input: " + e + "\n";
    r.issues.push_back("input: " + e);
  }
  const std::size_t last = r.table.rfind('\n', r.table.size() - 2);
  const std::size_t summary = last == std::string::npos ? 0 : last + 1;
  std::string tail = r.table.substr(summary);
  const std::size_t count = tail.rfind(", ");
  if (tail.starts_with("# ") && count != std::string::npos && tail.ends_with(" issue(s)\n")) {
    tail = tail.substr(0, count + 2) + std::to_string(r.issues.size()) + " issue(s)\n";
  }
  r.table = r.table.substr(0, summary) + lines + tail;
  return r;
}

}  // namespace seqc::compiler
