// `seqc studio`'s web server: the preview page of one file, live, on the loopback address.
//
// The server binds 127.0.0.1 only and answers nothing without its token (128 bits from an OS
// random source, 32 hex digits), given as the query's `token=` or the header X-Seqc-Token: any
// other request gets 403 whatever it asks for. With the token it serves a fixed set of routes
// and never a path from the request, so nothing outside the dance's page and its song is ever
// read for a client:
//   GET  /           the page: the last good compile's preview page with the live script
//                    (compiler/formats/preview/live.js), or while the file has never compiled,
//                    its diagnostics on a page that reloads until it does;
//   GET  /events     Server-Sent Events: at once, then after every compile, one event of JSON
//                    {"version": N, "ok": bool, "errors": text, "page": html (when ok)};
//   GET  /song       the song of the last good compile (its `music:` file), by that fixed route;
//   POST /playhead   {"ms": number, "mode": "playing"|"paused"|"scrubbed", "looped": bool}, passed
//                    to the PlayheadSink when there is one; answered with its FollowerState as
//                    {"slewing": bool, "slew_until_ms": number, "notices": [text]} ({} without);
//   POST /heartbeat  the page is still open;
//   POST /stop       the page is closing (sent as it unloads): the sink stops at once.
// run() polls the file's inputs (InputWatcher) and recompiles through the caller's compile
// function on a change, pushing the result; a compile with errors leaves the last good page (and
// the sink's program) as they were. It ends, after calling the sink's stop(), when `interrupted`
// is set (Ctrl-C), when a page said /stop and none has its event stream open `stop_grace`
// later, or when a page has been open and then none is (no event stream) and no request came
// for `page_gone_after`.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "base/result.hpp"
#include "base/source.hpp"
#include "compiler/compile.hpp"
#include "runtime/studio/playhead.hpp"
#include "runtime/studio/watcher.hpp"

namespace seqc::studio {

// An OS random source, passed in so that tests can fix the token.
class RandomSource {
 public:
  virtual ~RandomSource() = default;
  virtual Status fill(std::span<std::uint8_t> out) = 0;
};

// /dev/urandom.
class DevUrandom final : public RandomSource {
 public:
  Status fill(std::span<std::uint8_t> out) override;
};

// 128 random bits from `random`, as 32 lowercase hex digits.
Result<std::string> make_token(RandomSource& random);

// One compile of the file, as the page shows it.
struct StudioView {
  bool ok = false;          // a dance to show: `page` is set
  std::string page;         // its preview page (preview_program/preview_show), song by url
  std::string diagnostics;  // every diagnostic, rendered as the terminal shows them, no colour
  std::vector<std::string> inputs;  // every file the compile read (to watch)
  std::string song_path;            // the song the page plays from /song, "" for none
  std::string song_mime;
  // The program for the sink: null for a file with errors, or a show.
  std::shared_ptr<const compiler::CompileOutput> program;
};

// The address the page fetches the song at `path` from: the fixed route, the token, and a
// version that changes with the song file's stamp (so the page reloads the audio only then).
using SongUrl = std::function<std::string(const std::string& path)>;
using CompileView = std::function<StudioView(const SongUrl& song_url)>;

struct ServerOptions {
  int http_port = 0;  // 0: any free port
  PlayheadSink* sink = nullptr;
  std::chrono::milliseconds poll_every{50};
  // How soon a change is looked at again to see that it holds still (InputWatcher::poll).
  std::chrono::milliseconds settle{15};
  std::chrono::milliseconds stop_grace{2000};
  std::chrono::milliseconds page_gone_after{10000};
  // How often an idle event stream says it is still there (and so finds a page that has gone).
  std::chrono::milliseconds ping_every{1000};
  // When set, told each playhead report as a line ("playhead 4500 ms, scrubbed"), for -v.
  std::function<void(const std::string&)> log;
};

class Server {
 public:
  Server(ServerOptions options, CompileView compile, FileReader& files, FileStamps& stamps,
         RandomSource& random);
  ~Server();
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  // Compiles the file once and binds 127.0.0.1 (the port of the options); the error says why
  // not (no random bits, the port taken).
  Status start();
  int port() const;
  const std::string& token() const;
  // http://127.0.0.1:PORT/?token=TOKEN
  std::string url() const;
  // The latest compile: whether it was good, and how many there have been.
  bool ok() const;
  std::uint64_t version() const;

  enum class End { Interrupted, PageClosed };
  // Serves, watches and recompiles until one of the ends above; the sink is stopped first.
  End run(const std::atomic<bool>* interrupted);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace seqc::studio
