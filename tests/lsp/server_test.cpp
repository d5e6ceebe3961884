// The server in-process: JSON-RPC error codes, the lifecycle, and diagnostics compiled from
// open documents over files in memory, including a mistake in an included file, fixed by an
// incremental edit of an open document; and the debounce on made-up times.
#include <gtest/gtest.h>

#include "runtime/lsp/debounce.hpp"
#include "runtime/lsp/server.hpp"
#include "tests/lsp/lsp_test_util.hpp"

namespace seqc::lsp {
namespace {

using nlohmann::json;
using namespace std::chrono_literals;

const std::string kMain =
    "robot: xarm\n"
    "sequence:\n"
    "  - move: home\n"
    "    time: 1s\n"
    "  - include: inc/steps.yaml\n";
const std::string kSteps =
    "sequence:\n"
    "  - move: {claw: 200}\n"
    "    time: 300ms\n"
    "  - move: {claw: +900}\n"
    "    time: 300ms\n";

ServerOptions quick_options() {
  ServerOptions o;
  o.debounce = 0ms;
  o.version = "9.9";
  return o;
}

struct Fixture {
  test::CollectedOutput out;
  test::MemoryFiles disk{{{"/p/main.yaml", kMain}, {"/p/inc/steps.yaml", kSteps}}};
  Server server{out, disk, quick_options()};

  void send(const json& message) { server.handle(message.dump()); }
  void initialize() {
    send({{"jsonrpc", "2.0"}, {"id", 0}, {"method", "initialize"}, {"params", json::object()}});
  }
  // The messages written since the last call.
  std::vector<json> take() {
    std::vector<json> all = out.messages();
    std::vector<json> fresh(all.begin() + static_cast<std::ptrdiff_t>(seen_), all.end());
    seen_ = all.size();
    return fresh;
  }
  std::size_t seen_ = 0;
};

int error_code(const json& m) { return m.at("error").at("code").get<int>(); }

TEST(LspServer, ErrorCodesAndLifecycle) {
  Fixture f;
  f.send({{"jsonrpc", "2.0"}, {"id", 1}, {"method", "textDocument/hover"}, {"params", {}}});
  f.server.handle("{nope");
  f.server.handle("[]");
  f.server.handle(R"({"jsonrpc": "1.0", "id": 2, "method": "x"})");
  f.server.handle(R"({"jsonrpc": "2.0", "id": true, "method": "x"})");
  f.server.handle(R"({"jsonrpc": "2.0", "method": "exit-like-but-not"})");  // ignored
  f.server.handle(R"({"a": ")" + std::string(300, '[') + R"(\"", "b": )" + std::string(255, '[') +
                  std::string(255, ']') + "}");  // 256 deep; brackets in a string do not count
  f.server.handle(std::string(257, '[') + std::string(257, ']'));
  std::vector<json> got = f.take();
  ASSERT_EQ(got.size(), 7u);
  EXPECT_EQ(error_code(got[5]), -32600);  // parsed: no jsonrpc
  EXPECT_EQ(got[6], json::parse(R"({"jsonrpc": "2.0", "id": null, "error": {"code": -32700,
                                    "message": "the message nests more than 256 levels"}})"));
  EXPECT_EQ(got[0], json::parse(R"({"jsonrpc": "2.0", "id": 1, "error": {"code": -32002,
                                    "message": "the server is not initialized"}})"));
  EXPECT_EQ(error_code(got[1]), -32700);
  EXPECT_EQ(got[1]["id"], nullptr);
  EXPECT_EQ(error_code(got[2]), -32600);
  EXPECT_EQ(error_code(got[3]), -32600);
  EXPECT_EQ(got[3]["id"], 2);
  EXPECT_EQ(error_code(got[4]), -32600);

  f.initialize();
  got = f.take();
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0]["result"]["serverInfo"], json::parse(R"({"name": "seqc", "version": "9.9"})"));
  EXPECT_EQ(got[0]["result"]["capabilities"]["textDocumentSync"],
            json::parse(R"({"openClose": true, "change": 2, "save": {"includeText": false}})"));

  f.send({{"jsonrpc", "2.0"}, {"id", "s"}, {"method", "no/such"}});
  f.send({{"jsonrpc", "2.0"}, {"method", "$/cancelRequest"}, {"params", {{"id", 7}}}});
  f.send({{"jsonrpc", "2.0"}, {"id", 7}, {"method", "no/such"}});
  f.send({{"jsonrpc", "2.0"}, {"id", 8}, {"method", "no/such"}, {"params", 3}});
  f.send({{"jsonrpc", "2.0"}, {"id", 9}, {"method", "shutdown"}});
  f.send({{"jsonrpc", "2.0"}, {"id", 10}, {"method", "no/such"}});
  got = f.take();
  ASSERT_EQ(got.size(), 5u);
  EXPECT_EQ(got[0], json::parse(R"({"jsonrpc": "2.0", "id": "s", "error": {"code": -32601,
                                    "message": "unknown method: no/such"}})"));
  EXPECT_EQ(error_code(got[1]), -32800);
  EXPECT_EQ(error_code(got[2]), -32602);
  EXPECT_EQ(got[3], json::parse(R"({"jsonrpc": "2.0", "id": 9, "result": null})"));
  EXPECT_EQ(error_code(got[4]), -32600);
  EXPECT_FALSE(f.server.exited());
  f.send({{"jsonrpc", "2.0"}, {"method", "exit"}});
  EXPECT_TRUE(f.server.exited());
  EXPECT_EQ(f.server.exit_code(), 0);
}

