// The GroupDownload (CMD 5) handshake, as the project reads the document's table.
//
// Every reading of that table lives here and in group_download.cpp, each marked "reading"
// and pinned by a byte-exact test (tests/protocol/group_download_test.cpp), so a capture from
// real hardware corrects it in one edit. For group G with N actions (1..1020), in B blocks:
//   step 1 open    05 | 01 G n_0 [n_1 [n_2 [n_3]]]
//   step 2 size    05 | 02 G b n_b 00            once per block b = 0..B-1
//   step 3 blocks  05 | 03 G 00 00 [01 [02 [03]]]
//   step 4 action  05 | 04 G b i 0B tLo tHi {servo posLo posHi}...   i 0-based within b
//   step 5 close   05 | 05 G
// Each step is acknowledged by CMD 5 data "<step> 00"; a non-zero second byte is a refusal.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "base/result.hpp"
#include "protocol/lsc/lsc_frame.hpp"
#include "protocol/lsc/lsc_messages.hpp"

namespace seqc::lsc {

inline constexpr std::size_t kActionsPerBlock = 255;
inline constexpr std::size_t kMaxBlocks = 4;
inline constexpr std::size_t kMaxActions = kActionsPerBlock * kMaxBlocks;  // 1,020
inline constexpr std::uint8_t kActionMarker = 0x0b;  // reading: the table's constant "0B"
inline constexpr std::uint16_t kMinActionMs = 20;    // vendor tools' bounds per action
inline constexpr std::uint16_t kMaxActionMs = 30000;

// A step 4 (action) frame naming `servos` servos, its 4-byte header included: 55 55 LEN 05, then
// 04 G b i 0B tLo tHi (7 bytes) and 3 bytes per servo (id posLo posHi).
constexpr std::size_t action_frame_bytes(std::size_t servos) {
  return kHeaderSize + 7 + 3 * servos;
}
// Over USB HID each frame travels in one report of kHidReportData bytes, header included, so an
// action names at most (64 - 11) / 3 = 17 servos there; a serial link takes any frame.
inline constexpr std::size_t kHidMaxActionServos = (kHidReportData - action_frame_bytes(0)) / 3;

struct GroupAction {
  std::uint16_t time_ms = 0;
  std::vector<ServoTarget> servos;
  friend bool operator==(const GroupAction&, const GroupAction&) = default;
};

// Where action `n` (0-based in the group) goes: block n / 255, index n % 255.
struct ActionSlot {
  std::uint8_t block = 0;
  std::uint8_t index = 0;
};
ActionSlot slot_of(std::size_t action_number);

// The whole download of `actions` into `group`, in send order (steps 1, 2 per block, 3,
// 4 per action, 5). Error for 0 or more than 1,020 actions, or an action that does not fit
// in one frame.
Result<std::vector<Request>> plan_group_download(std::uint8_t group,
                                                 std::span<const GroupAction> actions);

// The step number (1..5) a GroupDownload request belongs to, or 0 for other requests.
int group_download_step(const Request& request);

// Encoding/decoding of the five steps and the acknowledgement (used by lsc_messages.cpp).
Result<Frame> encode_step(const GroupDownloadOpen& m);
Result<Frame> encode_step(const GroupDownloadSize& m);
Result<Frame> encode_step(const GroupDownloadBlocks& m);
Result<Frame> encode_step(const GroupDownloadAction& m);
Result<Frame> encode_step(const GroupDownloadClose& m);
Result<Request> decode_group_download(const Frame& frame);
Frame encode_ack(const GroupDownloadAck& ack);
Result<GroupDownloadAck> decode_ack(const Frame& frame);

}  // namespace seqc::lsc
