#include "runtime/emulator/raspblock_emulator.hpp"

#include <array>
#include <cstdio>
#include <type_traits>
#include <variant>

#include "runtime/io/time_text.hpp"

namespace seqc::emu {
namespace {

constexpr std::array<std::string_view, kRaspblockFieldCount> kFieldNames = {
    "pid.mode",        "pid.speed_kp", "pid.speed_ki", "pid.position_kp", "pid.position_ki",
    "pid.position_kd", "pid.yaw_kp",   "pid.yaw_ki",   "pid.yaw_kd",      "gimbal.horizontal",
    "gimbal.vertical", "servo.1",      "servo.2",      "servo.3",         "servo.4",
    "rocker.x",        "rocker.y",     "rocker.z"};

// The decoder reports rejections as text; a bad checksum is the one rejection a noisy line
// produces, so it is counted apart.
bool is_checksum_rejection(const std::string& reason) {
  return reason.find("checksum") != std::string::npos;
}

}  // namespace

std::string_view field_name(RaspblockField field) {
  return kFieldNames[static_cast<std::size_t>(field)];
}

void RaspblockEmulator::receive(ByteView bytes, io::TimePoint at) {
  if (bytes.empty()) return;
  chunks_.push_back(RaspblockChunk{at, Bytes(bytes.begin(), bytes.end())});
  decoder_.feed(bytes);
  while (auto result = decoder_.next()) {
    if (result->ok()) {
      packets_.push_back(RaspblockPacketRecord{at, result->value()});
      apply(result->value(), at);
    } else {
      const std::string& reason = result->error().message;
      rejections_.push_back(RaspblockRejection{at, reason, is_checksum_rejection(reason)});
    }
  }
}

std::size_t RaspblockEmulator::bad_checksums() const {
  std::size_t n = 0;
  for (const auto& r : rejections_) n += r.bad_checksum ? 1 : 0;
  return n;
}

Bytes RaspblockEmulator::received_bytes() const {
  Bytes out;
  for (const auto& c : chunks_) out.insert(out.end(), c.bytes.begin(), c.bytes.end());
  return out;
}

std::optional<int> RaspblockEmulator::value(RaspblockField field) const {
  return state_[static_cast<std::size_t>(field)];
}

void RaspblockEmulator::set(RaspblockField field, int value, io::TimePoint at) {
  auto& slot = state_[static_cast<std::size_t>(field)];
  if (slot == value) return;
  timeline_.push_back(RaspblockChange{at, field, slot, value});
  slot = value;
}

void RaspblockEmulator::apply(const raspblock::Packet& packet, io::TimePoint at) {
  using F = RaspblockField;
  std::visit(
      [&](const auto& p) {
        using T = std::decay_t<decltype(p)>;
        if constexpr (std::is_same_v<T, raspblock::PidAdjust>) {
          set(F::PidMode, static_cast<int>(p.mode), at);
          set(F::SpeedKp, p.speed_kp, at);
          set(F::SpeedKi, p.speed_ki, at);
          set(F::PositionKp, p.position_kp, at);
          set(F::PositionKi, p.position_ki, at);
          set(F::PositionKd, p.position_kd, at);
          set(F::YawKp, p.yaw_kp, at);
          set(F::YawKi, p.yaw_ki, at);
          set(F::YawKd, p.yaw_kd, at);
        } else if constexpr (std::is_same_v<T, raspblock::GimbalServos>) {
          set(F::GimbalHorizontal, p.horizontal, at);
          set(F::GimbalVertical, p.vertical, at);
        } else if constexpr (std::is_same_v<T, raspblock::SingleServo>) {
          if (p.index >= 1 && p.index <= 4) {
            set(static_cast<F>(static_cast<int>(F::Servo1) + p.index - 1), p.position, at);
          }
        } else if constexpr (std::is_same_v<T, raspblock::Rocker>) {
          set(F::RockerX, p.x, at);
          set(F::RockerY, p.y, at);
          set(F::RockerZ, p.z, at);
        }
      },
      packet);
}

std::string describe_change(const RaspblockChange& c) {
  std::string line = io::stamp_text(c.at);
  if (line.size() < 12) line.insert(0, 12 - line.size(), ' ');
  line += " s  ";
  line += field_name(c.field);
  if (c.previous) {
    line.append(" ").append(std::to_string(*c.previous)).append(" -> ");
  } else {
    line.append(" = ");
  }
  line += std::to_string(c.value);
  return line;
}

std::string timeline_csv(const std::vector<RaspblockChange>& timeline) {
  std::string out = "time_s,field,previous,value\n";
  for (const auto& c : timeline) {
    out += io::stamp_text(c.at) + "," + std::string(field_name(c.field)) + ",";
    if (c.previous) out += std::to_string(*c.previous);
    out.append(",").append(std::to_string(c.value)).append("\n");
  }
  return out;
}

}  // namespace seqc::emu
