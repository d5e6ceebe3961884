// The LSC-6 board: its own dialect (docs/protocol/lsc-6.md). Groups are stored with one
// DownloadAction per action (upload::upload_lsc6), live moves are its Move, and its firmware
// answers only DownloadAction, Run and EraseAll: nothing can serve as a probe or confirm a move
// or a stop, and its erase wipes every group. Reached in process as emu:lsc6.
#include <memory>
#include <string>
#include <utility>
#include <variant>

#include "compiler/formats/listing.hpp"
#include "compiler/targets/servo_controller/servo_wire.hpp"
#include "protocol/lsc/lsc_frame.hpp"
#include "protocol/lsc6/lsc6_messages.hpp"
#include "runtime/boards/board.hpp"
#include "runtime/boards/live_moves.hpp"
#include "runtime/boards/ports.hpp"
#include "runtime/emulator/emulator_transport.hpp"
#include "runtime/emulator/lsc6_emulator.hpp"
#include "runtime/upload/dialect_questions.hpp"
#include "runtime/upload/lsc6_link.hpp"
#include "runtime/upload/lsc6_uploader.hpp"

namespace seqc::boards {
namespace {

constexpr std::uint32_t kUartBaud = 9600;
constexpr std::string_view kEmulators[] = {"lsc6"};

Result<Plan> plan(const compiler::CompileOutput& output, std::uint8_t group) {
  const compiler::ServoProgram* program = output.servo_program();
  if (program == nullptr) return make_error("the program is not a servo program");
  auto frames = compiler::plan_lsc6_download(*program, group);
  if (!frames) return frames.error();
  return Plan{group, program->keyframes.size(), std::move(frames).value()};
}

Result<std::string> render(const compiler::CompileOutput& output, Emit emit, std::uint8_t group) {
  auto planned = plan(output, group);
  if (!planned) return planned.error();
  const compiler::ServoProgram& program = *output.servo_program();
  switch (emit) {
    case Emit::Hex:
      return compiler::render_hex(planned->frames);
    case Emit::Listing:
      // How the listing describes the group's storage: " (LSC-6 dialect)".
      return compiler::render_listing(program, planned->frames, group, output.sources,
                                      " (" + std::string(kLsc6Dialect.name) + " dialect)");
    case Emit::Json:
      return compiler::render_json(program, planned->frames, group, output.sources);
  }
  return make_error("unknown output form");
}

upload::UploadResult upload(const Line& line, const Plan& plan,
                            const upload::UploadOptions& options,
                            upload::UploadObserver* observer) {
  upload::Lsc6Link link(line.transport, line.clock, line.interrupted);
  return upload::upload_lsc6(link, plan.frames, options, observer);
}

std::optional<lsc6::Request> request_of(ByteView frame) {
  auto decoded = lsc::decode_serial(frame);
  if (!decoded) return std::nullopt;
  auto request = lsc6::decode_request(*decoded);
  if (!request) return std::nullopt;
  return *request;
}

// What a board that accepts everything answers: each stored action and each run.
Bytes acknowledge(ByteView frame) {
  const auto request = request_of(frame);
  if (!request) return {};
  if (std::holds_alternative<lsc6::DownloadAction>(*request)) {
    return lsc6::encode_serial(lsc6::Reply{lsc6::ActionStored{}});
  }
  if (std::holds_alternative<lsc6::Run>(*request)) {
    return lsc6::encode_serial(lsc6::Reply{lsc6::RunAccepted{}});
  }
  return {};
}

std::string comment(std::size_t /*index*/, ByteView frame) {
  const auto unit = kLsc6Dialect.decode(frame);
  if (!unit) return "?";
  const auto text = kLsc6Dialect.describe_request(*unit);
  return text ? *text : "?";
}

Result<std::vector<player::ScheduledFrame>> live_frames(const compiler::CompileOutput& output) {
  const compiler::ServoProgram* program = output.servo_program();
  if (program == nullptr) return make_error("the program is not a servo program");
  std::vector<player::ScheduledFrame> frames;
  for (const LiveMove& m : changed_moves(*program)) {
    auto bytes = lsc6::encode_serial(lsc6::Request{lsc6::Move{m.time_ms, m.targets}});
    if (!bytes) return bytes.error();
    frames.push_back({std::chrono::milliseconds(m.send_ms), std::move(*bytes)});
  }
  return frames;
}

// The LSC-6 answers nothing that could show it is there, so silence passes; the xArm question
// finds a board of the other dialect, which would take every move for another servo range.
Outcome probe(const Line& line) {
  Outcome out;
  if (upload::xarm_answers(line.transport, line.clock, line.interrupted,
                           upload::UploadOptions{}.reply_margin)) {
    out.failure = Failure::OtherDialect;
    out.request = "GetBatteryVoltage";
    out.answered = &kXarmDialect;
  }
  return out;
}

Bytes run_frame(std::uint8_t group, std::uint16_t times) {
  return lsc6::encode_serial(lsc6::Request{lsc6::Run{group, times}}).value();
}

// A failed wait on the board's answers, as an Outcome.
Outcome wait_failure(const upload::Lsc6Wait& w, std::string request, std::string awaiting) {
  Outcome out;
  out.request = std::move(request);
  out.awaiting = std::move(awaiting);
  if (w.status == upload::WaitStatus::Interrupted) {
    out.failure = Failure::Interrupted;
  } else {
    out.failure = Failure::ReadFailed;
    out.detail = w.message;
  }
  return out;
}

// The board answers Run before it looks at the group, and some copies of its firmware never
// answer at all: no answer within the timeout is a start left unconfirmed, not a failure.
RunOutcome confirm_run(const Line& line, std::uint8_t /*group*/, std::uint16_t /*times*/) {
  upload::Lsc6Link link(line.transport, line.clock, line.interrupted);
  const upload::Lsc6Wait w = link.wait_for(
      [](const lsc6::Reply& r) { return std::holds_alternative<lsc6::RunAccepted>(r); },
      link.clock().now() + line.timeout);
  RunOutcome out;
  if (w.ok()) {
    out.started = Confirmation::Reported;
  } else if (w.status == upload::WaitStatus::Timeout) {
    out.started = Confirmation::NeverAnswered;
  } else {
    static_cast<Outcome&>(out) = wait_failure(w, "Run", "the run's answer");
    out.started = Confirmation::NeverAnswered;
  }
  return out;
}

// A wait for a notice the board owes (time_run): a timeout is no reply, not a failed read.
Outcome notice_failure(const upload::Lsc6Wait& w, std::string request, std::string awaiting) {
  Outcome out = wait_failure(w, std::move(request), std::move(awaiting));
  if (w.status == upload::WaitStatus::Timeout) out.failure = Failure::NoReply;
  return out;
}

// Run is answered (55 55 02 06) as the group starts and a counted run's end announced
// (55 55 02 07): two 4-byte frames on one line, so the time between them is the run's length on
// the board's clock. A copy that sends either not cannot be timed (NoReply).
TimedRun time_run(const Line& line, std::uint8_t group, io::Duration longest) {
  upload::Lsc6Link link(line.transport, line.clock, line.interrupted);
  TimedRun out;
  upload::WaitStatus drained = upload::WaitStatus::Timeout;
  (void)link.drain(drained);
  if (link.interrupted()) {
    out.failure = Failure::Interrupted;
    out.request = "Run";
    return out;
  }
  if (auto sent = link.send(lsc6::Request{lsc6::Run{group, 1}}); !sent) {
    out.failure = Failure::SendFailed;
    out.request = "Run";
    out.detail = sent.error().message;
    return out;
  }
  const upload::Lsc6Wait started = link.wait_for(
      [](const lsc6::Reply& r) { return std::holds_alternative<lsc6::RunAccepted>(r); },
      line.clock.now() + line.timeout);
  if (!started.ok()) {
    static_cast<Outcome&>(out) = notice_failure(started, "Run", "the run's answer");
    return out;
  }
  const io::TimePoint from = line.clock.now();
  const upload::Lsc6Wait finished = link.wait_for(
      [](const lsc6::Reply& r) { return std::holds_alternative<lsc6::GroupFinished>(r); },
      from + longest + line.timeout);
  if (!finished.ok()) {
    static_cast<Outcome&>(out) = notice_failure(finished, "Run", "the end-of-run notice");
    return out;
  }
  out.lasted = line.clock.now() - from;
  return out;
}

Bytes stop_frame() { return lsc6::encode_serial(lsc6::Request{lsc6::Stop{}}).value(); }

Outcome send(const Line& line, const lsc6::Request& request, std::string what) {
  Outcome out;
  out.request = std::move(what);
  upload::Lsc6Link link(line.transport, line.clock, line.interrupted);
  link.discard_input();
  if (auto ok = link.send(request); !ok) {
    out.failure = Failure::SendFailed;
    out.detail = ok.error().message;
  }
  return out;
}

StopOutcome stop(const Line& line) {
  StopOutcome out;
  static_cast<Outcome&>(out) = send(line, lsc6::Stop{}, "Stop");
  out.stopped = Confirmation::NeverAnswered;
  return out;
}

// Its erase wipes every group whatever the number, so only "every group" is accepted.
Outcome erase(const Line& line, std::optional<std::uint8_t> group) {
  Outcome out;
  out.request = "EraseAll";
  if (group) {
    out.failure = Failure::SendFailed;
    out.detail = "the LSC-6 cannot erase one group; nothing was sent";
    return out;
  }
  upload::Lsc6Link link(line.transport, line.clock, line.interrupted);
  link.discard_input();
  if (auto ok = link.send(lsc6::EraseAll{}); !ok) {
    out.failure = Failure::SendFailed;
    out.detail = ok.error().message;
    return out;
  }
  const std::string awaiting = "the erase confirmation";
  const upload::Lsc6Wait w =
      link.wait_for([](const lsc6::Reply& r) { return std::holds_alternative<lsc6::Erased>(r); },
                    link.clock().now() + line.timeout);
  if (w.ok()) return out;
  if (w.status == upload::WaitStatus::Timeout) {
    out.failure = Failure::NoReply;
    out.awaiting = awaiting;
    return out;
  }
  return wait_failure(w, out.request, awaiting);
}

Outcome move(const Line& line, std::span<const lsc::ServoTarget> targets, std::uint16_t time_ms) {
  lsc6::Move request;
  request.time_ms = time_ms;
  for (const lsc::ServoTarget& t : targets) request.servos.push_back({t.id, t.position});
  return send(line, request, "Move");
}

bool open_emulator(const transport::PortSpec& spec, io::Clock& /*host*/, const Hooks& hooks,
                   OpenedPort& out, std::string& error) {
  out.emulated = true;
  if (hooks.lsc6 != nullptr && hooks.emulated_clock != nullptr) {
    out.transport = std::make_unique<emu::EmulatorTransport>(*hooks.lsc6, *hooks.emulated_clock);
    out.clock = hooks.emulated_clock;
    return true;
  }
  emu::Lsc6Config config;
  if (auto ok = emu::apply_lsc6_options(spec.emulator_options, config); !ok) {
    error = ok.error().message;
    return false;
  }
  out.emulated_clock = std::make_unique<io::ManualClock>();
  out.controller = std::make_unique<emu::Lsc6Emulator>(config);
  out.transport = std::make_unique<emu::EmulatorTransport>(*out.controller, *out.emulated_clock);
  out.clock = out.emulated_clock.get();
  return true;
}

}  // namespace

extern const Board kLsc6Board;
const Board kLsc6Board = {
    .key = "lsc6",
    .name = "LSC-6",
    .called = "the board",
    .family = "servo controller",
    .dialect = &kLsc6Dialect,
    .baud = kUartBaud,
    .over_hid = false,
    .discoverable = true,
    .render = render,
    .plan = plan,
    .upload = upload,
    .acknowledge = acknowledge,
    .comment = comment,
    .unconfirmed_run =
        "it did not answer Run, as some copies of the LSC-6 firmware never do: started, "
        "unconfirmed",
    .live_frames = live_frames,
    .probe = probe,
    .safe_stop = nullptr,
    .measure_departure = true,
    .check_schedule = true,
    .wait_for_end = true,
    .style = LiveStyle::Moves,
    .unprobed_note = "the LSC-6 answers no move, so nothing shows that the board hears them",
    .run_name = "Run",
    .run_frame = run_frame,
    .confirm_run = confirm_run,
    .run_note =
        "the LSC-6 accepts a run before looking at the group: an empty group, or a run "
        "of another group while one plays, does nothing",
    .time_run = time_run,
    .stop_frame = stop_frame,
    .stop = stop,
    .erase = erase,
    .erases_one_group = false,
    .move = move,
    .confirms_moves = false,
    .queries = false,
    .pose_profile = "lsc-6",
    .lacks =
        "its firmware knows only moves, group run/stop, erasing every group and storing "
        "actions",
    .emulators = kEmulators,
    .open_emulator = open_emulator,
    .serve = emu::serve_lsc6,
    .emulator_options = kBaud | kFaults | kSeed | kDumpGroups,
    .no_faults_reason = "",
    .no_groups_reason = "",
};

}  // namespace seqc::boards
