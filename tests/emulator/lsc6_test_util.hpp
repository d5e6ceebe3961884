// What the LSC-6 emulator's tests share: an unpaced board (replies at once, so the tests read
// the board's logic, not the line's timing) and the DownloadAction request, its bytes written
// out by hand from docs/protocol/lsc-6.md.
#pragma once

#include "runtime/emulator/lsc6_emulator.hpp"
#include "tests/emulator/emu_test_util.hpp"

namespace seqc::emu::test {

inline Lsc6Config unpaced() {
  Lsc6Config c;
  c.baud = 0;
  return c;
}

// 55 55 0b 19 G TOTAL IDX 01 tLo tHi ch pLo pHi: one channel per action (LEN = 8 + 3).
inline Bytes download_action(unsigned group, unsigned total, unsigned index, unsigned time_ms,
                             unsigned ch, unsigned pulse) {
  return Bytes{0x55, 0x55,        0x0b,        0x19,   lo(group), lo(total), lo(index),
               0x01, lo(time_ms), hi(time_ms), lo(ch), lo(pulse), hi(pulse)};
}

}  // namespace seqc::emu::test
