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

CompiledText compiled_text(const compiler::CompileOutput& output, std::uint8_t group, bool dry_run,
                           Emit emit) {
  const Board& board = board_for(output);
  CompiledText r;
  if (!dry_run || board.plan == nullptr) {
    auto text = board.render(output, emit, group);
    if (!text)
      r.error = text.error().message;
    else
      r.text = std::move(text).value();
    return r;
  }
  auto plan = plan_for(board, output, group);
  if (!plan) {
    r.error = plan.error().message;
    return r;
  }
  upload::UploadOptions options;
  options.group = group;
  DryRun dry = boards::dry_run(board, *plan, options);
  r.internal = !dry.result.ok();
  if (r.internal)
    r.error = dry.result.message;
  else
    r.text = std::move(dry.text);
  return r;
}

}  // namespace seqc::boards
