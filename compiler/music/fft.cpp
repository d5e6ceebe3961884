#include "compiler/music/fft.hpp"

#include <cmath>
#include <numbers>

namespace seqc::music {

Fft::Fft(std::size_t size) : size_(size), bit_reverse_(size), twiddle_(size / 2), scratch_(size) {
  std::size_t bits = 0;
  while ((std::size_t{1} << bits) < size) ++bits;
  for (std::size_t i = 0; i < size; ++i) {
    std::size_t r = 0;
    for (std::size_t b = 0; b < bits; ++b) r |= ((i >> b) & 1u) << (bits - 1 - b);
    bit_reverse_[i] = r;
  }
  for (std::size_t k = 0; k < size / 2; ++k) {
    const double angle = -2.0 * std::numbers::pi * double(k) / double(size);
    twiddle_[k] = {std::cos(angle), std::sin(angle)};
  }
}

void Fft::forward(std::vector<std::complex<double>>& data) const {
  for (std::size_t i = 0; i < size_; ++i) {
    if (i < bit_reverse_[i]) std::swap(data[i], data[bit_reverse_[i]]);
  }
  for (std::size_t len = 2; len <= size_; len <<= 1) {
    const std::size_t half = len / 2;
    const std::size_t step = size_ / len;
    for (std::size_t start = 0; start < size_; start += len) {
      for (std::size_t k = 0; k < half; ++k) {
        const std::complex<double> t = twiddle_[k * step] * data[start + k + half];
        data[start + k + half] = data[start + k] - t;
        data[start + k] += t;
      }
    }
  }
}

void Fft::magnitudes(const std::vector<double>& real, std::vector<double>& out) const {
  for (std::size_t i = 0; i < size_; ++i) scratch_[i] = {real[i], 0.0};
  forward(scratch_);
  out.resize(size_ / 2 + 1);
  for (std::size_t k = 0; k <= size_ / 2; ++k) out[k] = std::abs(scratch_[k]);
}

}  // namespace seqc::music
