// The compiler's SongReader on the audio boundary (runtime/audio), for the song of a `music:`
// block: how `seqc check`, `compile`,
// `simulate` and `plot` decode a choreography's `music:` song for the audio check.
#pragma once

#include <string>
#include <utility>

#include "base/source.hpp"
#include "runtime/audio/audio_files.hpp"

namespace seqc::boards {

class AudioSongReader final : public seqc::SongReader {
 public:
  explicit AudioSongReader(audio::AudioReader& audio) : audio_(audio) {}
  Result<seqc::SongSamples> read(const std::string& path) override {
    Result<audio::MonoAudio> a = audio_.read(path);
    if (!a) return a.error();
    return seqc::SongSamples{std::move(a->samples), a->sample_rate};
  }

 private:
  audio::AudioReader& audio_;
};

}  // namespace seqc::boards
