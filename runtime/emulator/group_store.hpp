// The controller's action-group flash (groups 0..254, up to 1,020 actions each, within the
// board's StoreLimits) and the GroupDownload step 1-5 state machine that writes it.
//
// The handshake is ENFORCED (layouts as group_download.hpp reads the document):
//   step 1  starts a download: the group is erased at once (empty from then on) and the
//           controller is busy for flash_erase_time. Counts: 1..4 blocks of 1..255 actions.
//   step 2  once per block, blocks in order, count equal to the one announced in step 1.
//   step 3  after every step 2; its block list must cover exactly the announced blocks.
//   step 4  actions strictly in order: block 0 index 0, 1, ... then block 1 index 0, ...
//   step 5  only once every announced action arrived; then, and only then, the group is valid.
// Anything out of order, for another group, with a wrong marker or a wrong length is refused
// with ack "<step> 01" and changes nothing. An exact repeat of the last accepted step 2-5
// frame (same slot, same contents) is accepted again and re-acknowledged without changing
// anything, so a host may retry after a lost acknowledgement. A step 1 always restarts.
// A download that never reaches step 5 leaves the group empty.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "protocol/lsc/group_download.hpp"
#include "protocol/lsc/lsc_frame.hpp"

namespace seqc::emu {

inline constexpr std::size_t kGroupCount = 255;  // groups 0..254; 255 means "all"

// How much a board stores: group numbers 0..groups-1, and at most flash_actions actions over
// every group together. Step 1 of a group beyond either is refused (ack "01 01"), so a host
// learns it before sending any action. The defaults hold every group the protocol numbers, each
// full; a smaller board is modelled with `emu:xarm?groups=N,flash=M`.
struct StoreLimits {
  std::size_t groups = kGroupCount;
  std::size_t flash_actions = kGroupCount * lsc::kMaxActions;
};

class GroupStore {
 public:
  explicit GroupStore(StoreLimits limits = {}) : limits_(limits) {}
  // Whether `actions` more actions fit in `group` (whatever the group holds now is rewritten).
  bool room_for(std::uint8_t group, std::size_t actions) const;
  // nullopt = empty (never written, erased, or an interrupted download).
  const std::optional<std::vector<lsc::GroupAction>>& group(std::uint8_t group) const;
  void store(std::uint8_t group, std::vector<lsc::GroupAction> actions);
  void erase(std::uint8_t group);
  void erase_all();

 private:
  StoreLimits limits_;
  std::array<std::optional<std::vector<lsc::GroupAction>>, kGroupCount + 1> groups_{};
};

class GroupDownloader {
 public:
  enum class Work { Ordinary, FlashErase, FlashWrite };  // what the busy time is spent on
  struct Outcome {
    lsc::GroupDownloadAck ack;
    Work work = Work::Ordinary;
  };

  // Handles one CMD 5 frame. nullopt if the frame names no step (empty data or a step byte
  // outside 1..5): the controller cannot tell which step to refuse, so it ignores it.
  std::optional<Outcome> handle(const lsc::Frame& frame, GroupStore& store);

  // Abandons a download in progress (power cycle, the group erased): the group stays empty.
  void abort();
  // The group being downloaded, if a download is in progress.
  std::optional<std::uint8_t> active_group() const;

 private:
  enum class Phase { Sizes, Blocks, Actions, Complete };
  struct Session {
    std::uint8_t group = 0;
    std::vector<std::uint8_t> counts;
    Phase phase = Phase::Sizes;
    std::size_t sizes_done = 0;
    std::size_t block = 0;
    std::size_t index = 0;
    std::vector<lsc::GroupAction> actions;
  };
  bool accept(const lsc::Request& request, GroupStore& store);

  std::optional<Session> session_;
  std::optional<Bytes> last_accepted_;  // data of the last accepted frame, for retries
};

}  // namespace seqc::emu
