// decode_request() and decode_reply(): a frame back into the typed message it carries, with
// every size and field checked (lsc_messages.hpp). Encoding lives in lsc_messages.cpp.
#include <string>

#include "protocol/lsc/group_download.hpp"
#include "protocol/lsc/lsc_fields.hpp"
#include "protocol/lsc/lsc_messages.hpp"

namespace seqc::lsc {
namespace {

using detail::check_limits;
using detail::cmd_of;
using detail::expect_size;
using detail::FieldReader;

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

Result<std::vector<std::uint8_t>> decode_ids(const Bytes& d, const std::string& what) {
  if (d.empty()) return make_error(what + ": missing the count byte");
  if (auto ok = expect_entries(d, 1, d[0], 1, what); !ok) return ok.error();
  return std::vector<std::uint8_t>(d.begin() + 1, d.end());
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

}  // namespace

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
      // reading: `id offset:sbyte` (2 bytes) as well as the table's `id offset:short`.
      if (d.size() == 2) {
        return Request{ServoOffsetAdjust{d[0], static_cast<std::int8_t>(d[1]), true}};
      }
      if (auto ok = expect_size(d, 3, "ServoOffsetAdjust (2 or 3 bytes)"); !ok) return ok.error();
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
      // reading: the id alone (1 byte), which every servo on the bus takes as its id.
      if (d.size() == 1) {
        BusServoInfoWrite m;
        m.servo = d[0];
        m.id_only = true;
        return Request{m};
      }
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

}  // namespace seqc::lsc
