// Decides, deterministically from XArmFaults::seed, which frames the emulated controller loses,
// corrupts, answers late or twice. Incoming and outgoing frames draw from two separate streams
// and every frame draws the same number of values whatever the outcome, so one fault never
// shifts the decisions made for unrelated frames.
#pragma once

#include <cstddef>
#include <cstdint>

#include "base/bytes.hpp"
#include "runtime/emulator/xarm_config.hpp"

namespace seqc::emu {

// SplitMix64: tiny, well-mixed, identical on every platform (unlike std distributions).
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next();
  // Uniform in [0, 1).
  double unit();

 private:
  std::uint64_t state_;
};

struct IncomingFault {
  std::size_t number = 0;  // 1-based count of framed requests received
  bool hangup = false;     // this frame closes the link
  bool silent = false;     // the controller has stopped answering
  bool drop = false;
  bool corrupt = false;
  // [0, 1): which byte is flipped, scaled by the frame's length (flip_index). A flip in
  // 55 55 LEN leaves a frame the controller cannot take; anywhere else the controller takes
  // the frame as it arrived, for the protocol has no checksum.
  double corrupt_where = 0;
  bool reset = false;  // the controller resets as this frame arrives
  bool busy = false;   // processing this frame takes busy_for longer
};

struct OutgoingFault {
  bool late = false;
  bool duplicate = false;
  bool corrupt = false;
  double corrupt_where = 0;  // [0, 1): position in the frame, scaled by its length
  bool split = false;        // handed to the host in two pieces
  double split_where = 0;    // [0, 1): where, scaled by the frame's length
};

class FaultInjector {
 public:
  explicit FaultInjector(const XArmFaults& faults);

  // Called once per request frame that arrived framed (55 55 LEN ...), in arrival order.
  IncomingFault on_request();
  // Called once per frame the controller sends (replies and notifications), in order.
  OutgoingFault on_reply();

  // The byte `where` selects in a frame of `size` bytes (size > 0).
  static std::size_t flip_index(std::size_t size, double where);
  // Flips one byte of `frame` (xor 0xff) at flip_index(frame.size(), where); returns it.
  static std::size_t flip(Bytes& frame, double where);

  bool silent() const { return silent_; }
  std::size_t frames_seen() const { return frames_; }
  std::size_t replies_seen() const { return replies_; }

 private:
  XArmFaults faults_;
  SplitMix64 in_;
  SplitMix64 out_;
  // Resets and busy periods draw from a third stream, so adding them to a configuration
  // leaves the drops, corruptions and reply faults of the same seed unchanged.
  SplitMix64 extra_;
  std::size_t frames_ = 0;
  std::size_t replies_ = 0;
  bool silent_ = false;
};

}  // namespace seqc::emu
