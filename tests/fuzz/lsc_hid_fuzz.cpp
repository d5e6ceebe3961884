// decode_hid_report on arbitrary input reports, then the messages inside.
#include <cstddef>
#include <cstdint>

#include "protocol/lsc/lsc_frame.hpp"
#include "protocol/lsc/lsc_messages.hpp"
#include "tests/fuzz/fuzz_check.hpp"

using namespace seqc;
using namespace seqc::lsc;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const ByteView report(data, size);
  auto frame = decode_hid_report(report);
  if (!frame) return 0;
  FUZZ_CHECK(size <= kHidReportData);
  FUZZ_CHECK(frame->data.size() <= kHidMaxData);

  auto out = encode_hid_report(*frame);
  FUZZ_CHECK(out.ok());
  FUZZ_CHECK(out->size() == 1 + kHidReportData && (*out)[0] == 0);
  for (std::size_t i = 1 + kHeaderSize + frame->data.size(); i < out->size(); ++i) {
    FUZZ_CHECK((*out)[i] == 0);
  }
  auto again = decode_hid_report(ByteView(*out).subspan(1));
  FUZZ_CHECK(again.ok() && *again == *frame);

  if (auto request = decode_request(*frame)) {
    auto encoded = encode(*request);
    FUZZ_CHECK(encoded.ok() && *encoded == *frame);
    auto back = decode_request(*encoded);
    FUZZ_CHECK(back.ok() && *back == *request);
  }
  if (auto reply = decode_reply(*frame)) {
    auto encoded = encode(*reply);
    FUZZ_CHECK(encoded.ok() && *encoded == *frame);
    auto back = decode_reply(*encoded);
    FUZZ_CHECK(back.ok() && *back == *reply);
  }
  return 0;
}
