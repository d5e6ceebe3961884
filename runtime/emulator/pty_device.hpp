// What the pseudo-terminal server drives: a byte-level device in emulated time, and adapters
// for the two emulators.
#pragma once

#include <cstddef>
#include <optional>
#include <ostream>

#include "runtime/emulator/raspblock_emulator.hpp"
#include "runtime/emulator/xarm_emulator.hpp"
#include "runtime/io/clock.hpp"
#include "runtime/protocol/bytes.hpp"

namespace seqc::emu {

class PtyDevice {
 public:
  virtual ~PtyDevice() = default;
  virtual void receive(ByteView bytes, io::TimePoint at) = 0;
  virtual std::optional<io::TimePoint> next_output_at() const = 0;
  virtual Bytes take_output(io::TimePoint upto) = 0;
  virtual bool hung_up() const = 0;
};

class XArmPtyDevice final : public PtyDevice {
 public:
  explicit XArmPtyDevice(XArmEmulator& emu) : emu_(emu) {}
  void receive(ByteView bytes, io::TimePoint at) override { emu_.receive(bytes, at); }
  std::optional<io::TimePoint> next_output_at() const override { return emu_.next_output_at(); }
  Bytes take_output(io::TimePoint upto) override { return emu_.take_output(upto); }
  bool hung_up() const override { return emu_.hung_up(); }

 private:
  XArmEmulator& emu_;
};

// Prints each new timeline entry (describe_change) on `log`, if given, as it happens.
class RaspblockPtyDevice final : public PtyDevice {
 public:
  RaspblockPtyDevice(RaspblockEmulator& emu, std::ostream* log) : emu_(emu), log_(log) {}
  void receive(ByteView bytes, io::TimePoint at) override;
  std::optional<io::TimePoint> next_output_at() const override { return std::nullopt; }
  Bytes take_output(io::TimePoint) override { return {}; }
  bool hung_up() const override { return false; }

 private:
  RaspblockEmulator& emu_;
  std::ostream* log_;
  std::size_t printed_ = 0;
  std::size_t rejections_printed_ = 0;
};

}  // namespace seqc::emu
