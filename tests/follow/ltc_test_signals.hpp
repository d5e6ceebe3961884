// The timecode signals tests/follow/ltc_signal.py writes with libltc into SEQC_LTC_DIR (a CTest
// fixture), read whole, and the labels they hold counted by hand: a label's successor written
// here, not asked of the code under test.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "protocol/ltc_timecode.hpp"
#include "runtime/audio/sndfile_audio.hpp"

namespace seqc::testing {

inline std::string ltc_signal_path(const std::string& name) {
  return std::string(SEQC_LTC_DIR) + "/" + name + ".wav";
}

// The samples of signal `name`; a skipped test when the fixture could not write it.
inline audio::MonoAudio read_ltc_signal(const std::string& name) {
  audio::SndfileAudioReader reader;
  auto audio = reader.read(ltc_signal_path(name));
  if (!audio) return {};
  return std::move(*audio);
}

// The label after `tc` at `fps` frames a second (30 for drop-frame): frames carry into seconds,
// minutes and hours; at drop-frame, frames 0 and 1 of a minute not a multiple of ten are not
// said.
inline ltc::Timecode next_label(ltc::Timecode tc, int fps) {
  if (++tc.frames == fps) {
    tc.frames = 0;
    if (++tc.seconds == 60) {
      tc.seconds = 0;
      if (++tc.minutes == 60) {
        tc.minutes = 0;
        tc.hours = (tc.hours + 1) % 24;
      }
      if (tc.drop_frame && tc.minutes % 10 != 0) tc.frames = 2;
    }
  }
  return tc;
}

}  // namespace seqc::testing
