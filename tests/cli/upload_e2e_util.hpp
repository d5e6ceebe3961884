// Process helpers for the end-to-end upload tests: spawning seqc with its output in files,
// waiting for it, and the actions `seqc compile --emit json` says a group gets, in the form
// `seqc emulate --dump-groups` writes.
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace seqc::e2e {

inline const std::string kSeqc = SEQC_BIN;
inline const std::string kWalk = std::string(SEQC_SOURCE_DIR) + "/tests/data/walk-joints.yaml";

inline pid_t spawn(const std::vector<std::string>& args, const std::string& out,
                   const std::string& err) {
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&fa, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, argv[0], &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  return rc == 0 ? pid : -1;
}

inline int wait_exit(pid_t pid) {
  int status = 0;
  if (waitpid(pid, &status, 0) != pid) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

inline std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

// The unsigned number after `"key": ` at or after `from` in `text` (-1 if absent); `from`
// moves past it.
inline long json_number(const std::string& text, const std::string& key, std::size_t& from) {
  const std::string needle = "\"" + key + "\":";
  const auto at = text.find(needle, from);
  if (at == std::string::npos) return -1;
  std::size_t i = at + needle.size();
  while (i < text.size() && text[i] == ' ') ++i;
  const std::size_t start = i;
  while (i < text.size() && text[i] >= '0' && text[i] <= '9') ++i;
  from = i;
  return i > start ? std::stol(text.substr(start, i - start)) : -1;
}

// The actions `seqc compile --emit json` says group `group` gets, one per keyframe (each
// keyframe line: {"start_ms": .., "time_ms": T, ..., "targets": [{.., "id": I, "position": P},
// ...]}), in the --dump-groups form "GROUP INDEX TIME ID=POS ...".
inline std::vector<std::string> compiled_actions(const std::string& json, int group) {
  std::vector<std::string> out;
  for (const auto& l : lines(json)) {
    if (l.find("\"start_ms\":") == std::string::npos) continue;
    std::size_t pos = 0;
    std::string action = std::to_string(group) + " " + std::to_string(out.size()) + " " +
                         std::to_string(json_number(l, "time_ms", pos));
    for (long id; (id = json_number(l, "id", pos)) >= 0;) {
      action += " " + std::to_string(id) + "=" + std::to_string(json_number(l, "position", pos));
    }
    out.push_back(action);
  }
  return out;
}

// Waits (polling every 10 ms, at most `tries` times) until `path` exists: `seqc emulate --link`
// has made its terminal.
inline bool wait_for_path(const std::string& path, int tries) {
  struct stat st {};
  for (int i = 0; i < tries && lstat(path.c_str(), &st) != 0; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return lstat(path.c_str(), &st) == 0;
}

// Stops `seqc emulate` as Ctrl-C would; its exit status. `pid` becomes -1.
inline int stop_with_sigint(pid_t& pid) {
  kill(pid, SIGINT);
  const int rc = wait_exit(pid);
  pid = -1;
  return rc;
}

// The actions of a --dump-groups file, without its '#' header lines.
inline std::vector<std::string> stored_actions(const std::string& dump) {
  std::vector<std::string> out;
  for (const auto& l : lines(dump)) {
    if (!l.empty() && l[0] != '#') out.push_back(l);
  }
  return out;
}

}  // namespace seqc::e2e
