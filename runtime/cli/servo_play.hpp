// The servo-controller path of `seqc play FILE`: the program is streamed live, one
// MultiServoMove per keyframe (kNoMove for the servos a step does not mention), each sent at
// its keyframe's start on the host's clock (absolute deadlines, runtime/player), so a dance can
// be tried without overwriting a stored group.
//
// The command returns when the sequence ends (its last move finished), not when the last
// frame is sent. Before streaming, one GetBatteryVoltage makes sure a controller answers (a missing
// one is a DeviceFailure, not a silent play into nothing). Nothing is stored on the controller.
// Ctrl-C stops sending at once (the servos finish the move they were given) and the message
// says which step was the last one sent; exit status Interrupted.
#pragma once

#include "compiler/compile.hpp"
#include "runtime/cli/context.hpp"
#include "runtime/cli/controller_session.hpp"
#include "runtime/cli/exit_codes.hpp"

namespace seqc::cli {

// `compiled` must hold a ServoProgram. Opens the port `device` names and streams.
ExitCode play_on_servo_controller(Context& ctx, const compiler::CompileOutput& compiled,
                                  const DeviceOptions& device);

// The same over a session that is already open (tests drive it over their own transport).
ExitCode stream_servo_program(Context& ctx, const compiler::CompileOutput& compiled,
                              ControllerSession& session);

}  // namespace seqc::cli
