// AudioReader and AudioWriter on libsndfile (LGPL, linked dynamically): WAV, AIFF, FLAC, Ogg
// Vorbis, Opus and MP3 in, whatever the library version was built with.
//
// Reading is bounded whatever the file claims or holds, so a small hostile file (a FLAC of
// silence at 655 kHz, /dev/zero, a FIFO that never ends) cannot take the machine's memory or
// never finish:
//  - a song is decoded in fixed blocks of frames, each mixed down to mono as it arrives;
//  - a song above max_kept_rate is decimated per block by the smallest integer factor that
//    brings it to that rate or below (each kept sample the mean of `factor` mono samples; a
//    last partial group is dropped), so the decoded song takes at most
//    max_kept_rate x max_seconds x 4 bytes (691 MB for an hour at 48 kHz);
//  - the file's samples (frames x channels) are limited, by its header before decoding and by
//    the count decoded while decoding, and so are its seconds and the kept mono samples;
//  - a path that is not a regular file (a FIFO, /dev/stdin, a device) is read into memory up to
//    max_stream_bytes, and decoded from there: its first block is tried alone first, so a
//    stream that is not audio (/dev/zero) is refused after one block; each read waits at most
//    idle_seconds for data (a FIFO with no writer).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "runtime/audio/audio_files.hpp"

namespace seqc::audio {

struct AudioReadLimits {
  double max_seconds = 3600;  // an hour
  // Samples (frames x channels) in the file: an hour of 48 kHz stereo.
  std::uint64_t max_file_samples = 3600ull * 48000 * 2;
  // Mono samples kept after decimation: an hour at 48 kHz.
  std::uint64_t max_mono_samples = 3600ull * 48000;
  // Above this, the song is decimated (the beat analysis reads about 11 kHz; playback, and a
  // click track mixed into the song, keep up to 48 kHz).
  double max_kept_rate = 48000;
  std::size_t max_stream_bytes = std::size_t{256} << 20;  // a FIFO or device, read into memory
  double idle_seconds = 10;  // the longest a FIFO or device may give nothing
};

class SndfileAudioReader final : public AudioReader {
 public:
  // Songs longer than max_seconds are refused unread (an hour of mono floats is 635 MB at
  // 44.1 kHz).
  explicit SndfileAudioReader(double max_seconds = 3600) { limits_.max_seconds = max_seconds; }
  explicit SndfileAudioReader(const AudioReadLimits& limits) : limits_(limits) {}
  Result<MonoAudio> read(const std::string& path) override;

 private:
  AudioReadLimits limits_;
};

class SndfileAudioWriter final : public AudioWriter {
 public:
  Status write_wav(const std::string& path, const MonoAudio& audio) override;
};

// `audio` as an Ogg Vorbis stream in memory (mono, at its rate), for a page to play a song too
// large to embed as it is: `quality` is libsndfile's VBR quality (0-1; 0.3 keeps ten minutes of
// a 44.1 kHz song near 5 MB). An Error when this libsndfile cannot write Vorbis
// (sf_format_check) or the stream would pass `max_bytes` (checked as it is written).
Result<std::string> encode_ogg_vorbis(const MonoAudio& audio, double quality,
                                      std::size_t max_bytes);

}  // namespace seqc::audio
