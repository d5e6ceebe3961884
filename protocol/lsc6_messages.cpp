#include "protocol/lsc6/lsc6_messages.hpp"

#include <string>

#include "protocol/lsc/lsc_fields.hpp"

namespace seqc::lsc6 {
namespace {

using lsc::detail::FieldReader;
using lsc::detail::FieldWriter;

constexpr std::uint8_t cmd_of(Command c) { return static_cast<std::uint8_t>(c); }
// The receiver never completes a frame whose LEN is 254 or 255 (its byte counter wraps before
// reaching LEN + 2) and swallows the frames that follow: the encoder never produces one.
constexpr std::size_t kMaxSafeData = 253 - 2;

Status check_time(std::uint16_t t, const std::string& what) {
  if (t < kMinTime || t > kMaxTime) {
    return make_error(what + ": time " + std::to_string(t) + " ms is outside " +
                      std::to_string(kMinTime) + ".." + std::to_string(kMaxTime) +
                      " (the board would change it)");
  }
  return Ok{};
}

Status check_targets(const std::vector<Target>& servos, const std::string& what) {
  for (const Target& t : servos) {
    if (t.id < kFirstChannel || t.id > kLastChannel) {
      return make_error(what + ": channel " + std::to_string(t.id) +
                        " is not one of the board's outputs 1..6");
    }
    if (t.position < kMinPulse || t.position > kMaxPulse) {
      return make_error(what + ": pulse " + std::to_string(t.position) + " us for channel " +
                        std::to_string(t.id) + " is outside 500..2500 (the board ignores it)");
    }
  }
  return Ok{};
}

void write_action(FieldWriter& w, std::uint16_t time_ms, const std::vector<Target>& servos) {
  w.u8(static_cast<std::uint8_t>(servos.size())).u16(time_ms);
  for (const Target& t : servos) w.u8(t.id).u16(t.position);
}

Result<Frame> finish(FieldWriter& w, const std::string& what) {
  auto frame = w.finish(what);
  if (frame && frame->data.size() > kMaxSafeData) {
    return make_error(what + ": " + std::to_string(frame->data.size()) +
                      " data bytes would make LEN 254 or more, which wedges the board's receiver");
  }
  return frame;
}

Result<Frame> encode_one(const Move& m) {
  if (m.servos.empty()) return make_error("Move: no servos");
  if (auto ok = check_time(m.time_ms, "Move"); !ok) return ok.error();
  if (auto ok = check_targets(m.servos, "Move"); !ok) return ok.error();
  FieldWriter w(cmd_of(Command::Move));
  write_action(w, m.time_ms, m.servos);
  return finish(w, "Move");
}
Result<Frame> encode_one(const Run& m) {
  FieldWriter w(cmd_of(Command::Run));
  w.u8(m.group).u16(m.times);
  return w.finish("Run");
}
Result<Frame> encode_one(const Stop&) { return Frame{cmd_of(Command::Stop), {}}; }
Result<Frame> encode_one(const EraseAll&) { return Frame{cmd_of(Command::EraseAll), {}}; }
Result<Frame> encode_one(const DownloadAction& m) {
  const std::string what = "DownloadAction";
  if (m.total == 0 || m.index >= m.total) {
    return make_error(what + ": index " + std::to_string(m.index) + " is not below total " +
                      std::to_string(m.total));
  }
  if (m.servos.size() > kMaxServosPerAction) {
    return make_error(what + ": " + std::to_string(m.servos.size()) +
                      " servos; the board plays at most 8 per action");
  }
  if (auto ok = check_time(m.time_ms, what); !ok) return ok.error();
  if (auto ok = check_targets(m.servos, what); !ok) return ok.error();
  FieldWriter w(cmd_of(Command::DownloadAction));
  w.u8(m.group).u8(m.total).u8(m.index);
  write_action(w, m.time_ms, m.servos);
  return w.finish(what);
}

// N tLo tHi {id pLo pHi}xN from the reader, exactly filling what is left.
Result<std::vector<Target>> read_action(FieldReader& r, std::uint16_t& time_ms,
                                        const std::string& what) {
  if (r.remaining() < 3) return make_error(what + ": missing the count and time");
  const std::uint8_t n = r.u8();
  time_ms = r.u16();
  if (r.remaining() != 3u * n) {
    return make_error(what + ": count " + std::to_string(n) + " needs " + std::to_string(3u * n) +
                      " bytes of servos, got " + std::to_string(r.remaining()));
  }
  std::vector<Target> servos;
  for (unsigned i = 0; i < n; ++i) {
    Target t;
    t.id = r.u8();
    t.position = r.u16();
    servos.push_back(t);
  }
  return servos;
}

Status expect_empty(const Frame& f, const std::string& what) {
  if (!f.data.empty()) {
    return make_error(what + ": expected no data, got " + std::to_string(f.data.size()) + " bytes");
  }
  return Ok{};
}

std::string targets_text(const std::vector<Target>& servos) {
  std::string out = "servos=[";
  for (std::size_t i = 0; i < servos.size(); ++i) {
    if (i != 0) out += ' ';
    out += "{ch=" + std::to_string(servos[i].id) + " pulse=" + std::to_string(servos[i].position) +
           "}";
  }
  return out + "]";
}

}  // namespace

Result<Frame> encode(const Request& request) {
  return std::visit([](const auto& m) { return encode_one(m); }, request);
}

Frame encode(const Reply& reply) {
  const Command cmd = std::visit(
      [](const auto& m) -> Command {
        using T = std::decay_t<decltype(m)>;
        if constexpr (std::is_same_v<T, RunAccepted>) return Command::Run;
        if constexpr (std::is_same_v<T, GroupFinished>) return Command::Stop;
        if constexpr (std::is_same_v<T, Erased>) return Command::EraseAll;
        return Command::DownloadAction;
      },
      reply);
  return Frame{cmd_of(cmd), {}};
}

Result<Request> decode_request(const Frame& f) {
  FieldReader r(f.data);
  switch (static_cast<Command>(f.cmd)) {
    case Command::Move: {
      Move m;
      auto servos = read_action(r, m.time_ms, "Move");
      if (!servos) return servos.error();
      m.servos = std::move(servos).value();
      return Request{m};
    }
    case Command::Run:
      if (f.data.size() != 3) {
        return make_error("Run: expected 3 data bytes, got " + std::to_string(f.data.size()));
      }
      return Request{Run{r.u8(), r.u16()}};
    case Command::Stop:
      if (auto ok = expect_empty(f, "Stop"); !ok) return ok.error();
      return Request{Stop{}};
    case Command::EraseAll:
      // The board erases every group whatever follows the command byte.
      return Request{EraseAll{}};
    case Command::DownloadAction: {
      if (f.data.size() < 3) return make_error("DownloadAction: missing group, total and index");
      DownloadAction a;
      a.group = r.u8();
      a.total = r.u8();
      a.index = r.u8();
      auto servos = read_action(r, a.time_ms, "DownloadAction");
      if (!servos) return servos.error();
      a.servos = std::move(servos).value();
      return Request{a};
    }
  }
  return make_error("command " + std::to_string(f.cmd) + " is not in the LSC-6 dialect");
}

Result<Reply> decode_reply(const Frame& f) {
  if (!f.data.empty()) {
    return make_error("an LSC-6 answer has no data, got " + std::to_string(f.data.size()) +
                      " bytes after command " + std::to_string(f.cmd));
  }
  switch (static_cast<Command>(f.cmd)) {
    case Command::Run:
      return Reply{RunAccepted{}};
    case Command::Stop:
      return Reply{GroupFinished{}};
    case Command::EraseAll:
      return Reply{Erased{}};
    case Command::DownloadAction:
      return Reply{ActionStored{}};
    case Command::Move:
      break;
  }
  return make_error("command " + std::to_string(f.cmd) + " is no LSC-6 answer");
}

Result<Bytes> encode_serial(const Request& request) {
  auto frame = encode(request);
  if (!frame) return frame.error();
  return lsc::encode_serial(*frame);
}

Bytes encode_serial(const Reply& reply) { return lsc::encode_serial(encode(reply)).value(); }

std::string describe(const Request& request) {
  return std::visit(
      [](const auto& m) -> std::string {
        using T = std::decay_t<decltype(m)>;
        if constexpr (std::is_same_v<T, Move>) {
          return "Move time=" + std::to_string(m.time_ms) + " " + targets_text(m.servos);
        } else if constexpr (std::is_same_v<T, Run>) {
          return "Run group=" + std::to_string(m.group) + " times=" + std::to_string(m.times);
        } else if constexpr (std::is_same_v<T, Stop>) {
          return "Stop";
        } else if constexpr (std::is_same_v<T, EraseAll>) {
          return "EraseAll";
        } else {
          return "DownloadAction group=" + std::to_string(m.group) +
                 " total=" + std::to_string(m.total) + " index=" + std::to_string(m.index) +
                 " time=" + std::to_string(m.time_ms) + " " + targets_text(m.servos);
        }
      },
      request);
}

std::string describe(const Reply& reply) {
  return std::visit(
      [](const auto& m) -> std::string {
        using T = std::decay_t<decltype(m)>;
        if constexpr (std::is_same_v<T, RunAccepted>) return "RunAccepted";
        if constexpr (std::is_same_v<T, GroupFinished>) return "GroupFinished";
        if constexpr (std::is_same_v<T, Erased>) return "Erased";
        return "ActionStored";
      },
      reply);
}

Result<std::vector<DownloadAction>> plan_download(std::uint8_t group,
                                                  const std::vector<PlannedAction>& actions) {
  if (actions.empty()) return make_error("there are no actions to store");
  if (actions.size() > kMaxActions) {
    return make_error(std::to_string(actions.size()) +
                      " actions do not fit one LSC-6 group (at most 255)");
  }
  std::vector<DownloadAction> plan;
  for (std::size_t i = 0; i < actions.size(); ++i) {
    const PlannedAction& a = actions[i];
    const std::string what = "action " + std::to_string(i + 1);
    if (a.servos.size() > kMaxServosPerAction) {
      return make_error(what + " moves " + std::to_string(a.servos.size()) +
                        " servos; the LSC-6 stops playing at an action with more than 8");
    }
    DownloadAction d{group, static_cast<std::uint8_t>(actions.size()), static_cast<std::uint8_t>(i),
                     a.time_ms, a.servos};
    if (auto frame = encode(Request{d}); !frame) {
      return make_error(what + ": " + frame.error().message);
    }
    plan.push_back(std::move(d));
  }
  return plan;
}

}  // namespace seqc::lsc6
