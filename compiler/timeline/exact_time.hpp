// Exact time for the timeline: a rational number of milliseconds. Beats at any tempo (a beat
// at 110 bpm is 6000/11 ms) add up without rounding, so a dance stays on its music however
// long it is; only action boundaries are rounded, once, on the absolute timeline (round()).
// Values are kept reduced with a positive denominator; arithmetic goes through 128-bit
// intermediates and saturates far beyond any group's length instead of overflowing.
#pragma once

#include <cmath>
#include <compare>
#include <cstdint>
#include <numeric>

namespace seqc::compiler {

// 128-bit intermediates (a GCC and Clang extension; __extension__ keeps -Wpedantic quiet).
__extension__ typedef __int128 WideInt;

class ExactMs {
 public:
  constexpr ExactMs() = default;
  constexpr ExactMs(std::int64_t ms) : num_(ms), den_(1) {}  // NOLINT: whole ms convert freely
  static ExactMs ratio(WideInt num, WideInt den) {
    ExactMs r;
    r.set(num, den);
    return r;
  }
  // A decimal value (e.g. a tempo or "1.5s" read as a double), exact to 1e-6.
  static ExactMs from_double(double v) {
    return ratio(static_cast<WideInt>(v * 1e6 + (v < 0 ? -0.5 : 0.5)), 1000000);
  }

  std::int64_t num() const { return num_; }
  std::int64_t den() const { return den_; }
  double value() const { return static_cast<double>(num_) / static_cast<double>(den_); }
  // Nearest whole millisecond, halves away from zero.
  std::int64_t round() const {
    const std::int64_t q = num_ / den_;
    const std::int64_t r = num_ % den_;
    if (2 * (r < 0 ? -r : r) >= den_) return q + (num_ < 0 ? -1 : 1);
    return q;
  }

  friend ExactMs operator+(ExactMs a, ExactMs b) {
    return ratio(static_cast<WideInt>(a.num_) * b.den_ + static_cast<WideInt>(b.num_) * a.den_,
                 static_cast<WideInt>(a.den_) * b.den_);
  }
  friend ExactMs operator-(ExactMs a, ExactMs b) {
    return ratio(static_cast<WideInt>(a.num_) * b.den_ - static_cast<WideInt>(b.num_) * a.den_,
                 static_cast<WideInt>(a.den_) * b.den_);
  }
  friend ExactMs operator*(ExactMs a, ExactMs b) {
    return ratio(static_cast<WideInt>(a.num_) * b.num_, static_cast<WideInt>(a.den_) * b.den_);
  }
  friend ExactMs operator/(ExactMs a, ExactMs b) {
    return ratio(static_cast<WideInt>(a.num_) * b.den_, static_cast<WideInt>(a.den_) * b.num_);
  }
  ExactMs& operator+=(ExactMs b) { return *this = *this + b; }
  friend bool operator==(ExactMs a, ExactMs b) { return a.num_ == b.num_ && a.den_ == b.den_; }
  friend std::strong_ordering operator<=>(ExactMs a, ExactMs b) {
    return static_cast<WideInt>(a.num_) * b.den_ <=> static_cast<WideInt>(b.num_) * a.den_;
  }

 private:
  void set(WideInt num, WideInt den) {
    if (den == 0) den = 1;
    if (den < 0) {
      num = -num;
      den = -den;
    }
    WideInt a = num < 0 ? -num : num;
    WideInt b = den;
    while (b != 0) {
      const WideInt t = a % b;
      a = b;
      b = t;
    }
    if (a > 1) {
      num /= a;
      den /= a;
    }
    // Saturate: nothing a group holds comes near 2^62 ms.
    constexpr WideInt kMax = std::int64_t{1} << 62;
    while (den > kMax || num > kMax || num < -kMax) {
      num /= 2;
      den = den / 2 == 0 ? 1 : den / 2;
    }
    num_ = static_cast<std::int64_t>(num);
    den_ = static_cast<std::int64_t>(den);
  }

  std::int64_t num_ = 0;
  std::int64_t den_ = 1;
};

// A point of the timeline as it is stored: milliseconds in a double. ExactMs values convert
// to it; it is exact for whole and half milliseconds and within 1e-9 ms of any other time a
// sequence can hold, so rounding it gives what rounding the ExactMs gives (a value with a
// denominator above 2 is never within 1e-6 of a half).
struct Instant {
  double ms = 0;
  constexpr Instant() = default;
  Instant(ExactMs t) : ms(t.value()) {}  // NOLINT: exact times convert freely
  double value() const { return ms; }
  std::int64_t round() const { return static_cast<std::int64_t>(std::llround(ms)); }
  friend auto operator<=>(const Instant&, const Instant&) = default;
};

}  // namespace seqc::compiler
