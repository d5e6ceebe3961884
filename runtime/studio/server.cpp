#include "runtime/studio/server.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <condition_variable>
#include <cstring>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>

#include <httplib.h>

#include <nlohmann/json.hpp>

#include "base/json_text.hpp"
#include "compiler/formats/preview_page_text.hpp"
#include "compiler/formats/svg_text.hpp"

namespace seqc::studio {
namespace {

using Clock = std::chrono::steady_clock;

constexpr const char* kTokenHeader = "X-Seqc-Token";

// Equal texts in a time that does not depend on where they first differ, so that the token cannot
// be guessed a digit at a time from how long a refusal takes.
bool same_secret(const std::string& given, const std::string& token) {
  if (given.size() != token.size()) return false;
  unsigned char diff = 0;
  for (std::size_t i = 0; i < token.size(); ++i) {
    diff |= static_cast<unsigned char>(given[i] ^ token[i]);
  }
  return diff == 0;
}

// The preview page with the live script after the preview's own, tagged with the compile it
// shows.
std::string live_page(const std::string& page, std::uint64_t version) {
  const std::string script = "<script data-version=\"" + std::to_string(version) + "\">\n" +
                             std::string(compiler::preview_live_script()) + "</script>\n";
  std::string out = page;
  const auto end = out.rfind("</body>");
  out.insert(end == std::string::npos ? out.size() : end, script);
  return out;
}

// While the file has never compiled there is no dance to show: its diagnostics, on a page that
// reloads every second until there is.
std::string waiting_page(const std::string& diagnostics) {
  return "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
         "<meta http-equiv=\"refresh\" content=\"1\">\n<title>seqc studio</title>\n</head>\n"
         "<body>\n<p>The file has no good version yet: this page shows the dance once it "
         "compiles.</p>\n<pre id=\"studio-errors\">" +
         compiler::svg::escape(diagnostics) + "</pre>\n</body>\n</html>\n";
}

std::string follower_json(const FollowerState& state) {
  std::string notices;
  for (const std::string& n : state.notices) {
    notices += (notices.empty() ? "" : ",") + json_string(n);
  }
  return std::string("{\"slewing\":") + (state.slewing ? "true" : "false") +
         ",\"slew_until_ms\":" + std::to_string(state.slew_until_ms) + ",\"notices\":[" + notices +
         "]}";
}

std::optional<PlayheadReport> parse_playhead(const std::string& body) {
  const nlohmann::json j = nlohmann::json::parse(body, nullptr, false);
  if (!j.is_object() || !j.contains("ms") || !j["ms"].is_number() || !j.contains("mode") ||
      !j["mode"].is_string()) {
    return std::nullopt;
  }
  PlayheadReport r;
  r.ms = j["ms"].get<double>();
  const std::string mode = j["mode"].get<std::string>();
  if (mode == "playing") {
    r.mode = PlayheadMode::Playing;
  } else if (mode == "paused") {
    r.mode = PlayheadMode::Paused;
  } else if (mode == "scrubbed") {
    r.mode = PlayheadMode::Scrubbed;
  } else {
    return std::nullopt;
  }
  r.looped = j.contains("looped") && j["looped"].is_boolean() && j["looped"].get<bool>();
  if (!(r.ms >= 0 && r.ms < 1e9)) return std::nullopt;
  return r;
}

}  // namespace

Status DevUrandom::fill(std::span<std::uint8_t> out) {
  const int fd = ::open("/dev/urandom", O_RDONLY | O_CLOEXEC);
  if (fd < 0) return make_error(std::string("/dev/urandom: ") + std::strerror(errno));
  std::size_t got = 0;
  while (got < out.size()) {
    const ssize_t n = ::read(fd, out.data() + got, out.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      ::close(fd);
      return make_error("/dev/urandom: cannot read");
    }
    got += static_cast<std::size_t>(n);
  }
  ::close(fd);
  return Ok{};
}

Result<std::string> make_token(RandomSource& random) {
  std::uint8_t bits[16] = {};
  if (Status s = random.fill(bits); !s) return s.error();
  static constexpr char kHex[] = "0123456789abcdef";
  std::string token;
  for (std::uint8_t b : bits) {
    token += kHex[b >> 4];
    token += kHex[b & 15];
  }
  return token;
}

struct Server::State {
  State(ServerOptions o, CompileView c, FileReader& f, FileStamps& s, RandomSource& r)
      : options(std::move(o)), compile(std::move(c)), files(f), stamps(s), random(r), watcher(s) {}

  ServerOptions options;
  CompileView compile;
  FileReader& files;
  FileStamps& stamps;
  RandomSource& random;
  InputWatcher watcher;                 // the run loop's alone
  std::optional<FileStamp> song_stamp;  // the run loop's alone: the stamp of `song`
  httplib::Server http;
  std::thread listener;
  int port = -1;
  std::string token;

