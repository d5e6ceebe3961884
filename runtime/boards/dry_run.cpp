#include "runtime/boards/dry_run.hpp"

#include <fmt/format.h>

#include "runtime/boards/recording_transport.hpp"

namespace seqc::boards {

DryRun dry_run(const Board& board, const Plan& plan, const upload::UploadOptions& options) {
  DryRun out;
  if (board.upload == nullptr || board.acknowledge == nullptr || board.comment == nullptr) {
    out.result.status = upload::UploadStatus::BadPlan;
    out.result.message = std::string(board.name) + " stores no groups";
    return out;
  }
  io::ManualClock clock;
  AcknowledgingTransport device(clock, board.acknowledge);
  out.result = board.upload(Line{device, clock, nullptr}, plan, options, nullptr);
  out.frames = device.writes();
  for (std::size_t i = 0; i < out.frames.size(); ++i) {
    out.text +=
        fmt::format("{:<40}  # {}\n", to_hex(out.frames[i]), board.comment(i, out.frames[i]));
  }
  return out;
}

}  // namespace seqc::boards
