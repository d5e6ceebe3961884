#include "compiler/formats/decode.hpp"

#include <fmt/format.h>

#include <optional>

#include "base/units.hpp"
#include "protocol/lsc/group_download.hpp"
#include "protocol/lsc/lsc_messages.hpp"
#include "protocol/lsc/lsc_stream.hpp"

namespace seqc::compiler {
namespace {

// What an open download announced, to check the steps that follow against.
struct Download {
  std::uint8_t group = 0;
  std::vector<std::uint8_t> counts;
  std::size_t actions = 0;  // step-4 frames seen
  std::vector<std::size_t> per_block = std::vector<std::size_t>(lsc::kMaxBlocks, 0);
};

class Decoder {
 public:
  DecodeResult run(ByteView bytes) {
    out_.table = fmt::format("{:<6} {:>5} {:>5} {:>5} {:>7}  {}\n", "frame", "group", "block",
                             "index", "time_ms", "servos");
    walk_frames(
        bytes, out_.frames, [this](const lsc::Frame& f) { on_frame(f); },
        [this](std::string m) { issue(std::move(m)); });
    if (open_) {
      issue(fmt::format("group {} download was opened but never closed (step 5 missing)",
                        open_->group));
    }
    out_.table +=
        fmt::format("# {} frame(s), {} action(s), {} total, {} issue(s)\n", out_.frames,
                    out_.actions, seqc::format_seconds(total_ms_), out_.issues.size());
    return std::move(out_);
  }

 private:
  void issue(std::string message) {
    out_.table += fmt::format("! frame {}: {}\n", out_.frames, message);
    out_.issues.push_back(fmt::format("frame {}: {}", out_.frames, std::move(message)));
  }
  void line(std::string text) { out_.table += fmt::format("{:<6} {}\n", out_.frames, text); }

  void on_frame(const lsc::Frame& frame) {
    auto request = lsc::decode_request(frame);
    if (!request) {
      Bytes raw = {0x55, 0x55, static_cast<std::uint8_t>(frame.data.size() + 2), frame.cmd};
      raw.insert(raw.end(), frame.data.begin(), frame.data.end());
      issue(fmt::format("cannot decode {}: {}", to_hex(raw), request.error().message));
      return;
    }
    std::visit([this](const auto& m) { on_request(m); }, *request);
  }

  bool check_group(std::uint8_t group, const char* step) {
    if (!open_) {
      issue(fmt::format("{} for group {} without an open download (step 1)", step, group));
      return false;
    }
    if (open_->group != group) {
      issue(fmt::format("{} is for group {} but the open download is group {}", step, group,
                        open_->group));
    }
    return true;
  }

