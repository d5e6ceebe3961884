// Helpers for the emulator tests. Request bytes are written by hand here (hex strings, or the
// framing 55 55 LEN added around hand-written data), never produced by the project's encoder.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <string_view>
#include <vector>

#include "runtime/emulator/xarm_emulator.hpp"
#include "base/bytes.hpp"

namespace seqc::emu::test {

using namespace std::chrono_literals;

inline Bytes hex(std::string_view text) {
  auto r = parse_hex(text);
  EXPECT_TRUE(r.ok()) << text;
  return r.ok() ? *r : Bytes{};
}

// 55 55 LEN CMD DATA with LEN = len(DATA) + 2.
inline Bytes frame(std::uint8_t cmd, const Bytes& data) {
  // Sized once and filled in place: GCC 12 warns (-Warray-bounds, a false positive) about
  // inserting into a vector built from a four-byte initializer list.
  Bytes out(4 + data.size());
  out[0] = 0x55;
  out[1] = 0x55;
  out[2] = static_cast<std::uint8_t>(data.size() + 2);
  out[3] = cmd;
  std::copy(data.begin(), data.end(), out.begin() + 4);
  return out;
}

inline std::uint8_t lo(unsigned v) { return static_cast<std::uint8_t>(v & 0xff); }
inline std::uint8_t hi(unsigned v) { return static_cast<std::uint8_t>((v >> 8) & 0xff); }

inline io::TimePoint at_ms(std::int64_t ms) { return io::TimePoint{std::chrono::milliseconds(ms)}; }

// Sends `request` at `t`, then collects everything the emulator sends until it has nothing
// more scheduled by `t + window`; `t` ends at the time the last byte came (or unchanged).
inline Bytes exchange(ControllerDevice& emu, const Bytes& request, io::TimePoint& t,
                      io::Duration window = std::chrono::seconds(1)) {
  emu.receive(request, t);
  Bytes out;
  const io::TimePoint limit = t + window;
  while (auto next = emu.next_output_at()) {
    if (*next > limit) break;
    t = std::max(t, *next);
    Bytes got = emu.take_output(t);
    out.insert(out.end(), got.begin(), got.end());
  }
  return out;
}

inline std::string hex_of(const Bytes& b) { return to_hex(b); }

// The step 1-5 frames of a download, built by hand from the table in group_download.hpp.
struct DownloadFrames {
  std::vector<Bytes> frames;
};

inline lsc::GroupAction test_action(std::size_t k) {
  lsc::GroupAction a;
  a.time_ms = static_cast<std::uint16_t>(20 + k % 100);
  a.servos = {{1, static_cast<std::uint16_t>(k % 1001)},
              {6, static_cast<std::uint16_t>(1000 - k % 1001)}};
  return a;
}

inline Bytes action_frame(std::uint8_t group, std::uint8_t block, std::uint8_t index,
                          const lsc::GroupAction& a) {
  Bytes d{0x04, group, block, index, 0x0b, lo(a.time_ms), hi(a.time_ms)};
  for (const auto& s : a.servos) {
    d.push_back(s.id);
    d.push_back(lo(s.position));
    d.push_back(hi(s.position));
  }
  return frame(0x05, d);
}

inline std::vector<Bytes> download_frames(std::uint8_t group,
                                          const std::vector<lsc::GroupAction>& actions) {
  std::vector<Bytes> out;
  const std::size_t n = actions.size();
  const std::size_t blocks = (n + 254) / 255;
  Bytes open{0x01, group};
  for (std::size_t b = 0; b < blocks; ++b) {
    open.push_back(static_cast<std::uint8_t>(std::min<std::size_t>(255, n - 255 * b)));
  }
  out.push_back(frame(0x05, open));
  for (std::size_t b = 0; b < blocks; ++b) {
    out.push_back(frame(0x05, {0x02, group, static_cast<std::uint8_t>(b), open[2 + b], 0x00}));
  }
  Bytes list{0x03, group, 0x00};
  for (std::size_t b = 0; b < blocks; ++b) list.push_back(static_cast<std::uint8_t>(b));
  out.push_back(frame(0x05, list));
  for (std::size_t k = 0; k < n; ++k) {
    out.push_back(action_frame(group, static_cast<std::uint8_t>(k / 255),
                               static_cast<std::uint8_t>(k % 255), actions[k]));
  }
  out.push_back(frame(0x05, {0x05, group}));
  return out;
}

inline Bytes ack(std::uint8_t step, std::uint8_t status = 0) {
  return Bytes{0x55, 0x55, 0x04, 0x05, step, status};
}

// Runs a whole download, each frame after the previous acknowledgement; returns false (with
// a test failure) at the first frame not acknowledged with "<step> 00".
inline bool download(XArmEmulator& emu, std::uint8_t group,
                     const std::vector<lsc::GroupAction>& actions, io::TimePoint& t) {
  for (const Bytes& f : download_frames(group, actions)) {
    const Bytes reply = exchange(emu, f, t);
    if (reply != ack(f[4])) {
      ADD_FAILURE() << "frame " << to_hex(f) << " answered " << to_hex(reply);
      return false;
    }
  }
  return true;
}

}  // namespace seqc::emu::test
