// What the studio's page says about its playhead, for the robot that follows it.
//
// The studio's web server (runtime/studio/server.hpp) receives the page's playhead as it plays,
// pauses, loops and is scrubbed, and passes each report to a PlayheadSink; with `--port`, the
// sink is the robot follower (runtime/studio/robot_follower.hpp), which moves the board to the
// dance's positions at that instant through its live moves, never faster than each servo's
// max_speed. Without `--port` there is no sink. A new program (the file was saved) replaces the
// one followed; stop() holds the robot where it is and ends every move (the page closed, Ctrl-C).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "compiler/compile.hpp"

namespace seqc::studio {

enum class PlayheadMode {
  Playing,  // the song and the dance run from `ms` on
  Paused,   // held at `ms`
  Scrubbed  // dragged to `ms` (a jump the robot slews to)
};

struct PlayheadReport {
  double ms = 0;  // the dance's time at the page
  PlayheadMode mode = PlayheadMode::Paused;
  // Set when the page's loop wrapped: the playhead went back to the loop's start.
  bool looped = false;
};

// What the follower says back for the page to show: a jump being slewed (and until when), a
// scrub refused (a car's drive cannot run backwards in time), the link's trouble.
struct FollowerState {
  bool slewing = false;
  double slew_until_ms = 0;  // page time at which the robot reaches the playhead again
  std::vector<std::string> notices;
};

class PlayheadSink {
 public:
  virtual ~PlayheadSink() = default;
  // The program now shown; its output outlives the call only as the sink copies it.
  virtual void set_program(const compiler::CompileOutput& output) = 0;
  virtual FollowerState report(const PlayheadReport& playhead) = 0;
  virtual void stop() = 0;
};

}  // namespace seqc::studio
