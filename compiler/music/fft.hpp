// A small in-place radix-2 FFT for the beat analysis: power-of-two sizes only, no allocation
// per call once the plan exists. Written here so seqc links no FFT library.
#pragma once

#include <complex>
#include <cstddef>
#include <vector>

namespace seqc::music {

class Fft {
 public:
  // `size` must be a power of two (>= 2).
  explicit Fft(std::size_t size);
  std::size_t size() const { return size_; }
  // Forward transform of `data` (size() values), in place.
  void forward(std::vector<std::complex<double>>& data) const;
  // The magnitudes |X[0..size/2]| of the transform of `real` (size() samples).
  void magnitudes(const std::vector<double>& real, std::vector<double>& out) const;

 private:
  std::size_t size_;
  std::vector<std::size_t> bit_reverse_;
  std::vector<std::complex<double>> twiddle_;
  mutable std::vector<std::complex<double>> scratch_;
};

}  // namespace seqc::music
