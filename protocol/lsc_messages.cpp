// encode() of every servo-controller message and the range-checked narrowing helpers
// (lsc_messages.hpp); decoding lives in lsc_decode.cpp.
#include "protocol/lsc/lsc_messages.hpp"

#include <limits>
#include <string>

#include "protocol/lsc/group_download.hpp"
#include "protocol/lsc/lsc_fields.hpp"

namespace seqc::lsc {

namespace {

using detail::check_limits;
using detail::cmd_of;
using detail::FieldWriter;

constexpr std::size_t kMaxCount = 255;  // a (byte)count field

Status check_count(std::size_t count, const std::string& what) {
  if (count > kMaxCount) {
    return make_error(what + ": " + std::to_string(count) +
                      " entries do not fit the one-byte count (at most 255)");
  }
  return Ok{};
}

// ---- requests --------------------------------------------------------------------------

Result<Frame> encode_ids(Command cmd, const std::vector<std::uint8_t>& ids,
                         const std::string& what) {
  if (auto ok = check_count(ids.size(), what); !ok) return ok.error();
  FieldWriter w(cmd_of(cmd));
  w.u8(static_cast<std::uint8_t>(ids.size()));
  for (std::uint8_t id : ids) w.u8(id);
  return w.finish(what);
}

void write_limits(FieldWriter& w, const BusServoLimits& l) {
  w.u16(l.position_min).u16(l.position_max).u16(l.millivolts_min).u16(l.millivolts_max);
  w.u16(l.temp_max).u8(l.led_status).u8(l.led_warning);
}

Result<Frame> encode_one(const MultiServoMove& m) {
  const std::string what = "MultiServoMove";
  if (auto ok = check_count(m.servos.size(), what); !ok) return ok.error();
  FieldWriter w(cmd_of(Command::MultiServoMove));
  w.u8(static_cast<std::uint8_t>(m.servos.size())).u16(m.time_ms);
  for (const auto& s : m.servos) {
    if (s.position == kNoMove) {
      return make_error(what + ": servo " + std::to_string(s.id) +
                        " position 65280 (0xff00) is the \"do not move\" value; leave the "
                        "position empty instead");
    }
    w.u8(s.id).u16(s.position.value_or(kNoMove));
  }
  return w.finish(what + " with " + std::to_string(m.servos.size()) + " servos");
}

Result<Frame> encode_one(const GroupDownloadOpen& m) { return encode_step(m); }
Result<Frame> encode_one(const GroupDownloadSize& m) { return encode_step(m); }
Result<Frame> encode_one(const GroupDownloadBlocks& m) { return encode_step(m); }
Result<Frame> encode_one(const GroupDownloadAction& m) { return encode_step(m); }
Result<Frame> encode_one(const GroupDownloadClose& m) { return encode_step(m); }

Result<Frame> encode_one(const GroupRun& m) {
  return FieldWriter(cmd_of(Command::GroupRun)).u8(m.group).u16(m.times).finish("GroupRun");
}
Result<Frame> encode_one(const GroupStop&) { return Frame{cmd_of(Command::GroupStop), {}}; }
Result<Frame> encode_one(const GroupErase& m) {
  return Frame{cmd_of(Command::GroupErase), {m.group}};
}
Result<Frame> encode_one(const GroupSpeed& m) {
  return FieldWriter(cmd_of(Command::GroupSpeed)).u8(m.group).u16(m.percent).finish("GroupSpeed");
}
Result<Frame> encode_one(const GetBatteryVoltage&) {
  return Frame{cmd_of(Command::GetBatteryVoltage), {}};
}
Result<Frame> encode_one(const MultiServoOff& m) {
  return encode_ids(Command::MultiServoOff, m.servos, "MultiServoOff");
}
Result<Frame> encode_one(const ServoPositionRead& m) {
  return encode_ids(Command::ServoPositionRead, m.servos, "ServoPositionRead");
}
Result<Frame> encode_one(const ServoOffsetWrite& m) {
  return encode_ids(Command::ServoOffsetWrite, m.servos, "ServoOffsetWrite");
}
Result<Frame> encode_one(const ServoOffsetRead& m) {
  return encode_ids(Command::ServoOffsetRead, m.servos, "ServoOffsetRead");
}
Result<Frame> encode_one(const ServoOffsetAdjust& m) {
  if (m.one_byte) {
    if (m.offset < -128 || m.offset > 127) {
      return make_error("ServoOffsetAdjust: offset " + std::to_string(m.offset) +
                        " does not fit the one-byte form (-128..127)");
    }
    return FieldWriter(cmd_of(Command::ServoOffsetAdjust))
        .u8(m.servo)
        .i8(static_cast<std::int8_t>(m.offset))
        .finish("ServoOffsetAdjust");
  }
  return FieldWriter(cmd_of(Command::ServoOffsetAdjust))
      .u8(m.servo)
      .i16(m.offset)
      .finish("ServoOffsetAdjust");
}
Result<Frame> encode_one(const ServoSpeed& m) {
  const auto mode = static_cast<std::uint8_t>(m.mode);
  if (mode > 1) {
    return make_error("ServoSpeed: mode " + std::to_string(mode) +
                      " is outside 0..1 (0 = servo, 1 = motor)");
  }
  return FieldWriter(cmd_of(Command::ServoSpeed))
      .u8(m.servo)
      .u8(mode)
      .u16(m.milliseconds)
      .finish("ServoSpeed");
}
Result<Frame> encode_one(const BusServoInfoWrite& m) {
  if (m.id_only) {
    if (m.limits != BusServoLimits{}) {
      return make_error("BusServoInfoWrite: the id-only form carries no limits");
    }
    return FieldWriter(cmd_of(Command::BusServoInfoWrite)).u8(m.servo).finish("BusServoInfoWrite");
  }
  if (auto ok = check_limits(m.limits, "BusServoInfoWrite"); !ok) return ok.error();
  FieldWriter w(cmd_of(Command::BusServoInfoWrite));
  w.u8(m.servo);
  write_limits(w, m.limits);
  return w.finish("BusServoInfoWrite");
}
Result<Frame> encode_one(const BusServoInfoRead&) {
  return Frame{cmd_of(Command::BusServoInfoRead), {}};
}

// ---- replies ---------------------------------------------------------------------------

Result<Frame> encode_one(const GroupDownloadAck& m) { return encode_ack(m); }
Result<Frame> encode_one(const GroupStarted& m) {
  return FieldWriter(cmd_of(Command::GroupRun)).u8(m.group).u16(m.times).finish("GroupStarted");
}
Result<Frame> encode_one(const GroupStopped& m) {
  FieldWriter w(cmd_of(Command::GroupStop));
  if (m.detail) w.u8(m.detail->group).u16(m.detail->times);
  return w.finish("GroupStopped");
}
Result<Frame> encode_one(const GroupFinished& m) {
  return FieldWriter(cmd_of(Command::GroupErase)).u8(m.group).u16(m.times).finish("GroupFinished");
}
Result<Frame> encode_one(const GroupErased&) { return Frame{cmd_of(Command::GroupErase), {}}; }
Result<Frame> encode_one(const BatteryVoltage& m) {
  return FieldWriter(cmd_of(Command::GetBatteryVoltage)).u16(m.millivolts).finish("BatteryVoltage");
}
Result<Frame> encode_one(const ServoPositions& m) {
  const std::string what = "ServoPositions";
  if (auto ok = check_count(m.servos.size(), what); !ok) return ok.error();
  FieldWriter w(cmd_of(Command::ServoPositionRead));
  w.u8(static_cast<std::uint8_t>(m.servos.size()));
  for (const auto& s : m.servos) w.u8(s.id).u16(s.position);
  return w.finish(what + " with " + std::to_string(m.servos.size()) + " servos");
}
Result<Frame> encode_one(const ServoOffsets& m) {
  const std::string what = "ServoOffsets";
  if (auto ok = check_count(m.servos.size(), what); !ok) return ok.error();
  FieldWriter w(cmd_of(Command::ServoOffsetRead));
  w.u8(static_cast<std::uint8_t>(m.servos.size()));
  for (const auto& s : m.servos) w.u8(s.id).i8(s.offset);
  return w.finish(what + " with " + std::to_string(m.servos.size()) + " servos");
}
Result<Frame> encode_one(const BusServoInfo& m) {
  if (auto ok = check_limits(m.limits, "BusServoInfo"); !ok) return ok.error();
  FieldWriter w(cmd_of(Command::BusServoInfoRead));
  w.u8(m.id);
  write_limits(w, m.limits);
  w.i8(m.offset).u16(m.position).u8(m.temp).u16(m.millivolts);
  return w.finish("BusServoInfo");
}

template <class T>
Result<T> checked(long long value, const char* field) {
  const long long lo = std::numeric_limits<T>::min();
  const long long hi = std::numeric_limits<T>::max();
  if (value < lo || value > hi) {
    return make_error(std::string(field) + " must be " + std::to_string(lo) + ".." +
                      std::to_string(hi) + ", got " + std::to_string(value));
  }
  return static_cast<T>(value);
}

}  // namespace

Result<Frame> encode(const Request& request) {
  return std::visit([](const auto& m) { return encode_one(m); }, request);
}

Result<Frame> encode(const Reply& reply) {
  return std::visit([](const auto& m) { return encode_one(m); }, reply);
}

Result<Bytes> encode_serial(const Request& request) {
  auto frame = encode(request);
  if (!frame) return frame.error();
  return encode_serial(*frame);
}

Result<Bytes> encode_serial(const Reply& reply) {
  auto frame = encode(reply);
  if (!frame) return frame.error();
  return encode_serial(*frame);
}

Result<std::uint8_t> checked_u8(long long value, const char* field) {
  return checked<std::uint8_t>(value, field);
}
Result<std::uint16_t> checked_u16(long long value, const char* field) {
  return checked<std::uint16_t>(value, field);
}
Result<std::int16_t> checked_i16(long long value, const char* field) {
  return checked<std::int16_t>(value, field);
}

}  // namespace seqc::lsc
