#include "runtime/follow/multisync_clock.hpp"

#include <chrono>
#include <cmath>
#include <variant>

namespace seqc::follow {
namespace {

std::string_view last_component(std::string_view path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string_view::npos ? path : path.substr(slash + 1);
}

bool has_extension(std::string_view name) {
  const std::string_view base = last_component(name);
  const auto dot = base.find_last_of('.');
  return dot != std::string_view::npos && dot > 0;
}

std::string_view stem(std::string_view base) {
  const auto dot = base.find_last_of('.');
  return dot == std::string_view::npos || dot == 0 ? base : base.substr(0, dot);
}

ShowClockKind kind_of(fpp::SyncAction action) {
  switch (action) {
    case fpp::SyncAction::Open:
      return ShowClockKind::Open;
    case fpp::SyncAction::Start:
      return ShowClockKind::Start;
    case fpp::SyncAction::Stop:
      return ShowClockKind::Stop;
    case fpp::SyncAction::Sync:
      break;
  }
  return ShowClockKind::Sync;
}

}  // namespace

bool names_followed(std::string_view name, std::string_view file_name) {
  const std::string_view base = last_component(file_name);
  if (base.empty()) return false;
  if (has_extension(name)) return base == last_component(name);
  return stem(base) == name;
}

MultisyncClock::MultisyncClock(io::DatagramSocket& socket, io::Clock& clock,
                               MultisyncOptions options)
    : socket_(socket), clock_(clock), options_(std::move(options)) {}

Bytes MultisyncClock::ping_answer() const {
  fpp::PingPacket p;
  p.discover = false;
  p.system_type = fpp::kSystemOther;
  p.major = options_.major;
  p.minor = options_.minor;
  p.mode = fpp::kModeRemote;
  p.address = {0, 0, 0, 0};  // the master records the address the answer came from
  p.hostname = options_.hostname;
  p.version_text = options_.version;
  p.hardware = "seqc";
  return fpp::encode_ping(p);
}

std::optional<ShowClockEvent> MultisyncClock::on_sync(const fpp::SyncPacket& p,
                                                      const io::Datagram& d) {
  const bool sequence = p.file == fpp::SyncFile::Sequence;
  if (!names_followed(options_.name, p.file_name) || (!sequence && heard_sequence_)) {
    ++counts_.other_names;
    return std::nullopt;
  }
  heard_sequence_ = heard_sequence_ || sequence;
  ++counts_.followed;
  ShowClockEvent e;
  e.kind = kind_of(p.action);
  // As FPP's remote: the seconds elapsed when the packet carries them, else the frame.
  e.dance_ms = p.seconds > 0.0001f ? static_cast<double>(p.seconds) * 1000.0
                                   : static_cast<double>(p.frame) * options_.frame_ms;
  e.at = d.at;
  e.detail = std::string(sequence ? "sequence" : "media") + " " + p.file_name + " from " +
             io::address_text(d.from);
  return e;
}

void MultisyncClock::answer(const io::UdpAddress& to) {
  // A flood of discovers gets one answer every kAnswerInterval: seqc amplifies nothing.
  const io::TimePoint now = clock_.now();
  if (answered_at_ && now - *answered_at_ < kAnswerInterval) return;
  answered_at_ = now;
  // To the address and port it came from: a master sends from 32320 and listens there.
  if (const Status sent = socket_.send_to(to, ping_answer()); sent) {
    ++counts_.answered;
  } else {
    counts_.last_error = sent.error().message;
  }
}

std::optional<ShowClockEvent> MultisyncClock::next(io::TimePoint deadline) {
  while (!ended_) {
    io::Received r = socket_.receive(deadline);
    if (r.status == io::ReceiveStatus::Timeout) return std::nullopt;
    if (r.status == io::ReceiveStatus::Error) {
      counts_.last_error = r.message;
      ended_ = true;
      return std::nullopt;
    }
    const Result<fpp::Packet> packet = fpp::decode(r.datagram.bytes);
    if (!packet) {
      ++counts_.malformed;
      counts_.last_error = packet.error().message;
    } else if (const auto* sync = std::get_if<fpp::SyncPacket>(&*packet)) {
      if (auto e = on_sync(*sync, r.datagram)) return e;
    } else if (const auto* ping = std::get_if<fpp::PingPacket>(&*packet)) {
      ++counts_.pings;
      if (ping->discover) answer(r.datagram.from);
    } else {
      ++counts_.other_types;
    }
    if (clock_.now() > deadline) return std::nullopt;  // only packets that are not events came
  }
  return std::nullopt;
}

}  // namespace seqc::follow
