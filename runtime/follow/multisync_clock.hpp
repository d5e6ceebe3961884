// A ShowClock from FPP MultiSync packets (protocol/fpp_multisync.hpp): the master's open, start,
// sync and stop of one named file become Open, Start, Sync and Stop events, dated when the
// datagram reached the socket (io::Datagram::at: a packet read late, after an upload, keeps its
// time; the network's delay, under a millisecond on a show's LAN, is not taken away). Packets about
// other files are ignored and counted; a master's discovery ping is answered with a remote's ping
// (mode remote, system type "other"), so the master lists seqc among its remotes. See
// docs/protocol/fpp-multisync.md and docs/shows.md.
//
// Which file names are followed (names_followed): the last path component of the packet's name
// is compared with NAME. A NAME with an extension ("show.fseq") must match exactly; a NAME
// without one ("show") matches any extension, and once a sequence packet of that name has been
// heard, media packets ("show.mp3", sent by the same master for the same playlist entry) are
// ignored, so one entry does not start the robot twice.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "protocol/fpp_multisync.hpp"
#include "runtime/follow/show_clock.hpp"
#include "runtime/io/udp_socket.hpp"

namespace seqc::follow {

struct MultisyncOptions {
  std::string name;  // --fpp NAME
  // The remote's ping answer.
  std::string hostname = "seqc";
  std::string version = "0.0";
  std::uint16_t major = 0, minor = 0;
  // A packet's position when it carries no seconds elapsed (an FSEQ start, an old master): its
  // frame number times this. FPP sequences are usually 25 ms (40 fps) or 50 ms a frame.
  double frame_ms = 25;
};

// The shortest time between two answers to discovery pings.
inline constexpr io::Duration kAnswerInterval = std::chrono::milliseconds(100);

struct MultisyncCounts {
  std::size_t followed = 0;     // sync packets naming NAME, turned into events
  std::size_t other_names = 0;  // sync packets about other files (or the duplicate media)
  std::size_t pings = 0;        // discovery pings heard
  std::size_t answered = 0;     // ...answered (one every kAnswerInterval at most)
  std::size_t malformed = 0;    // datagrams that did not decode
  std::size_t other_types = 0;  // commands, events, blanking, plugins: not acted on
  std::string last_error;       // the last malformed datagram's reason, or a send that failed
};

// Whether `file_name` (from a packet) names what `--fpp name` follows (see the top of this file).
bool names_followed(std::string_view name, std::string_view file_name);

class MultisyncClock final : public ShowClock {
 public:
  // `clock` is the socket's: a flood of packets that are not events cannot hold next() past
  // its deadline.
  MultisyncClock(io::DatagramSocket& socket, io::Clock& clock, MultisyncOptions options);
  std::optional<ShowClockEvent> next(io::TimePoint deadline) override;
  bool ended() const override { return ended_; }
  const MultisyncCounts& counts() const { return counts_; }
  // The ping seqc answers a discovery with.
  Bytes ping_answer() const;

 private:
  std::optional<ShowClockEvent> on_sync(const fpp::SyncPacket& p, const io::Datagram& d);
  void answer(const io::UdpAddress& to);

  io::DatagramSocket& socket_;
  io::Clock& clock_;
  MultisyncOptions options_;
  MultisyncCounts counts_;
  bool heard_sequence_ = false;
  std::optional<io::TimePoint> answered_at_;
  bool ended_ = false;
};

}  // namespace seqc::follow
