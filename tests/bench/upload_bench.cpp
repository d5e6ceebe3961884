// upload_bench: a 1,020-action, 6-servo upload through the real uploader and SerialTransport to
// the emulated controller served on a pseudo-terminal (PtyServer in a thread, processing
// times 0), at 9600 and 115200 baud, in real time. Prints wall time and the wire-time bound:
// every byte both ways (frames, acks, probe, stop, barriers) x 10 bits / baud.
//
// What the ratio means here: the pty server paces the emulator's replies at the baud rate but
// delivers the host's bytes as soon as they are written (a pty has no line rate), so the
// request half of the bound is not spent on the wire. A ratio below 1 is therefore possible
// and says the uploader adds little; it is not the ratio a real 9600-baud UART would give.
//
// Usage: upload_bench [--baud N]... [--actions N]   (default: --baud 9600 --baud 115200)
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "runtime/emulator/pty_device.hpp"
#include "runtime/emulator/pty_server.hpp"
#include "runtime/emulator/xarm_emulator.hpp"
#include "runtime/io/clock.hpp"
#include "runtime/protocol/group_download.hpp"
#include "runtime/transport/serial_transport.hpp"
#include "runtime/upload/uploader.hpp"

using namespace seqc;

namespace {

int bench(std::uint32_t baud, std::size_t count) {
  emu::XArmConfig config;
  config.baud = baud;
  config.command_time = io::Duration{0};
  config.flash_erase_time = io::Duration{0};
  config.flash_write_time = io::Duration{0};
  emu::XArmEmulator emulator(config);
  emu::XArmPtyDevice device(emulator);
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
  upload::ControllerLink link(**port, clock);
  upload::Uploader uploader(link, {});
  const auto t0 = std::chrono::steady_clock::now();
  const upload::UploadResult r = uploader.upload(plan);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  stop = true;
  serving.join();

  const std::size_t bytes = r.link.bytes_sent + r.link.bytes_received;
  const double bound = static_cast<double>(bytes) * 10.0 / baud;
  const bool stored = emulator.stored_group(0) == std::optional(actions);
  std::printf(
      "upload_bench: %zu actions x 6 servos at %u baud: %s, stored %s; wall %.3f s; "
      "%zu bytes sent + %zu received = %zu bytes -> wire bound %.3f s; wall/bound = %.3f "
      "(re-sends %d, restarts %d)\n",
      count, baud, upload::to_string(r.status), stored ? "= plan" : "!= plan", wall,
      r.link.bytes_sent, r.link.bytes_received, bytes, bound, wall / bound, r.retries, r.restarts);
  return r.ok() && stored ? 0 : 1;
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
