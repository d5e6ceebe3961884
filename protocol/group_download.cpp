// Every reading of the document's GroupDownload (CMD 5) table is here, each marked
// "reading:" with what a capture from real hardware would settle. The byte-exact tests in
// tests/protocol/group_download_test.cpp pin each one.
#include "protocol/lsc/group_download.hpp"

#include <string>

#include "protocol/lsc/lsc_fields.hpp"

namespace seqc::lsc {

namespace {

using detail::expect_size;
using detail::FieldReader;
using detail::FieldWriter;

constexpr auto kCmd = static_cast<std::uint8_t>(Command::GroupDownload);

// The first data byte names the step (the document's "(byte)cmd").
constexpr std::uint8_t kStepOpen = 1;
constexpr std::uint8_t kStepSize = 2;
constexpr std::uint8_t kStepBlocks = 3;
constexpr std::uint8_t kStepAction = 4;
constexpr std::uint8_t kStepClose = 5;

// reading: step 1 "{ (byte)count[mod(255)] }[extends by byte as needed]" is one count byte
// per used block: 255 for each full block and the remainder for the last, so 256 actions
// open as "01 G FF 01". A capture of a 256-action download would settle it (the other
// candidate reading, a little-endian total, would send "01 G 00 01").
constexpr std::size_t kOpenFixed = 2;  // 01 G

// reading: step 2 "00 (byte)count 00" is sent once per block, the first 00 being the block
// number (always 0 in the document's one-block example) and the last a constant 00. A capture
// of a download over 255 actions would show whether a second "02 G 01 n 00" is sent.
constexpr std::size_t kSizeBytes = 5;  // 02 G b n 00

// reading: step 3 "00 00 [01 [02 [03]]]" is a 00 followed by the numbers of the used blocks
// (the document's "[512 actions]" for three list entries is read as 510, two full blocks).
// Captures of 1- and 2-block downloads would confirm the leading 00 is a constant.
constexpr std::size_t kBlocksFixed = 3;  // 03 G 00

// reading: step 4 "(byte)block (byte)index 0B (ushort)ms {servo pos}": the index is 0-based
// within its block (action 255 of a group is block 1, index 0), 0B is the constant
// kActionMarker exactly as written, and the servo entries run to the end of the frame (there
// is no count byte). A capture would show whether 0B is really a constant or a servo count
// (it is 11 for no obvious reason) and whether the index starts at 0 or 1.
constexpr std::size_t kActionFixed = 7;  // 04 G b i 0B tLo tHi

// reading: step 5 "-none-" means no parameters after the step and the group: "05 G".
constexpr std::size_t kCloseBytes = 2;

// reading: every step is acknowledged by a CMD 5 frame whose data is "<step> 00"; a second
// byte other than 00 is read as a refusal (the document only ever shows 00).
constexpr std::size_t kAckBytes = 2;

std::string step_name(std::uint8_t step) { return "GroupDownload step " + std::to_string(step); }

Status check_block(std::uint8_t block, const std::string& what) {
  if (block >= kMaxBlocks) {
    return make_error(what + ": block " + std::to_string(block) + " is outside 0..3");
  }
  return Ok{};
}

Status check_count(std::size_t count, const std::string& what) {
  if (count < 1 || count > kActionsPerBlock) {
    return make_error(what + ": block count " + std::to_string(count) + " is outside 1..255");
  }
  return Ok{};
}

struct StepOf {
  int operator()(const GroupDownloadOpen&) const { return kStepOpen; }
  int operator()(const GroupDownloadSize&) const { return kStepSize; }
  int operator()(const GroupDownloadBlocks&) const { return kStepBlocks; }
  int operator()(const GroupDownloadAction&) const { return kStepAction; }
  int operator()(const GroupDownloadClose&) const { return kStepClose; }
  int operator()(const auto&) const { return 0; }
};

}  // namespace

ActionSlot slot_of(std::size_t action_number) {
  // Callers keep action_number below kMaxActions, so both values fit a byte.
  return ActionSlot{static_cast<std::uint8_t>(action_number / kActionsPerBlock),
                    static_cast<std::uint8_t>(action_number % kActionsPerBlock)};
}

Result<Frame> encode_step(const GroupDownloadOpen& m) {
  const std::string what = step_name(kStepOpen) + " (open)";
  if (m.block_counts.empty() || m.block_counts.size() > kMaxBlocks) {
    return make_error(what + ": " + std::to_string(m.block_counts.size()) +
                      " block counts, expected 1..4");
  }
  FieldWriter w(kCmd);
  w.u8(kStepOpen).u8(m.group);
  for (std::uint8_t n : m.block_counts) {
    if (auto ok = check_count(n, what); !ok) return ok.error();
    w.u8(n);
  }
  return w.finish(what);
}

Result<Frame> encode_step(const GroupDownloadSize& m) {
  const std::string what = step_name(kStepSize) + " (size)";
  if (auto ok = check_block(m.block, what); !ok) return ok.error();
  if (auto ok = check_count(m.count, what); !ok) return ok.error();
  FieldWriter w(kCmd);
  w.u8(kStepSize).u8(m.group).u8(m.block).u8(m.count).u8(0x00);
  return w.finish(what);
}

Result<Frame> encode_step(const GroupDownloadBlocks& m) {
  const std::string what = step_name(kStepBlocks) + " (blocks)";
  if (m.block_count < 1 || m.block_count > kMaxBlocks) {
    return make_error(what + ": block_count " + std::to_string(m.block_count) + " is outside 1..4");
  }
  FieldWriter w(kCmd);
  w.u8(kStepBlocks).u8(m.group).u8(0x00);
  for (std::uint8_t b = 0; b < m.block_count; ++b) w.u8(b);
  return w.finish(what);
}

Result<Frame> encode_step(const GroupDownloadAction& m) {
  const std::string what = step_name(kStepAction) + " (action)";
  if (auto ok = check_block(m.block, what); !ok) return ok.error();
  if (m.index >= kActionsPerBlock) {
    return make_error(what + ": index " + std::to_string(m.index) + " is outside 0..254");
  }
  FieldWriter w(kCmd);
  w.u8(kStepAction).u8(m.group).u8(m.block).u8(m.index).u8(kActionMarker).u16(m.time_ms);
  for (const ServoTarget& s : m.servos) w.u8(s.id).u16(s.position);
  return w.finish(what + " with " + std::to_string(m.servos.size()) + " servos");
}

Result<Frame> encode_step(const GroupDownloadClose& m) {
  FieldWriter w(kCmd);
  w.u8(kStepClose).u8(m.group);
  return w.finish(step_name(kStepClose) + " (close)");
}

Result<Request> decode_group_download(const Frame& frame) {
  if (frame.cmd != kCmd) return make_error("not a GroupDownload frame");
  const Bytes& d = frame.data;
  if (d.size() < 2) {
    return make_error("GroupDownload: expected at least 2 data bytes (step, group), got " +
                      std::to_string(d.size()));
  }
  const std::uint8_t step = d[0];
  const std::uint8_t group = d[1];
  switch (step) {
    case kStepOpen: {
      const std::string what = step_name(step) + " (open)";
      const std::size_t blocks = d.size() - kOpenFixed;
      if (blocks < 1 || blocks > kMaxBlocks) {
        return make_error(what + ": " + std::to_string(blocks) + " block counts, expected 1..4");
      }
      GroupDownloadOpen m{group, Bytes(d.begin() + kOpenFixed, d.end())};
      for (std::uint8_t n : m.block_counts) {
        if (auto ok = check_count(n, what); !ok) return ok.error();
      }
      return Request{std::move(m)};
    }
    case kStepSize: {
      const std::string what = step_name(step) + " (size)";
      if (auto ok = expect_size(d, kSizeBytes, what); !ok) return ok.error();
      if (auto ok = check_block(d[2], what); !ok) return ok.error();
      if (auto ok = check_count(d[3], what); !ok) return ok.error();
      if (d[4] != 0x00) {
        return make_error(what + ": last byte is " + to_hex(ByteView(d).subspan(4, 1)) +
                          ", expected 00");
      }
      return Request{GroupDownloadSize{group, d[2], d[3]}};
    }
    case kStepBlocks: {
      const std::string what = step_name(step) + " (blocks)";
      if (d.size() < kBlocksFixed + 1 || d.size() > kBlocksFixed + kMaxBlocks) {
        return make_error(what + ": expected 4..7 data bytes, got " + std::to_string(d.size()));
      }
      if (d[2] != 0x00) return make_error(what + ": third byte must be 00");
      const std::size_t count = d.size() - kBlocksFixed;
      for (std::size_t b = 0; b < count; ++b) {
        if (d[kBlocksFixed + b] != b) {
          return make_error(what + ": block list must read 00 01 02 03 in order, got " +
                            to_hex(ByteView(d).subspan(kBlocksFixed)));
        }
      }
      return Request{GroupDownloadBlocks{group, static_cast<std::uint8_t>(count)}};
    }
    case kStepAction: {
      const std::string what = step_name(step) + " (action)";
      if (d.size() < kActionFixed || (d.size() - kActionFixed) % 3 != 0) {
        return make_error(what + ": " + std::to_string(d.size()) +
                          " data bytes is not 7 + 3 per servo");
      }
      FieldReader r(d);
      r.u8();
      r.u8();
      GroupDownloadAction m;
      m.group = group;
      m.block = r.u8();
      m.index = r.u8();
      const std::uint8_t marker = r.u8();
      m.time_ms = r.u16();
      if (auto ok = check_block(m.block, what); !ok) return ok.error();
      if (m.index >= kActionsPerBlock) {
        return make_error(what + ": index " + std::to_string(m.index) + " is outside 0..254");
      }
      if (marker != kActionMarker) {
        return make_error(what + ": fifth byte is " + to_hex(ByteView(&marker, 1)) +
                          ", expected 0b");
      }
      while (r.remaining() > 0) {
        const std::uint8_t id = r.u8();
        m.servos.push_back(ServoTarget{id, r.u16()});
      }
      return Request{std::move(m)};
    }
    case kStepClose: {
      const std::string what = step_name(step) + " (close)";
      if (auto ok = expect_size(d, kCloseBytes, what); !ok) return ok.error();
      return Request{GroupDownloadClose{group}};
    }
    default:
      return make_error("GroupDownload: unknown step " + std::to_string(step) + " (expected 1..5)");
  }
}

Frame encode_ack(const GroupDownloadAck& ack) { return Frame{kCmd, Bytes{ack.step, ack.status}}; }

Result<GroupDownloadAck> decode_ack(const Frame& frame) {
  if (frame.cmd != kCmd) return make_error("not a GroupDownload acknowledgement");
  if (auto ok = expect_size(frame.data, kAckBytes, "GroupDownload acknowledgement"); !ok) {
    return ok.error();
  }
  const std::uint8_t step = frame.data[0];
  if (step < kStepOpen || step > kStepClose) {
    return make_error("GroupDownload acknowledgement: step " + std::to_string(step) +
                      " is outside 1..5");
  }
  return GroupDownloadAck{step, frame.data[1]};
}

int group_download_step(const Request& request) { return std::visit(StepOf{}, request); }

Result<std::vector<Request>> plan_group_download(std::uint8_t group,
                                                 std::span<const GroupAction> actions) {
  const std::size_t n = actions.size();
  if (n < 1 || n > kMaxActions) {
    return make_error("a group holds 1 to 1020 actions (4 blocks of 255), got " +
                      std::to_string(n));
  }
  const std::size_t blocks = (n + kActionsPerBlock - 1) / kActionsPerBlock;
  std::vector<std::uint8_t> counts;
  for (std::size_t b = 0; b < blocks; ++b) {
    const std::size_t left = n - b * kActionsPerBlock;
    counts.push_back(static_cast<std::uint8_t>(left < kActionsPerBlock ? left : kActionsPerBlock));
  }

  std::vector<Request> plan;
  plan.reserve(n + blocks + 3);
  plan.push_back(GroupDownloadOpen{group, counts});
  for (std::size_t b = 0; b < blocks; ++b) {
    plan.push_back(GroupDownloadSize{group, static_cast<std::uint8_t>(b), counts[b]});
  }
  plan.push_back(GroupDownloadBlocks{group, static_cast<std::uint8_t>(blocks)});
  for (std::size_t i = 0; i < n; ++i) {
    const GroupAction& a = actions[i];
    const std::string where = "action " + std::to_string(i + 1) + " of " + std::to_string(n);
    if (a.time_ms < kMinActionMs || a.time_ms > kMaxActionMs) {
      return make_error(where + ": time " + std::to_string(a.time_ms) + " ms is outside 20..30000");
    }
    const ActionSlot slot = slot_of(i);
    GroupDownloadAction m{group, slot.block, slot.index, a.time_ms, a.servos};
    if (auto frame = encode_step(m); !frame)
      return make_error(where + ": " + frame.error().message);
    plan.push_back(std::move(m));
  }
  plan.push_back(GroupDownloadClose{group});
  return plan;
}

}  // namespace seqc::lsc
