// `seqc lsp`: a Language Server Protocol 3.17 server for choreography files.
//
// The server reads JSON-RPC 2.0 messages (framing.hpp) and answers on one thread: the protocol's
// lifecycle (initialize, shutdown, exit), the open documents (didOpen, didChange with full or
// incremental edits, didClose, didSave) and every other request through the language features
// (features.hpp). Diagnostics are compiled on a second thread, `debounce` after the last change,
// by the real compiler as `seqc check` compiles (compiler::load), each open document that no
// other open document includes (a song decoded once while its file is unchanged, song_cache.hpp);
// they are published for every open document and for each file
// with diagnostics, and a file that had some and has none is published empty. A change that
// arrives while a compile runs makes that compile's result stale: it is dropped and a new
// compile follows, so the reading thread never waits for the compiler and no client sees
// diagnostics of text it has since changed.
//
// Errors follow JSON-RPC: -32700 for a body that is no JSON (or a framing error), -32600 for a
// message that is no request, -32601 for an unknown method, -32602 for params of the wrong
// shape, -32002 for a request before initialize, -32800 for a request cancelled
// ($/cancelRequest) before it was answered; after shutdown every request but exit is -32600.
// Notifications with wrong params, and unknown notifications, are ignored.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <thread>

#include <nlohmann/json.hpp>

#include "base/source.hpp"
#include "compiler/load.hpp"
#include "runtime/lsp/debounce.hpp"
#include "runtime/lsp/documents.hpp"
#include "runtime/lsp/framing.hpp"
#include "runtime/lsp/lsp_diagnostics.hpp"
#include "runtime/lsp/song_cache.hpp"

namespace seqc::lsp {

struct ServerOptions {
  std::chrono::milliseconds debounce{150};
  compiler::LoadOptions compile;  // as `seqc check` loads a file
  std::string version;            // serverInfo.version
};

// JSON-RPC and LSP error codes.
enum ErrorCode : int {
  kParseError = -32700,
  kInvalidRequest = -32600,
  kMethodNotFound = -32601,
  kInvalidParams = -32602,
  kInternalError = -32603,
  kServerNotInitialized = -32002,
  kRequestCancelled = -32800,
};

class Server {
 public:
  // `disk`: files that are not open. Both outlive the server, and `disk` is used from the
  // compiling thread too.
  Server(MessageOutput& out, FileReader& disk, ServerOptions options);
  ~Server();
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  // Reads and answers until `exit` or the end of the input. The exit status: 0 after shutdown
  // then exit, 1 otherwise (exit without shutdown, or the input ended).
  int run(MessageInput& in);

  // One message's body, as run() handles it (tests).
  void handle(std::string_view body);
  // A framing error, as run() answers it.
  void handle_framing_error(const std::string& message);
  bool exited() const { return exit_code_.has_value(); }
  int exit_code() const { return exit_code_.value_or(1); }
  // Waits until no compile is pending or running (tests), at most `limit`: false if it is
  // still busy then.
  bool wait_idle(std::chrono::milliseconds limit = std::chrono::seconds(10));

 private:
  void send(const nlohmann::json& message);
  void respond(const nlohmann::json& id, nlohmann::json result);
  void respond_error(const nlohmann::json& id, int code, const std::string& message);
  void request(const nlohmann::json& id, const std::string& method, const nlohmann::json& params);
  void notification(const std::string& method, const nlohmann::json& params);
  nlohmann::json initialize_result() const;
  // Documents, under docs_mutex_; a change schedules diagnostics.
  void open(const nlohmann::json& params);
  void change(const nlohmann::json& params);
  void close(const nlohmann::json& params);
  void schedule();
  DocumentTexts snapshot() const;
  // The compiling thread.
  void work();
  void publish_round(const std::map<std::string, std::string>& uris, const DocumentTexts& docs,
                     std::uint64_t generation);

  MessageOutput& out_;
  FileReader& disk_;
  ServerOptions options_;
  std::unique_ptr<SongCache> songs_;  // over options_'s song reader, which it replaces
  std::mutex out_mutex_;

  bool initialized_ = false;
  bool shutdown_ = false;
  std::optional<int> exit_code_;
  std::set<std::string> cancelled_;  // request ids (dumped) cancelled before they were answered

  struct Document {
    std::string uri;
    std::shared_ptr<const std::string> text;
    std::int64_t version = 0;
  };
  mutable std::mutex docs_mutex_;
  std::condition_variable wake_;
  std::map<std::string, Document> docs_;  // by normal path
  Debounce debounce_;
  bool compiling_ = false;
  bool stopping_ = false;
  std::condition_variable idle_;
  // The compiling thread's own: the files last published with diagnostics (normal path -> uri).
  std::map<std::string, std::string> published_;
  std::thread worker_;
};

}  // namespace seqc::lsp
