// `seqc studio`'s server (runtime/studio/server.hpp) and its watcher, with a fake disk: files held
// in memory, each with a stamp the test sets, and a random source that gives known bits. The
// server is real, on a free port of 127.0.0.1, asked with httplib's client: the token is needed
// for everything, no path is served, a change to an included file recompiles and reaches the
// page, a file with errors keeps the last good page and program, and the page's playhead reaches
// the sink and its answer comes back.
#include <gtest/gtest.h>
#include <httplib.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "compiler/compile.hpp"
#include "compiler/formats/program_views.hpp"
#include "compiler/show.hpp"
#include "runtime/studio/server.hpp"
#include "runtime/studio/watcher.hpp"

namespace seqc::studio {
namespace {

using namespace std::chrono_literals;

// Files in memory; each write moves its stamp on.
class MemoryDisk final : public FileReader, public FileStamps {
 public:
  void write(const std::string& path, const std::string& text) {
    const std::lock_guard<std::mutex> lock(mutex_);
    files_[path] = text;
    stamps_[path] = FileStamp{++tick_, text.size()};
  }
  Result<std::string> read(const std::string& path) override {
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto it = files_.find(path);
    if (it == files_.end()) return make_error(path + ": No such file or directory");
    return it->second;
  }
  std::optional<FileStamp> stamp(const std::string& path) override {
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto it = stamps_.find(path);
    if (it == stamps_.end()) return std::nullopt;
    return it->second;
  }

 private:
  std::mutex mutex_;
  std::map<std::string, std::string> files_;
  std::map<std::string, FileStamp> stamps_;
  std::int64_t tick_ = 0;
};

// Bytes 0, 1, 2, ...: the token is 000102...0f.
class CountingRandom final : public RandomSource {
 public:
  Status fill(std::span<std::uint8_t> out) override {
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = static_cast<std::uint8_t>(i);
    return Ok{};
  }
};

class BrokenRandom final : public RandomSource {
 public:
  Status fill(std::span<std::uint8_t>) override { return make_error("no entropy"); }
};

class RecordingSink final : public PlayheadSink {
 public:
  void set_program(const compiler::CompileOutput& output) override {
    const std::lock_guard<std::mutex> lock(mutex);
    programs.push_back(output.servo_program() != nullptr ? output.servo_program()->keyframes.size()
                                                         : 0);
  }
  FollowerState report(const PlayheadReport& playhead) override {
    const std::lock_guard<std::mutex> lock(mutex);
    reports.push_back(playhead);
    return FollowerState{true, 2500, {"a notice"}};
  }
  void stop() override { stops.fetch_add(1); }

  std::mutex mutex;
  std::vector<std::size_t> programs;  // the actions of each program set
  std::vector<PlayheadReport> reports;
  std::atomic<int> stops{0};
};

constexpr const char* kToken = "000102030405060708090a0b0c0d0e0f";

const char* const kDance = R"(robot: xarm
sequence:
  - move: {claw: 300}
    time: 500ms
  - include: inc.yaml
)";
std::string include_with_claw(int claw) {
  return "robot: xarm\nsequence:\n  - move: {claw: " + std::to_string(claw) +
         "}\n    time: 500ms\n";
}

// The studio's compile, as the command's but on the memory disk (a song is not decoded).
CompileView memory_compile(MemoryDisk& disk) {
  return [&disk](const SongUrl& song_url) {
    compiler::CompileOutput out = compiler::compile_file("dance.yaml", disk);
    StudioView view;
    view.inputs = out.inputs();
    view.diagnostics = render_all(out.diagnostics, out.sources);
    if (!out.program) return view;
    const compiler::Song* song = compiler::song_of(out);
    if (song != nullptr) {
      view.song_path = song->file;
      view.song_mime = compiler::audio_mime(song->file);
    }
    view.page = compiler::preview_program(*out.program, "dance.yaml", nullptr, disk, nullptr,
                                          song != nullptr ? song_url(song->file) : "");
    view.ok = true;
    view.program = std::make_shared<const compiler::CompileOutput>(std::move(out));
    return view;
  };
}

// The page's data, as its script reads it: the claw's last target is in the actions.
bool page_has_claw(const std::string& page, int claw) {
  return page.find("[0," + std::to_string(claw) + "]") != std::string::npos;
}

struct Studio {
  MemoryDisk disk;
  CountingRandom random;
  RecordingSink sink;
  std::atomic<bool> interrupted{false};
  std::unique_ptr<Server> server;
  std::thread runner;
  Server::End end{};

