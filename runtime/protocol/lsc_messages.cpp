#include "runtime/protocol/lsc_messages.hpp"

#include <limits>
#include <string>

#include "runtime/protocol/group_download.hpp"
#include "runtime/protocol/lsc_fields.hpp"

namespace seqc::lsc {

namespace {

using detail::expect_size;
using detail::FieldReader;
using detail::FieldWriter;

constexpr std::uint8_t cmd_of(Command c) { return static_cast<std::uint8_t>(c); }
constexpr std::size_t kMaxCount = 255;  // a (byte)count field

Status check_count(std::size_t count, const std::string& what) {
  if (count > kMaxCount) {
    return make_error(what + ": " + std::to_string(count) +
                      " entries do not fit the one-byte count (at most 255)");
  }
  return Ok{};
}

// Error unless `count` entries of `entry_size` bytes after `fixed` bytes are exactly `data`.
Status expect_entries(const Bytes& data, std::size_t fixed, std::size_t count,
                      std::size_t entry_size, const std::string& what) {
  const std::size_t expected = fixed + count * entry_size;
  if (data.size() != expected) {
    return make_error(what + ": count " + std::to_string(count) + " needs " +
                      std::to_string(expected) + " data bytes, got " + std::to_string(data.size()));
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

Result<std::vector<std::uint8_t>> decode_ids(const Bytes& d, const std::string& what) {
  if (d.empty()) return make_error(what + ": missing the count byte");
  if (auto ok = expect_entries(d, 1, d[0], 1, what); !ok) return ok.error();
  return std::vector<std::uint8_t>(d.begin() + 1, d.end());
}

Status check_limits(const BusServoLimits& l, const std::string& what) {
  if (l.led_status > 1) {
    return make_error(what + ": led_status " + std::to_string(l.led_status) +
                      " is outside 0..1 (0 = enable, 1 = disable)");
  }
  if ((l.led_warning & ~0x07) != 0) {
    return make_error(what + ": led_warning " + std::to_string(l.led_warning) +
                      " sets bits other than 0-2 (overheat, overvoltage, overposition)");
  }
  return Ok{};
}

void write_limits(FieldWriter& w, const BusServoLimits& l) {
  w.u16(l.position_min).u16(l.position_max).u16(l.millivolts_min).u16(l.millivolts_max);
  w.u16(l.temp_max).u8(l.led_status).u8(l.led_warning);
}

BusServoLimits read_limits(FieldReader& r) {
  BusServoLimits l;
  l.position_min = r.u16();
  l.position_max = r.u16();
  l.millivolts_min = r.u16();
  l.millivolts_max = r.u16();
  l.temp_max = r.u16();
  l.led_status = r.u8();
  l.led_warning = r.u8();
  return l;
}

constexpr std::size_t kLimitsBytes = 12;
constexpr std::size_t kBusServoInfoBytes = 1 + kLimitsBytes + 1 + 2 + 1 + 2;

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
  if (auto ok = check_limits(m.limits, "BusServoInfoWrite"); !ok) return ok.error();
  FieldWriter w(cmd_of(Command::BusServoInfoWrite));
  w.u8(m.servo);
  write_limits(w, m.limits);
  return w.finish("BusServoInfoWrite");
}
Result<Frame> encode_one(const BusServoInfoRead&) {
  return Frame{cmd_of(Command::BusServoInfoRead), {}};
}

Result<Request> decode_move(const Bytes& d) {
  const std::string what = "MultiServoMove";
  if (d.empty()) return make_error(what + ": missing the count byte");
  if (auto ok = expect_entries(d, 3, d[0], 3, what); !ok) return ok.error();
  FieldReader r(d);
  MultiServoMove m;
  const std::size_t count = r.u8();
  m.time_ms = r.u16();
  for (std::size_t i = 0; i < count; ++i) {
    MultiServoMove::Entry e;
    e.id = r.u8();
    const std::uint16_t pos = r.u16();
    if (pos != kNoMove) e.position = pos;
    m.servos.push_back(e);
  }
  return Request{std::move(m)};
}

template <class T>
Result<Request> decode_ids_as(const Bytes& d, const char* what) {
  auto ids = decode_ids(d, what);
  if (!ids) return ids.error();
  return Request{T{std::move(*ids)}};
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

// GroupStarted, GroupFinished and the detailed GroupStopped share "group timesLo timesHi".
struct GroupTimes {
  std::uint8_t group;
  std::uint16_t times;
};
GroupTimes read_group_times(const Bytes& d) {
  FieldReader r(d);
  const std::uint8_t group = r.u8();
  return GroupTimes{group, r.u16()};
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

Result<Request> decode_request(const Frame& frame) {
  const Bytes& d = frame.data;
  switch (static_cast<Command>(frame.cmd)) {
    case Command::MultiServoMove:
      return decode_move(d);
    case Command::GroupDownload:
      return decode_group_download(frame);
    case Command::GroupRun: {
      if (auto ok = expect_size(d, 3, "GroupRun"); !ok) return ok.error();
      const GroupTimes gt = read_group_times(d);
      return Request{GroupRun{gt.group, gt.times}};
    }
    case Command::GroupStop:
      if (auto ok = expect_size(d, 0, "GroupStop"); !ok) return ok.error();
      return Request{GroupStop{}};
    case Command::GroupErase:
      if (auto ok = expect_size(d, 1, "GroupErase"); !ok) return ok.error();
      return Request{GroupErase{d[0]}};
    case Command::GroupSpeed: {
      if (auto ok = expect_size(d, 3, "GroupSpeed"); !ok) return ok.error();
      const GroupTimes gt = read_group_times(d);
      return Request{GroupSpeed{gt.group, gt.times}};
    }
    case Command::GetBatteryVoltage:
      if (auto ok = expect_size(d, 0, "GetBatteryVoltage"); !ok) return ok.error();
      return Request{GetBatteryVoltage{}};
    case Command::MultiServoOff:
      return decode_ids_as<MultiServoOff>(d, "MultiServoOff");
    case Command::ServoPositionRead:
      return decode_ids_as<ServoPositionRead>(d, "ServoPositionRead");
    case Command::ServoOffsetWrite:
      return decode_ids_as<ServoOffsetWrite>(d, "ServoOffsetWrite");
    case Command::ServoOffsetRead:
      return decode_ids_as<ServoOffsetRead>(d, "ServoOffsetRead");
    case Command::ServoOffsetAdjust: {
      if (auto ok = expect_size(d, 3, "ServoOffsetAdjust"); !ok) return ok.error();
      FieldReader r(d);
      const std::uint8_t servo = r.u8();
      return Request{ServoOffsetAdjust{servo, r.i16()}};
    }
    case Command::ServoSpeed: {
      if (auto ok = expect_size(d, 4, "ServoSpeed"); !ok) return ok.error();
      if (d[1] > 1) {
        return make_error("ServoSpeed: mode " + std::to_string(d[1]) +
                          " is outside 0..1 (0 = servo, 1 = motor)");
      }
      FieldReader r(d);
      ServoSpeed m;
      m.servo = r.u8();
      m.mode = static_cast<ServoMode>(r.u8());
      m.milliseconds = r.u16();
      return Request{m};
    }
    case Command::BusServoInfoWrite: {
      if (auto ok = expect_size(d, 1 + kLimitsBytes, "BusServoInfoWrite"); !ok) {
        return ok.error();
      }
      FieldReader r(d);
      BusServoInfoWrite m;
      m.servo = r.u8();
      m.limits = read_limits(r);
      if (auto ok = check_limits(m.limits, "BusServoInfoWrite"); !ok) return ok.error();
      return Request{m};
    }
    case Command::BusServoInfoRead:
      if (auto ok = expect_size(d, 0, "BusServoInfoRead"); !ok) return ok.error();
      return Request{BusServoInfoRead{}};
  }
  return make_error("unknown command " + std::to_string(frame.cmd) + " (0x" +
                    to_hex(ByteView(&frame.cmd, 1)) + ")");
}

Result<Reply> decode_reply(const Frame& frame) {
  const Bytes& d = frame.data;
  switch (frame.cmd) {
    case cmd_of(Command::GroupDownload): {
      auto ack = decode_ack(frame);
      if (!ack) return ack.error();
      return Reply{*ack};
    }
    case cmd_of(Command::GroupRun): {
      if (auto ok = expect_size(d, 3, "GroupStarted"); !ok) return ok.error();
      const GroupTimes gt = read_group_times(d);
      return Reply{GroupStarted{gt.group, gt.times}};
    }
    case cmd_of(Command::GroupStop): {
      if (d.empty()) return Reply{GroupStopped{}};
      if (auto ok = expect_size(d, 3, "GroupStopped (0 or 3 bytes)"); !ok) return ok.error();
      const GroupTimes gt = read_group_times(d);
      return Reply{GroupStopped{GroupStopped::Detail{gt.group, gt.times}}};
    }
    case cmd_of(Command::GroupErase): {
      // CMD 8 is GroupErase's empty response with no data and GroupFinished with 3 bytes.
      if (d.empty()) return Reply{GroupErased{}};
      if (auto ok = expect_size(d, 3, "GroupFinished (GroupErased has 0 bytes)"); !ok) {
        return ok.error();
      }
      const GroupTimes gt = read_group_times(d);
      return Reply{GroupFinished{gt.group, gt.times}};
    }
    case cmd_of(Command::GetBatteryVoltage): {
      if (auto ok = expect_size(d, 2, "BatteryVoltage"); !ok) return ok.error();
      FieldReader r(d);
      return Reply{BatteryVoltage{r.u16()}};
    }
    case cmd_of(Command::ServoPositionRead): {
      if (d.empty()) return make_error("ServoPositions: missing the count byte");
      if (auto ok = expect_entries(d, 1, d[0], 3, "ServoPositions"); !ok) return ok.error();
      FieldReader r(d);
      ServoPositions m;
      const std::size_t count = r.u8();
      for (std::size_t i = 0; i < count; ++i) {
        const std::uint8_t id = r.u8();
        m.servos.push_back(ServoTarget{id, r.u16()});
      }
      return Reply{std::move(m)};
    }
    case cmd_of(Command::ServoOffsetRead): {
      if (d.empty()) return make_error("ServoOffsets: missing the count byte");
      if (auto ok = expect_entries(d, 1, d[0], 2, "ServoOffsets"); !ok) return ok.error();
      FieldReader r(d);
      ServoOffsets m;
      const std::size_t count = r.u8();
      for (std::size_t i = 0; i < count; ++i) {
        const std::uint8_t id = r.u8();
        m.servos.push_back(ServoOffsets::Entry{id, r.i8()});
      }
      return Reply{std::move(m)};
    }
    case cmd_of(Command::BusServoInfoRead): {
      if (auto ok = expect_size(d, kBusServoInfoBytes, "BusServoInfo"); !ok) return ok.error();
      FieldReader r(d);
      BusServoInfo m;
      m.id = r.u8();
      m.limits = read_limits(r);
      m.offset = r.i8();
      m.position = r.u16();
      m.temp = r.u8();
      m.millivolts = r.u16();
      if (auto ok = check_limits(m.limits, "BusServoInfo"); !ok) return ok.error();
      return Reply{m};
    }
    default:
      return make_error("command " + std::to_string(frame.cmd) + " (0x" +
                        to_hex(ByteView(&frame.cmd, 1)) + ") is not a known reply");
  }
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
