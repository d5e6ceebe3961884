// The compiler's SongReader on the audio boundary (runtime/audio), for the song of a `music:`
// block: how `seqc check`, `compile`, `simulate` and `plot` decode a choreography's `music:`
// song for the audio check, and how `seqc preview` gets a song too large to embed as it is
// (over the file reader's limit) as Ogg Vorbis at a modest quality, at most kMaxPageSongBytes.
#pragma once

#include <string>
#include <utility>

#include "base/source.hpp"
#include "runtime/audio/audio_files.hpp"
#include "runtime/audio/sndfile_audio.hpp"

namespace seqc::boards {

// An hour of mono Vorbis at quality 0.3 is about 30 MB.
inline constexpr std::size_t kMaxPageSongBytes = std::size_t{48} << 20;

class AudioSongReader final : public seqc::SongReader {
 public:
  explicit AudioSongReader(audio::AudioReader& audio) : audio_(audio) {}
  Result<seqc::SongSamples> read(const std::string& path) override {
    Result<audio::MonoAudio> a = audio_.read(path);
    if (!a) return a.error();
    return seqc::SongSamples{std::move(a->samples), a->sample_rate};
  }
  Result<std::string> compressed(const std::string& path) override {
    Result<audio::MonoAudio> a = audio_.read(path);
    if (!a) return a.error();
    return audio::encode_ogg_vorbis(*a, 0.3, kMaxPageSongBytes);
  }

 private:
  audio::AudioReader& audio_;
};

}  // namespace seqc::boards
