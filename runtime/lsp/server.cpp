#include "runtime/lsp/server.hpp"

#include <algorithm>
#include <exception>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include "runtime/lsp/features.hpp"

namespace seqc::lsp {
namespace {

using nlohmann::json;

Debounce::Time steady_now() {
  return std::chrono::duration_cast<Debounce::Time>(
      std::chrono::steady_clock::now().time_since_epoch());
}

// The most cancelled ids remembered: a client that cancels what was long answered cannot
// make the set grow without end.
constexpr std::size_t kMaxCancelled = 1024;

std::uint32_t u32(const json& v) {
  if (!v.is_number_unsigned() || v.get<std::uint64_t>() > std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("not a position");
  return v.get<std::uint32_t>();
}

Position position(const json& v) { return {u32(v.at("line")), u32(v.at("character"))}; }

const std::string& text_of(const json& v) { return v.get_ref<const std::string&>(); }

// The diagnostics of one loaded file (and of a show's performers), under the files they are in.
void collect(const compiler::Loaded& loaded, const std::string& path, FileDiagnostics& into) {
  add_lsp_diagnostics(loaded.sources(), loaded.diagnostics(), path, loaded.read_error(), into);
  if (!loaded.is_show()) return;
  for (const compiler::Performer& p : loaded.show().performers) {
    if (p.output.read_error) continue;  // reported in the show file, where it is named
    add_lsp_diagnostics(p.output.sources, p.output.diagnostics, p.file, std::nullopt, into);
  }
}

// The most arrays and objects one message may nest: JSON's values are freed (and dumped)
// recursively, so a body of a million '[' would overflow the stack. No LSP message nests more
// than a few levels.
constexpr int kMaxNesting = 256;

// Whether `body` nests arrays and objects deeper than kMaxNesting (outside strings).
bool nested_too_deeply(std::string_view body) {
  int depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < body.size(); ++i) {
    const char c = body[i];
    if (in_string) {
      if (c == '\\') {
        ++i;
      } else if (c == '"') {
        in_string = false;
      }
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxNesting) return true;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return false;
}

}  // namespace

Server::Server(MessageOutput& out, FileReader& disk, ServerOptions options)
    : out_(out),
      disk_(disk),
      options_(std::move(options)),
      debounce_(std::chrono::duration_cast<Debounce::Time>(options_.debounce)) {
  if (SongReader* songs = options_.compile.program.songs) {
    songs_ = std::make_unique<SongCache>(*songs);
    options_.compile.program.songs = songs_.get();
    if (options_.compile.performers.songs == songs)
      options_.compile.performers.songs = songs_.get();
  }
  worker_ = std::thread([this] { work(); });
}

Server::~Server() {
  {
    std::lock_guard lock(docs_mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  worker_.join();
}

int Server::run(MessageInput& in) {
  MessageReader reader(in);
  while (!exited()) {
    Frame frame = reader.next();
    if (std::holds_alternative<EndOfInput>(frame)) break;
    if (const auto* e = std::get_if<FramingError>(&frame)) {
      handle_framing_error(e->message);
    } else {
      handle(std::get<FramedBody>(frame).body);
    }
  }
  return exited() ? exit_code() : (shutdown_ ? 0 : 1);
}

void Server::send(const json& message) {
  // A message may quote bytes of a file that are no UTF-8 (a binary file): replaced, not thrown.
  const std::string body = message.dump(-1, ' ', false, json::error_handler_t::replace);
  std::lock_guard lock(out_mutex_);
  out_.write(frame(body));
}

void Server::respond(const json& id, json result) {
  send({{"jsonrpc", "2.0"}, {"id", id}, {"result", std::move(result)}});
}

void Server::respond_error(const json& id, int code, const std::string& message) {
  send({{"jsonrpc", "2.0"}, {"id", id}, {"error", {{"code", code}, {"message", message}}}});
}

void Server::handle_framing_error(const std::string& message) {
  respond_error(nullptr, kParseError, message);
}

void Server::handle(std::string_view body) {
  if (nested_too_deeply(body)) {
    respond_error(nullptr, kParseError, "the message nests more than 256 levels");
    return;
  }
  json msg;
  try {
    msg = json::parse(body);
  } catch (const json::exception&) {
    respond_error(nullptr, kParseError, "the message is not JSON");
    return;
  }
  if (!msg.is_object()) {
    respond_error(nullptr, kInvalidRequest, "the message is not a JSON-RPC object");
    return;
  }
  const bool has_id = msg.contains("id");
  const json id = has_id ? msg["id"] : json(nullptr);
  if (has_id && !id.is_number_integer() && !id.is_string()) {
    respond_error(nullptr, kInvalidRequest, "id is neither a number nor a string");
    return;
  }
  const auto version = msg.find("jsonrpc");
  if (version == msg.end() || *version != "2.0") {
    respond_error(id, kInvalidRequest, "jsonrpc is not \"2.0\"");
    return;
  }
  const auto method = msg.find("method");
  if (method == msg.end()) {
    if (has_id && (msg.contains("result") || msg.contains("error"))) return;  // a response
    respond_error(id, kInvalidRequest, "the message has no method");
    return;
  }
  if (!method->is_string()) {
    respond_error(id, kInvalidRequest, "method is not a string");
    return;
  }
  const json params = msg.value("params", json(nullptr));
  if (!params.is_null() && !params.is_object() && !params.is_array()) {
    if (has_id) respond_error(id, kInvalidParams, "params is neither an object nor an array");
    return;
  }
  if (has_id) {
    request(id, method->get<std::string>(), params);
  } else {
    notification(method->get<std::string>(), params);
  }
}

json Server::initialize_result() const {
  json caps = feature_capabilities();
  if (!caps.is_object()) caps = json::object();
  caps["textDocumentSync"] = {
      {"openClose", true}, {"change", 2}, {"save", {{"includeText", false}}}};
  return {{"capabilities", caps},
          {"serverInfo", {{"name", "seqc"}, {"version", options_.version}}}};
}

void Server::request(const json& id, const std::string& method, const json& params) {
  if (shutdown_) {
    respond_error(id, kInvalidRequest, "the server is shutting down");
    return;
  }
  if (method == "initialize") {
    if (initialized_) {
      respond_error(id, kInvalidRequest, "the server is already initialized");
    } else if (!params.is_object()) {
      respond_error(id, kInvalidParams, "initialize takes an object");
    } else {
      initialized_ = true;
      respond(id, initialize_result());
    }
    return;
  }
  if (!initialized_) {
    respond_error(id, kServerNotInitialized, "the server is not initialized");
    return;
  }
  if (cancelled_.erase(id.dump()) > 0) {
    respond_error(id, kRequestCancelled, "the request was cancelled");
    return;
  }
  if (method == "shutdown") {
    shutdown_ = true;
    respond(id, nullptr);
    return;
  }
  try {
    OverlayReader files(snapshot(), disk_);
    FeatureContext ctx{files, &uri_to_path, &path_to_uri};
    std::optional<json> answer = answer_feature(method, params, ctx);
    if (answer) {
      respond(id, std::move(*answer));
    } else {
      respond_error(id, kMethodNotFound, "unknown method: " + method);
    }
  } catch (const json::exception& e) {
    respond_error(id, kInvalidParams, std::string("invalid params: ") + e.what());
  } catch (const std::exception& e) {
    respond_error(id, kInternalError, e.what());
  }
}

void Server::notification(const std::string& method, const json& params) {
  if (method == "exit") {
    exit_code_ = shutdown_ ? 0 : 1;
    return;
  }
  if (!initialized_) return;  // the protocol drops notifications before initialize
  try {
    if (method == "$/cancelRequest") {
      const json& id = params.at("id");
      if (!id.is_number_integer() && !id.is_string()) return;
      if (cancelled_.size() >= kMaxCancelled) cancelled_.clear();
      cancelled_.insert(id.dump());
    } else if (method == "textDocument/didOpen") {
      open(params);
    } else if (method == "textDocument/didChange") {
      change(params);
    } else if (method == "textDocument/didClose") {
      close(params);
    } else if (method == "textDocument/didSave") {
      schedule();
    }
  } catch (const std::exception&) {
    // A notification with params of the wrong shape has no one to answer: it changes nothing.
  }
}

void Server::open(const json& params) {
  const json& doc = params.at("textDocument");
  const std::string& uri = text_of(doc.at("uri"));
  auto text = std::make_shared<const std::string>(text_of(doc.at("text")));
  const std::int64_t version = doc.value("version", std::int64_t{0});
  {
    std::lock_guard lock(docs_mutex_);
    docs_[normal_path(uri_to_path(uri))] = Document{uri, std::move(text), version};
  }
  schedule();
}

void Server::change(const json& params) {
  const json& doc = params.at("textDocument");
  const std::string path = normal_path(uri_to_path(text_of(doc.at("uri"))));
  const json& changes = params.at("contentChanges");
  if (!changes.is_array()) return;
  std::shared_ptr<const std::string> old;
  {
    std::lock_guard lock(docs_mutex_);
    auto it = docs_.find(path);
    if (it == docs_.end()) return;
    old = it->second.text;
  }
  std::string text = *old;
  for (const json& c : changes) {
    if (c.contains("range")) {
      const json& range = c.at("range");
      apply_edit(text, position(range.at("start")), position(range.at("end")),
                 text_of(c.at("text")));
    } else {
      text = text_of(c.at("text"));
    }
  }
  {
    std::lock_guard lock(docs_mutex_);
    auto it = docs_.find(path);
    if (it == docs_.end()) return;
    it->second.text = std::make_shared<const std::string>(std::move(text));
    it->second.version = doc.value("version", it->second.version);
  }
  schedule();
}

void Server::close(const json& params) {
  const std::string path = normal_path(uri_to_path(text_of(params.at("textDocument").at("uri"))));
  {
    std::lock_guard lock(docs_mutex_);
    docs_.erase(path);
  }
  schedule();
}

void Server::schedule() {
  {
    std::lock_guard lock(docs_mutex_);
    debounce_.touch(steady_now());
  }
  wake_.notify_all();
}

DocumentTexts Server::snapshot() const {
  std::lock_guard lock(docs_mutex_);
  DocumentTexts out;
  for (const auto& [path, doc] : docs_) out.emplace(path, doc.text);
  return out;
}

bool Server::wait_idle(std::chrono::milliseconds limit) {
  std::unique_lock lock(docs_mutex_);
  return idle_.wait_for(lock, limit,
                        [this] { return stopping_ || (!compiling_ && !debounce_.due()); });
}

void Server::work() {
  std::unique_lock lock(docs_mutex_);
  for (;;) {
    if (stopping_) return;
    const std::optional<Debounce::Time> due = debounce_.due();
    if (!due) {
      wake_.wait(lock);
      continue;
    }
    if (!debounce_.take(steady_now())) {
      wake_.wait_until(lock,
                       std::chrono::steady_clock::time_point(
                           std::chrono::duration_cast<std::chrono::steady_clock::duration>(*due)));
      continue;
    }
    const std::uint64_t generation = debounce_.generation();
    std::map<std::string, std::string> uris;
    DocumentTexts texts;
    for (const auto& [path, doc] : docs_) {
      uris.emplace(path, doc.uri);
      texts.emplace(path, doc.text);
    }
    compiling_ = true;
    lock.unlock();
    publish_round(uris, texts, generation);
    lock.lock();
    compiling_ = false;
    idle_.notify_all();
  }
}

void Server::publish_round(const std::map<std::string, std::string>& uris,
                           const DocumentTexts& texts, std::uint64_t generation) {
  // Every open document compiled on its own, then only those no other open one includes kept
  // (an included file's diagnostics are those of the file that includes it).
  struct Compiled {
    FileDiagnostics diagnostics;
    std::set<std::string> inputs;
  };
  std::map<std::string, Compiled> compiled;
  for (const auto& [path, uri] : uris) {
    OverlayReader files(texts, disk_);
    Compiled c;
    try {
      const compiler::Loaded loaded = compiler::load(path, files, options_.compile);
      collect(loaded, path, c.diagnostics);
      for (const std::string& input : loaded.inputs()) c.inputs.insert(normal_path(input));
    } catch (const std::exception& e) {
      c.diagnostics[path] =
          json::array({{{"range", lsp_range(SourceManager(), {})},
                        {"severity", 1},
                        {"code", "internal-error"},
                        {"source", "seqc"},
                        {"message", std::string("internal error: ") + e.what()}}});
    }
    compiled.emplace(path, std::move(c));
    std::lock_guard lock(docs_mutex_);
    if (stopping_ || debounce_.generation() != generation) return;  // superseded
  }
  std::vector<const Compiled*> roots;
  for (const auto& [path, c] : compiled) {
    bool included = false;
    for (const auto& [other, o] : compiled)
      included = included || (other != path && o.inputs.count(path));
    if (!included) roots.push_back(&c);
  }
  if (roots.empty()) {
    for (const auto& [path, c] : compiled) roots.push_back(&c);
  }
  FileDiagnostics merged;
  for (const Compiled* c : roots) {
    for (const auto& [path, list] : c->diagnostics) {
      json& into = merged[path];
      if (!into.is_array()) into = json::array();
      for (const json& d : list) {
        if (std::find(into.begin(), into.end(), d) == into.end()) into.push_back(d);
      }
    }
  }
  std::map<std::string, std::string> now_published;
  auto publish = [this](const std::string& uri, const json& list) {
    send({{"jsonrpc", "2.0"},
          {"method", "textDocument/publishDiagnostics"},
          {"params", {{"uri", uri}, {"diagnostics", list}}}});
  };
  for (const auto& [path, uri] : uris) {
    auto it = merged.find(path);
    publish(uri, it == merged.end() ? json::array() : it->second);
    if (it != merged.end() && !it->second.empty()) now_published[path] = uri;
  }
  for (const auto& [path, list] : merged) {
    if (uris.count(path) || list.empty()) continue;
    const std::string uri = path_to_uri(path);
    publish(uri, list);
    now_published[path] = uri;
  }
  for (const auto& [path, uri] : published_) {
    if (!now_published.count(path) && !uris.count(path)) publish(uri, json::array());
  }
  published_ = std::move(now_published);
}

}  // namespace seqc::lsp
