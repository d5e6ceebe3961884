#include "runtime/upload/trace_transport.hpp"

#include <cstdio>
#include <ostream>

namespace seqc::upload {

TraceTransport::TraceTransport(io::Transport& inner, io::Clock& clock, std::ostream& out,
                               const Dialect* dialect)
    : inner_(inner), clock_(clock), out_(out), start_(clock.now()) {
  out_ << "# seqc trace of " << inner_.describe() << "; t in seconds, > to the device, < from it\n";
  if (dialect != nullptr) out_ << "# dialect: " << dialect->name << "\n";
  out_.flush();
}

void TraceTransport::line(char direction, const std::string& text) {
  const double t = std::chrono::duration<double>(clock_.now() - start_).count();
  char stamp[40];
  std::snprintf(stamp, sizeof stamp, "t=%.6f %c ", t, direction);
  out_ << stamp << text << '\n';
  // Flushed per line: a trace is most useful exactly when seqc is killed half way.
  out_.flush();
}

Status TraceTransport::write(ByteView bytes) {
  line('>', to_hex(bytes));
  auto st = inner_.write(bytes);
  if (!st) line('#', "write failed: " + st.error().message);
  return st;
}

io::ReadResult TraceTransport::read(std::span<std::uint8_t> buffer, io::TimePoint deadline) {
  io::ReadResult r = inner_.read(buffer, deadline);
  switch (r.status) {
    case io::ReadStatus::Data:
      line('<', to_hex(ByteView(buffer.data(), r.count)));
      break;
    case io::ReadStatus::HangUp:
      line('<', "hang-up");
      break;
    case io::ReadStatus::Error:
      line('#', "read failed: " + r.message);
      break;
    case io::ReadStatus::Timeout:
      break;
  }
  return r;
}

bool TraceTransport::reopen(io::TimePoint deadline) {
  const bool back = inner_.reopen(deadline);
  line('#', back ? "reopened the device" : "the device did not come back");
  return back;
}

void TraceTransport::discard_input() {
  line('#', "discarded pending input");
  inner_.discard_input();
}

}  // namespace seqc::upload
