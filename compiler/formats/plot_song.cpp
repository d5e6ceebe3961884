#include "compiler/formats/plot_song.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "compiler/formats/svg_text.hpp"

namespace seqc::compiler::plot {

using svg::num;

std::string song_lane(const PlotSong& song, const Frame& f, double y0) {
  std::string out = "<g class=\"song\"><title>" + svg::escape(song.label) + "</title>\n";
  out += svg::rect(kLeft, y0, kWidth - kLeft - kRight, kSongLane,
                   "fill=\"#f8fafc\" stroke=\"#d1d5db\"");
  out += svg::text(12, y0 + 16, "song", "font-weight=\"bold\"");
  out += svg::text(12, y0 + 30, song.label, "fill=\"#6b7280\" font-size=\"10\"");
  out += svg::text(12, y0 + 44, "red: beats found", "fill=\"#dc2626\" font-size=\"10\"");

  // One bar per whole pixel column: the column's time span in the audio, its peak.
  const double mid = y0 + kSongLane / 2;
  const auto columns = static_cast<std::size_t>(kWidth - kLeft - kRight);
  const double ms_per_column = (f.to - f.from) / static_cast<double>(columns);
  const auto count = static_cast<double>(song.samples.size());
  std::string path;
  for (std::size_t c = 0; c < columns && song.sample_rate > 0; ++c) {
    const double t0 = f.from + static_cast<double>(c) * ms_per_column;
    const double first = std::max(0.0, (song.downbeat_s + t0 / 1000.0) * song.sample_rate);
    const double last =
        std::min(count, (song.downbeat_s + (t0 + ms_per_column) / 1000.0) * song.sample_rate);
    float peak = 0;
    for (auto i = static_cast<std::size_t>(std::ceil(first)); static_cast<double>(i) < last; ++i) {
      peak = std::max(peak, std::abs(song.samples[i]));
    }
    const double half = std::min(1.0, static_cast<double>(peak)) * kSongLane / 2;
    if (half < 0.25) continue;
    const double x = kLeft + static_cast<double>(c) + 0.5;
    path += "M" + num(x) + " " + num(mid - half) + "V" + num(mid + half);
  }
  if (!path.empty()) {
    out += "<path class=\"waveform\" d=\"" + path + "\" stroke=\"#94a3b8\" stroke-width=\"1\"/>\n";
  }
  for (const double beat : song.beats_s) {
    const double t = (beat - song.downbeat_s) * 1000.0;
    if (!f.inside(t)) continue;
    out += svg::line(f.x(t), y0, f.x(t), y0 + kSongLane / 4,
                     "class=\"beat\" stroke=\"#dc2626\" stroke-width=\"1.5\"");
  }
  return out + "</g>\n";
}

}  // namespace seqc::compiler::plot
