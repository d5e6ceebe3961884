// The whole byte stream `seqc upload` sends for a plan, as commented hex, one frame a line:
// probe, stop, barrier, the download (steps 1-5), barrier, and with a run GroupRun and its
// barrier. `seqc upload --dry-run` and `seqc compile --dry-run` print it, and `seqc decode -`
// reads it back (the comments start with '#').
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "runtime/protocol/lsc6_messages.hpp"
#include "runtime/protocol/lsc_messages.hpp"

namespace seqc::cli {

// run_times: 0 plays until stopped; ignored without run.
std::string upload_session_hex(const std::vector<lsc::Request>& plan, std::uint8_t group, bool run,
                               std::uint16_t run_times);

// The same for an LSC-6 board: Stop, one DownloadAction per action, and with a run Run.
std::string lsc6_session_hex(const std::vector<lsc6::DownloadAction>& plan, std::uint8_t group,
                             bool run, std::uint16_t run_times);

}  // namespace seqc::cli
