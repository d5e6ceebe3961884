// upload_bench: a 1,020-action, 6-servo upload through the real uploader and SerialTransport to
// the emulated controller served on a pseudo-terminal (PtyServer in a thread, as `seqc emulate
// xarm` serves it, with processing and flash times 0), at 9600 and 115200 baud, in real time.
//
// What is measured and how:
//   wall    steady_clock around Uploader::upload (probe, stop, barriers, steps 1-5).
//   bytes   host -> controller and controller -> host, as the uploader's link counted them,
//           cross-checked with what the emulator received.
//   bound   every byte both ways x 10 bits / baud: the time the wire alone needs, since the
//           upload is stop-and-wait (a frame, then its reply, then the next frame).
//   ratio   wall / bound. The emulator models both directions of the UART: the host's bytes
//           reach the controller one byte time apart (a frame is processed when its last
//           byte has arrived) and replies leave one byte time apart, so the ratio cannot go
//           below 1; what is above 1 is time the line stands idle.
//   idle    where the line stands idle: for each reply, the time from its last byte being
//           due to the host's next bytes being read by the server, split into the server
//           writing that byte late (its wake-up after the due time), the uploader (from the
//           host's read that returned data to its next write, timed around the transport),
//           and the rest: the pty carrying the reply to the host and the request to the
//           server, and both sides waking up.
//
// Usage: upload_bench [--baud N]... [--actions N]   (default: --baud 9600 --baud 115200)
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "runtime/emulator/pty_device.hpp"
#include "runtime/emulator/pty_server.hpp"
#include "runtime/emulator/xarm_emulator.hpp"
#include "runtime/io/clock.hpp"
#include "protocol/lsc/group_download.hpp"
#include "runtime/transport/serial_transport.hpp"
#include "runtime/upload/uploader.hpp"

using namespace seqc;

namespace {

double ms(io::Duration d) { return std::chrono::duration<double, std::milli>(d).count(); }

std::int64_t wall_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// Forwards to the xArm device and times the idle line between a reply and the next request.
// It takes output one wake-up time (next_output_at: a whole reply) at a time, so it knows
// when the last byte handed over was due; the emulator's timeline does not change (it only
// depends on the times the host's bytes were read).
class TimedDevice final : public emu::PtyDevice {
 public:
  explicit TimedDevice(emu::PtyDevice& inner) : inner_(inner) {}

  void receive(ByteView bytes, io::TimePoint at) override {
    if (last_due_) {
      idle_ += io::Duration{wall_ns() - last_written_wall_};
      late_ += last_written_ - *last_due_;
      lates_.push_back(last_written_ - *last_due_);
      ++gaps_;
      last_due_.reset();
    }
    inner_.receive(bytes, at);
  }
  std::optional<io::TimePoint> next_output_at() const override { return inner_.next_output_at(); }
  Bytes take_output(io::TimePoint upto) override {
    Bytes out;
    for (int guard = 0; guard < 10000; ++guard) {
      const auto next = inner_.next_output_at();
      if (!next || *next > upto) break;
      Bytes got = inner_.take_output(*next);
      if (!got.empty()) {
        last_due_ = *next;
        last_written_ = upto;
        last_written_wall_ = wall_ns();
      }
      out.insert(out.end(), got.begin(), got.end());
    }
    Bytes rest = inner_.take_output(upto);
    out.insert(out.end(), rest.begin(), rest.end());
    return out;
  }
  bool hung_up() const override { return inner_.hung_up(); }

  // Due time of each reply's last byte -> the server handing it to the pty.
  io::Duration late() const { return late_; }
  // The server handing a reply's last byte to the pty -> reading the next request from it.
  io::Duration after_write() const { return idle_; }
  std::size_t gaps() const { return gaps_; }
  const std::vector<io::Duration>& lates() const { return lates_; }

 private:
  emu::PtyDevice& inner_;
  std::optional<io::TimePoint> last_due_;
  io::TimePoint last_written_{0};
  std::int64_t last_written_wall_ = 0;
  io::Duration idle_{0};
  io::Duration late_{0};
  std::size_t gaps_ = 0;
  std::vector<io::Duration> lates_;
};

// Forwards to the host's transport and times the uploader itself: from a read that returned
// data to the next write (deciding the reply was the ack, building and sending the next frame).
class TimedTransport final : public io::Transport {
 public:
  explicit TimedTransport(io::Transport& inner) : inner_(inner) {}
  Status write(ByteView bytes) override {
    if (last_read_) {
      host_ += io::Duration{wall_ns() - *last_read_};
      last_read_.reset();
    }
    return inner_.write(bytes);
  }
  io::ReadResult read(std::span<std::uint8_t> buffer, io::TimePoint deadline) override {
    io::ReadResult r = inner_.read(buffer, deadline);
    if (r.status == io::ReadStatus::Data) last_read_ = wall_ns();
    return r;
  }
  void discard_input() override { inner_.discard_input(); }
  std::string describe() const override { return inner_.describe(); }
  double seconds_per_byte() const override { return inner_.seconds_per_byte(); }
  io::Duration host() const { return host_; }

