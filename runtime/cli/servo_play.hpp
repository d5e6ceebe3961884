// The servo-controller path of `seqc play FILE`: the program is streamed live, one move per
// keyframe (MultiServoMove with kNoMove for the servos a step does not mention; on an LSC-6 its
// own Move with the servos the step names), each sent at its keyframe's start on the host's
// clock (absolute deadlines, runtime/player), so a dance can be tried without overwriting a
// stored group.
//
// Honest timing. Before anything is sent, the schedule is checked against the link: at 9600
// baud a six-servo move takes 26 ms on the wire, so moves closer together than that cannot
// leave on time (HID: one report per polling interval). A schedule that cannot be met is
// refused, naming the first late move and by how much, with `seqc upload --run` as the fix;
// with allow_late it is played anyway after a warning. While streaming, each move's lateness is
// measured after its bytes have left the port (Transport::drain, tcdrain on a serial port)
// against its deadline plus its own wire time, and p50/p99/max are reported at the end.
//
// The command returns when the sequence ends (its last move finished). On the xArm dialect one
// GetBatteryVoltage first makes sure a controller answers (a missing one is a DeviceFailure, not
// a silent play into nothing); the LSC-6 has nothing to ask, which the command says. Ctrl-C
// stops sending at once (the servos finish the move they were given); exit status Interrupted.
#pragma once

#include <string>

#include "compiler/compile.hpp"
#include "runtime/cli/context.hpp"
#include "runtime/cli/controller_session.hpp"
#include "runtime/cli/exit_codes.hpp"

namespace seqc::cli {

struct LivePlayOptions {
  std::string file;         // for messages and the `seqc upload FILE --run` hint
  bool allow_late = false;  // play a schedule the link cannot keep, with a warning
};

// `compiled` must hold a ServoProgram. Opens the port `device` names and streams.
ExitCode play_on_servo_controller(Context& ctx, const compiler::CompileOutput& compiled,
                                  const DeviceOptions& device, const LivePlayOptions& options);

// The same over a session that is already open (tests drive it over their own transport).
ExitCode stream_servo_program(Context& ctx, const compiler::CompileOutput& compiled,
                              ControllerSession& session, const LivePlayOptions& options = {});

}  // namespace seqc::cli
