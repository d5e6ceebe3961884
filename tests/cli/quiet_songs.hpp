// The song reader the CLI tests with `music:` share: every song is 2 s of quiet at 8 kHz, except a
// path with "missing" in it, which cannot be read; the paths asked for are kept.
#pragma once

#include <string>
#include <vector>

#include "runtime/audio/audio_files.hpp"

namespace seqc::cli::test {

class QuietSongs final : public audio::AudioReader {
 public:
  Result<audio::MonoAudio> read(const std::string& path) override {
    asked.push_back(path);
    if (path.find("missing") != std::string::npos) return make_error(path + ": no such file");
    return audio::MonoAudio{std::vector<float>(16000, 0.1f), 8000};
  }
  std::vector<std::string> asked;
};

}  // namespace seqc::cli::test
