// describe(): one line of text per message, field by field, for listings, traces, decode and
// the emulator's record.
#include <string>
#include <vector>

#include "protocol/lsc/group_download.hpp"
#include "protocol/lsc/lsc_messages.hpp"

namespace seqc::lsc {
namespace {

std::string group_text(std::uint8_t group) {
  return group == kAllGroups ? std::string("all") : std::to_string(group);
}

std::string ids_text(const std::vector<std::uint8_t>& ids) {
  std::string out = "servos=[";
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (i != 0) out += ' ';
    out += std::to_string(ids[i]);
  }
  return out + "]";
}

std::string targets_text(const std::vector<ServoTarget>& servos) {
  std::string out = "servos=[";
  for (std::size_t i = 0; i < servos.size(); ++i) {
    if (i != 0) out += ' ';
    out += "{id=" + std::to_string(servos[i].id) +
           " position=" + std::to_string(servos[i].position) + "}";
  }
  return out + "]";
}

std::string limits_text(const BusServoLimits& l) {
  return "position_min=" + std::to_string(l.position_min) +
         " position_max=" + std::to_string(l.position_max) +
         " millivolts_min=" + std::to_string(l.millivolts_min) +
         " millivolts_max=" + std::to_string(l.millivolts_max) +
         " temp_max=" + std::to_string(l.temp_max) + " led_status=" + std::to_string(l.led_status) +
         " led_warning=" + std::to_string(l.led_warning);
}

struct Describer {
  std::string operator()(const MultiServoMove& m) const {
    std::string out = "MultiServoMove time_ms=" + std::to_string(m.time_ms) + " servos=[";
    for (std::size_t i = 0; i < m.servos.size(); ++i) {
      if (i != 0) out += ' ';
      out += "{id=" + std::to_string(m.servos[i].id) + " position=" +
             (m.servos[i].position ? std::to_string(*m.servos[i].position) : "none") + "}";
    }
    return out + "]";
  }
  std::string operator()(const GroupDownloadOpen& m) const {
    std::string out = "GroupDownloadOpen group=" + std::to_string(m.group) + " block_counts=[";
    for (std::size_t i = 0; i < m.block_counts.size(); ++i) {
      if (i != 0) out += ' ';
      out += std::to_string(m.block_counts[i]);
    }
    return out + "]";
  }
  std::string operator()(const GroupDownloadSize& m) const {
    return "GroupDownloadSize group=" + std::to_string(m.group) +
           " block=" + std::to_string(m.block) + " count=" + std::to_string(m.count);
  }
  std::string operator()(const GroupDownloadBlocks& m) const {
    return "GroupDownloadBlocks group=" + std::to_string(m.group) +
           " block_count=" + std::to_string(m.block_count);
  }
  std::string operator()(const GroupDownloadAction& m) const {
    return "GroupDownloadAction group=" + std::to_string(m.group) +
           " block=" + std::to_string(m.block) + " index=" + std::to_string(m.index) +
           " time_ms=" + std::to_string(m.time_ms) + " " + targets_text(m.servos);
  }
  std::string operator()(const GroupDownloadClose& m) const {
    return "GroupDownloadClose group=" + std::to_string(m.group);
  }
  std::string operator()(const GroupRun& m) const {
    return "GroupRun group=" + std::to_string(m.group) + " times=" + std::to_string(m.times);
  }
  std::string operator()(const GroupStop&) const { return "GroupStop"; }
  std::string operator()(const GroupErase& m) const {
    return "GroupErase group=" + group_text(m.group);
  }
  std::string operator()(const GroupSpeed& m) const {
    return "GroupSpeed group=" + group_text(m.group) + " percent=" + std::to_string(m.percent);
  }
  std::string operator()(const GetBatteryVoltage&) const { return "GetBatteryVoltage"; }
  std::string operator()(const MultiServoOff& m) const {
    return "MultiServoOff " + ids_text(m.servos);
  }
  std::string operator()(const ServoPositionRead& m) const {
    return "ServoPositionRead " + ids_text(m.servos);
  }
  std::string operator()(const ServoOffsetWrite& m) const {
    return "ServoOffsetWrite " + ids_text(m.servos);
  }
  std::string operator()(const ServoOffsetRead& m) const {
    return "ServoOffsetRead " + ids_text(m.servos);
  }
  std::string operator()(const ServoOffsetAdjust& m) const {
    return "ServoOffsetAdjust servo=" + std::to_string(m.servo) +
           " offset=" + std::to_string(m.offset) + (m.one_byte ? " (one-byte form)" : "");
  }
  std::string operator()(const ServoSpeed& m) const {
    const char* mode = m.mode == ServoMode::Servo   ? "servo"
                       : m.mode == ServoMode::Motor ? "motor"
                                                    : "invalid";
    return "ServoSpeed servo=" + std::to_string(m.servo) + " mode=" + mode +
           " milliseconds=" + std::to_string(m.milliseconds);
  }
  std::string operator()(const BusServoInfoWrite& m) const {
    if (m.id_only)
      return "BusServoInfoWrite id-only: every servo takes id " + std::to_string(m.servo);
    return "BusServoInfoWrite servo=" + std::to_string(m.servo) + " " + limits_text(m.limits);
  }
  std::string operator()(const BusServoInfoRead&) const { return "BusServoInfoRead"; }

  std::string operator()(const GroupDownloadAck& m) const {
    return "GroupDownloadAck step=" + std::to_string(m.step) +
           " status=" + std::to_string(m.status) + (m.accepted() ? " (accepted)" : " (refused)");
  }
  std::string operator()(const GroupStarted& m) const {
    return "GroupStarted group=" + std::to_string(m.group) + " times=" + std::to_string(m.times);
  }
  std::string operator()(const GroupStopped& m) const {
    if (!m.detail) return "GroupStopped";
    return "GroupStopped group=" + std::to_string(m.detail->group) +
           " times=" + std::to_string(m.detail->times);
  }
  std::string operator()(const GroupFinished& m) const {
    return "GroupFinished group=" + std::to_string(m.group) + " times=" + std::to_string(m.times);
  }
  std::string operator()(const GroupErased&) const { return "GroupErased"; }
  std::string operator()(const BatteryVoltage& m) const {
    return "BatteryVoltage millivolts=" + std::to_string(m.millivolts);
  }
  std::string operator()(const ServoPositions& m) const {
    return "ServoPositions " + targets_text(m.servos);
  }
  std::string operator()(const ServoOffsets& m) const {
    std::string out = "ServoOffsets servos=[";
    for (std::size_t i = 0; i < m.servos.size(); ++i) {
      if (i != 0) out += ' ';
      out += "{id=" + std::to_string(m.servos[i].id) +
             " offset=" + std::to_string(m.servos[i].offset) + "}";
    }
    return out + "]";
  }
  std::string operator()(const BusServoInfo& m) const {
    return "BusServoInfo id=" + std::to_string(m.id) + " " + limits_text(m.limits) +
           " offset=" + std::to_string(m.offset) + " position=" + std::to_string(m.position) +
           " temp=" + std::to_string(m.temp) + " millivolts=" + std::to_string(m.millivolts);
  }
};

}  // namespace

std::string describe(const Request& request) { return std::visit(Describer{}, request); }
std::string describe(const Reply& reply) { return std::visit(Describer{}, reply); }

}  // namespace seqc::lsc
