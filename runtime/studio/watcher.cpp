#include "runtime/studio/watcher.hpp"

#include <sys/stat.h>

namespace seqc::studio {

std::optional<FileStamp> DiskStamps::stamp(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return std::nullopt;
  return FileStamp{
      static_cast<std::int64_t>(st.st_mtim.tv_sec) * 1'000'000'000 + st.st_mtim.tv_nsec,
      static_cast<std::uint64_t>(st.st_size)};
}

InputWatcher::Stamps InputWatcher::read_all() const {
  Stamps now;
  for (const auto& [path, stamp] : compiled_) now[path] = stamps_.stamp(path);
  return now;
}

void InputWatcher::watch(const std::vector<std::string>& paths) {
  Stamps next;
  for (const std::string& path : paths) {
    if (seen_ && seen_->count(path) != 0) {
      next[path] = seen_->at(path);
    } else {
      next[path] = stamps_.stamp(path);
    }
  }
  compiled_ = std::move(next);
  seen_.reset();
}

bool InputWatcher::poll() {
  Stamps now = read_all();
  if (now == compiled_) {
    seen_.reset();
    return false;
  }
  const bool settled = seen_ && *seen_ == now;
  seen_ = std::move(now);
  return settled;
}

}  // namespace seqc::studio
