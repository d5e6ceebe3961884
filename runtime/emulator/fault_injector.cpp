#include "runtime/emulator/fault_injector.hpp"

namespace seqc::emu {

std::uint64_t SplitMix64::next() {
  std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

double SplitMix64::unit() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

// The outgoing stream gets its own seed so that adding a reply never changes which incoming
// frames are dropped.
FaultInjector::FaultInjector(const XArmFaults& faults)
    : faults_(faults),
      in_(faults.seed),
      out_(faults.seed ^ 0x6a09e667f3bcc908ULL),
      extra_(faults.seed ^ 0xbb67ae8584caa73bULL) {}

IncomingFault FaultInjector::on_request() {
  IncomingFault f;
  f.number = ++frames_;
  const double drop = in_.unit();
  const double corrupt = in_.unit();
  const double where = in_.unit();
  if (faults_.hangup_at && f.number == *faults_.hangup_at) f.hangup = true;
  if (faults_.silent_after && f.number > *faults_.silent_after) silent_ = true;
  f.silent = silent_;
  f.drop = drop < faults_.drop;
  f.corrupt = !f.drop && corrupt < faults_.corrupt;
  f.corrupt_where = where;
  const double reset = extra_.unit();
  const double busy = extra_.unit();
  f.reset = reset < faults_.reset || (faults_.reset_at && f.number == *faults_.reset_at);
  f.busy = busy < faults_.busy;
  return f;
}

OutgoingFault FaultInjector::on_reply() {
  ++replies_;
  OutgoingFault f;
  f.late = out_.unit() < faults_.late_ack;
  f.duplicate = out_.unit() < faults_.duplicate_ack;
  f.corrupt = out_.unit() < faults_.corrupt;
  f.corrupt_where = out_.unit();
  // Drawn only when asked for, so the other faults' draws stay as they were for a given seed.
  if (faults_.split > 0) {
    f.split = out_.unit() < faults_.split;
    f.split_where = out_.unit();
  }
  return f;
}

std::size_t FaultInjector::flip_index(std::size_t size, double where) {
  const auto i = static_cast<std::size_t>(where * static_cast<double>(size));
  return i >= size ? size - 1 : i;
}

std::size_t FaultInjector::flip(Bytes& frame, double where) {
  if (frame.empty()) return 0;
  const std::size_t i = flip_index(frame.size(), where);
  frame[i] = static_cast<std::uint8_t>(frame[i] ^ 0xff);
  return i;
}

}  // namespace seqc::emu