TEST(LspServer, ExitWithoutShutdownIsStatusOne) {
  Fixture f;
  test::ChunkedInput in(
      frame(R"({"jsonrpc": "2.0", "id": 1, "method": "initialize", "params": {}})") +
      frame(R"({"jsonrpc": "2.0", "method": "exit"})") +
      frame(R"({"jsonrpc": "2.0", "id": 2, "method": "never/read"})"));
  EXPECT_EQ(f.server.run(in), 1);
  EXPECT_EQ(f.take().size(), 1u);  // the initialize result; nothing after exit is read
}

json publish(const std::string& uri, json diagnostics) {
  return {{"jsonrpc", "2.0"},
          {"method", "textDocument/publishDiagnostics"},
          {"params", {{"uri", uri}, {"diagnostics", std::move(diagnostics)}}}};
}

TEST(LspServer, DiagnosticsOfAnIncludedFileFixedInItsOpenDocument) {
  Fixture f;
  f.initialize();
  f.take();
  f.send({{"jsonrpc", "2.0"},
          {"method", "textDocument/didOpen"},
          {"params",
           {{"textDocument", {{"uri", "file:///p/main.yaml"}, {"version", 1}, {"text", kMain}}}}}});
  ASSERT_TRUE(f.server.wait_idle());
  const json claw = json::parse(R"([
    {"range": {"start": {"line": 3, "character": 17}, "end": {"line": 3, "character": 21}},
     "severity": 1, "code": "out-of-limits", "source": "seqc",
     "message": "'claw' would move to 1100 (200 +900), above its max 1000",
     "relatedInformation": [{"location": {"uri": "file:///p/main.yaml",
       "range": {"start": {"line": 4, "character": 13}, "end": {"line": 4, "character": 27}}},
       "message": "included from here"}]}])");
  std::vector<json> got = f.take();
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[0], publish("file:///p/main.yaml", json::array()));
  EXPECT_EQ(got[1], publish("file:///p/inc/steps.yaml", claw));

  // The included file opened (it is no root: the main file's compile covers it), then "+900"
  // edited to "+100": both published empty.
  f.send({{"jsonrpc", "2.0"},
          {"method", "textDocument/didOpen"},
          {"params",
           {{"textDocument",
             {{"uri", "file:///p/inc/steps.yaml"}, {"version", 1}, {"text", kSteps}}}}}});
  ASSERT_TRUE(f.server.wait_idle());
  got = f.take();
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[1], publish("file:///p/main.yaml", json::array()));
  EXPECT_EQ(got[0], publish("file:///p/inc/steps.yaml", claw));
  f.send(json::parse(R"({"jsonrpc": "2.0", "method": "textDocument/didChange", "params": {
    "textDocument": {"uri": "file:///p/inc/steps.yaml", "version": 2},
    "contentChanges": [{"range": {"start": {"line": 3, "character": 18},
                                  "end": {"line": 3, "character": 19}}, "text": "1"}]}})"));
  ASSERT_TRUE(f.server.wait_idle());
  got = f.take();
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[0], publish("file:///p/inc/steps.yaml", json::array()));
  EXPECT_EQ(got[1], publish("file:///p/main.yaml", json::array()));
}

TEST(LspServer, NoChoreographyAndHalfTypedFilesGetDiagnosticsNotCrashes) {
  Fixture f;
  f.initialize();
  for (const std::string text :
       {"- 1\n- 2\n", "robot: xarm\nsequence:\n  - move: {cl", "\x01\x02", "", "robot: [\n"}) {
    f.take();
    f.send({{"jsonrpc", "2.0"},
            {"method", "textDocument/didOpen"},
            {"params", {{"textDocument", {{"uri", "file:///p/x.yaml"}, {"text", text}}}}}});
    ASSERT_TRUE(f.server.wait_idle());
    std::vector<json> got = f.take();
    ASSERT_EQ(got.size(), 1u) << text;
    EXPECT_FALSE(got[0]["params"]["diagnostics"].empty()) << text;
    EXPECT_EQ(got[0]["params"]["diagnostics"][0]["severity"], 1) << text;
  }
}

TEST(LspDebounce, DueAfterTheLastChangeAndSuperseded) {
  Debounce d(150ms);
  EXPECT_FALSE(d.due());
  EXPECT_FALSE(d.take(Debounce::Time(0)));
  d.touch(Debounce::Time(1000ms));
  EXPECT_EQ(d.due(), Debounce::Time(1150ms));
  d.touch(Debounce::Time(1100ms));  // a keystroke 100 ms later moves it on
  EXPECT_EQ(d.due(), Debounce::Time(1250ms));
  EXPECT_EQ(d.generation(), 2u);
  EXPECT_FALSE(d.take(Debounce::Time(1249ms)));
  EXPECT_TRUE(d.take(Debounce::Time(1250ms)));
  EXPECT_FALSE(d.due());
  EXPECT_FALSE(d.take(Debounce::Time(2000ms)));  // taken once
}

}  // namespace
}  // namespace seqc::lsp
