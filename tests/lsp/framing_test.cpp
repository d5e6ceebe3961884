// The base protocol's framing: messages split across reads or sharing one, header fields
// other than Content-Length, and every way a header or a body can be wrong.
#include <gtest/gtest.h>

#include "runtime/lsp/framing.hpp"
#include "tests/lsp/lsp_test_util.hpp"

namespace seqc::lsp {
namespace {

using test::ChunkedInput;

std::string body_of(const Frame& f) {
  const auto* b = std::get_if<FramedBody>(&f);
  return b == nullptr ? "<no body>" : b->body;
}

std::string error_of(const Frame& f) {
  const auto* e = std::get_if<FramingError>(&f);
  return e == nullptr ? "<no error>" : e->message;
}

TEST(LspFraming, MessageSplitIntoOneByteReads) {
  ChunkedInput in("Content-Length: 7\r\n\r\n{\"a\":1}", 1);
  MessageReader reader(in);
  EXPECT_EQ(body_of(reader.next()), "{\"a\":1}");
  EXPECT_TRUE(std::holds_alternative<EndOfInput>(reader.next()));
  EXPECT_GT(in.reads(), 20u);
}

TEST(LspFraming, TwoMessagesInOneChunkAndOtherFields) {
  ChunkedInput in(
      "Content-Length: 2\r\n\r\n{}"
      "content-type: application/vscode-jsonrpc; charset=utf-8\r\ncontent-length:  3 \r\n\r\n[1]");
  MessageReader reader(in);
  EXPECT_EQ(body_of(reader.next()), "{}");
  EXPECT_TRUE(reader.has_buffered());
  EXPECT_EQ(body_of(reader.next()), "[1]");
  EXPECT_FALSE(reader.has_buffered());
  EXPECT_TRUE(std::holds_alternative<EndOfInput>(reader.next()));
}

TEST(LspFraming, BadHeadersAreErrorsAndReadingGoesOn) {
  ChunkedInput in(
      "Content-Length: -4\r\n\r\n"
      "Content-Length: 2\r\n\r\n{}"
      "Content-Type: x\r\n\r\n"
      "Content-Length: 1\r\n\r\n1"
      "no colon here\r\n\r\n"
      "Content-Length: 12abc\r\n\r\n"
      "Content-Length: 1\r\n\r\n2");
  MessageReader reader(in);
  EXPECT_EQ(error_of(reader.next()), "Content-Length is not a number of bytes");
  EXPECT_EQ(body_of(reader.next()), "{}");
  EXPECT_EQ(error_of(reader.next()), "header without a Content-Length");
  EXPECT_EQ(body_of(reader.next()), "1");
  EXPECT_EQ(error_of(reader.next()), "header line without a ':'");
  EXPECT_EQ(error_of(reader.next()), "Content-Length is not a number of bytes");
  EXPECT_EQ(body_of(reader.next()), "2");
}

TEST(LspFraming, HeaderLineOverTheLimit) {
  ChunkedInput in("X: " + std::string(kMaxHeaderLine + 10, 'a') + "\r\nContent-Length: 2\r\n\r\n{}",
                  100);
  MessageReader reader(in);
  EXPECT_EQ(error_of(reader.next()), "header line longer than 1024 bytes");
  EXPECT_EQ(body_of(reader.next()), "{}");
}

TEST(LspFraming, BodyOverTheLimitIsDroppedUnkept) {
  ChunkedInput in(
      "Content-Length: 50\r\n\r\n" + std::string(50, 'x') + "Content-Length: 5\r\n\r\nhello", 7);
  MessageReader reader(in, 10);
  EXPECT_EQ(error_of(reader.next()), "message of 50 bytes is over the limit of 10 bytes");
  EXPECT_EQ(body_of(reader.next()), "hello");
}

TEST(LspFraming, HugeLengthAndInputEndingInsideABody) {
  ChunkedInput huge("Content-Length: 999999999999\r\n\r\nabc");
  MessageReader reader(huge);
  EXPECT_EQ(error_of(reader.next()),
            "message of 999999999999 bytes is over the limit of 16777216 bytes");
  EXPECT_TRUE(std::holds_alternative<EndOfInput>(reader.next()));

  ChunkedInput cut("Content-Length: 10\r\n\r\nabc");
  MessageReader cut_reader(cut);
  EXPECT_TRUE(std::holds_alternative<EndOfInput>(cut_reader.next()));
}

TEST(LspFraming, FrameWritesTheLengthInBytes) {
  EXPECT_EQ(frame("{\"t\":\"\xC3\xA9\"}"), "Content-Length: 10\r\n\r\n{\"t\":\"\xC3\xA9\"}");
}

}  // namespace
}  // namespace seqc::lsp
