// The audio-file boundary: decoding a song to mono samples and writing one as a WAV file. The
// analysis (compiler/music) never sees a file; `seqc beats` gets these interfaces passed in, so
// tests can hand it samples without a disk.
#pragma once

#include <string>
#include <vector>

#include "base/result.hpp"

namespace seqc::audio {

struct MonoAudio {
  std::vector<float> samples;  // channels averaged, in [-1, 1]
  double sample_rate = 0;
};

class AudioReader {
 public:
  virtual ~AudioReader() = default;
  // The whole file, or an Error naming the path and what is wrong with it.
  virtual Result<MonoAudio> read(const std::string& path) = 0;
};

class AudioWriter {
 public:
  virtual ~AudioWriter() = default;
  // A 16-bit PCM WAV file, written as io::write_file_safely writes: a file is replaced whole
  // (nothing is left at `path` when writing fails), a device or FIFO is written directly.
  virtual Status write_wav(const std::string& path, const MonoAudio& audio) = 0;
};

}  // namespace seqc::audio
