#include "runtime/cli/play_progress.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ostream>

namespace seqc::cli {

std::string format_play_progress(io::Duration at, io::Duration total, std::size_t frame,
                                 std::size_t frames, int cells) {
  const double t = std::chrono::duration<double>(at).count();
  const double all = std::chrono::duration<double>(total).count();
  const int filled = all > 0 ? std::clamp(static_cast<int>(t / all * cells), 0, cells) : cells;
  std::string out = "[" + std::string(static_cast<std::size_t>(filled), '#') +
                    std::string(static_cast<std::size_t>(cells - filled), '.') + "]";
  char text[96];
  std::snprintf(text, sizeof text, "  %.1f / %.1f s  frame %zu/%zu", t, all, frame, frames);
  return out + text;
}

PlayProgress::PlayProgress(std::ostream& err, bool enabled, int columns, io::Duration total,
                           std::size_t frames)
    : err_(err), enabled_(enabled), total_(total), frames_(frames) {
  // The text after the bar is at most about 40 columns; keep one spare so it never wraps.
  const int text = static_cast<int>(format_play_progress(total, total, frames, frames, 0).size());
  cells_ = columns > 0 ? std::clamp(columns - text - 1, 5, 50) : 30;
}

PlayProgress::~PlayProgress() { finish(); }

void PlayProgress::on_sent(std::size_t index, io::Duration at) {
  if (!enabled_) return;
  const long quarter =
      static_cast<long>(std::chrono::duration_cast<std::chrono::milliseconds>(at).count() / 250);
  if (quarter == last_quarter_ && index + 1 != frames_) return;
  last_quarter_ = quarter;
  err_ << "\r\033[K" << format_play_progress(at, total_, index + 1, frames_, cells_);
  err_.flush();
  shown_ = true;
}

void PlayProgress::finish() {
  if (!shown_) return;
  err_ << "\r\033[K";
  err_.flush();
  shown_ = false;
}

}  // namespace seqc::cli
