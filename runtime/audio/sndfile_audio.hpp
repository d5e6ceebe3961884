// AudioReader and AudioWriter on libsndfile (LGPL, linked dynamically): WAV, AIFF, FLAC, Ogg
// Vorbis, Opus and MP3 in, whatever the library version was built with.
#pragma once

#include <cstddef>

#include "runtime/audio/audio_files.hpp"

namespace seqc::audio {

class SndfileAudioReader final : public AudioReader {
 public:
  // Songs longer than max_seconds are refused unread (an hour of mono floats is 635 MB at
  // 44.1 kHz).
  explicit SndfileAudioReader(double max_seconds = 3600) : max_seconds_(max_seconds) {}
  Result<MonoAudio> read(const std::string& path) override;

 private:
  double max_seconds_;
};

class SndfileAudioWriter final : public AudioWriter {
 public:
  Status write_wav(const std::string& path, const MonoAudio& audio) override;
};

}  // namespace seqc::audio
