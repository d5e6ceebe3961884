// What the language server's tests share: input given in chunks of chosen sizes, output
// collected and split back into messages, and files served from memory.
#pragma once

#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "base/source.hpp"
#include "runtime/lsp/framing.hpp"

namespace seqc::lsp::test {

// Gives `text` at most `chunk` bytes per read, so a message can arrive split anywhere.
class ChunkedInput final : public MessageInput {
 public:
  explicit ChunkedInput(std::string text, std::size_t chunk = 1 << 20)
      : text_(std::move(text)), chunk_(chunk) {}
  std::size_t read(char* buffer, std::size_t size) override {
    const std::size_t n = std::min({size, chunk_, text_.size() - pos_});
    text_.copy(buffer, n, pos_);
    pos_ += n;
    reads_ += n > 0 ? 1 : 0;
    return n;
  }
  std::size_t reads() const { return reads_; }

 private:
  std::string text_;
  std::size_t chunk_;
  std::size_t pos_ = 0;
  std::size_t reads_ = 0;
};

// Collects what the server writes (from any thread: the server serialises its writes).
class CollectedOutput final : public MessageOutput {
 public:
  bool write(std::string_view bytes) override {
    text_.append(bytes);
    return true;
  }
  // Every message written so far, parsed.
  std::vector<nlohmann::json> messages() const {
    ChunkedInput in(text_);
    MessageReader reader(in);
    std::vector<nlohmann::json> out;
    for (;;) {
      Frame f = reader.next();
      auto* body = std::get_if<FramedBody>(&f);
      if (body == nullptr) return out;
      out.push_back(nlohmann::json::parse(body->body));
    }
  }

 private:
  std::string text_;
};

class MemoryFiles final : public FileReader {
 public:
  explicit MemoryFiles(std::map<std::string, std::string> files) : files_(std::move(files)) {}
  Result<std::string> read(const std::string& path) override {
    auto it = files_.find(path);
    if (it == files_.end()) return make_error(path + ": No such file or directory");
    return it->second;
  }

 private:
  std::map<std::string, std::string> files_;
};

inline std::string framed(std::string_view body) { return frame(body); }

}  // namespace seqc::lsp::test
