#include "runtime/audio/sndfile_audio.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sndfile.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

#include "runtime/io/disk.hpp"

namespace seqc::audio {
namespace {

struct CloseSndfile {
  void operator()(SNDFILE* f) const { sf_close(f); }
};
using SndfilePtr = std::unique_ptr<SNDFILE, CloseSndfile>;

// A growable file in memory for sf_open_virtual: libsndfile seeks back to patch the header.
// Writing past `max_bytes` fails, so an encoder's output cannot outgrow what its caller allows.
struct MemoryFile {
  std::string bytes;
  std::size_t at = 0;
  std::size_t max_bytes = static_cast<std::size_t>(-1);
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
  if (m->at + n > m->max_bytes) return 0;
  if (m->bytes.size() < m->at + n) m->bytes.resize(m->at + n);
  std::memcpy(m->bytes.data() + m->at, ptr, n);
  m->at += n;
  return count;
}

sf_count_t memory_tell(void* user) {
  return static_cast<sf_count_t>(static_cast<MemoryFile*>(user)->at);
}

// Closes a descriptor on every path out.
class Descriptor {
 public:
  explicit Descriptor(int fd) : fd_(fd) {}
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  ~Descriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  int get() const { return fd_; }

 private:
  int fd_;
};

// What a stream's first block must show: a format libsndfile knows (cover art in a FLAC's
// metadata fits in it).
constexpr std::size_t kSniffBytes = std::size_t{1} << 20;

// Appends what `fd` (non-blocking) gives until `into` holds `upto` bytes or the stream ends
// (`ended`), waiting at most idle_seconds for each read.
Status read_stream(int fd, const std::string& path, std::size_t upto, double idle_seconds,
                   std::string& into, bool& ended) {
  std::vector<char> chunk(64 * 1024);
  const int idle_ms = static_cast<int>(std::lround(idle_seconds * 1000));
  while (into.size() < upto) {
    pollfd ready{fd, POLLIN, 0};
    const int polled = ::poll(&ready, 1, idle_ms);
    if (polled < 0 && errno == EINTR) continue;
    if (polled < 0) return make_error(path + ": cannot read: " + std::strerror(errno));
    if (polled == 0) {
      char text[96];
      std::snprintf(text, sizeof text, ": nothing to read for %g s (a FIFO with no writer?)",
                    idle_seconds);
      return make_error(path + text);
    }
    const ssize_t n = ::read(fd, chunk.data(), std::min(chunk.size(), upto - into.size()));
    if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
    if (n < 0) return make_error(path + ": cannot read: " + std::strerror(errno));
    if (n == 0) {
      ended = true;
      return Ok{};
    }
    into.append(chunk.data(), static_cast<std::size_t>(n));
  }
  return Ok{};
}

Error too_long(const std::string& path, double max_seconds) {
  char text[80];
  std::snprintf(text, sizeof text, ": longer than %.0f s, the most seqc reads", max_seconds);
  return make_error(path + text);
}

Error too_many_samples(const std::string& path, std::uint64_t max) {
  return make_error(path + ": more than " + std::to_string(max) +
                    " samples (frames x channels), the most seqc reads");
}

// The open song, block by block: each block's frames mixed down to mono (the mean of the
// channels), then decimated when the rate is above limits.max_kept_rate.
Result<MonoAudio> decode(const std::string& path, SNDFILE* file, const SF_INFO& info,
                         const AudioReadLimits& limits) {
  if (info.channels < 1 || info.samplerate < 1 || info.frames < 0) {
    return make_error(path + ": cannot decode: no audio in it");
  }
  const double rate = info.samplerate;
  const auto channels = static_cast<std::uint64_t>(info.channels);
  const auto frames = static_cast<std::uint64_t>(info.frames);
  if (double(info.frames) / rate > limits.max_seconds) return too_long(path, limits.max_seconds);
  const std::uint64_t max_frames = limits.max_file_samples / channels;
  if (frames > max_frames) return too_many_samples(path, limits.max_file_samples);
  const auto factor = static_cast<std::uint64_t>(
      rate > limits.max_kept_rate ? std::ceil(rate / limits.max_kept_rate) : 1.0);
  MonoAudio audio;
  audio.sample_rate = rate / double(factor);
  audio.samples.reserve(
      static_cast<std::size_t>(std::min(frames / factor, limits.max_mono_samples)));
  const std::size_t block_frames = std::clamp<std::size_t>(std::size_t{65536} / channels, 1, 4096);
  std::vector<float> block(block_frames * channels);
  std::uint64_t read = 0;
  double group_sum = 0;
  std::uint64_t in_group = 0;
  for (;;) {
    const sf_count_t got =
        sf_readf_float(file, block.data(), static_cast<sf_count_t>(block_frames));
    if (got <= 0) break;
    // A header may lie, or not know (a stream): what is decoded is counted as well.
    read += static_cast<std::uint64_t>(got);
    if (read > max_frames) return too_many_samples(path, limits.max_file_samples);
    if (double(read) / rate > limits.max_seconds) return too_long(path, limits.max_seconds);
    for (std::size_t i = 0; i < static_cast<std::size_t>(got); ++i) {
      float sum = 0;
      for (std::size_t c = 0; c < channels; ++c) sum += block[i * channels + c];
      const float mono = sum / float(channels);
      if (factor > 1) {
        group_sum += mono;
        if (++in_group < factor) continue;
      }
      if (audio.samples.size() >= limits.max_mono_samples) {
        return make_error(path + ": more than " + std::to_string(limits.max_mono_samples) +
                          " samples once mixed down to mono, the most seqc keeps");
      }
      audio.samples.push_back(factor > 1 ? float(group_sum / double(factor)) : mono);
      group_sum = 0;
      in_group = 0;
    }
  }
  if (sf_error(file) != SF_ERR_NO_ERROR) {
    return make_error(path + ": cannot decode: " + sf_strerror(file));
  }
  return audio;
}

}  // namespace

Result<MonoAudio> SndfileAudioReader::read(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return make_error(path + ": no such file");
  if (std::filesystem::is_directory(path, ec)) return make_error(path + ": is a directory");
  // O_NONBLOCK: opening a FIFO with no writer must not block; reads then wait in poll().
  Descriptor fd(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC));
  if (fd.get() < 0) return make_error(path + ": cannot read: " + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd.get(), &st) != 0) {
    return make_error(path + ": cannot read: " + std::strerror(errno));
  }
  if (S_ISREG(st.st_mode)) {
    ::fcntl(fd.get(), F_SETFL, ::fcntl(fd.get(), F_GETFL) & ~O_NONBLOCK);
    SF_INFO info{};
    SndfilePtr file(sf_open_fd(fd.get(), SFM_READ, &info, SF_FALSE));
    // libsndfile says "File contains data in an unknown format." and the like.
    if (!file) return make_error(path + ": cannot decode: " + sf_strerror(nullptr));
    return decode(path, file.get(), info, limits_);
  }
  // A FIFO, a terminal, a device: no size to trust and no seeking, so it is read into memory,
  // first one block alone to see that it is audio at all.
  MemoryFile memory;
  bool ended = false;
  const std::size_t sniff = std::min(kSniffBytes, limits_.max_stream_bytes + 1);
  if (Status s = read_stream(fd.get(), path, sniff, limits_.idle_seconds, memory.bytes, ended);
      !s) {
    return s.error();
  }
  SF_VIRTUAL_IO io{memory_length, memory_seek, memory_read, memory_write, memory_tell};
  if (!ended) {
    SF_INFO info{};
    SndfilePtr first(sf_open_virtual(&io, SFM_READ, &info, &memory));
    if (!first) return make_error(path + ": cannot decode: " + sf_strerror(nullptr));
    first.reset();
    memory.at = 0;
    if (Status s = read_stream(fd.get(), path, limits_.max_stream_bytes + 1, limits_.idle_seconds,
                               memory.bytes, ended);
        !s) {
      return s.error();
    }
  }
  if (memory.bytes.size() > limits_.max_stream_bytes) {
    return make_error(path + ": more than " + std::to_string(limits_.max_stream_bytes) +
                      " bytes, the most seqc reads from a FIFO or device");
  }
  SF_INFO info{};
  SndfilePtr file(sf_open_virtual(&io, SFM_READ, &info, &memory));
  if (!file) return make_error(path + ": cannot decode: " + sf_strerror(nullptr));
  return decode(path, file.get(), info, limits_);
}

