// What `seqc studio` watches: every file the last compile read (CompileOutput::inputs(): the file,
// its includes, its song), by its modification time and size, polled (every ~50 ms by the
// server) through FileStamps, so tests drive it with a fake disk. A change is compiled once the
// files have held still for one poll, so an editor's save in several writes is compiled whole.
// The stamps a poll read are the ones the next compile is compared with: a save made while the
// compile runs is seen at the next poll, never lost.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace seqc::studio {

struct FileStamp {
  std::int64_t mtime_ns = 0;
  std::uint64_t size = 0;
  bool operator==(const FileStamp&) const = default;
};

class FileStamps {
 public:
  virtual ~FileStamps() = default;
  // nullopt: the file does not exist (or cannot be looked at); its coming back is a change.
  virtual std::optional<FileStamp> stamp(const std::string& path) = 0;
};

// stat(2) on the disk, links followed.
class DiskStamps final : public FileStamps {
 public:
  std::optional<FileStamp> stamp(const std::string& path) override;
};

class InputWatcher {
 public:
  explicit InputWatcher(FileStamps& stamps) : stamps_(stamps) {}

  // The files the compile just made read: each is compared from now on with the stamp the last
  // poll read for it (when it read one), else with its stamp now.
  void watch(const std::vector<std::string>& paths);
  // One poll: true when a watched file changed and has not changed again since the poll before;
  // the caller then compiles and calls watch().
  bool poll();
  // Whether the last poll saw a change that has yet to hold still (the caller polls again soon).
  bool settling() const { return seen_.has_value(); }

 private:
  using Stamps = std::map<std::string, std::optional<FileStamp>>;
  Stamps read_all() const;

  FileStamps& stamps_;
  Stamps compiled_;             // what the shown compile read
  std::optional<Stamps> seen_;  // what the last poll read, when it differed from compiled_
};

}  // namespace seqc::studio
