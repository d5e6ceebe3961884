// What `seqc play` shows while it streams: on a terminal, one line redrawn in place
//   [##########..........]  12.5 / 25.0 s  frame 120/240
// at most every quarter second of the schedule (the line is written between frames, so it
// must stay cheap); nothing when stderr is not a terminal or with --quiet.
#pragma once

#include <cstddef>
#include <iosfwd>
#include <string>

#include "runtime/io/clock.hpp"

namespace seqc::cli {

// The line itself (no "\r"): `cells` wide bar, elapsed and total in seconds, frames.
std::string format_play_progress(io::Duration at, io::Duration total, std::size_t frame,
                                 std::size_t frames, int cells);

class PlayProgress {
 public:
  // enabled: stderr is a terminal and not --quiet; columns: its width (0 = unknown).
  PlayProgress(std::ostream& err, bool enabled, int columns, io::Duration total,
               std::size_t frames);
  ~PlayProgress();
  // After frame `index` (0-based), scheduled at `at`, was written.
  void on_sent(std::size_t index, io::Duration at);
  // Ends the line (call before printing the result).
  void finish();

 private:
  std::ostream& err_;
  bool enabled_;
  int cells_;
  io::Duration total_;
  std::size_t frames_;
  long last_quarter_ = -1;
  bool shown_ = false;
};

}  // namespace seqc::cli
