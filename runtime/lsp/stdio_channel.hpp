// The real ends of the server's messages: file descriptors (standard input and output), read
// and written with read(2) and write(2) so no stream buffering delays a message.
#pragma once

#include "runtime/lsp/framing.hpp"

namespace seqc::lsp {

class FdInput final : public MessageInput {
 public:
  explicit FdInput(int fd) : fd_(fd) {}
  // Retries an interrupted read; any other error ends the input.
  std::size_t read(char* buffer, std::size_t size) override;

 private:
  int fd_;
};

class FdOutput final : public MessageOutput {
 public:
  explicit FdOutput(int fd) : fd_(fd) {}
  // Writes every byte (retrying short and interrupted writes); false once the fd is gone.
  bool write(std::string_view bytes) override;

 private:
  int fd_;
};

}  // namespace seqc::lsp
