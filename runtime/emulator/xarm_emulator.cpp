#include "runtime/emulator/xarm_emulator.hpp"

#include <algorithm>
#include <limits>
#include <type_traits>
#include <variant>

namespace seqc::emu {
namespace {

ServoModelConfig servo_config(const XArmConfig& c) {
  return ServoModelConfig{c.servo_count, c.servo_min, c.servo_max, c.servo_home,
                          c.initial_positions};
}

std::optional<lsc::Frame> reply_frame(const lsc::Reply& reply) {
  auto frame = lsc::encode(reply);
  if (!frame) return std::nullopt;  // cannot happen for the replies built here
  return std::move(*frame);
}

}  // namespace

XArmEmulator::XArmEmulator(XArmConfig config)
    : config_(config),
      faults_(config.faults),
      framer_(config.faults.frame_gap),
      line_(config.baud),
      servos_(servo_config(config)),
      store_(config.store),
      player_(config.faults.clock_ppm),
      speeds_(kGroupCount + 1, 100) {}

void XArmEmulator::receive(ByteView bytes, io::TimePoint at) {
  if (hung_up_ || bytes.empty()) return;
  at = std::max(at, now_);
  advance_to(at);
  received_bytes_.insert(received_bytes_.end(), bytes.begin(), bytes.end());
  std::vector<RequestFramer::Piece> pieces;
  framer_.feed(bytes, at, pieces);
  for (auto& piece : pieces) {
    if (hung_up_) break;
    handle_piece(std::move(piece), at);
  }
}

void XArmEmulator::handle_piece(RequestFramer::Piece piece, io::TimePoint at) {
  ReceivedFrame rec;
  rec.at = at;
  rec.raw = std::move(piece.raw);
  if (!piece.framed) {
    received_.push_back(std::move(rec));
    return;
  }
  const IncomingFault fault = faults_.on_request();
  if (fault.hangup) {
    hung_up_ = true;
    hung_up_at_ = at;
    line_.clear();
    player_.stop();
  }
  if (fault.hangup || fault.silent || fault.drop) {
    rec.dropped_fault = true;
    rec.dropped = fault.hangup   ? DropReason::FaultHangUp
                  : fault.silent ? DropReason::FaultSilent
                                 : DropReason::FaultDrop;
    received_.push_back(std::move(rec));
    return;
  }
  if (fault.corrupt) {
    const std::size_t at_byte = FaultInjector::flip(rec.raw, fault.corrupt_where);
    if (at_byte < 3) {
      // 55 55 LEN no longer frames these bytes: the controller ignores them.
      rec.dropped_fault = true;
      rec.dropped = DropReason::FaultCorrupt;
      received_.push_back(std::move(rec));
      return;
    }
    rec.flipped_at = at_byte;
  }
  if (fault.reset) {
    // The dip takes the frame with it; the controller boots and is deaf meanwhile.
    rec.dropped_fault = true;
    rec.dropped = DropReason::FaultReset;
    received_.push_back(std::move(rec));
    ++resets_;
    power_cycle(at);
    busy_until_ = at + config_.faults.boot_time;
    return;
  }
  lsc::Frame frame{rec.raw[3], Bytes(rec.raw.begin() + 4, rec.raw.end())};
  rec.frame = frame;
  if (at < busy_until_) {
    rec.dropped_busy = true;
    rec.dropped = DropReason::Busy;
    received_.push_back(std::move(rec));
    return;
  }
  received_.push_back(std::move(rec));
  Processed p = process(frame, at);
  if (fault.busy) p.busy += config_.faults.busy_for;
  busy_until_ = at + p.busy;
  for (const auto& reply : p.replies) emit(reply, busy_until_);
}

XArmEmulator::Processed XArmEmulator::process(const lsc::Frame& frame, io::TimePoint at) {
  Processed p;
  p.busy = config_.command_time;
  const io::TimePoint done = at + config_.command_time;
  auto reply = [&](const lsc::Reply& r) {
    if (auto f = reply_frame(r)) p.replies.push_back(std::move(*f));
  };

  if (frame.cmd == static_cast<std::uint8_t>(lsc::Command::GroupDownload)) {
    auto outcome = downloader_.handle(frame, store_);
    if (!outcome) return p;
    if (outcome->work == GroupDownloader::Work::FlashErase) p.busy = config_.flash_erase_time;
    if (outcome->work == GroupDownloader::Work::FlashWrite) p.busy = config_.flash_write_time;
    // Step 1 erased the group; a group being played while it is rewritten stops.
    if (outcome->ack.step == 1 && outcome->ack.accepted() && player_.group() == frame.data[1]) {
      player_.stop();
    }
    p.replies.push_back(lsc::encode_ack(outcome->ack));
    return p;
  }

  auto request = lsc::decode_request(frame);
  if (!request) return p;  // unknown command or malformed data: ignored

  std::visit(
      [&](const auto& m) {
        using T = std::decay_t<decltype(m)>;
        if constexpr (std::is_same_v<T, lsc::MultiServoMove>) {
          for (const auto& e : m.servos) {
            if (e.position) {
              servos_.move(e.id, *e.position, std::chrono::milliseconds(m.time_ms), at);
            }
          }
        } else if constexpr (std::is_same_v<T, lsc::GroupRun>) {
          if (m.group >= kGroupCount) return;
          const auto& actions = store_.group(m.group);
          if (!actions || actions->empty()) return;
          player_.start(m.group, m.times, *actions, speeds_[m.group], done);
          player_.advance_to(done, servos_);  // issues the first action's moves
          reply(lsc::GroupStarted{m.group, m.times});
        } else if constexpr (std::is_same_v<T, lsc::GroupStop>) {
          const auto playing = player_.group();
          player_.stop();
          if constexpr (kGroupStoppedHasData) {
            reply(lsc::GroupStopped{lsc::GroupStopped::Detail{playing.value_or(0), 0}});
          } else {
            reply(lsc::GroupStopped{});
          }
        } else if constexpr (std::is_same_v<T, lsc::GroupErase>) {
          const bool all = m.group == lsc::kAllGroups;
          if (all) {
            store_.erase_all();
          } else {
            store_.erase(m.group);
          }
          if (player_.group() && (all || *player_.group() == m.group)) player_.stop();
          if (downloader_.active_group() && (all || *downloader_.active_group() == m.group)) {
            downloader_.abort();
          }
          p.busy = config_.flash_erase_time;
          reply(lsc::GroupErased{});
        } else if constexpr (std::is_same_v<T, lsc::GroupSpeed>) {
          if (m.percent == 0) return;
          const bool all = m.group == lsc::kAllGroups;
          if (all) {
            std::fill(speeds_.begin(), speeds_.end(), m.percent);
          } else if (m.group < kGroupCount) {
            speeds_[m.group] = m.percent;
          }
          if (player_.group() && (all || *player_.group() == m.group)) {
            player_.set_speed(m.percent, at, servos_);
          }
        } else if constexpr (std::is_same_v<T, lsc::GetBatteryVoltage>) {
          reply(lsc::BatteryVoltage{config_.battery_mv});
        } else if constexpr (std::is_same_v<T, lsc::MultiServoOff>) {
          for (auto id : m.servos) servos_.power_off(id, at);
        } else if constexpr (std::is_same_v<T, lsc::ServoPositionRead>) {
          lsc::ServoPositions r;
          for (auto id : m.servos) {
            if (servos_.has(id)) r.servos.push_back({id, servos_.position(id, at)});
          }
          reply(r);
        } else if constexpr (std::is_same_v<T, lsc::ServoOffsetWrite>) {
          for (auto id : m.servos) servos_.write_offset(id);
        } else if constexpr (std::is_same_v<T, lsc::ServoOffsetRead>) {
          lsc::ServoOffsets r;
          for (auto id : m.servos) {
            if (servos_.has(id)) r.servos.push_back({id, servos_.offset(id)});
          }
          reply(r);
        } else if constexpr (std::is_same_v<T, lsc::ServoOffsetAdjust>) {
          if (m.offset >= std::numeric_limits<std::int8_t>::min() &&
              m.offset <= std::numeric_limits<std::int8_t>::max()) {
            servos_.adjust_offset(m.servo, static_cast<std::int8_t>(m.offset));
          }
        } else if constexpr (std::is_same_v<T, lsc::ServoSpeed>) {
          servos_.set_mode(m.servo, m.mode, m.milliseconds);
        } else if constexpr (std::is_same_v<T, lsc::BusServoInfoWrite>) {
          if (m.id_only) {
            servos_.write_id(m.servo);
          } else {
            servos_.write_limits(m.limits);
          }
        } else if constexpr (std::is_same_v<T, lsc::BusServoInfoRead>) {
          const std::vector<std::uint8_t> ids = servos_.ids();
          if (ids.empty()) return;
          const std::uint8_t first = ids.front();
          lsc::BusServoInfo r;
          r.id = first;
          r.limits = servos_.limits(first);
          r.offset = servos_.offset(first);
          r.position = servos_.position(first, at);
          r.temp = config_.servo_temperature_c;
          r.millivolts = config_.battery_mv;
          reply(r);
        }
        // GroupDownload requests never get here (handled above by frame.cmd).
      },
      *request);
  return p;
}

void XArmEmulator::emit(const lsc::Frame& frame, io::TimePoint ready) {
  if (hung_up_ || faults_.silent()) return;
  auto bytes = lsc::encode_serial(frame);
  if (!bytes) return;
  const OutgoingFault fault = faults_.on_reply();
  if (fault.corrupt) FaultInjector::flip(*bytes, fault.corrupt_where);
  if (fault.late) ready += config_.faults.late_by;
  if (fault.duplicate) line_.send(*bytes, ready);
  if (fault.split && bytes->size() >= 2) {
    // Two messages back to back on the line: the host is handed the first piece on its own.
    const auto cut =
        1 + static_cast<std::ptrdiff_t>(fault.split_where * static_cast<double>(bytes->size() - 1));
    line_.send(Bytes(bytes->begin(), bytes->begin() + cut), ready);
    line_.send(Bytes(bytes->begin() + cut, bytes->end()), ready);
    return;
  }
  line_.send(std::move(*bytes), ready);
}

void XArmEmulator::advance_to(io::TimePoint t) {
  if (t <= now_) return;
  for (auto& n : player_.advance_to(t, servos_)) {
    if (auto f = reply_frame(n.message)) emit(*f, n.at);
  }
  now_ = t;
}

std::optional<io::TimePoint> XArmEmulator::next_output_at() const {
  if (hung_up_) return std::nullopt;
  std::optional<io::TimePoint> next = line_.next_byte_at();
  if (auto n = player_.next_notification_at(); n && !faults_.silent()) {
    const io::TimePoint first_byte = std::max(*n, now_) + line_.byte_time();
    if (!next || first_byte < *next) next = first_byte;
  }
  return next;
}

std::optional<io::TimePoint> XArmEmulator::next_message_end_at() const {
  if (hung_up_) return std::nullopt;
  std::optional<io::TimePoint> next = line_.front_last_byte_at();
  if (auto n = player_.next_notification_at(); n && !faults_.silent()) {
    const io::TimePoint first_byte = std::max(*n, now_) + line_.byte_time();
    if (!next || first_byte < *next) next = first_byte;
  }
  return next;
}

Bytes XArmEmulator::take_output(io::TimePoint upto) {
  advance_to(upto);
  if (hung_up_) return {};
  return line_.take(upto);
}

std::optional<std::vector<lsc::GroupAction>> XArmEmulator::stored_group(std::uint8_t group) const {
  return store_.group(group);
}

std::uint16_t XArmEmulator::servo_position(std::uint8_t id, io::TimePoint at) const {
  return servos_.position(id, at);
}

bool XArmEmulator::pose_by_hand(std::uint8_t id, std::uint16_t position, io::TimePoint at) {
  advance_to(std::max(at, now_));
  return servos_.pose_by_hand(id, position, std::max(at, now_));
}

std::optional<io::TimePoint> XArmEmulator::back_at() const {
  if (!hung_up_ || !config_.faults.back_after) return std::nullopt;
  return hung_up_at_ + *config_.faults.back_after;
}

bool XArmEmulator::reconnect(io::TimePoint at) {
  if (!hung_up_) return true;
  const auto back = back_at();
  if (!back || at < *back) return false;
  at = std::max(at, now_);
  advance_to(at);
  hung_up_ = false;
  framer_.reset();
  line_.clear();
  return true;
}

void XArmEmulator::power_cycle(io::TimePoint at) {
  at = std::max(at, now_);
  advance_to(at);
  servos_.power_cycle(at);
  player_.stop();
  downloader_.abort();
  std::fill(speeds_.begin(), speeds_.end(), std::uint16_t{100});
  line_.clear();
  framer_.reset();
  busy_until_ = at;
}

}  // namespace seqc::emu
