#include "runtime/cli/lsc6_commands.hpp"

#include <functional>
#include <ostream>

#include "runtime/cli/commands.hpp"
#include "runtime/cli/device_args.hpp"
#include "runtime/cli/port_open.hpp"
#include "runtime/upload/lsc6_link.hpp"

namespace seqc::cli {
namespace {

using Body = std::function<ExitCode(upload::Lsc6Link&, io::Duration timeout)>;

ExitCode with_board(Context& ctx, const DeviceOptions& device, const Body& body) {
  auto timeout = parse_timeout(device.timeout);
  if (!timeout) return usage_error(ctx, timeout.error().message);
  PortOpenResult opened = open_controller_port(device.port, ctx);
  if (!opened.port) {
    ctx.err << "seqc: error: " << opened.failure.message << "\n";
    return opened.failure.code;
  }
  upload::Lsc6Link link(*opened.port->transport, *opened.port->clock, ctx.interrupted);
  link.discard_input();
  return body(link, *timeout);
}

ExitCode send_failed(Context& ctx, upload::Lsc6Link& link, const std::string& what,
                     const Error& e) {
  ctx.err << "seqc: error: cannot send " << what << " to " << link.transport().describe() << ": "
          << e.message << "\n";
  return ExitCode::DeviceFailure;
}

ExitCode wait_failed(Context& ctx, upload::Lsc6Link& link, const upload::Lsc6Wait& w) {
  if (w.status == upload::WaitStatus::Interrupted) {
    ctx.err << "seqc: error: interrupted\n";
    return ExitCode::Interrupted;
  }
  ctx.err << "seqc: error: reading from " << link.transport().describe() << " failed: " << w.message
          << "\n";
  return ExitCode::DeviceFailure;
}

template <class Answer>
bool is(const lsc6::Reply& r) {
  return std::holds_alternative<Answer>(r);
}

}  // namespace

bool is_lsc6_board(const std::string& robot, const std::string& port) {
  return robot == "lsc-6" || port == "emu:lsc6" || port.starts_with("emu:lsc6?");
}

ExitCode refuse_on_lsc6(Context& ctx, const std::string& command) {
  ctx.err << "seqc: error: the LSC-6 board has no " << command
          << " command: its firmware knows only moves, group run/stop, erasing every group and "
             "storing actions; nothing was sent\n";
  return ExitCode::Usage;
}

ExitCode lsc6_run(Context& ctx, const DeviceOptions& device, std::uint8_t group,
                  std::uint16_t times) {
  return with_board(ctx, device, [&](upload::Lsc6Link& link, io::Duration timeout) {
    if (auto ok = link.send(lsc6::Run{group, times}); !ok) {
      return send_failed(ctx, link, "Run", ok.error());
    }
    const std::string how = times == 0 ? "looping until `seqc group stop`"
                                       : std::to_string(times) + (times == 1 ? " time" : " times");
    const upload::Lsc6Wait w = link.wait_for(is<lsc6::RunAccepted>, link.clock().now() + timeout);
    if (w.ok()) {
      summarize(ctx, "group " + std::to_string(group) + ": run accepted, " + how);
      ctx.err << "seqc: note: the LSC-6 accepts a run before looking at the group: an empty "
                 "group, or a run of another group while one plays, does nothing\n";
      return ExitCode::Ok;
    }
    if (w.status != upload::WaitStatus::Timeout) return wait_failed(ctx, link, w);
    summarize(ctx, "group " + std::to_string(group) + ": run sent, " + how);
    ctx.err << "seqc: warning: the board did not answer Run within " << describe_duration(timeout)
            << "; some copies of the LSC-6 firmware never do, so the group may have started "
               "(started, unconfirmed)\n";
    return ExitCode::Ok;
  });
}

ExitCode lsc6_stop(Context& ctx, const DeviceOptions& device) {
  return with_board(ctx, device, [&](upload::Lsc6Link& link, io::Duration) {
    if (auto ok = link.send(lsc6::Stop{}); !ok) return send_failed(ctx, link, "Stop", ok.error());
    summarize(ctx, "stop sent (the LSC-6 does not confirm it)");
    return ExitCode::Ok;
  });
}

ExitCode lsc6_erase(Context& ctx, const DeviceOptions& device, bool all) {
  if (!all) {
    return usage_error(ctx,
                       "the LSC-6 cannot erase one group: its erase command wipes every group on "
                       "the board, whatever the number; to do that, give --all");
  }
  return with_board(ctx, device, [&](upload::Lsc6Link& link, io::Duration timeout) {
    if (auto ok = link.send(lsc6::EraseAll{}); !ok) {
      return send_failed(ctx, link, "EraseAll", ok.error());
    }
    const upload::Lsc6Wait w = link.wait_for(is<lsc6::Erased>, link.clock().now() + timeout);
    if (w.ok()) {
      summarize(ctx, "every group erased");
      return ExitCode::Ok;
    }
    if (w.status != upload::WaitStatus::Timeout) return wait_failed(ctx, link, w);
    ctx.err << "seqc: error: no answer from the board on " << link.transport().describe()
            << " within " << describe_duration(timeout)
            << " (waiting for the erase confirmation); check that the board is powered and "
               "connected, and --port\n";
    return ExitCode::DeviceFailure;
  });
}

ExitCode lsc6_move(Context& ctx, const DeviceOptions& device, const lsc6::Move& move,
                   const std::string& summary) {
  auto bytes = lsc6::encode_serial(lsc6::Request{move});
  if (!bytes) return usage_error(ctx, bytes.error().message);
  return with_board(ctx, device, [&](upload::Lsc6Link& link, io::Duration) {
    if (auto ok = link.send_bytes(*bytes); !ok) return send_failed(ctx, link, "Move", ok.error());
    summarize(ctx, summary + " (the LSC-6 does not confirm moves)");
    return ExitCode::Ok;
  });
}

}  // namespace seqc::cli