 private:
  io::Transport& inner_;
  std::optional<std::int64_t> last_read_;
  io::Duration host_{0};
};

int bench(std::uint32_t baud, std::size_t count) {
  emu::XArmConfig config;
  config.baud = baud;
  config.command_time = io::Duration{0};
  config.flash_erase_time = io::Duration{0};
  config.flash_write_time = io::Duration{0};
  emu::XArmEmulator emulator(config);
  emu::ControllerPtyDevice xarm(emulator);
  TimedDevice device(xarm);
  auto server = emu::PtyServer::open(emu::PtyOptions{baud, std::nullopt});
  if (!server) {
    std::fprintf(stderr, "upload_bench: %s\n", server.error().message.c_str());
    return 1;
  }
  std::atomic<bool> stop{false};
  io::SteadyClock server_clock;
  std::thread serving([&] { (void)server->serve(device, server_clock, stop); });

  io::SteadyClock clock;
  transport::SerialOptions so;
  so.baud = baud;
  auto port = transport::SerialTransport::open(server->slave_path(), clock, so);
  if (!port) {
    std::fprintf(stderr, "upload_bench: %s\n", port.error().message.c_str());
    stop = true;
    serving.join();
    return 1;
  }
  std::vector<lsc::GroupAction> actions(count);
  for (std::size_t i = 0; i < count; ++i) {
    actions[i].time_ms = static_cast<std::uint16_t>(20 + i % 1000);
    for (std::uint8_t s = 1; s <= 6; ++s) {
      actions[i].servos.push_back({s, static_cast<std::uint16_t>((i * 13 + s * 97) % 1001)});
    }
  }
  const auto plan = lsc::plan_group_download(0, actions).value();
  TimedTransport timed(**port);
  upload::ControllerLink link(timed, clock);
  upload::Uploader uploader(link, {});
  const auto t0 = std::chrono::steady_clock::now();
  const upload::UploadResult r = uploader.upload(plan);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  stop = true;
  serving.join();

  const std::size_t sent = r.link.bytes_sent;
  const std::size_t received = r.link.bytes_received;
  const double bound = static_cast<double>(sent + received) * 10.0 / baud;
  const bool stored = emulator.stored_group(0) == std::optional(actions);
  const bool counted = emulator.received_bytes().size() == sent;
  const io::Duration late = device.late();
  const io::Duration after = device.after_write();
  const io::Duration host = timed.host();
  const double n = static_cast<double>(std::max<std::size_t>(device.gaps(), 1));
  auto us_each = [&](io::Duration d) { return ms(d) * 1000.0 / n; };
  std::printf(
      "upload_bench: %zu actions x 6 servos at %u baud over a pty (SerialTransport -> PtyServer "
      "-> XArmEmulator, processing 0): %s, stored group %s\n"
      "  bytes   host->controller %zu in %zu frames (emulator received %s), "
      "controller->host %zu in %zu frames\n"
      "  bound   (%zu + %zu) bytes x 10 bits / %u baud = %.3f s\n"
      "  wall    %.3f s (steady_clock around Uploader::upload)\n"
      "  ratio   wall / bound = %.4f   (re-sends %d, restarts %d)\n"
      "  idle    line idle after %zu replies: %.1f ms = %.1f us each:\n"
      "            server late writing a reply's last byte  %7.1f us\n"
      "            pty to host + pty to server, wake-ups    %7.1f us\n"
      "            uploader (last read -> next write)       %7.1f us\n",
      count, baud, upload::to_string(r.status), stored ? "= plan" : "!= plan", sent,
      r.link.frames_sent, counted ? "the same" : "A DIFFERENT COUNT", received,
      r.link.frames_received, sent, received, baud, bound, wall, wall / bound, r.retries,
      r.restarts, device.gaps(), ms(late + after), us_each(late + after), us_each(late),
      us_each(after - host), us_each(host));
  std::vector<io::Duration> lates = device.lates();
  std::sort(lates.begin(), lates.end());
  if (!lates.empty()) {
    auto pct = [&](std::size_t p) { return ms(lates[(lates.size() - 1) * p / 100]) * 1000.0; };
    std::printf(
        "  late    server's lateness per reply (its wake-up on this machine's load): p50 %.1f us, "
        "p90 %.1f us, p99 %.1f us, max %.1f us\n",
        pct(50), pct(90), pct(99), pct(100));
  }
  return r.ok() && stored && counted ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::uint32_t> bauds;
  std::size_t count = 1020;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--baud") == 0) {
      bauds.push_back(static_cast<std::uint32_t>(std::strtoul(argv[i + 1], nullptr, 10)));
    } else if (std::strcmp(argv[i], "--actions") == 0) {
      count = std::strtoul(argv[i + 1], nullptr, 10);
    }
  }
  if (bauds.empty()) bauds = {9600, 115200};
  int rc = 0;
  for (auto b : bauds) rc |= bench(b, count);
  return rc;
}
