// `seqc decode` for the LSC-6 dialect (docs/protocol/lsc-6.md): one line per frame, the actions
// of a download in a table, and the checks a download must pass.
#include <fmt/format.h>

#include <optional>

#include "compiler/formats/decode_formats.hpp"
#include "base/units.hpp"
#include "protocol/lsc6/lsc6_messages.hpp"

namespace seqc::compiler {
namespace {

class Lsc6Decoder {
 public:
  DecodeResult run(ByteView bytes) {
    out_.table = fmt::format("{:<6} {:>5} {:>5} {:>5} {:>7}  {}\n", "frame", "group", "total",
                             "index", "time_ms", "servos");
    walk_frames(
        bytes, out_.frames, [this](const lsc::Frame& f) { on_frame(f); },
        [this](std::string m) { issue(std::move(m)); });
    if (open_) {
      issue(
          fmt::format("group {} download ends without its last index ({}): the board keeps "
                      "its old action count",
                      open_->group, open_->total - 1));
    }
    out_.table +=
        fmt::format("# LSC-6: {} frame(s), {} action(s), {} total, {} issue(s)\n", out_.frames,
                    out_.actions, seqc::format_seconds(total_ms_), out_.issues.size());
    return std::move(out_);
  }

 private:
  struct Download {
    std::uint8_t group = 0;
    std::uint8_t total = 0;
    std::size_t next = 0;
  };

  void issue(std::string message) {
    out_.table += fmt::format("! frame {}: {}\n", out_.frames, message);
    out_.issues.push_back(fmt::format("frame {}: {}", out_.frames, std::move(message)));
  }
  void line(const std::string& text) { out_.table += fmt::format("{:<6} {}\n", out_.frames, text); }

  void on_frame(const lsc::Frame& frame) {
    // Requests and the board's four-byte answers share command numbers (7, 8): a frame with no
    // data after CMD 6 or 25 can only be an answer.
    if (frame.data.empty() && (frame.cmd == 0x06 || frame.cmd == 0x19)) {
      line("answer: " + lsc6::describe(*lsc6::decode_reply(frame)));
      return;
    }
    auto request = lsc6::decode_request(frame);
    if (!request) {
      issue(fmt::format("cannot decode CMD {:02x}: {}", frame.cmd, request.error().message));
      return;
    }
    if (const auto* a = std::get_if<lsc6::DownloadAction>(&*request)) {
      on_action(*a);
      return;
    }
    if (std::holds_alternative<lsc6::EraseAll>(*request)) {
      line("EraseAll (wipes every group on the board)");
      return;
    }
    line(lsc6::describe(*request));
  }

  void on_action(const lsc6::DownloadAction& a) {
    ++out_.actions;
    total_ms_ += a.time_ms;
    std::string servos;
    for (const lsc6::Target& t : a.servos) {
      servos += fmt::format("{}{}={}", servos.empty() ? "" : " ", t.id, t.position);
    }
    out_.table += fmt::format("{:<6} {:>5} {:>5} {:>5} {:>7}  {}\n", out_.frames, a.group, a.total,
                              a.index, a.time_ms, servos);
    if (a.time_ms < lsc6::kMinTime || a.time_ms > lsc6::kMaxTime) {
      issue(fmt::format("time {} ms is outside the board's 20-30000 ms", a.time_ms));
    }
    if (a.servos.size() > lsc6::kMaxServosPerAction) {
      issue(fmt::format("{} servos: the board stops playing at an action with more than 8",
                        a.servos.size()));
    }
    for (const lsc6::Target& t : a.servos) {
      if (t.id < lsc6::kFirstChannel || t.id > lsc6::kLastChannel || t.position < lsc6::kMinPulse ||
          t.position > lsc6::kMaxPulse) {
        issue(fmt::format("channel {} at {} us is not an output 1-6 at 500-2500 us", t.id,
                          t.position));
      }
    }
    if (a.index == 0) {
      if (open_) {
        issue(fmt::format("group {} download restarted before its last index", open_->group));
      }
      open_ = Download{a.group, a.total, 0};
    }
    if (!open_) {
      issue(fmt::format("index {} without index 0 before it (index 0 erases the group)", a.index));
      return;
    }
    if (a.group != open_->group || a.total != open_->total) {
      issue(fmt::format("group {} total {} differs from the download's group {} total {}", a.group,
                        a.total, open_->group, open_->total));
    }
    if (a.index != open_->next) {
      issue(fmt::format("expected index {} next, got {}", open_->next, a.index));
    }
    open_->next = a.index + 1u;
    if (a.index + 1u == a.total) {
      line(fmt::format("group {} stored: {} action(s)", a.group, a.total));
      open_.reset();
    }
  }

  DecodeResult out_;
  std::optional<Download> open_;
  std::uint64_t total_ms_ = 0;
};

}  // namespace

DecodeResult decode_lsc6_frames(ByteView bytes) { return Lsc6Decoder{}.run(bytes); }

}  // namespace seqc::compiler
