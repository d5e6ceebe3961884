// FrameDecoder fed in chunks, then decode_request/decode_reply on every frame it yields.
// Input: byte 0 picks the chunk size (1..16), the rest is the byte stream.
#include <cstddef>
#include <cstdint>

#include "protocol/lsc/lsc_messages.hpp"
#include "protocol/lsc/lsc_stream.hpp"
#include "tests/fuzz/fuzz_check.hpp"

namespace {

using namespace seqc;
using namespace seqc::lsc;

void check_frame(const Frame& frame) {
  FUZZ_CHECK(frame.data.size() + kMinLen <= 255);
  FUZZ_CHECK(frame.data.size() + kMinLen != kHeaderByte);  // the 55 55 55 reading
  auto bytes = encode_serial(frame);
  FUZZ_CHECK(bytes.ok());
  auto again = decode_serial(*bytes);
  FUZZ_CHECK(again.ok() && *again == frame);

  // Whatever decodes re-encodes to the very same frame (decoders accept only what the
  // encoders produce) and decodes again to the same value.
  if (auto request = decode_request(frame)) {
    auto encoded = encode(*request);
    FUZZ_CHECK(encoded.ok());
    FUZZ_CHECK(*encoded == frame);
    auto back = decode_request(*encoded);
    FUZZ_CHECK(back.ok() && *back == *request);
    FUZZ_CHECK(!describe(*request).empty());
  }
  if (auto reply = decode_reply(frame)) {
    auto encoded = encode(*reply);
    FUZZ_CHECK(encoded.ok());
    FUZZ_CHECK(*encoded == frame);
    auto back = decode_reply(*encoded);
    FUZZ_CHECK(back.ok() && *back == *reply);
    FUZZ_CHECK(!describe(*reply).empty());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::size_t chunk = data[0] % 16 + 1;
  const ByteView stream(data + 1, size - 1);
  FrameDecoder decoder;
  std::size_t consumed = 0;
  for (std::size_t at = 0; at < stream.size(); at += chunk) {
    decoder.feed(stream.subspan(at, std::min(chunk, stream.size() - at)));
    while (auto frame = decoder.next()) {
      check_frame(*frame);
      consumed += kHeaderSize + frame->data.size();
    }
    // Nothing is left that would already form a whole frame.
    FUZZ_CHECK(decoder.pending_bytes() <= 255 + 1);
  }
  FUZZ_CHECK(consumed + decoder.skipped_bytes() + decoder.pending_bytes() == stream.size());
  return 0;
}
