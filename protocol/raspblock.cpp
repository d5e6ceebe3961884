#include "protocol/raspblock/raspblock.hpp"

#include <cstdlib>
#include <string>

namespace seqc::raspblock {

namespace {

constexpr std::size_t kFrameOverhead = 5;  // FF FE FUNC LEN ... CHK
constexpr std::uint8_t kPidLen = 9;
constexpr std::uint8_t kGimbalLen = 4;
constexpr std::uint8_t kSingleLen = 3;
constexpr std::uint8_t kRockerLen = 8;
constexpr std::uint8_t kRockerMode = 0x01;  // the only mode the document lists

struct Range {
  int lo;
  int hi;
};
constexpr Range kHorizontal{500, 2500};
constexpr Range kVertical{500, 1950};
constexpr Range kSingleIndex{1, 4};
constexpr Range kSinglePosition{500, 2500};

// One rocker axis: a big-endian magnitude and one bit of the direction byte 0b00000XYZ.
struct Axis {
  const char* name;
  std::uint8_t bit;
  bool bit_means_negative;
  int max_magnitude;
};
constexpr Axis kAxisX{"x", 0x04, true, 25};  // bit set when X < 0 (vendor driver)
constexpr Axis kAxisY{"y", 0x02, true, 25};  // bit set when Y < 0 (vendor driver)
// reading: Z is sent like X and Y, as a magnitude of at most 200 (the document's "0-200")
// with the sign in the direction byte, but its bit is set when Z >= 0, the opposite sense,
// exactly as the vendor driver does. So Z spans -200..200 and Z = 0 sets the bit. A capture
// of the board turning counterclockwise would confirm whether it honours negative Z.
constexpr Axis kAxisZ{"z", 0x01, false, 200};
constexpr std::uint8_t kDirectionMask = kAxisX.bit | kAxisY.bit | kAxisZ.bit;

bool in(Range r, int v) { return v >= r.lo && v <= r.hi; }

Status check(Range r, int v, const std::string& what) {
  if (!in(r, v)) {
    return make_error(what + " " + std::to_string(v) + " is outside " + std::to_string(r.lo) +
                      ".." + std::to_string(r.hi));
  }
  return Ok{};
}

bool sets_bit(const Axis& a, int v) { return a.bit_means_negative ? v < 0 : v >= 0; }

Status check_axis(const Axis& a, int v) {
  return check(Range{-a.max_magnitude, a.max_magnitude}, v, std::string("Rocker ") + a.name);
}

std::uint8_t hi(int v) { return static_cast<std::uint8_t>((v >> 8) & 0xff); }
std::uint8_t lo(int v) { return static_cast<std::uint8_t>(v & 0xff); }
int be16(const Bytes& d, std::size_t at) { return (d[at] << 8) | d[at + 1]; }

std::uint8_t checksum(std::uint8_t func, ByteView data) {
  unsigned sum = func + static_cast<unsigned>(data.size());
  for (std::uint8_t b : data) sum += b;
  return static_cast<std::uint8_t>(sum & 0xff);
}

Bytes packet(Function func, const Bytes& data) {
  const auto f = static_cast<std::uint8_t>(func);
  Bytes out;
  out.reserve(data.size() + kFrameOverhead);
  for (std::uint8_t b : {kHeader0, kHeader1, f, static_cast<std::uint8_t>(data.size())}) {
    out.push_back(b);
  }
  for (std::uint8_t b : data) out.push_back(b);
  out.push_back(checksum(f, data));
  return out;
}

Result<Bytes> encode_one(const PidAdjust& p) {
  const auto mode = static_cast<std::uint8_t>(p.mode);
  if (mode > 1) {
    return make_error("PidAdjust mode " + std::to_string(mode) +
                      " is outside 0..1 (0 = speed, 1 = position)");
  }
  return packet(Function::Pid, {mode, p.speed_kp, p.speed_ki, p.position_kp, p.position_ki,
                                p.position_kd, p.yaw_kp, p.yaw_ki, p.yaw_kd});
}

Result<Bytes> encode_one(const GimbalServos& g) {
  if (auto ok = check(kHorizontal, g.horizontal, "GimbalServos horizontal"); !ok) {
    return ok.error();
  }
  if (auto ok = check(kVertical, g.vertical, "GimbalServos vertical"); !ok) return ok.error();
  return packet(Function::Servo,
                {hi(g.horizontal), lo(g.horizontal), hi(g.vertical), lo(g.vertical)});
}

Result<Bytes> encode_one(const SingleServo& s) {
  if (auto ok = check(kSingleIndex, s.index, "SingleServo index"); !ok) return ok.error();
  if (auto ok = check(kSinglePosition, s.position, "SingleServo position"); !ok) {
    return ok.error();
  }
  return packet(Function::Servo, {s.index, hi(s.position), lo(s.position)});
}

Result<Bytes> encode_one(const Rocker& r) {
  for (auto [axis, v] : {std::pair{kAxisX, r.x}, std::pair{kAxisY, r.y}, std::pair{kAxisZ, r.z}}) {
    if (auto ok = check_axis(axis, v); !ok) return ok.error();
  }
  std::uint8_t dir = 0;
  if (sets_bit(kAxisX, r.x)) dir |= kAxisX.bit;
  if (sets_bit(kAxisY, r.y)) dir |= kAxisY.bit;
  if (sets_bit(kAxisZ, r.z)) dir |= kAxisZ.bit;
  const int x = std::abs(r.x), y = std::abs(r.y), z = std::abs(r.z);
  return packet(Function::Rocker, {kRockerMode, hi(x), lo(x), hi(y), lo(y), hi(z), lo(z), dir});
}

// The signed value of one axis from its magnitude and the direction byte. A sign bit that
// makes zero negative ("-0") is rejected: the vendor driver never sends it.
Result<int> read_axis(const Axis& a, int magnitude, std::uint8_t dir) {
  const std::string what = std::string("Rocker ") + a.name;
  if (magnitude > a.max_magnitude) {
    return make_error(what + " magnitude " + std::to_string(magnitude) + " is outside 0.." +
                      std::to_string(a.max_magnitude));
  }
  const bool bit = (dir & a.bit) != 0;
  const bool negative = bit == a.bit_means_negative;
  if (negative && magnitude == 0) {
    return make_error(what + " is 0 but its direction bit says negative");
  }
  return negative ? -magnitude : magnitude;
}

Result<Packet> decode_rocker(const Bytes& d) {
  if (d[0] != kRockerMode) {
    return make_error("Rocker mode " + std::to_string(d[0]) + " is not 1");
  }
  const std::uint8_t dir = d[7];
  if ((dir & ~kDirectionMask) != 0) {
    return make_error("Rocker direction byte " + std::to_string(dir) +
                      " sets bits other than 0b00000111");
  }
  auto x = read_axis(kAxisX, be16(d, 1), dir);
  if (!x) return x.error();
  auto y = read_axis(kAxisY, be16(d, 3), dir);
  if (!y) return y.error();
  auto z = read_axis(kAxisZ, be16(d, 5), dir);
  if (!z) return z.error();
  return Packet{Rocker{*x, *y, *z}};
}

// Function 02 is told apart by LEN, so the function alone does not fix the length.
bool valid_len(std::uint8_t func, std::uint8_t len) {
  switch (func) {
    case static_cast<std::uint8_t>(Function::Pid):
      return len == kPidLen;
    case static_cast<std::uint8_t>(Function::Servo):
      return len == kGimbalLen || len == kSingleLen;
    case static_cast<std::uint8_t>(Function::Rocker):
      return len == kRockerLen;
    default:
      return false;
  }
}

Result<Packet> decode_data(std::uint8_t func, const Bytes& d) {
  if (func == static_cast<std::uint8_t>(Function::Pid)) {
    if (d[0] > 1) {
      return make_error("PidAdjust mode " + std::to_string(d[0]) + " is outside 0..1");
    }
    return Packet{
        PidAdjust{static_cast<PidMode>(d[0]), d[1], d[2], d[3], d[4], d[5], d[6], d[7], d[8]}};
  }
  if (func == static_cast<std::uint8_t>(Function::Servo) && d.size() == kGimbalLen) {
    const int h = be16(d, 0), v = be16(d, 2);
    if (auto ok = check(kHorizontal, h, "GimbalServos horizontal"); !ok) return ok.error();
    if (auto ok = check(kVertical, v, "GimbalServos vertical"); !ok) return ok.error();
    return Packet{GimbalServos{static_cast<std::uint16_t>(h), static_cast<std::uint16_t>(v)}};
  }
  if (func == static_cast<std::uint8_t>(Function::Servo)) {
    const int pos = be16(d, 1);
    if (auto ok = check(kSingleIndex, d[0], "SingleServo index"); !ok) return ok.error();
    if (auto ok = check(kSinglePosition, pos, "SingleServo position"); !ok) return ok.error();
    return Packet{SingleServo{d[0], static_cast<std::uint16_t>(pos)}};
  }
  return decode_rocker(d);
}

std::string len_error(std::uint8_t func, std::uint8_t len) {
  if (func < 1 || func > 3) return "unknown function " + std::to_string(func);
  return "function " + std::to_string(func) + " cannot have LEN " + std::to_string(len);
}

struct Describer {
  std::string operator()(const PidAdjust& p) const {
    return std::string("PidAdjust mode=") + (p.mode == PidMode::Speed ? "speed" : "position") +
           " speed_kp=" + std::to_string(p.speed_kp) + " speed_ki=" + std::to_string(p.speed_ki) +
           " position_kp=" + std::to_string(p.position_kp) +
           " position_ki=" + std::to_string(p.position_ki) +
           " position_kd=" + std::to_string(p.position_kd) + " yaw_kp=" + std::to_string(p.yaw_kp) +
           " yaw_ki=" + std::to_string(p.yaw_ki) + " yaw_kd=" + std::to_string(p.yaw_kd);
  }
  std::string operator()(const GimbalServos& g) const {
    return "GimbalServos horizontal=" + std::to_string(g.horizontal) +
           " vertical=" + std::to_string(g.vertical);
  }
  std::string operator()(const SingleServo& s) const {
    return "SingleServo index=" + std::to_string(s.index) +
           " position=" + std::to_string(s.position);
  }
  std::string operator()(const Rocker& r) const {
    return "Rocker x=" + std::to_string(r.x) + " y=" + std::to_string(r.y) +
           " z=" + std::to_string(r.z);
  }
};

}  // namespace

Result<Bytes> encode(const Packet& p) {
  return std::visit([](const auto& m) { return encode_one(m); }, p);
}

Result<Packet> decode(ByteView bytes) {
  if (bytes.size() < kFrameOverhead) {
    return make_error("Raspblock packet of " + std::to_string(bytes.size()) +
                      " bytes is shorter than FF FE FUNC LEN CHK");
  }
  if (bytes[0] != kHeader0 || bytes[1] != kHeader1) {
    return make_error("Raspblock packet does not start with ff fe");
  }
  const std::uint8_t func = bytes[2];
  const std::uint8_t len = bytes[3];
  if (!valid_len(func, len)) return make_error("Raspblock packet: " + len_error(func, len));
  if (bytes.size() != len + kFrameOverhead) {
    return make_error("Raspblock packet: LEN " + std::to_string(len) + " means " +
                      std::to_string(len + kFrameOverhead) + " bytes, got " +
                      std::to_string(bytes.size()));
  }
  const Bytes data(bytes.begin() + 4, bytes.begin() + 4 + len);
  const std::uint8_t want = checksum(func, data);
  if (bytes[4 + len] != want) {
    return make_error("Raspblock packet: checksum " + to_hex(bytes.subspan(4 + len, 1)) +
                      ", expected " + to_hex(ByteView(&want, 1)));
  }
  return decode_data(func, data);
}

std::string describe(const Packet& p) { return std::visit(Describer{}, p); }

void PacketDecoder::feed(ByteView bytes) { buf_.insert(buf_.end(), bytes.begin(), bytes.end()); }

std::optional<Result<Packet>> PacketDecoder::next() {
  // A rejected header drops one byte and rescans, so a packet that starts inside a rejected
  // one is still found. A packet whose checksum holds but whose values do not is dropped whole.
  auto drop = [this](std::size_t n) {
    buf_.erase(buf_.begin(), buf_.begin() + static_cast<long>(n));
    skipped_ += n;
  };
  while (!buf_.empty()) {
    if (buf_[0] != kHeader0) {
      drop(1);
      continue;
    }
    if (buf_.size() < 2) return std::nullopt;
    if (buf_[1] != kHeader1) {
      drop(1);
      continue;
    }
    if (buf_.size() < 4) return std::nullopt;
    const std::uint8_t func = buf_[2];
    const std::uint8_t len = buf_[3];
    if (!valid_len(func, len)) {
      drop(1);
      return Result<Packet>(make_error("Raspblock packet rejected: " + len_error(func, len)));
    }
    const std::size_t total = len + kFrameOverhead;
    if (buf_.size() < total) return std::nullopt;
    const Bytes bytes(buf_.begin(), buf_.begin() + static_cast<long>(total));
    Result<Packet> result = decode(bytes);
    if (result.ok()) {
      buf_.erase(buf_.begin(), buf_.begin() + static_cast<long>(total));
    } else if (bytes.back() == checksum(func, ByteView(bytes).subspan(4, len))) {
      drop(total);
    } else {
      drop(1);
    }
    return result;
  }
  return std::nullopt;
}

}  // namespace seqc::raspblock
