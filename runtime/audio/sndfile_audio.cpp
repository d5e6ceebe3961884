#include "runtime/audio/sndfile_audio.hpp"

#include <sndfile.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <system_error>

namespace seqc::audio {
namespace {

struct CloseSndfile {
  void operator()(SNDFILE* f) const { sf_close(f); }
};
using SndfilePtr = std::unique_ptr<SNDFILE, CloseSndfile>;

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
  // Written beside the target and renamed over it, so a failed write leaves nothing half done.
  const std::string temp = path + ".part";
  SF_INFO info{};
  info.samplerate = static_cast<int>(std::lround(audio.sample_rate));
  info.channels = 1;
  info.format = SF_FORMAT_WAV | SF_FORMAT_PCM_16;
  {
    SndfilePtr file(sf_open(temp.c_str(), SFM_WRITE, &info));
    if (!file) return make_error(path + ": cannot write: " + sf_strerror(nullptr));
    // Floats beyond [-1, 1] are clipped, not wrapped, when converted to 16 bits.
    sf_command(file.get(), SFC_SET_CLIPPING, nullptr, SF_TRUE);
    // In blocks: libsndfile 1.2.0's Vorbis encoder crashes on one very large write, and a
    // block at a time costs nothing for the other formats.
    constexpr std::size_t kBlock = 4096;
    for (std::size_t at = 0; at < audio.samples.size(); at += kBlock) {
      const auto frames = static_cast<sf_count_t>(std::min(kBlock, audio.samples.size() - at));
      if (sf_writef_float(file.get(), audio.samples.data() + at, frames) != frames) {
        const std::string why = sf_strerror(file.get());
        file.reset();
        std::remove(temp.c_str());
        return make_error(path + ": cannot write: " + why);
      }
    }
  }
  std::error_code ec;
  std::filesystem::rename(temp, path, ec);
  if (ec) {
    std::remove(temp.c_str());
    return make_error(path + ": cannot write: " + ec.message());
  }
  return Ok{};
}

}  // namespace seqc::audio
