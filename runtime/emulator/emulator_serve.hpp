// `seqc emulate`'s servers: each emulator served on a pseudo-terminal until the stop flag is set,
// one function per emulator. A server reports what happens while it runs through ServeEvents
// (the terminal's path, a hang-up and the device coming back) and returns what it received and,
// when asked, the record and the stored groups as text. It words nothing for people beyond
// facts about the device ("an LSC-6 board", "9600 baud, faults: none"), writes no file and
// chooses no exit code: the caller composes the sentences and writes the files.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>

#include "runtime/io/clock.hpp"

namespace seqc::emu {

struct ServeOptions {
  std::optional<std::uint32_t> baud;  // default: the device's own rate; 0 = unpaced
  std::string faults;                 // the emulator's fault options, as on emu:NAME?OPTIONS
  std::optional<std::uint64_t> seed;  // overrides the faults' seed
  std::string positions;              // xArm: servo positions at power-on, ID=POSITION,...
  std::optional<std::string> link;    // also create this symlink to the terminal
  bool record = false;                // fill ServeResult::record
  bool dump_groups = false;           // fill ServeResult::groups
};

enum class ServeStatus {
  Stopped,       // the stop flag was set
  HungUp,        // an emulated hang-up that does not come back (hung_up_at_frame)
  BadFaults,     // detail: the fault parser's words; nothing was served
  BadPositions,  // detail: the position parser's words; nothing was served
  NoTerminal,    // detail: why no pseudo-terminal could be made; nothing was served
  NotBack,       // after a hang-up, no new terminal; detail: why, "" if the device refused
  Failed,        // serving failed; detail: why
};

struct ServeResult {
  ServeStatus status = ServeStatus::Stopped;
  std::string detail;
  std::string device;    // "an xArm controller", "an LSC-6 board", "a Raspblock board"
  std::string received;  // "1 frames, 4 bytes" / "1 packets, 0 rejected (0 bad checksums)"
  std::size_t hung_up_at_frame = 0;  // HungUp: frames received before the hang-up
  std::string record;                // with ServeOptions::record: the CSV
  std::string groups;                // with ServeOptions::dump_groups: every valid stored group
};

class ServeEvents {
 public:
  virtual ~ServeEvents() = default;
  // The device is on `path` (again, after a hang-up, with back()). `settings` ends the sentence
  // after the path: " (9600 baud, faults: none)", "; state changes follow".
  virtual void serving(const std::string& path, const std::string& device,
                       const std::string& settings) = 0;
  // An emulated hang-up at `frame`; the device comes back on a new terminal in `back_in`.
  virtual void hung_up(std::size_t frame, io::Duration back_in) = 0;
  virtual void back(const std::string& path) = 0;
  // Where the Raspblock's state lines go; nullptr: nowhere.
  virtual std::ostream* log() = 0;
};

ServeResult serve_xarm(const ServeOptions& options, io::Clock& clock, const std::atomic<bool>& stop,
                       ServeEvents& events);
ServeResult serve_lsc6(const ServeOptions& options, io::Clock& clock, const std::atomic<bool>& stop,
                       ServeEvents& events);
ServeResult serve_raspblock(const ServeOptions& options, io::Clock& clock,
                            const std::atomic<bool>& stop, ServeEvents& events);

// `seqc emulate --faults`' help: every key of the xarm emulator's faults (fault_keys) and of the
// LSC-6's (lsc6_option_keys), one a line, from the very tables their parsers check keys
// against, so the help cannot miss a key either takes.
std::string faults_help();

}  // namespace seqc::emu
