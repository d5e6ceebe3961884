#include "runtime/audio/sndfile_audio.hpp"

#include <sndfile.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <system_error>

#include "runtime/io/disk.hpp"

namespace seqc::audio {
namespace {

struct CloseSndfile {
  void operator()(SNDFILE* f) const { sf_close(f); }
};
using SndfilePtr = std::unique_ptr<SNDFILE, CloseSndfile>;

// A growable file in memory for sf_open_virtual: libsndfile seeks back to patch the header.
struct MemoryFile {
  std::string bytes;
  std::size_t at = 0;
};

sf_count_t memory_length(void* user) {
  return static_cast<sf_count_t>(static_cast<MemoryFile*>(user)->bytes.size());
}

sf_count_t memory_seek(sf_count_t offset, int whence, void* user) {
  auto* m = static_cast<MemoryFile*>(user);
  sf_count_t base = 0;
  if (whence == SEEK_CUR) base = static_cast<sf_count_t>(m->at);
  if (whence == SEEK_END) base = static_cast<sf_count_t>(m->bytes.size());
  if (base + offset < 0) return -1;
  m->at = static_cast<std::size_t>(base + offset);
  return static_cast<sf_count_t>(m->at);
}

sf_count_t memory_read(void* ptr, sf_count_t count, void* user) {
  auto* m = static_cast<MemoryFile*>(user);
  if (m->at >= m->bytes.size() || count <= 0) return 0;
  const std::size_t n = std::min(static_cast<std::size_t>(count), m->bytes.size() - m->at);
  std::memcpy(ptr, m->bytes.data() + m->at, n);
  m->at += n;
  return static_cast<sf_count_t>(n);
}

sf_count_t memory_write(const void* ptr, sf_count_t count, void* user) {
  auto* m = static_cast<MemoryFile*>(user);
  if (count <= 0) return 0;
  const auto n = static_cast<std::size_t>(count);
  if (m->bytes.size() < m->at + n) m->bytes.resize(m->at + n);
  std::memcpy(m->bytes.data() + m->at, ptr, n);
  m->at += n;
  return count;
}

sf_count_t memory_tell(void* user) {
  return static_cast<sf_count_t>(static_cast<MemoryFile*>(user)->at);
}

}  // namespace

Result<MonoAudio> SndfileAudioReader::read(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return make_error(path + ": no such file");
  if (std::filesystem::is_directory(path, ec)) return make_error(path + ": is a directory");
  SF_INFO info{};
  SndfilePtr file(sf_open(path.c_str(), SFM_READ, &info));
  if (!file) {
    // libsndfile says "File contains data in an unknown format." and the like.
    return make_error(path + ": cannot decode: " + sf_strerror(nullptr));
  }
  if (info.channels < 1 || info.samplerate < 1 || info.frames < 0) {
    return make_error(path + ": cannot decode: no audio in it");
  }
  if (double(info.frames) / info.samplerate > max_seconds_) {
    char text[80];
    std::snprintf(text, sizeof text, ": longer than %.0f s, the most seqc reads", max_seconds_);
    return make_error(path + text);
  }
  MonoAudio audio;
  audio.sample_rate = info.samplerate;
  audio.samples.reserve(static_cast<std::size_t>(info.frames));
  const auto channels = static_cast<std::size_t>(info.channels);
  std::vector<float> block(4096 * channels);
  for (;;) {
    const sf_count_t got = sf_readf_float(file.get(), block.data(), 4096);
    if (got <= 0) break;
    for (std::size_t i = 0; i < static_cast<std::size_t>(got); ++i) {
      float sum = 0;
      for (std::size_t c = 0; c < channels; ++c) sum += block[i * channels + c];
      audio.samples.push_back(sum / float(channels));
    }
  }
  if (sf_error(file.get()) != SF_ERR_NO_ERROR) {
    return make_error(path + ": cannot decode: " + sf_strerror(file.get()));
  }
  return audio;
}

Status SndfileAudioWriter::write_wav(const std::string& path, const MonoAudio& audio) {
  // Encoded in memory, then written by the one safe writer (io::write_file_safely): nothing is
  // opened at a guessable name, a device stays a device, and a failed run leaves nothing behind.
  MemoryFile memory;
  SF_VIRTUAL_IO io{memory_length, memory_seek, memory_read, memory_write, memory_tell};
  SF_INFO info{};
  info.samplerate = static_cast<int>(std::lround(audio.sample_rate));
  info.channels = 1;
  info.format = SF_FORMAT_WAV | SF_FORMAT_PCM_16;
  {
    SndfilePtr file(sf_open_virtual(&io, SFM_WRITE, &info, &memory));
    if (!file) return make_error(path + ": cannot write: " + sf_strerror(nullptr));
    // Floats beyond [-1, 1] are clipped, not wrapped, when converted to 16 bits.
    sf_command(file.get(), SFC_SET_CLIPPING, nullptr, SF_TRUE);
    // In blocks: libsndfile 1.2.0's Vorbis encoder crashes on one very large write, and a
    // block at a time costs nothing for the other formats.
    constexpr std::size_t kBlock = 4096;
    for (std::size_t at = 0; at < audio.samples.size(); at += kBlock) {
      const auto frames = static_cast<sf_count_t>(std::min(kBlock, audio.samples.size() - at));
      if (sf_writef_float(file.get(), audio.samples.data() + at, frames) != frames) {
        return make_error(path + ": cannot write: " + sf_strerror(file.get()));
      }
    }
  }  // sf_close writes the final header sizes
  return io::write_file_safely(path, memory.bytes);
}

}  // namespace seqc::audio
