#include "runtime/boards/upload_run.hpp"

#include <utility>

namespace seqc::boards {

upload::UploadOptions upload_options(const UploadRequest& request, const Board& board,
                                     const compiler::CompileOutput& output,
                                     const std::atomic<bool>* interrupted,
                                     std::optional<FirstMoveTooFast>& too_fast) {
  upload::UploadOptions options;
  options.group = request.group;
  options.retries = request.retries;
  options.run = request.run && (!request.music || request.dry_run);
  options.run_times = request.times;
  if (const compiler::ServoProgram* program = output.servo_program();
      request.run && !request.force && program != nullptr) {
    options.may_run = [&board, &too_fast, interrupted, program](io::Transport& t,
                                                                io::Clock& clock) {
      too_fast = first_move_too_fast(board, Line{t, clock, interrupted}, *program);
      return !too_fast;
    };
  }
  return options;
}

ResyncCut cut_for_resync(const compiler::ServoProgram& program, std::uint32_t bars,
                         std::int32_t clock_ppm, std::uint8_t first_group) {
  ResyncCut cut;
  auto pieces = compiler::split_at_bars(program, bars, clock_ppm);
  if (!pieces) {
    cut.error = pieces.error().message;
    return cut;
  }
  cut.pieces = std::move(pieces).value();
  cut.last_group = static_cast<std::size_t>(first_group) + cut.pieces.size() - 1;
  return cut;
}

}  // namespace seqc::boards