  void on_request(const lsc::GroupDownloadOpen& m) {
    line(fmt::format("open group {}: block counts {}", m.group, fmt::join(m.block_counts, " ")));
    if (open_) issue(fmt::format("group {} download opened again before step 5", open_->group));
    open_ = Download{m.group, m.block_counts};
  }
  void on_request(const lsc::GroupDownloadSize& m) {
    line(fmt::format("size group {}: block {} holds {}", m.group, m.block, m.count));
    if (!check_group(m.group, "step 2 (size)")) return;
    if (m.block >= open_->counts.size()) {
      issue(fmt::format("block {} was not announced by step 1", m.block));
    } else if (open_->counts[m.block] != m.count) {
      issue(fmt::format("block {} size {} differs from step 1's {}", m.block, m.count,
                        open_->counts[m.block]));
    }
  }
  void on_request(const lsc::GroupDownloadBlocks& m) {
    line(fmt::format("blocks group {}: {} block(s)", m.group, m.block_count));
    if (!check_group(m.group, "step 3 (blocks)")) return;
    if (m.block_count != open_->counts.size()) {
      issue(fmt::format("{} block(s) listed but step 1 announced {}", m.block_count,
                        open_->counts.size()));
    }
  }
  void on_request(const lsc::GroupDownloadAction& m) {
    ++out_.actions;
    total_ms_ += m.time_ms;
    std::string servos;
    for (const lsc::ServoTarget& t : m.servos) {
      servos += fmt::format("{}{}={}", servos.empty() ? "" : " ", t.id, t.position);
    }
    out_.table += fmt::format("{:<6} {:>5} {:>5} {:>5} {:>7}  {}\n", out_.frames, m.group, m.block,
                              m.index, m.time_ms, servos);
    if (m.time_ms < lsc::kMinActionMs || m.time_ms > lsc::kMaxActionMs) {
      issue(fmt::format("time {} ms is outside the controller's 20-30000 ms", m.time_ms));
    }
    for (std::size_t i = 0; i < m.servos.size(); ++i) {
      for (std::size_t j = 0; j < i; ++j) {
        if (m.servos[i].id == m.servos[j].id) {
          issue(fmt::format("servo {} appears twice in one action", m.servos[i].id));
        }
      }
    }
    if (!check_group(m.group, "step 4 (action)")) return;
    const lsc::ActionSlot expected = lsc::slot_of(open_->actions);
    if (m.block != expected.block || m.index != expected.index) {
      issue(fmt::format("expected block {} index {} next, got block {} index {}", expected.block,
                        expected.index, m.block, m.index));
    }
    ++open_->actions;
    if (m.block < lsc::kMaxBlocks) {
      const std::size_t used = ++open_->per_block[m.block];
      const std::size_t announced = m.block < open_->counts.size() ? open_->counts[m.block] : 0;
      if (used > announced) {
        issue(fmt::format("block {} gets more actions than the {} announced", m.block, announced));
      }
    }
  }
  void on_request(const lsc::GroupDownloadClose& m) {
    line(fmt::format("close group {}", m.group));
    if (!check_group(m.group, "step 5 (close)")) return;
    std::size_t announced = 0;
    for (std::uint8_t c : open_->counts) announced += c;
    if (announced != open_->actions) {
      issue(fmt::format("group {} closed after {} action(s); step 1 announced {}", m.group,
                        open_->actions, announced));
    }
    open_.reset();
  }
  void on_request(const lsc::MultiServoMove& m) {
    ++out_.actions;
    total_ms_ += m.time_ms;
    std::string servos;
    for (const auto& e : m.servos) {
      servos += fmt::format("{}{}={}", servos.empty() ? "" : " ", e.id,
                            e.position ? std::to_string(*e.position) : std::string("-"));
    }
    out_.table += fmt::format("{:<6} {:>5} {:>5} {:>5} {:>7}  {}\n", out_.frames, "live", "-", "-",
                              m.time_ms, servos);
  }
  template <class Other>
  void on_request(const Other& m) {
    line(lsc::describe(lsc::Request{m}));
  }

  DecodeResult out_;
  std::optional<Download> open_;
  std::uint64_t total_ms_ = 0;
};

}  // namespace

void walk_frames(ByteView bytes, std::size_t& frames,
                 const std::function<void(const lsc::Frame&)>& on_frame,
                 const std::function<void(std::string)>& issue) {
  lsc::FrameDecoder decoder;
  decoder.feed(bytes);
  std::size_t skipped = 0;
  while (auto frame = decoder.next()) {
    ++frames;
    if (decoder.skipped_bytes() != skipped) {
      issue(fmt::format("{} byte(s) before this frame are not part of any frame",
                        decoder.skipped_bytes() - skipped));
      skipped = decoder.skipped_bytes();
    }
    on_frame(*frame);
  }
  if (decoder.skipped_bytes() != skipped) {
    issue(fmt::format("{} byte(s) after the last frame are not part of any frame",
                      decoder.skipped_bytes() - skipped));
  }
  if (decoder.pending_bytes() != 0) {
    issue(fmt::format("the input ends inside a frame ({} byte(s) left over)",
                      decoder.pending_bytes()));
  }
}

DecodeResult decode_frames(ByteView bytes) { return Decoder{}.run(bytes); }

}  // namespace seqc::compiler
