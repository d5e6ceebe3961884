// A SongReader that keeps each decoded song while its file is unchanged. The server compiles
// on every pause in typing, and a choreography with a `music:` song would otherwise decode
// the whole song each time (most of the compile: 0.35 s of 0.4 s for examples/
// final-step-dance.yaml). A song is decoded again when its file's size or modification time
// changes. Used from the compiling thread alone.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>

#include "base/source.hpp"

namespace seqc::lsp {

class SongCache final : public SongReader {
 public:
  explicit SongCache(SongReader& songs) : songs_(songs) {}
  Result<SongSamples> read(const std::string& path) override;
  Result<std::string> compressed(const std::string& path) override {
    return songs_.compressed(path);
  }

 private:
  struct Stamp {
    std::uintmax_t size = 0;
    std::filesystem::file_time_type modified{};
    friend bool operator==(const Stamp&, const Stamp&) = default;
  };
  struct Entry {
    Stamp stamp;
    SongSamples song;
  };
  static std::optional<Stamp> stamp_of(const std::string& path);
  static constexpr std::size_t kMaxSongs = 3;

  SongReader& songs_;
  std::map<std::string, Entry> cache_;
};

}  // namespace seqc::lsp