namespace {

// `audio` encoded in memory as `format` (libsndfile's), at most `max_bytes`; `what` names it in
// an error. `quality`, when given, is SFC_SET_VBR_ENCODING_QUALITY's (0-1, for Vorbis).
Result<std::string> encode(const MonoAudio& audio, int format, std::optional<double> quality,
                           std::size_t max_bytes, const std::string& what) {
  MemoryFile memory;
  memory.max_bytes = max_bytes;
  SF_VIRTUAL_IO io{memory_length, memory_seek, memory_read, memory_write, memory_tell};
  SF_INFO info{};
  info.samplerate = static_cast<int>(std::lround(audio.sample_rate));
  info.channels = 1;
  info.format = format;
  {
    SndfilePtr file(sf_open_virtual(&io, SFM_WRITE, &info, &memory));
    if (!file) return make_error(what + ": cannot write: " + sf_strerror(nullptr));
    // Floats beyond [-1, 1] are clipped, not wrapped, when converted to 16 bits.
    sf_command(file.get(), SFC_SET_CLIPPING, nullptr, SF_TRUE);
    if (quality) {
      double q = *quality;
      sf_command(file.get(), SFC_SET_VBR_ENCODING_QUALITY, &q, sizeof q);
    }
    // In blocks: libsndfile 1.2.0's Vorbis encoder crashes on one very large write, and a
    // block at a time costs nothing for the other formats.
    constexpr std::size_t kBlock = 4096;
    for (std::size_t at = 0; at < audio.samples.size(); at += kBlock) {
      const auto frames = static_cast<sf_count_t>(std::min(kBlock, audio.samples.size() - at));
      if (sf_writef_float(file.get(), audio.samples.data() + at, frames) != frames) {
        if (memory.at + kBlock * 4 > max_bytes) {
          return make_error(what + ": would be larger than " + std::to_string(max_bytes >> 20) +
                            " MiB");
        }
        return make_error(what + ": cannot write: " + sf_strerror(file.get()));
      }
    }
  }  // sf_close writes the final header sizes (and a Vorbis stream's last pages)
  if (memory.bytes.empty()) return make_error(what + ": cannot write: nothing was encoded");
  return std::move(memory.bytes);
}

}  // namespace

Status SndfileAudioWriter::write_wav(const std::string& path, const MonoAudio& audio) {
  // Encoded in memory, then written by the one safe writer (io::write_file_safely): nothing is
  // opened at a guessable name, a device stays a device, and a failed run leaves nothing behind.
  Result<std::string> bytes = encode(audio, SF_FORMAT_WAV | SF_FORMAT_PCM_16, std::nullopt,
                                     static_cast<std::size_t>(-1), path);
  if (!bytes) return bytes.error();
  return io::write_file_safely(path, *bytes);
}

Result<std::string> encode_ogg_vorbis(const MonoAudio& audio, double quality,
                                      std::size_t max_bytes) {
  const int format = SF_FORMAT_OGG | SF_FORMAT_VORBIS;
  SF_INFO info{};
  info.samplerate = static_cast<int>(std::lround(audio.sample_rate));
  info.channels = 1;
  info.format = format;
  if (sf_format_check(&info) == 0) {
    return make_error("this libsndfile cannot write Ogg Vorbis (it was built without it)");
  }
  return encode(audio, format, quality, max_bytes, "the song as Ogg Vorbis");
}

}  // namespace seqc::audio
