// The xArm / LSC-16 / LSC-32 controller family: groups stored with GroupDownload steps 1-5
// (upload::Uploader), live moves as MultiServoMove, every command without an answer of its own
// confirmed with a battery check (XarmSession), and the emulator reached as emu:xarm (serial
// framing, paced at 9600 baud) or emu:xarm-hid (behind its USB HID face).
#include <fmt/format.h>

#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>

#include "compiler/formats/listing.hpp"
#include "compiler/targets/servo_controller/servo_wire.hpp"
#include "protocol/lsc/group_download.hpp"
#include "protocol/lsc/lsc_frame.hpp"
#include "runtime/boards/board.hpp"
#include "runtime/boards/live_moves.hpp"
#include "runtime/boards/ports.hpp"
#include "runtime/boards/xarm_session.hpp"
#include "runtime/emulator/emulator_transport.hpp"
#include "runtime/emulator/hid_face.hpp"
#include "runtime/emulator/xarm_config.hpp"
#include "runtime/transport/open_port.hpp"
#include "runtime/upload/controller_link.hpp"
#include "runtime/upload/dialect_questions.hpp"

namespace seqc::boards {
namespace {

// The controllers' UART rate (docs/protocol/servo-controller.md, Framing).
constexpr std::uint32_t kUartBaud = 9600;
// What the dry run's controller reports as its battery voltage.
constexpr std::uint16_t kAcknowledgedMillivolts = 7400;

constexpr std::string_view kEmulators[] = {"xarm", "xarm-hid"};

Result<const compiler::ServoProgram*> servo_program(const compiler::CompileOutput& output) {
  const compiler::ServoProgram* program = output.servo_program();
  if (program == nullptr) return make_error("the program is not a servo program");
  return program;
}

Result<Plan> plan(const compiler::CompileOutput& output, std::uint8_t group) {
  auto program = servo_program(output);
  if (!program) return program.error();
  auto frames = compiler::plan_download(**program, group);
  if (!frames) return frames.error();
  return Plan{group, (*program)->keyframes.size(), std::move(frames).value()};
}

// " in 2 blocks": how the controller stores the actions (255 to a block).
std::string storage(const compiler::ServoProgram& program) {
  const std::size_t n = program.keyframes.size();
  const std::size_t blocks = (n + lsc::kActionsPerBlock - 1) / lsc::kActionsPerBlock;
  return fmt::format(" in {} block{}", blocks, blocks == 1 ? "" : "s");
}

Result<std::string> render(const compiler::CompileOutput& output, Emit emit, std::uint8_t group) {
  auto planned = plan(output, group);
  if (!planned) return planned.error();
  const compiler::ServoProgram& program = *output.servo_program();
  switch (emit) {
    case Emit::Hex:
      return compiler::render_hex(planned->frames);
    case Emit::Listing:
      return compiler::render_listing(program, planned->frames, group, output.sources,
                                      storage(program));
    case Emit::Json:
      return compiler::render_json(program, planned->frames, group, output.sources);
  }
  return make_error("unknown output form");
}

upload::UploadResult upload(const Line& line, const Plan& plan,
                            const upload::UploadOptions& options,
                            upload::UploadObserver* observer) {
  upload::ControllerLink link(line.transport, line.clock, line.interrupted);
  return upload::Uploader(link, options, observer).upload(plan.frames);
}

std::optional<lsc::Request> request_of(ByteView frame) {
  auto decoded = lsc::decode_serial(frame);
  if (!decoded) return std::nullopt;
  auto request = lsc::decode_request(*decoded);
  if (!request) return std::nullopt;
  return *request;
}

Bytes reply_bytes(const lsc::Reply& reply) { return lsc::encode_serial(reply).value(); }

// What a controller that accepts everything answers.
Bytes acknowledge(ByteView frame) {
  const auto request = request_of(frame);
  if (!request) return {};
  if (std::holds_alternative<lsc::GetBatteryVoltage>(*request)) {
    return reply_bytes(lsc::BatteryVoltage{kAcknowledgedMillivolts});
  }
  if (std::holds_alternative<lsc::GroupStop>(*request)) return reply_bytes(lsc::GroupStopped{});
  if (const auto* run = std::get_if<lsc::GroupRun>(&*request)) {
    return reply_bytes(lsc::GroupStarted{run->group, run->times});
  }
  if (const int step = lsc::group_download_step(*request); step > 0) {
    return reply_bytes(lsc::GroupDownloadAck{static_cast<std::uint8_t>(step), 0});
  }
  return {};
}

// The upload opens with its probe; every later battery check is a barrier.
std::string comment(std::size_t index, ByteView frame) {
  const auto request = request_of(frame);
  if (!request) return "?";
  std::string role;
  if (std::holds_alternative<lsc::GetBatteryVoltage>(*request)) {
    role = index == 0 ? "probe: " : "barrier: ";
  } else if (std::holds_alternative<lsc::ServoPositionRead>(*request)) {
    role = "first moves: ";  // before the run, where the servos are (boards/first_move.hpp)
  }
  return role + lsc::describe(*request);
}

Result<std::vector<player::ScheduledFrame>> live_frames(const compiler::CompileOutput& output) {
  auto program = servo_program(output);
  if (!program) return program.error();
  std::vector<player::ScheduledFrame> frames;
  for (const LiveMove& m : changed_moves(**program)) {
    lsc::MultiServoMove move;
    move.time_ms = m.time_ms;
    for (const lsc::ServoTarget& t : m.targets) move.servos.push_back({t.id, t.position});
    auto bytes = lsc::encode_serial(lsc::Request{move});
    if (!bytes) return bytes.error();
    frames.push_back({std::chrono::milliseconds(m.send_ms), std::move(*bytes)});
  }
  return frames;
}

Outcome outcome_of(const XarmSession& session) {
  return session.failure() ? *session.failure() : Outcome{};
}

// The battery question; when it goes unanswered, the LSC-6 question (of group 0's unplayed
// slot 255), so an LSC-6 on the line is named rather than taken for a board switched off.
Outcome probe(const Line& line) {
  upload::ControllerLink link(line.transport, line.clock, line.interrupted);
  XarmSession session(link, line.timeout);
  (void)session.ask<lsc::BatteryVoltage>(lsc::GetBatteryVoltage{}, "the battery voltage");
  Outcome out = outcome_of(session);
  if (out.failure == Failure::NoReply &&
      upload::lsc6_answers(line.transport, line.clock, line.interrupted, 0, line.timeout)) {
    out.failure = Failure::OtherDialect;
    out.answered = &kLsc6Dialect;
  }
  return out;
}

Bytes run_frame(std::uint8_t group, std::uint16_t times) {
  return lsc::encode_serial(lsc::Request{lsc::GroupRun{group, times}}).value();
}

// GroupRun has no answer of its own: the battery check confirms it arrived, and the controller
// announces the start (GroupStarted) when the group has actions.
RunOutcome confirm_run(const Line& line, std::uint8_t group, std::uint16_t times) {
  upload::ControllerLink link(line.transport, line.clock, line.interrupted);
  XarmSession session(link, line.timeout);
  RunOutcome out;
  if (!session.confirm(lsc::describe(lsc::Request{lsc::GroupRun{group, times}}))) {
    static_cast<Outcome&>(out) = outcome_of(session);
    out.started = Confirmation::NeverAnswered;
    return out;
  }
  out.started = Confirmation::NotReported;
  for (const lsc::Reply& r : session.notifications()) {
    if (const auto* started = std::get_if<lsc::GroupStarted>(&r);
        started && started->group == group) {
      out.started = Confirmation::Reported;
    }
  }
  return out;
}

// The link's wait, as a failure of the run being timed.
void fail_wait(const upload::WaitResult& r, const std::string& request, const std::string& awaiting,
               Outcome& out) {
  out.request = request;
  out.awaiting = awaiting;
  out.detail = r.message;
  switch (r.status) {
    case upload::WaitStatus::Matched:
      return;
    case upload::WaitStatus::Timeout:
      out.failure = Failure::NoReply;
      return;
    case upload::WaitStatus::HangUp:
      out.failure = Failure::HangUp;
      return;
    case upload::WaitStatus::Interrupted:
      out.failure = Failure::Interrupted;
      return;
    case upload::WaitStatus::Error:
      out.failure = Failure::ReadFailed;
      return;
  }
}

// GroupStarted is sent as the first action starts and GroupFinished as the last one ends
// (docs/protocol/servo-controller.md): both are 7-byte frames, so the time between their
// arrivals is the run's length on the controller's clock, read on the host's.
TimedRun time_run(const Line& line, std::uint8_t group, io::Duration longest) {
  upload::ControllerLink link(line.transport, line.clock, line.interrupted);
  TimedRun out;
  const lsc::Request run{lsc::GroupRun{group, 1}};
  const std::string request = lsc::describe(run);
  link.drain([](const lsc::Reply&) {});
  if (link.interrupted()) {
    out.failure = Failure::Interrupted;
    out.request = request;
    return out;
  }
  if (auto sent = link.send(run); !sent) {
    out.failure = Failure::SendFailed;
    out.request = request;
    out.detail = sent.error().message;
    return out;
  }
  auto notice = [&](auto* type) {
    using T = std::remove_pointer_t<decltype(type)>;
    return [group](const lsc::Reply& r) {
      const auto* n = std::get_if<T>(&r);
      return n != nullptr && n->group == group ? upload::Verdict::Take : upload::Verdict::Skip;
    };
  };
  auto started = link.wait_for(notice(static_cast<lsc::GroupStarted*>(nullptr)),
                               line.clock.now() + line.timeout);
  if (!started.ok()) {
    fail_wait(started, request, "the group-started notice", out);
    return out;
  }
  const io::TimePoint from = line.clock.now();
  auto finished = link.wait_for(notice(static_cast<lsc::GroupFinished*>(nullptr)),
                                from + longest + line.timeout);
  if (!finished.ok()) {
    fail_wait(finished, request, "the group-finished notice", out);
    return out;
  }
  out.lasted = line.clock.now() - from;
  return out;
}

Bytes stop_frame() { return lsc::encode_serial(lsc::Request{lsc::GroupStop{}}).value(); }

StopOutcome stop(const Line& line) {
  upload::ControllerLink link(line.transport, line.clock, line.interrupted);
  XarmSession session(link, line.timeout);
  StopOutcome out;
  if (!session.tell(lsc::GroupStop{})) {
    static_cast<Outcome&>(out) = outcome_of(session);
    return out;
  }
  out.stopped = Confirmation::NotReported;
  for (const lsc::Reply& r : session.notifications()) {
    if (const auto* stopped = std::get_if<lsc::GroupStopped>(&r)) {
      out.stopped = Confirmation::Reported;
      if (stopped->detail) out.group = stopped->detail->group;
    }
  }
  return out;
}

Outcome erase(const Line& line, std::optional<std::uint8_t> group) {
  upload::ControllerLink link(line.transport, line.clock, line.interrupted);
  XarmSession session(link, line.timeout);
  (void)session.ask<lsc::GroupErased>(lsc::GroupErase{group.value_or(lsc::kAllGroups)},
                                      "the erase confirmation");
  return outcome_of(session);
}

Outcome move(const Line& line, std::span<const lsc::ServoTarget> targets, std::uint16_t time_ms) {
  lsc::MultiServoMove request;
  request.time_ms = time_ms;
  for (const lsc::ServoTarget& t : targets) request.servos.push_back({t.id, t.position});
  upload::ControllerLink link(line.transport, line.clock, line.interrupted);
  XarmSession session(link, line.timeout);
  (void)session.tell(request);
  return outcome_of(session);
}

// A fresh emulator on its own clock with the spec's options over `baud`; false (and the option
// parser's words) when the options are wrong.
bool new_emulator(const transport::PortSpec& spec, std::uint32_t baud, OpenedPort& out,
                  std::string& error) {
  emu::XArmConfig config;
  config.baud = baud;
  if (auto ok = emu::apply_emulator_options(spec.emulator_options, config); !ok) {
    error = ok.error().message;
    return false;
  }
  out.emulated_clock = std::make_unique<io::ManualClock>();
  out.controller = std::make_unique<emu::XArmEmulator>(config);
  out.clock = out.emulated_clock.get();
  out.emulated = true;
  return true;
}

// emu:xarm-hid: the emulator behind its USB HID face, opened as a real HID device is. A
// failure to open leaves out.transport empty with `error` set (the port cannot be opened).
bool open_hid(const transport::PortSpec& spec, OpenedPort& out, std::string& error) {
  // No UART on this path: reports are paced by the USB frames.
  if (!new_emulator(spec, 0, out, error)) return false;
  auto& emulator = static_cast<emu::XArmEmulator&>(*out.controller);
  auto backend = std::make_shared<emu::EmulatedHidBackend>(emulator, *out.emulated_clock);
  out.hid_backend = backend;
  auto opened =
      transport::open_port(transport::hid_port(), *out.emulated_clock, kUartBaud, *backend);
  if (!opened) {
    error = opened.error().message;
    return true;
  }
  out.transport = std::move(opened).value();
  return true;
}

bool open_emulator(const transport::PortSpec& spec, io::Clock& /*host*/, const Hooks& hooks,
                   OpenedPort& out, std::string& error) {
  if (spec.emulator == kEmulators[1]) return open_hid(spec, out, error);
  if (hooks.xarm != nullptr && hooks.emulated_clock != nullptr) {
    // The caller's emulator; its own config holds any faults.
    out.transport = std::make_unique<emu::EmulatorTransport>(*hooks.xarm, *hooks.emulated_clock);
    out.clock = hooks.emulated_clock;
    out.emulated = true;
    return true;
  }
  // Paced like the real line (and `seqc emulate xarm`), so times and rates are the wire's;
  // `emu:xarm?baud=0` runs unpaced.
  if (!new_emulator(spec, kUartBaud, out, error)) return false;
  out.transport = std::make_unique<emu::EmulatorTransport>(*out.controller, *out.emulated_clock);
  return true;
}

}  // namespace

extern const Board kXarmBoard;
const Board kXarmBoard = {
    .key = "xarm",
    .name = "xArm / LSC-16 / LSC-32",
    .called = "the controller",
    .family = "servo controller",
    .dialect = &kXarmDialect,
    .baud = kUartBaud,
    .over_hid = true,
    .discoverable = true,
    .render = render,
    .plan = plan,
    .upload = upload,
    .acknowledge = acknowledge,
    .comment = comment,
    .unconfirmed_run = "it did not report starting it",
    .live_frames = live_frames,
    .probe = probe,
    .safe_stop = nullptr,
    .measure_departure = true,
    .check_schedule = true,
    .wait_for_end = true,
    .style = LiveStyle::Moves,
    .unprobed_note = "",
    .run_name = "GroupRun",
    .run_frame = run_frame,
    .confirm_run = confirm_run,
    .run_note = "",
    .time_run = time_run,
    .stop_frame = stop_frame,
    .stop = stop,
    .erase = erase,
    .erases_one_group = true,
    .move = move,
    .confirms_moves = true,
    .queries = true,
    .pose_profile = "xarm",
    .lacks = "",
    .emulators = kEmulators,
    .open_emulator = open_emulator,
    .serve = emu::serve_xarm,
    .emulator_options = kBaud | kFaults | kSeed | kPositions | kDumpGroups,
    .no_faults_reason = "",
    .no_groups_reason = "",
};

}  // namespace seqc::boards
