#include "runtime/emulator/emulator_transport.hpp"

#include <algorithm>

namespace seqc::emu {

EmulatorTransport::EmulatorTransport(ControllerDevice& emulator, io::ManualClock& clock)
    : emu_(emulator), clock_(clock), input_(emulator.baud()) {}

double EmulatorTransport::seconds_per_byte() const {
  const auto baud = emu_.baud();
  return baud == 0 ? 0.0 : 10.0 / baud;
}

Status EmulatorTransport::write(ByteView bytes) {
  if (emu_.hung_up()) return make_error(emu_.port_name() + ": the link has hung up");
  const io::TimePoint arrived = input_.push(bytes, clock_.now());
  clock_.sleep_until(arrived);
  for (const InputLine::Arrival& a : input_.take(arrived)) {
    if (emu_.hung_up()) break;
    emu_.receive(a.bytes, a.at);
  }
  input_.clear();  // only left over after a hang-up
  return Ok{};
}

io::ReadResult EmulatorTransport::deliver(std::span<std::uint8_t> buffer) {
  const std::size_t n = std::min(buffer.size(), inbox_.size());
  std::copy_n(inbox_.begin(), n, buffer.begin());
  inbox_.erase(inbox_.begin(), inbox_.begin() + static_cast<std::ptrdiff_t>(n));
  return io::ReadResult{io::ReadStatus::Data, n, {}};
}

io::ReadResult EmulatorTransport::read(std::span<std::uint8_t> buffer, io::TimePoint deadline) {
  if (buffer.empty()) return io::ReadResult{io::ReadStatus::Error, 0, "empty read buffer"};
  while (true) {
    if (!inbox_.empty()) return deliver(buffer);
    if (emu_.hung_up())
      return io::ReadResult{io::ReadStatus::HangUp, 0, emu_.port_name() + " hung up"};
    Bytes due = emu_.take_output(clock_.now());
    if (!due.empty()) {
      inbox_ = std::move(due);
      continue;
    }
    const auto next = emu_.next_output_at();
    if (!next) break;
    // next_output_at() may be a lower bound (a notification not yet on the line): advance
    // and look again; each round moves the clock forward.
    const io::TimePoint target = std::max(*next, clock_.now() + io::Duration{1});
    if (target > deadline) break;
    clock_.sleep_until(target);
  }
  clock_.sleep_until(deadline);
  emu_.advance_to(clock_.now());
  return io::ReadResult{io::ReadStatus::Timeout, 0, {}};
}

bool EmulatorTransport::reopen(io::TimePoint deadline) {
  if (!emu_.hung_up()) return true;
  const auto back = emu_.back_at();
  if (!back || *back > deadline) {
    clock_.sleep_until(deadline);
    return false;
  }
  clock_.sleep_until(*back);
  inbox_.clear();
  input_.clear();
  return emu_.reconnect(clock_.now());
}

void EmulatorTransport::discard_input() {
  inbox_.clear();
  (void)emu_.take_output(clock_.now());
}

}  // namespace seqc::emu
