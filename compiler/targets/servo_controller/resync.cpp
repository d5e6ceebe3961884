#include "compiler/targets/servo_controller/resync.hpp"

#include <algorithm>
#include <cstdlib>

namespace seqc::compiler {

using compiler::ExactMs;

Result<std::vector<ResyncPiece>> split_at_bars(const compiler::ServoProgram& program,
                                               std::uint32_t bars, std::int32_t clock_ppm) {
  if (bars == 0) return make_error("--resync takes a number of bars, at least 1");
  const std::vector<compiler::Keyframe>& kf = program.keyframes;
  if (kf.empty()) return make_error("the program has no actions");
  const compiler::TempoMap& map = program.timeline.tempo_map;
  const ExactMs scale = ExactMs::ratio(1000000 + std::int64_t{clock_ppm}, 1000000);

  std::vector<std::size_t> first = {0};  // each piece's first keyframe
  for (std::int64_t k = 1;; ++k) {
    const auto beat = map.beat_of_bar(ExactMs(k * std::int64_t{bars}));
    const auto at = beat ? map.time_of_beat(*beat) : std::nullopt;
    if (!at) {
      if (k == 1) {
        return make_error(
            "--resync needs bar lines: give the file a tempo and a meter (or a "
            "music: block)");
      }
      break;
    }
    if (*at >= program.timeline.end) break;
    const std::int64_t board = (*at * scale).round();
    // The boundary nearest the bar line: the first start at or after it, or the one before.
    auto next = std::lower_bound(
        kf.begin(), kf.end(), board,
        [](const compiler::Keyframe& f, std::int64_t t) { return std::int64_t{f.start_ms} < t; });
    std::size_t i = static_cast<std::size_t>(next - kf.begin());
    if (i == kf.size() || (i > 0 && board - std::int64_t{kf[i - 1].start_ms} <
                                        std::int64_t{kf[i].start_ms} - board)) {
      --i;
    }
    if (i > first.back()) first.push_back(i);
  }

  std::vector<ResyncPiece> pieces;
  for (std::size_t p = 0; p < first.size(); ++p) {
    const std::size_t from = first[p];
    const std::size_t to = p + 1 < first.size() ? first[p + 1] : kf.size();
    ResyncPiece piece;
    piece.board_start_ms = kf[from].start_ms;
    piece.host_start = ExactMs(std::int64_t{piece.board_start_ms}) / scale;
    for (std::size_t i = from; i < to; ++i) {
      compiler::Keyframe k = kf[i];
      k.start_ms -= piece.board_start_ms;
      piece.keyframes.push_back(std::move(k));
    }
    pieces.push_back(std::move(piece));
  }
  return pieces;
}

}  // namespace seqc::compiler
