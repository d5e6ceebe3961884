#include "runtime/boards/upload_run.hpp"

#include <algorithm>
#include <utility>

#include <fmt/format.h>

#include "compiler/frontend/profiles.hpp"

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

std::string pieces_text(const ResyncCut& cut, std::uint32_t bars) {
  const std::size_t n = cut.pieces.size();
  if (!cut.chained) {
    return fmt::format("{} {} of {} {}", n, n == 1 ? "piece" : "pieces", bars,
                       bars == 1 ? "bar" : "bars");
  }
  std::string starts;
  for (std::size_t k = 0; k < cut.bars.size(); ++k) {
    if (k > 0) starts += k + 1 == cut.bars.size() ? " and " : ", ";
    starts += std::to_string(cut.bars[k]);
  }
  if (cut.bars.empty() || cut.bars.back() == 0) return fmt::format("{} chained groups", n);
  return fmt::format("{} chained groups starting on bars {}", n, starts);
}

bool needs_chain(const compiler::ServoProgram& program) {
  return program.group_capacity > 0 && program.keyframes.size() > program.group_capacity;
}

ResyncCut cut_for_resync(const compiler::ServoProgram& program, std::uint32_t bars,
                         std::int32_t clock_ppm, std::uint8_t first_group) {
  ResyncCut cut;
  const std::size_t capacity =
      program.group_capacity > 0 ? program.group_capacity : program.keyframes.size();
  if (bars == 0) {
    auto chain = compiler::chain_groups(program, capacity, clock_ppm);
    if (!chain) {
      cut.error = chain.error().message;
      return cut;
    }
    cut.pieces = std::move(chain->pieces);
    cut.bars = std::move(chain->bars);
    cut.chained = true;
  } else {
    auto pieces = compiler::split_at_bars(program, bars, clock_ppm);
    if (!pieces) {
      cut.error = pieces.error().message;
      return cut;
    }
    cut.pieces = std::move(pieces).value();
    for (std::size_t k = 0; k < cut.pieces.size(); ++k) {
      if (cut.pieces[k].keyframes.size() > capacity) {
        cut.error = fmt::format(
            "piece {} of {} bars needs {} actions, and a group holds {}; give --resync fewer bars",
            k + 1, bars, cut.pieces[k].keyframes.size(), capacity);
        cut.pieces.clear();
        return cut;
      }
    }
  }
  cut.last_group = static_cast<std::size_t>(first_group) + cut.pieces.size() - 1;
  // Groups 0-254 can be started (255 names every group on the xArm family).
  const std::size_t stored = std::min<std::size_t>(
      255, compiler::stored_groups(compiler::find_profile(program.robot.profile)));
  if (cut.last_group >= stored) {
    cut.error = cut.chained
                    ? fmt::format(
                          "the dance needs {} groups of at most {} actions, groups {}-{}; "
                          "the board's groups go up to {} (give a lower --group)",
                          cut.pieces.size(), capacity, first_group, cut.last_group, stored - 1)
                    : fmt::format(
                          "{} pieces of {} {} need groups {}-{}; groups go up to {} (give "
                          "a lower --group or more bars)",
                          cut.pieces.size(), bars, bars == 1 ? "bar" : "bars", first_group,
                          cut.last_group, stored - 1);
    cut.pieces.clear();
  }
  return cut;
}

}  // namespace seqc::boards
