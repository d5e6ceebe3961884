#include "runtime/lsp/song_cache.hpp"

#include <system_error>

namespace seqc::lsp {

std::optional<SongCache::Stamp> SongCache::stamp_of(const std::string& path) {
  std::error_code ec;
  Stamp s;
  s.size = std::filesystem::file_size(path, ec);
  if (ec) return std::nullopt;
  s.modified = std::filesystem::last_write_time(path, ec);
  if (ec) return std::nullopt;
  return s;
}

Result<SongSamples> SongCache::read(const std::string& path) {
  const std::optional<Stamp> stamp = stamp_of(path);
  if (!stamp) {  // no regular file to watch: decoded every time, never kept
    cache_.erase(path);
    return songs_.read(path);
  }
  if (auto it = cache_.find(path); it != cache_.end() && it->second.stamp == *stamp) {
    return it->second.song;
  }
  Result<SongSamples> song = songs_.read(path);
  if (!song) {
    cache_.erase(path);
    return song;
  }
  // A song may be tens of MB: a few are kept (a show's performers may each have one), and
  // when more come all are let go.
  if (cache_.size() >= kMaxSongs) cache_.clear();
  cache_.emplace(path, Entry{*stamp, *song});
  return song;
}

}  // namespace seqc::lsp
