// The base protocol of the Language Server Protocol: each message is a header block
// (`Content-Length: N\r\n`, other fields ignored, an empty line) then N bytes of JSON.
//
// The bytes come through MessageInput and go out through MessageOutput, so the server never
// touches a file descriptor itself: the command passes standard input and output, tests pass
// strings. A client is not trusted: a header line longer than kMaxHeaderLine, a header block
// without a valid Content-Length, or a body over the reader's limit is a framing error, found
// while reading (no more than the limit is ever held). After a bad header the reader skips to
// the next "Content-Length:" it sees; after a body over the limit, it drops that many bytes
// as they come, unkept. The server answers each with a parse error and reads on.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>

namespace seqc::lsp {

// Where the messages come from: standard input, or a string in tests.
class MessageInput {
 public:
  virtual ~MessageInput() = default;
  // Up to `size` bytes into `buffer`: how many were read, 0 at the end of the input (or on an
  // error that ends it). Blocks until at least one byte or the end.
  virtual std::size_t read(char* buffer, std::size_t size) = 0;
};

// Where the messages go: standard output, or a string in tests. Written whole, one message
// at a time (the server serialises its writers).
class MessageOutput {
 public:
  virtual ~MessageOutput() = default;
  // false when the output is gone (the client closed it).
  virtual bool write(std::string_view bytes) = 0;
};

inline constexpr std::size_t kMaxHeaderLine = 1024;
inline constexpr std::size_t kMaxBodyBytes = 16u << 20;

// One step of the reader: a message's body, a framing error (what was wrong), or the end.
struct FramedBody {
  std::string body;
};
struct FramingError {
  std::string message;
};
struct EndOfInput {};
using Frame = std::variant<FramedBody, FramingError, EndOfInput>;

class MessageReader {
 public:
  explicit MessageReader(MessageInput& input, std::size_t max_body = kMaxBodyBytes)
      : input_(input), max_body_(max_body) {}
  Frame next();
  // Whether bytes already read wait in the buffer (a message read in the same chunk).
  bool has_buffered() const { return pos_ < buffer_.size(); }

 private:
  // Reads more input into the buffer; false at the end.
  bool fill();
  // The next header line without its "\r\n" (a lone "\n" is accepted), an error for a line
  // over kMaxHeaderLine, or the end of the input.
  std::variant<std::string, FramingError, EndOfInput> header_line();

  MessageInput& input_;
  std::size_t max_body_;
  std::string buffer_;
  std::size_t pos_ = 0;
  bool resync_ = false;     // after a bad header: skip to the next "Content-Length:"
  std::uint64_t skip_ = 0;  // after a body over the limit: its bytes, still to drop
};

// `body` framed for sending: "Content-Length: N\r\n\r\n" + body.
std::string frame(std::string_view body);

}  // namespace seqc::lsp