  // Everything below is shared with the server's threads, under `mutex`.
  std::mutex mutex;
  std::condition_variable changed;
  std::uint64_t version = 0;  // compiles so far
  bool ok = false;            // the latest compile's
  std::uint64_t good_version = 0;
  std::string page;  // the last good compile's page, live; or the waiting page
  std::string event;
  std::string song_path, song_mime;
  std::shared_ptr<const std::string> song;
  bool ending = false;
  int open_streams = 0;
  bool seen_page = false;
  Clock::time_point last_request = Clock::now();
  std::optional<Clock::time_point> stop_said;

  // The sink is called from the server's threads and the run loop: one call at a time.
  std::mutex sink_mutex;

  void compile_now();
  void routes();
};

void Server::State::compile_now() {
  const SongUrl song_url = [this](const std::string& path) {
    const std::optional<FileStamp> s = stamps.stamp(path);
    const std::uint64_t v = s ? static_cast<std::uint64_t>(s->mtime_ns) * 31 + s->size : 0;
    return "/song?token=" + token + "&v=" + std::to_string(v);
  };
  StudioView view = compile(song_url);
  watcher.watch(view.inputs);
  // The song is read here when it changed, not for each save of the dance nor for each of the
  // browser's range requests. (`song` and `song_path` change on this thread alone.)
  std::shared_ptr<const std::string> song_bytes;
  if (view.ok && !view.song_path.empty()) {
    const std::optional<FileStamp> stamp = stamps.stamp(view.song_path);
    if (song && stamp && view.song_path == song_path && stamp == song_stamp) {
      song_bytes = song;
    } else if (Result<std::string> bytes = files.read(view.song_path)) {
      song_bytes = std::make_shared<const std::string>(std::move(*bytes));
      song_stamp = stamp;
    }
  }
  {
    const std::lock_guard<std::mutex> lock(mutex);
    ++version;
    ok = view.ok;
    if (view.ok) {
      good_version = version;
      page = live_page(view.page, version);
      song_path = view.song_path;
      song_mime = view.song_mime;
      song = std::move(song_bytes);
    } else if (good_version == 0) {
      page = waiting_page(view.diagnostics);
    }
    event = "{\"version\":" + std::to_string(version) + ",\"ok\":" + (view.ok ? "true" : "false") +
            ",\"errors\":" + json_string(view.diagnostics) +
            (view.ok ? ",\"page\":" + json_string(view.page) : std::string()) + "}";
  }
  changed.notify_all();
  if (view.ok && view.program && options.sink != nullptr) {
    const std::lock_guard<std::mutex> lock(sink_mutex);
    options.sink->set_program(*view.program);
  }
}

void Server::State::routes() {
  using httplib::Request;
  using httplib::Response;
  http.new_task_queue = [] { return new httplib::ThreadPool(16); };
  http.set_payload_max_length(64 * 1024);
  http.set_keep_alive_timeout(2);
  // The token before anything else: without it, every request is refused alike, whatever it
  // names.
  http.set_pre_routing_handler([this](const Request& req, Response& res) {
    const std::string given =
        req.has_param("token") ? req.get_param_value("token") : req.get_header_value(kTokenHeader);
    if (!same_secret(given, token)) {
      res.status = 403;
      res.set_content("403: this address needs the token in the URL that seqc studio printed\n",
                      "text/plain");
      return httplib::Server::HandlerResponse::Handled;
    }
    const std::lock_guard<std::mutex> lock(mutex);
    last_request = Clock::now();
    return httplib::Server::HandlerResponse::Unhandled;
  });
  http.set_error_handler([](const Request&, Response& res) {
    if (res.status == 404) res.set_content("404: not a page of the studio\n", "text/plain");
  });
  http.Get("/", [this](const Request&, Response& res) {
    const std::lock_guard<std::mutex> lock(mutex);
    res.set_header("Cache-Control", "no-store");
    res.set_content(page, "text/html; charset=utf-8");
  });
  http.Get("/song", [this](const Request&, Response& res) {
    std::shared_ptr<const std::string> bytes;
    std::string mime;
    {
      const std::lock_guard<std::mutex> lock(mutex);
      bytes = song;
      mime = song_mime;
    }
    if (!bytes) {
      res.status = 404;
      return;
    }
    res.set_content(*bytes, mime);
  });
  http.Get("/events", [this](const Request&, Response& res) {
    {
      const std::lock_guard<std::mutex> lock(mutex);
      ++open_streams;
      seen_page = true;
      stop_said.reset();  // a page (re)opened: a reload, not a close
    }
    res.set_header("Cache-Control", "no-store");
    auto sent = std::make_shared<std::uint64_t>(0);
    res.set_chunked_content_provider(
        "text/event-stream",
        [this, sent](std::size_t, httplib::DataSink& sink) {
          std::unique_lock<std::mutex> lock(mutex);
          // A comment now and then keeps the stream open and finds a page that has gone.
          changed.wait_for(lock, options.ping_every, [&] { return ending || version != *sent; });
          if (ending) return false;
          std::string out = ": still here\n\n";
          if (version != *sent) {
            out = "data: " + event + "\n\n";
            *sent = version;
          }
          lock.unlock();
          return sink.write(out.data(), out.size());
        },
        [this](bool) {
          const std::lock_guard<std::mutex> lock(mutex);
          --open_streams;
        });
  });
  http.Post("/playhead", [this](const Request& req, Response& res) {
    const std::optional<PlayheadReport> report = parse_playhead(req.body);
    if (!report) {
      res.status = 400;
      res.set_content(
          "400: expected {\"ms\": number, \"mode\": \"playing\"|\"paused\"|"
          "\"scrubbed\", \"looped\": bool}\n",
          "text/plain");
      return;
    }
    const std::lock_guard<std::mutex> lock(sink_mutex);
    if (options.log) {
      static constexpr const char* kModes[] = {"playing", "paused", "scrubbed"};
      options.log("playhead " + std::to_string(static_cast<long long>(report->ms)) + " ms, " +
                  kModes[static_cast<int>(report->mode)] + (report->looped ? ", looped" : ""));
    }
    if (options.sink == nullptr) {
      res.set_content("{}", "application/json");
      return;
    }
    res.set_content(follower_json(options.sink->report(*report)), "application/json");
  });
  http.Post("/heartbeat", [](const Request&, Response& res) { res.status = 204; });
  http.Post("/stop", [this](const Request&, Response& res) {
    {
      const std::lock_guard<std::mutex> lock(mutex);
      stop_said = Clock::now();
    }
    if (options.sink != nullptr) {
      const std::lock_guard<std::mutex> lock(sink_mutex);
      options.sink->stop();
    }
    res.status = 204;
  });
}

Server::Server(ServerOptions options, CompileView compile, FileReader& files, FileStamps& stamps,
               RandomSource& random)
    : state_(
          std::make_unique<State>(std::move(options), std::move(compile), files, stamps, random)) {}

Server::~Server() {
  if (state_->listener.joinable()) {
    {
      const std::lock_guard<std::mutex> lock(state_->mutex);
      state_->ending = true;
    }
    state_->changed.notify_all();
    state_->http.stop();
    state_->listener.join();
  }
}

Status Server::start() {
  State& s = *state_;
  Result<std::string> token = make_token(s.random);
  if (!token) return token.error();
  s.token = std::move(*token);
  s.compile_now();
  s.routes();
  if (s.options.http_port == 0) {
    s.port = s.http.bind_to_any_port("127.0.0.1");
  } else {
    s.port = s.http.bind_to_port("127.0.0.1", s.options.http_port) ? s.options.http_port : -1;
  }
  if (s.port < 0) {
    return make_error("cannot listen on 127.0.0.1:" + std::to_string(s.options.http_port) +
                      " (the port is taken or not allowed)");
  }
  s.listener = std::thread([&s] { s.http.listen_after_bind(); });
  // stop() is lost on a server not yet running: the listener is running before anyone may stop it.
  for (int i = 0; i < 5000 && !s.http.is_running(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return Ok{};
}

int Server::port() const { return state_->port; }
const std::string& Server::token() const { return state_->token; }
std::string Server::url() const {
  return "http://127.0.0.1:" + std::to_string(state_->port) + "/?token=" + state_->token;
}
bool Server::ok() const {
  const std::lock_guard<std::mutex> lock(state_->mutex);
  return state_->ok;
}
std::uint64_t Server::version() const {
  const std::lock_guard<std::mutex> lock(state_->mutex);
  return state_->version;
}

Server::End Server::run(const std::atomic<bool>* interrupted) {
  State& s = *state_;
  End end = End::Interrupted;
  for (;;) {
    if (interrupted != nullptr && interrupted->load()) break;
    std::this_thread::sleep_for(s.watcher.settling() ? s.options.settle : s.options.poll_every);
    if (s.watcher.poll()) s.compile_now();
    const std::lock_guard<std::mutex> lock(s.mutex);
    const Clock::time_point now = Clock::now();
    if (s.open_streams == 0 &&
        ((s.stop_said && now - *s.stop_said >= s.options.stop_grace) ||
         (s.seen_page && now - s.last_request >= s.options.page_gone_after))) {
      end = End::PageClosed;
      break;
    }
  }
  if (s.options.sink != nullptr) {
    const std::lock_guard<std::mutex> lock(s.sink_mutex);
    s.options.sink->stop();
  }
  {
    const std::lock_guard<std::mutex> lock(s.mutex);
    s.ending = true;
  }
  s.changed.notify_all();
  s.http.stop();
  if (s.listener.joinable()) s.listener.join();
  return end;
}

}  // namespace seqc::studio
