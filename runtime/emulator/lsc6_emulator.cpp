#include "runtime/emulator/lsc6_emulator.hpp"

#include <algorithm>
#include <charconv>
#include <string>

#include "runtime/emulator/board_clock.hpp"

namespace seqc::emu {
namespace {

using lsc6::Command;

constexpr std::uint8_t kErased = 0xff;
constexpr std::size_t kSlotsPerGroup = 256;
// The firmware counts time in 1 ms ticks: an action stored with time 0 still lasts one pass of
// its main loop, modelled as one tick so that a loop of such actions cannot stall time.
constexpr io::Duration kTick = std::chrono::milliseconds(1);

io::Duration ms(unsigned v) { return std::chrono::milliseconds(v); }

std::string_view trim(std::string_view s) {
  while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
  while (!s.empty() && s.back() == ' ') s.remove_suffix(1);
  return s;
}

constexpr Lsc6OptionKey kOptionKeys[] = {
    {"drop", "P", "a completed frame is lost"},
    {"no-run-reply", "", "Run is never answered (some firmware copies)"},
    {"no-finish", "", "the end of a counted run is never announced (some firmware copies)"},
    {"seed", "N", "seed of drop (1)"},
    {"clock", "ERR",
     "the board's clock is this fast or slow (+0.8%, -1%, +120ppm): its actions and moves "
     "take that much less or more time"},
    {"baud", "N", "the line's rate", false},
};

}  // namespace

std::span<const Lsc6OptionKey> lsc6_option_keys() { return kOptionKeys; }

Status apply_lsc6_options(std::string_view spec, Lsc6Config& config) {
  while (!spec.empty()) {
    const std::size_t comma = spec.find(',');
    const std::string_view item = trim(spec.substr(0, comma));
    spec = comma == std::string_view::npos ? std::string_view{} : spec.substr(comma + 1);
    if (item.empty()) continue;
    const std::size_t eq = item.find('=');
    const std::string_view key = item.substr(0, eq);
    const std::string value(eq == std::string_view::npos ? "" : item.substr(eq + 1));
    auto bad = [&](const std::string& why) {
      return make_error("emu:lsc6 option '" + std::string(item) + "': " + why);
    };
    const bool known = std::any_of(std::begin(kOptionKeys), std::end(kOptionKeys),
                                   [&](const Lsc6OptionKey& k) { return k.key == key; });
    if (!known) {
      return bad("unknown; expected drop=P, seed=N, clock=ERR, baud=N, no-run-reply or no-finish");
    }
    if (key == "no-run-reply" && eq == std::string_view::npos) {
      config.run_reply = false;
    } else if (key == "no-finish" && eq == std::string_view::npos) {
      config.finish_notice = false;
    } else if (key == "drop") {
      char* end = nullptr;
      const double p = std::strtod(value.c_str(), &end);
      if (value.empty() || *end != '\0' || !(p >= 0.0 && p <= 1.0)) {
        return bad("expected a fraction 0..1");
      }
      config.drop = p;
    } else if (key == "clock") {
      auto ppm = parse_clock_error(value);
      if (!ppm) return bad(ppm.error().message);
      config.clock_ppm = *ppm;
    } else if (key == "seed" || key == "baud") {
      std::uint64_t v = 0;
      const auto [ptr, ec] = std::from_chars(value.data(), value.data() + value.size(), v);
      if (value.empty() || ec != std::errc{} || ptr != value.data() + value.size()) {
        return bad("expected a whole number");
      }
      if (key == "seed") {
        config.seed = v;
      } else {
        if (v > 4000000) return bad("baud rate too high");
        config.baud = static_cast<std::uint32_t>(v);
      }
    } else {
      return bad("unknown; expected drop=P, seed=N, clock=ERR, baud=N, no-run-reply or no-finish");
    }
  }
  return Ok{};
}

Lsc6Emulator::Lsc6Emulator(Lsc6Config config)
    : config_(config), rng_(config.seed), line_(config.baud), slots_(256) {}

void Lsc6Emulator::receive(ByteView bytes, io::TimePoint at) {
  for (std::uint8_t b : bytes) {
    advance_to(at);
    received_bytes_.push_back(b);
    feed_byte(b, std::max(at, now_));
  }
  advance_to(at);  // an idle main loop takes a completed frame at once
}

// The interrupt routine, byte for byte (docs/protocol/lsc-6.md, "Receiver").
void Lsc6Emulator::feed_byte(std::uint8_t b, io::TimePoint at) {
  if (!frame_start_) {
    if (b == 0x55) {
      if (++start_count_ == 2) {
        start_count_ = 0;
        frame_start_ = true;
        msg_len_ = 1;
      }
    } else {
      msg_len_ = 0;
      start_count_ = 0;
    }
  }
  if (!frame_start_) return;
  rx_[msg_len_] = b;
  if (msg_len_ == 2) {
    expected_ = b;
    if (expected_ < 2) {
      expected_ = 2;
      frame_start_ = false;
    }
  }
  ++msg_len_;  // a byte: wraps at 256, which is why LEN 254/255 never completes
  if (msg_len_ == expected_ + 2) {
    complete_frame(at);
    frame_start_ = false;
  }
}

void Lsc6Emulator::complete_frame(io::TimePoint at) {
  Lsc6Received r;
  r.at = at;
  r.raw.push_back(0x55);
  r.raw.insert(r.raw.end(), rx_.begin() + 1, rx_.begin() + msg_len_);
  if (config_.drop > 0 && rng_.unit() < config_.drop) {
    r.dropped_fault = true;
    r.dropped = DropReason::FaultDrop;
  } else if (held_since_) {
    r.dropped_busy = true;
    r.dropped = DropReason::Busy;
  } else {
    std::copy_n(rx_.begin(), msg_len_, cmd_.begin());
    held_since_ = at;
  }
  received_.push_back(std::move(r));
}

std::optional<io::TimePoint> Lsc6Emulator::next_playback_event() const {
  if (!playing_) return std::nullopt;
  return playing_->action_end;
}

void Lsc6Emulator::advance_to(io::TimePoint t) {
  for (;;) {
    std::optional<io::TimePoint> cmd_at;
    if (held_since_) cmd_at = std::max(*held_since_, busy_until_);
    const std::optional<io::TimePoint> play_at = next_playback_event();
    const bool cmd_due = cmd_at && *cmd_at <= t;
    const bool play_due = play_at && *play_at <= t;
    if (!cmd_due && !play_due) break;
    if (cmd_due && (!play_due || *cmd_at <= *play_at)) {
      now_ = std::max(now_, *cmd_at);
      held_since_.reset();
      busy_until_ = *cmd_at + process(*cmd_at);
    } else {
      now_ = std::max(now_, *play_at);
      play_until(*play_at);
    }
  }
  now_ = std::max(now_, t);
}

// Every answer of this firmware is 55 55 02 <cmd>.
void Lsc6Emulator::answer(Command cmd, io::TimePoint ready) {
  line_.send(Bytes{0x55, 0x55, 0x02, static_cast<std::uint8_t>(cmd)}, ready);
}

// One command from the buffer, as the main loop's handler; returns how long it keeps the loop.
io::Duration Lsc6Emulator::process(io::TimePoint at) {
  auto byte = [this](std::size_t i) -> std::uint8_t { return i < cmd_.size() ? cmd_[i] : 0; };
  const io::Duration answer_time = 4 * line_.byte_time();
  switch (static_cast<Command>(cmd_[3])) {
    case Command::Move: {
      const std::uint8_t n = byte(4);
      const auto time = static_cast<std::uint16_t>(byte(5) | (byte(6) << 8));
      for (std::size_t i = 0; i < n; ++i) {
        set_servo(byte(7 + 3 * i),
                  static_cast<std::uint16_t>(byte(8 + 3 * i) | (byte(9 + 3 * i) << 8)), time, at);
      }
      return io::Duration{0};
    }
    case Command::Run: {
      if (config_.run_reply) answer(Command::Run, at);
      full_act_run(byte(4), static_cast<std::uint16_t>(byte(5) | (byte(6) << 8)), at);
      return config_.run_reply ? answer_time : io::Duration{0};
    }
    case Command::Stop:
      playing_.reset();
      return io::Duration{0};
    case Command::EraseAll: {
      counts_.fill(0);
      const io::Duration d = config_.sector_erase + config_.table_write;
      answer(Command::EraseAll, at + d);
      return d + answer_time;
    }
    case Command::DownloadAction: {
      const std::uint8_t group = byte(4);
      const std::uint8_t total = byte(5);
      const std::uint8_t index = byte(6);
      io::Duration d{0};
      auto& slots = slots_[group];
      if (index == 0) {
        slots.clear();  // four 4 KiB sectors: the group's 256 slots read 0xff again
        d += 4 * config_.sector_erase;
      }
      if (slots.empty()) {
        slots.resize(kSlotsPerGroup);
        for (auto& s : slots) s.fill(kErased);
      }
      for (std::size_t k = 0; k < lsc6::kSlotBytes; ++k) slots[index][k] &= byte(7 + k);
      d += config_.slot_write;
      if (index + 1 == total) {
        counts_[group] = total;
        d += config_.sector_erase + config_.table_write;
      }
      answer(Command::DownloadAction, at + d);
      return d + answer_time;
    }
  }
  return io::Duration{0};  // unknown commands are ignored
}

void Lsc6Emulator::set_servo(std::uint8_t channel, std::uint16_t pulse, std::uint16_t time_ms,
                             io::TimePoint at) {
  if (channel >= channels_.size() || pulse < lsc6::kMinPulse || pulse > lsc6::kMaxPulse) return;
  const std::uint16_t t = std::clamp(time_ms, lsc6::kMinTime, lsc6::kMaxTime);
  Channel& c = channels_[channel];
  c.from = this->pulse(channel, at);
  c.to = pulse;
  c.start = at;
  c.duration = board_ms(t);
}

io::Duration Lsc6Emulator::board_ms(unsigned v) const {
  return board_to_host(ms(v), config_.clock_ppm);
}

std::uint16_t Lsc6Emulator::pulse(std::uint8_t channel, io::TimePoint at) const {
  if (channel >= channels_.size()) return 0;
  const Channel& c = channels_[channel];
  if (at >= c.start + c.duration || c.duration.count() == 0) return c.to;
  if (at <= c.start) return c.from;
  const double f = std::chrono::duration<double>(at - c.start) / c.duration;
  return static_cast<std::uint16_t>(c.from + (c.to - c.from) * f + 0.5);
}

// The firmware's FullActRun: an empty group does nothing; a run of another group while one
// plays is ignored unless it is group 0; a run of the playing group only changes its count.
void Lsc6Emulator::full_act_run(std::uint8_t group, std::uint16_t times, io::TimePoint at) {
  const std::uint8_t count = counts_[group];
  if (count == 0) return;
  if (playing_) playing_->count = count;
  if (last_group_ != group) {
    if (group == 0) playing_.reset();
  } else if (playing_) {
    playing_->times = times;
  }
  if (playing_) return;
  last_group_ = group;
  playing_ = Playback{group, times, 0, count, 0, at};
  playing_->action_end = at + play_action(at);
}

// Starts the current action; returns how long it lasts. Stops playback at an unplayable one.
io::Duration Lsc6Emulator::play_action(io::TimePoint at) {
  const auto& slots = slots_[playing_->group];
  std::array<std::uint8_t, lsc6::kSlotBytes> slot{};
  if (slots.empty()) {
    slot.fill(kErased);
  } else {
    slot = slots[playing_->index];
  }
  const std::uint8_t n = slot[0];
  const auto time = static_cast<std::uint16_t>(slot[1] | (slot[2] << 8));
  if (n > lsc6::kMaxServosPerAction) {
    playing_.reset();
    return io::Duration{0};
  }
  for (std::size_t i = 0; i < n; ++i) {
    set_servo(slot[3 + 3 * i], static_cast<std::uint16_t>(slot[4 + 3 * i] | (slot[5 + 3 * i] << 8)),
              time, at);
  }
  return std::max(board_ms(time), kTick);
}

// The action that ends at `at` is over: the next one, the next loop, or the end of the run.
void Lsc6Emulator::play_until(io::TimePoint at) {
  Playback& p = *playing_;
  if (++p.index >= p.count) {
    p.index = 0;
    if (p.times != 0 && ++p.loops >= p.times) {
      const std::uint8_t group = p.group;
      playing_.reset();
      if (config_.finish_notice) answer(Command::Stop, at);
      if (group == 100) full_act_run(101, 1, at);  // the firmware chains these two
      return;
    }
  }
  const io::Duration d = play_action(at);
  if (playing_) playing_->action_end = at + d;
}

// The earlier of `line_time` and the next moment the board may start sending: a held command
// being processed or a run ending (a lower bound, as ControllerDevice allows).
std::optional<io::TimePoint> Lsc6Emulator::earliest_with_pending(
    std::optional<io::TimePoint> line_time) const {
  std::optional<io::TimePoint> next = line_time;
  auto earliest = [&next](std::optional<io::TimePoint> t) {
    if (t && (!next || *t < *next)) next = t;
  };
  if (held_since_) earliest(std::max(*held_since_, busy_until_));
  earliest(next_playback_event());
  return next;
}

std::optional<io::TimePoint> Lsc6Emulator::next_output_at() const {
  return earliest_with_pending(line_.next_byte_at());
}

std::optional<io::TimePoint> Lsc6Emulator::next_message_end_at() const {
  return earliest_with_pending(line_.front_last_byte_at());
}

Bytes Lsc6Emulator::take_output(io::TimePoint upto) {
  advance_to(upto);
  return line_.take(upto);
}

std::optional<std::vector<lsc6::PlannedAction>> Lsc6Emulator::stored_group(
    std::uint8_t group) const {
  const std::uint8_t count = counts_[group];
  if (count == 0) return std::nullopt;
  std::vector<lsc6::PlannedAction> out;
  for (std::size_t i = 0; i < count; ++i) {
    std::array<std::uint8_t, lsc6::kSlotBytes> slot{};
    if (slots_[group].empty()) {
      slot.fill(kErased);
    } else {
      slot = slots_[group][i];
    }
    lsc6::PlannedAction a;
    a.time_ms = static_cast<std::uint16_t>(slot[1] | (slot[2] << 8));
    const std::size_t n = std::min<std::size_t>(slot[0], (lsc6::kSlotBytes - 3) / 3);
    for (std::size_t k = 0; k < n; ++k) {
      a.servos.push_back(
          {slot[3 + 3 * k], static_cast<std::uint16_t>(slot[4 + 3 * k] | (slot[5 + 3 * k] << 8))});
    }
    out.push_back(std::move(a));
  }
  return out;
}

std::optional<std::uint8_t> Lsc6Emulator::playing_group() const {
  if (!playing_) return std::nullopt;
  return playing_->group;
}

bool Lsc6Emulator::receiver_wedged() const { return frame_start_ && expected_ >= 254; }

void Lsc6Emulator::power_cycle(io::TimePoint at) {
  advance_to(at);
  frame_start_ = false;
  start_count_ = 0;
  msg_len_ = 0;
  expected_ = 2;
  held_since_.reset();
  playing_.reset();
  last_group_ = 0;
  channels_ = {};
  line_.clear();
  busy_until_ = at;
}

}  // namespace seqc::emu
