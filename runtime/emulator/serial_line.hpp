// The emulated controller's UART: the receive line that delivers the host's bytes at the line
// rate, the receive parser that cuts them into frames, and the transmit line that sends
// replies one byte after another.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "base/bytes.hpp"
#include "runtime/io/clock.hpp"

namespace seqc::emu {

// Cuts the request stream into pieces the way the controller's receive routine does:
// 55 55 LEN then LEN - 1 more bytes (CMD and data). A LEN below 2 ends the piece at once as
// malformed. Bytes outside any frame come out as a malformed piece of their own, so that
// every received byte is accounted for in exactly one piece.
//
// Modelling choice (not from the document): if the next byte arrives more than `gap` after
// the previous one, a partial frame is discarded (as a malformed piece). Without it, a frame
// whose LEN was corrupted upwards would swallow the frames that follow.
class RequestFramer {
 public:
  struct Piece {
    Bytes raw;
    bool framed = false;  // a whole 55 55 LEN CMD ... frame with LEN >= 2
  };

  explicit RequestFramer(io::Duration gap) : gap_(gap) {}

  // All `bytes` arrive at `at`. Appends the pieces they complete to `out`.
  void feed(ByteView bytes, io::TimePoint at, std::vector<Piece>& out);
  void reset();

 private:
  void flush_garbage(std::vector<Piece>& out);

  io::Duration gap_;
  std::optional<io::TimePoint> last_at_;
  Bytes garbage_;
  Bytes frame_;  // 55, 55 55, 55 55 LEN, or more of a frame
};

// Receive side on the wire: the host may hand over many bytes at once (a pty or a driver's
// buffer takes them instantly), but the line carries one byte every 10 bits at `baud`. A byte
// written at time t is delivered at max(t, the previous byte's delivery) + 10 bits / baud, so
// a frame is complete (and can be processed) only after its own wire time, and bytes written
// while the line is busy queue behind the ones before them. Baud 0 delivers at once.
class InputLine {
 public:
  // Bytes delivered together (more than one only when unpaced).
  struct Arrival {
    io::TimePoint at;
    Bytes bytes;
  };

  explicit InputLine(std::uint32_t baud);

  // The host writes `bytes` at `at`. Returns when the last of them is delivered (`at` for
  // none).
  io::TimePoint push(ByteView bytes, io::TimePoint at);
  // When the next queued byte is delivered; nullopt when none is queued.
  std::optional<io::TimePoint> next_delivery_at() const;
  // The bytes delivered at or before `upto`, in order, grouped by delivery time; removed.
  std::vector<Arrival> take(io::TimePoint upto);
  bool empty() const { return head_ == queue_.size(); }
  // Drops the queued bytes (the line stays busy until the last of them would have arrived).
  void clear();
  io::Duration byte_time() const { return byte_time_; }

 private:
  struct Byte {
    io::TimePoint at;
    std::uint8_t value;
  };
  io::Duration byte_time_;
  std::vector<Byte> queue_;  // delivery times ascending; [head_, end) still queued
  std::size_t head_ = 0;
  std::optional<io::TimePoint> last_delivery_;
};

// Transmit side: messages become ready at some time and go out in order of readiness, one
// byte every 10 bits at `baud` (all at once when baud is 0), never overlapping on the wire.
class OutputLine {
 public:
  explicit OutputLine(std::uint32_t baud);

  void send(Bytes bytes, io::TimePoint ready);
  std::optional<io::TimePoint> next_byte_at() const;
  // When the last byte of the message at the front (going out now or next) is due.
  std::optional<io::TimePoint> front_last_byte_at() const;
  // The bytes due at or before `upto`, removed from the line. Callers never send() a message
  // ready before a time they have already taken output up to.
  Bytes take(io::TimePoint upto);
  void clear();
  io::Duration byte_time() const { return byte_time_; }

 private:
  struct Message {
    io::TimePoint ready;
    std::uint64_t seq;
    Bytes bytes;
  };
  io::TimePoint start_of_front() const;

  io::Duration byte_time_;
  std::vector<Message> queue_;  // by (ready, seq); the front may be partly sent
  std::size_t front_sent_ = 0;
  io::TimePoint front_start_{0};
  io::TimePoint line_free_{0};
  std::uint64_t seq_ = 0;
};

}  // namespace seqc::emu
