// Raspblock: decode() on the whole input, and PacketDecoder fed in chunks.
// Input: byte 0 picks the chunk size (1..16); the rest is the byte stream (and, whole, the
// single packet given to decode()).
#include <cstddef>
#include <cstdint>

#include "protocol/raspblock/raspblock.hpp"
#include "tests/fuzz/fuzz_check.hpp"

using namespace seqc;
using namespace seqc::raspblock;

namespace {

void check_packet(const Packet& packet) {
  auto bytes = encode(packet);
  FUZZ_CHECK(bytes.ok());
  auto back = decode(*bytes);
  FUZZ_CHECK(back.ok() && *back == packet);
  FUZZ_CHECK(!describe(packet).empty());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::size_t chunk = data[0] % 16 + 1;
  const ByteView stream(data + 1, size - 1);

  // A packet that decodes is canonical: it re-encodes to exactly the same bytes.
  if (auto packet = decode(stream)) {
    check_packet(*packet);
    auto bytes = encode(*packet);
    FUZZ_CHECK(Bytes(stream.begin(), stream.end()) == *bytes);
  }

  PacketDecoder decoder;
  for (std::size_t at = 0; at < stream.size(); at += chunk) {
    decoder.feed(stream.subspan(at, std::min(chunk, stream.size() - at)));
    while (auto result = decoder.next()) {
      if (result->ok()) check_packet(result->value());
      FUZZ_CHECK(result->ok() || !result->error().message.empty());
    }
  }
  FUZZ_CHECK(decoder.skipped_bytes() <= stream.size());
  return 0;
}
