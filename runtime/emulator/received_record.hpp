// The --record CSV of `seqc emulate xarm|lsc6`: what the emulated controller received, one line
// per piece, under the header `time_s,status,bytes,message`:
//   time_s   when the piece reached the controller, in seconds with six decimals
//   status   ok                 a frame the controller took (it may still ignore an unknown
//                               command; message says so, and names a byte the `corrupt`
//                               fault flipped after 55 55 LEN: no checksum tells)
//            dropped:<reason>   a whole frame the controller dropped on purpose, so it had no
//                               effect; <reason> is drop_reason_name (busy, fault-drop, ...)
//            unframed           bytes the controller could not frame (noise between frames, a
//                               LEN below 2, a partial frame cut by the frame-gap fault)
//   bytes    the piece as the controller saw it (after an injected corruption), hex
//   message  the request the bytes carry, or why they do not decode; CSV-quoted if needed
// `seqc decode` of such a file reports every line that is not `ok` as an issue.
#pragma once

#include <string>

#include "runtime/emulator/lsc6_emulator.hpp"
#include "runtime/emulator/xarm_emulator.hpp"

namespace seqc::emu {

std::string xarm_record_csv(const XArmEmulator& emu);
// Only frames the LSC-6 receiver completed: it abandons the rest without a trace.
std::string lsc6_record_csv(const Lsc6Emulator& emu);

}  // namespace seqc::emu