  explicit Studio(std::chrono::milliseconds page_gone_after = 10s) {
    // As seqc's main does: a page gone while the server writes to it is an error, not a signal.
    std::signal(SIGPIPE, SIG_IGN);
    disk.write("dance.yaml", kDance);
    disk.write("inc.yaml", include_with_claw(650));
    ServerOptions options;
    options.sink = &sink;
    options.poll_every = 5ms;
    options.settle = 1ms;
    options.stop_grace = 20ms;
    options.page_gone_after = page_gone_after;
    options.ping_every = 5ms;
    server = std::make_unique<Server>(options, memory_compile(disk), disk, disk, random);
  }
  ~Studio() {
    interrupted = true;
    if (runner.joinable()) runner.join();
  }
  void run() {
    runner = std::thread([this] { end = server->run(&interrupted); });
  }
  httplib::Client client() const { return httplib::Client("127.0.0.1", server->port()); }
  bool wait_for_version(std::uint64_t v) const {
    for (int i = 0; i < 400 && server->version() < v; ++i) std::this_thread::sleep_for(5ms);
    return server->version() >= v;
  }
};

TEST(StudioToken, Is128BitsOfTheRandomSourceInHex) {
  CountingRandom random;
  const Result<std::string> token = make_token(random);
  ASSERT_TRUE(token);
  EXPECT_EQ(*token, kToken);
  BrokenRandom broken;
  EXPECT_FALSE(make_token(broken));
}

TEST(StudioWatcher, AChangeToAnIncludeIsCompiledOnceItHoldsStill) {
  MemoryDisk disk;
  disk.write("dance.yaml", kDance);
  disk.write("inc.yaml", include_with_claw(650));
  InputWatcher watcher(disk);
  watcher.watch({"dance.yaml", "inc.yaml"});
  EXPECT_FALSE(watcher.poll());
  disk.write("inc.yaml", include_with_claw(600));
  EXPECT_FALSE(watcher.poll());  // just changed: it may still be being written
  EXPECT_TRUE(watcher.settling());
  EXPECT_TRUE(watcher.poll());  // held still for one poll
  watcher.watch({"dance.yaml", "inc.yaml"});
  EXPECT_FALSE(watcher.poll());
  EXPECT_FALSE(watcher.settling());
}

TEST(StudioWatcher, ASaveDuringTheCompileIsNotLost) {
  MemoryDisk disk;
  disk.write("dance.yaml", kDance);
  InputWatcher watcher(disk);
  watcher.watch({"dance.yaml"});
  disk.write("dance.yaml", std::string(kDance) + "# 1\n");
  EXPECT_FALSE(watcher.poll());
  EXPECT_TRUE(watcher.poll());
  // The compile runs; the file is saved again before it ends.
  disk.write("dance.yaml", std::string(kDance) + "# 2\n");
  watcher.watch({"dance.yaml"});
  EXPECT_FALSE(watcher.poll());
  EXPECT_TRUE(watcher.poll());
}

TEST(StudioWatcher, AFileThatComesBackIsAChange) {
  MemoryDisk disk;
  InputWatcher watcher(disk);
  watcher.watch({"dance.yaml"});  // missing
  EXPECT_FALSE(watcher.poll());
  disk.write("dance.yaml", kDance);
  EXPECT_FALSE(watcher.poll());
  EXPECT_TRUE(watcher.poll());
}

TEST(StudioServer, RefusesEveryRequestWithoutTheToken) {
  Studio studio;
  ASSERT_TRUE(studio.server->start());
  EXPECT_EQ(studio.server->url(),
            "http://127.0.0.1:" + std::to_string(studio.server->port()) + "/?token=" + kToken);
  httplib::Client c = studio.client();
  for (const char* path :
       {"/", "/events", "/song", "/?token=", "/?token=000102030405060708090a0b0c0d0e0",
        "/?token=100102030405060708090a0b0c0d0e0f", "/nothing"}) {
    const auto r = c.Get(path);
    ASSERT_TRUE(r) << path;
    EXPECT_EQ(r->status, 403) << path;
    EXPECT_EQ(r->body.find("seqc-state"), std::string::npos) << path;
  }
  const auto post = c.Post("/playhead", "{\"ms\": 1, \"mode\": \"paused\"}", "application/json");
  ASSERT_TRUE(post);
  EXPECT_EQ(post->status, 403);
  EXPECT_TRUE(studio.sink.reports.empty());
  const auto stop = c.Post("/stop", "", "text/plain");
  ASSERT_TRUE(stop);
  EXPECT_EQ(stop->status, 403);
  EXPECT_EQ(studio.sink.stops.load(), 0);

  const auto page = c.Get(std::string("/?token=") + kToken);
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_NE(page->body.find("seqc-state"), std::string::npos);
  EXPECT_NE(page->body.find("<script data-version=\"1\">"), std::string::npos);
  const auto by_header = c.Get("/", {{"X-Seqc-Token", kToken}});
  ASSERT_TRUE(by_header);
  EXPECT_EQ(by_header->status, 200);
}

TEST(StudioServer, ServesNoPathFromTheRequest) {
  Studio studio;
  ASSERT_TRUE(studio.server->start());
  httplib::Client c = studio.client();
  const std::string t = std::string("?token=") + kToken;
  for (const std::string path :
       {"/../../etc/passwd", "/dance.yaml", "/inc.yaml", "/song/../dance.yaml",
        "/%2e%2e/%2e%2e/etc/passwd", "/index.html"}) {
    const auto r = c.Get(path + t);
    ASSERT_TRUE(r) << path;
    EXPECT_EQ(r->status, 404) << path;
    EXPECT_EQ(r->body.find("robot: xarm"), std::string::npos) << path;
  }
  // No song in this dance: the song's route has nothing.
  const auto song = c.Get("/song" + t);
  ASSERT_TRUE(song);
  EXPECT_EQ(song->status, 404);
}

TEST(StudioServer, AChangeToAnIncludeReachesThePageAndErrorsKeepTheLastGoodOne) {
  Studio studio;
  ASSERT_TRUE(studio.server->start());
  ASSERT_EQ(studio.server->version(), 1u);
  studio.run();
  httplib::Client c = studio.client();
  const std::string page = std::string("/?token=") + kToken;
  ASSERT_TRUE(page_has_claw(c.Get(page)->body, 650));

  studio.disk.write("inc.yaml", include_with_claw(600));
  ASSERT_TRUE(studio.wait_for_version(2));
  EXPECT_TRUE(studio.server->ok());
  const std::string second = c.Get(page)->body;
  EXPECT_TRUE(page_has_claw(second, 600));
  EXPECT_NE(second.find("<script data-version=\"2\">"), std::string::npos);

  // An error in the include: the page and the sink's program stay the last good ones.
  studio.disk.write("inc.yaml", "robot: xarm\nsequence:\n  - move: {claw: <b>}\n    time: 500ms\n");
  ASSERT_TRUE(studio.wait_for_version(3));
  EXPECT_FALSE(studio.server->ok());
  EXPECT_EQ(c.Get(page)->body, second);
  {
    const std::lock_guard<std::mutex> lock(studio.sink.mutex);
    EXPECT_EQ(studio.sink.programs.size(), 2u);
  }

  // The page's events say what happened to the file, as text: the error at its line.
  std::string events;
  httplib::Client stream = studio.client();
  stream.Get(("/events" + page.substr(1)).c_str(), [&](const char* data, std::size_t n) {
    events.append(data, n);
    return events.find("\n\n") == std::string::npos;
  });
  EXPECT_EQ(events.rfind("data: {\"version\":3,\"ok\":false,\"errors\":\"inc.yaml:3:", 0), 0u)
      << events.substr(0, 200);
  EXPECT_EQ(events.find("\"page\":"), std::string::npos);

  studio.disk.write("inc.yaml", include_with_claw(640));
  ASSERT_TRUE(studio.wait_for_version(4));
  EXPECT_TRUE(page_has_claw(c.Get(page)->body, 640));
  studio.interrupted = true;
  studio.runner.join();
  EXPECT_EQ(studio.end, Server::End::Interrupted);
  EXPECT_EQ(studio.sink.stops.load(), 1);
}

TEST(StudioServer, PassesThePlayheadToTheSinkAndItsAnswerBack) {
  Studio studio;
  ASSERT_TRUE(studio.server->start());
  httplib::Client c = studio.client();
  const std::string path = std::string("/playhead?token=") + kToken;
  const auto r = c.Post(path.c_str(), "{\"ms\": 1234.5, \"mode\": \"scrubbed\", \"looped\": true}",
                        "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_EQ(r->body, "{\"slewing\":true,\"slew_until_ms\":2500.000000,\"notices\":[\"a notice\"]}");
  const auto bad =
      c.Post(path.c_str(), "{\"ms\": \"soon\", \"mode\": \"paused\"}", "application/json");
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->status, 400);
  {
    const std::lock_guard<std::mutex> lock(studio.sink.mutex);
    ASSERT_EQ(studio.sink.reports.size(), 1u);
    EXPECT_EQ(studio.sink.reports[0].ms, 1234.5);
    EXPECT_EQ(studio.sink.reports[0].mode, PlayheadMode::Scrubbed);
    EXPECT_TRUE(studio.sink.reports[0].looped);
  }
  // Closing the page: the sink stops at once, and with no page open the server ends.
  const auto stop = c.Post((std::string("/stop?token=") + kToken).c_str(), "", "text/plain");
  ASSERT_TRUE(stop);
  EXPECT_EQ(stop->status, 204);
  EXPECT_EQ(studio.sink.stops.load(), 1);
}

TEST(StudioServer, ServesTheSongByItsRouteAndItsNewBytesOnceSaved) {
  Studio studio;
  studio.disk.write("dance.yaml",
                    "robot: xarm\nmusic:\n  file: song.wav\n  downbeat: 0s\n"
                    "  tempo: 120\n  meter: 4/4\nsequence:\n  - move: {claw: 300}\n    time: 1b\n");
  studio.disk.write("song.wav", "RIFF-one");
  ASSERT_TRUE(studio.server->start());
  studio.run();
  httplib::Client c = studio.client();
  const std::string t = std::string("?token=") + kToken;
  const std::string page = c.Get("/" + t)->body;
  EXPECT_NE(page.find(std::string("<audio id=\"song\" preload=\"auto\" src=\"/song?token=") +
                      kToken + "&amp;v="),
            std::string::npos);
  auto song = c.Get("/song" + t);
  ASSERT_TRUE(song);
  EXPECT_EQ(song->status, 200);
  EXPECT_EQ(song->body, "RIFF-one");
  EXPECT_EQ(song->get_header_value("Content-Type"), "audio/wav");
  auto part = c.Get("/song" + t, {{"Range", "bytes=1-3"}});
  ASSERT_TRUE(part);
  EXPECT_EQ(part->status, 206);
  EXPECT_EQ(part->body, "IFF");

  studio.disk.write("song.wav", "RIFF-two!");
  ASSERT_TRUE(studio.wait_for_version(2));
  EXPECT_EQ(c.Get("/song" + t)->body, "RIFF-two!");
  EXPECT_NE(c.Get("/" + t)->body, page);  // the song's address changed with it
}

// The page's event stream read to its first event, then closed, as a page closes.
void open_and_close_the_page(httplib::Client& c) {
  std::string events;
  c.Get((std::string("/events?token=") + kToken).c_str(), [&](const char* data, std::size_t n) {
    events.append(data, n);
    return events.find("\n\n") == std::string::npos;
  });
  ASSERT_EQ(events.rfind("data: {\"version\":1,\"ok\":true", 0), 0u);
}

TEST(StudioServer, EndsWhenThePageSaysItIsLeavingAndNoneComesBack) {
  Studio studio;
  ASSERT_TRUE(studio.server->start());
  studio.run();
  httplib::Client c = studio.client();
  open_and_close_the_page(c);
  ASSERT_TRUE(c.Post((std::string("/stop?token=") + kToken).c_str(), "", "text/plain"));
  studio.runner.join();
  EXPECT_EQ(studio.end, Server::End::PageClosed);
  EXPECT_GE(studio.sink.stops.load(), 1);
}

TEST(StudioServer, EndsWhenThePageHasGoneQuiet) {
  Studio studio(50ms);
  ASSERT_TRUE(studio.server->start());
  studio.run();
  httplib::Client c = studio.client();
  open_and_close_the_page(c);
  studio.runner.join();  // no /stop: the page's stream closed and no request came since
  EXPECT_EQ(studio.end, Server::End::PageClosed);
  EXPECT_EQ(studio.sink.stops.load(), 1);
}

}  // namespace
}  // namespace seqc::studio
