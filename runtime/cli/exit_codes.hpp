// The one set of exit statuses seqc uses (documented in docs/cli.md and `seqc --help`).
#pragma once

namespace seqc::cli {

enum class ExitCode : int {
  Ok = 0,
  InvalidInput = 1,     // the choreography file has errors (diagnostics on stderr)
  Usage = 2,            // bad command line
  PortUnavailable = 3,  // no such port, busy, permission denied, no device or several found
  DeviceFailure = 4,    // no answer, refusal, hang-up, protocol violation during a command
  FileError = 5,        // an input or output file could not be read or written
  Internal = 70,        // a bug in seqc (sysexits' EX_SOFTWARE)
  Interrupted = 130,    // Ctrl-C (128 + SIGINT); see exit_status for SIGTERM and SIGHUP
};

constexpr int to_int(ExitCode c) { return static_cast<int>(c); }

// Commands return Interrupted whichever signal stopped them (SIGINT, SIGTERM, SIGHUP); the
// process ends as a shell reports a death by that signal, 128 + its number: 130 for SIGINT,
// 143 for SIGTERM, 129 for SIGHUP. signal: the first that arrived, 0 for none.
constexpr int exit_status(int code, int signal) {
  return code == to_int(ExitCode::Interrupted) && signal > 0 && signal < 64 ? 128 + signal : code;
}

}  // namespace seqc::cli
