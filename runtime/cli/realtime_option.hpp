// `--realtime` on the commands that keep time on the host (play, upload --run, show): the
// stretch of the command that must not be delayed runs with real-time (SCHED_FIFO) priority
// (runtime/io/realtime.hpp), and a refusal is a warning, not an error: the command goes on at
// normal priority, as it would without the option.
#pragma once

#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "runtime/cli/context.hpp"
#include "runtime/io/realtime.hpp"

namespace seqc::cli {

// `--realtime` with `help`; `needs`: an option it needs (upload's --run), or null.
CLI::Option* add_realtime_option(CLI::App& cmd, bool& realtime, const std::string& help,
                                 CLI::Option* needs = nullptr);

// Real-time priority for the calling thread while the result lives, when `wanted`, through
// ctx.scheduler. When refused: "seqc: warning: <why>; playing at normal priority" on ctx.err.
std::unique_ptr<io::RealtimeScope> realtime_stretch(Context& ctx, bool wanted);

}  // namespace seqc::cli
