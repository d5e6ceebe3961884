#include "runtime/io/disk.hpp"

#include <fcntl.h>
#include <linux/magic.h>
#include <poll.h>
#include <pthread.h>
#include <sys/stat.h>
#include <sys/vfs.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <istream>
#include <optional>
#include <random>
#include <utility>

namespace seqc::io {
namespace {

constexpr std::size_t kChunk = 64 * 1024;

std::string too_large(const std::string& name, std::size_t max_bytes) {
  return name + ": file is too large (more than " + std::to_string(max_bytes) + " bytes)";
}

// Closes a descriptor on every path out of a function.
class Fd {
 public:
  explicit Fd(int fd) : fd_(fd) {}
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  ~Fd() {
    if (fd_ >= 0) ::close(fd_);
  }
  int get() const { return fd_; }
  // Closes now, for the error close() may report (a delayed write failing on NFS, a full disk).
  int close() {
    const int r = ::close(fd_);
    fd_ = -1;
    return r;
  }

 private:
  int fd_;
};

Error cannot_write(const std::string& path, const std::string& why) {
  return make_error(path + ": cannot write: " + why);
}

Status write_all(int fd, std::string_view data, const std::string& path) {
  std::size_t at = 0;
  while (at < data.size()) {
    const ssize_t n = ::write(fd, data.data() + at, data.size() - at);
    if (n < 0) {
      if (errno == EINTR) continue;
      return cannot_write(path, std::strerror(errno));
    }
    at += static_cast<std::size_t>(n);
  }
  return Ok{};
}

// The path a chain of symlinks ends at, as open() would follow it; the end may not exist. ""
// when the chain goes through a link in /proc (/dev/stdout, /dev/fd/N): those name a file some
// process holds open, which is written where it is, not replaced.
Result<std::string> resolve_links(const std::string& path) {
  namespace fs = std::filesystem;
  std::string at = path;
  for (int hops = 0;; ++hops) {
    struct stat st {};
    if (::lstat(at.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) return at;
    const std::string folder = fs::path(at).parent_path().string();
    struct statfs fsys {};
    if (::statfs(folder.empty() ? "." : folder.c_str(), &fsys) == 0 &&
        fsys.f_type == PROC_SUPER_MAGIC) {
      return std::string();
    }
    if (hops == 40) return cannot_write(path, std::strerror(ELOOP));
    std::error_code ec;
    const fs::path link = fs::read_symlink(at, ec);
    if (ec) return cannot_write(path, ec.message());
    at = link.is_absolute() ? link.string() : (fs::path(at).parent_path() / link).string();
  }
}

std::string random_suffix() {
  static constexpr char kLetters[] =
      "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
  std::random_device random;
  std::string s;
  for (int i = 0; i < 10; ++i) s += kLetters[random() % (sizeof kLetters - 1)];
  return s;
}

// A fresh temporary beside `target` (absent or a regular file), created exclusively.
Result<std::pair<int, std::string>> create_temporary(const std::string& path,
                                                     const std::string& target) {
  namespace fs = std::filesystem;
  const fs::path folder = fs::path(target).parent_path();
  const std::string stem = "." + fs::path(target).filename().string() + ".seqc-";
  for (int attempt = 0; attempt < 100; ++attempt) {
    // O_EXCL: the name is created here or not at all, so nothing planted at it (a link, a file
    // of someone else's) is opened; the mode is an ordinary new file's, 0666 less the umask.
    std::string temp = (folder / (stem + random_suffix())).string();
    const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd >= 0) return std::make_pair(fd, std::move(temp));
    if (errno != EEXIST) return cannot_write(path, std::strerror(errno));
  }
  return cannot_write(path, "no unused temporary name beside it");
}

// Holds SIGINT, SIGTERM and SIGHUP off while it lives, so a stop signal that ends seqc at once
// waits until a temporary is renamed or removed and never leaves one behind.
class HeldStopSignals {
 public:
  HeldStopSignals() {
    sigset_t stop;
    sigemptyset(&stop);
    sigaddset(&stop, SIGINT);
    sigaddset(&stop, SIGTERM);
    sigaddset(&stop, SIGHUP);
    ::pthread_sigmask(SIG_BLOCK, &stop, &old_);
  }
  HeldStopSignals(const HeldStopSignals&) = delete;
  HeldStopSignals& operator=(const HeldStopSignals&) = delete;
  ~HeldStopSignals() { ::pthread_sigmask(SIG_SETMASK, &old_, nullptr); }

 private:
  sigset_t old_;
};

}  // namespace

Result<std::string> DiskFileReader::read(const std::string& path) {
  // O_NONBLOCK: opening a FIFO no one writes to would otherwise wait for a writer forever, and
  // a serial device for its carrier. What is not a regular file is then read as it comes, each
  // wait bounded (poll).
  Fd fd(::open(path.c_str(), O_RDONLY | O_NOCTTY | O_CLOEXEC | O_NONBLOCK));
  if (fd.get() < 0) return make_error(path + ": " + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd.get(), &st) != 0) return make_error(path + ": " + std::strerror(errno));
  if (S_ISDIR(st.st_mode)) return make_error(path + ": is a directory");
  const bool regular = S_ISREG(st.st_mode);
  if (regular && static_cast<std::uintmax_t>(st.st_size) > max_bytes_) {
    return make_error(too_large(path, max_bytes_));
  }
  // Whatever the size said (a device's is 0, a file may grow), at most max_bytes + 1 are read.
  std::string text;
  if (regular) text.reserve(static_cast<std::size_t>(st.st_size));
  std::size_t have = 0;
  // A FIFO read before any writer opened it reads as ended: wait for one first.
  bool await_writer = S_ISFIFO(st.st_mode);
  for (;;) {
    const std::size_t want = std::min(kChunk, max_bytes_ + 1 - have);
    text.resize(have + want);
    const ssize_t n = ::read(fd.get(), text.data() + have, want);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && errno != EAGAIN) return make_error(path + ": " + std::strerror(errno));
    if (n > 0) {
      await_writer = false;
      have += static_cast<std::size_t>(n);
      if (have > max_bytes_) return make_error(too_large(path, max_bytes_));
      continue;
    }
    if (n == 0 && !await_writer) break;
    pollfd p{fd.get(), POLLIN, 0};
    const auto wait = await_writer ? writer_wait_ : idle_wait_;
    const int ready = ::poll(&p, 1, static_cast<int>(wait.count()));
    if (ready < 0 && errno != EINTR) return make_error(path + ": " + std::strerror(errno));
    if (ready == 0) {
      return make_error(path + (await_writer ? ": no process opened this FIFO for writing"
                                             : ": nothing arrived for " +
                                                   std::to_string(wait.count() / 1000) + " s"));
    }
    // A writer came and went without writing: the FIFO ends here, empty.
    if (ready > 0 && await_writer && (p.revents & POLLIN) == 0) break;
    await_writer = false;
  }
  text.resize(have);
  return text;
}

std::optional<std::uint64_t> DiskFileReader::size(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return std::nullopt;
  return static_cast<std::uint64_t>(st.st_size);
}

Result<std::string> read_stream(std::istream& in, const std::string& name, std::size_t max_bytes) {
  std::string text;
  std::size_t have = 0;
  while (in) {
    const std::size_t want = std::min(kChunk, max_bytes + 1 - have);
    text.resize(have + want);
    in.read(text.data() + have, static_cast<std::streamsize>(want));
    have += static_cast<std::size_t>(in.gcount());
    if (have > max_bytes) return make_error(too_large(name, max_bytes));
  }
  if (in.bad()) return make_error(name + ": read error");
  text.resize(have);
  return text;
}

Result<std::string> read_input(const std::string& path, seqc::FileReader& files, std::istream* in,
                               const std::string& stdin_name) {
  if (path != "-") return files.read(path);
  if (in == nullptr) return std::string();
  return read_stream(*in, stdin_name);
}

Result<std::unique_ptr<OutputFile>> OutputFile::open(const std::string& path) {
  // A device, a FIFO or a file reached through a link that names no path (/proc/self/fd/1):
  // it is opened as it is and written; nothing is created and nothing renamed.
  auto in_place = [&]() -> Result<std::unique_ptr<OutputFile>> {
    const int fd = ::open(path.c_str(), O_WRONLY | O_TRUNC | O_NOCTTY | O_CLOEXEC);
    if (fd < 0) return cannot_write(path, std::strerror(errno));
    return std::unique_ptr<OutputFile>(new OutputFile(path, fd, "", ""));
  };
  struct stat st {};
  const bool exists = ::stat(path.c_str(), &st) == 0;
  if (!exists && errno != ENOENT) return cannot_write(path, std::strerror(errno));
  if (exists && S_ISDIR(st.st_mode)) return cannot_write(path, "is a directory");
  if (exists && !S_ISREG(st.st_mode)) return in_place();
  auto target = resolve_links(path);
  if (!target) return target.error();
  if (target->empty()) return in_place();
  if (exists) {
    // A chain that does not end at the file open() reaches (a folder renamed meanwhile).
    struct stat end {};
    if (::lstat(target->c_str(), &end) != 0 || end.st_dev != st.st_dev || end.st_ino != st.st_ino) {
      return in_place();
    }
  }
  auto temp = create_temporary(path, *target);
  if (!temp) return temp.error();
  return std::unique_ptr<OutputFile>(
      new OutputFile(path, temp->first, std::move(temp->second), *target));
}

OutputFile::OutputFile(std::string path, int fd, std::string temp, std::string target)
    : path_(std::move(path)), temp_(std::move(temp)), target_(std::move(target)), fd_(fd) {}

OutputFile::~OutputFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!temp_.empty()) ::unlink(temp_.c_str());
}

Status OutputFile::write(std::string_view data) {
  if (fd_ < 0) return cannot_write(path_, "already finished");
  return write_all(fd_, data, path_);
}

Status OutputFile::finish() {
  if (fd_ < 0) return cannot_write(path_, "already finished");
  const int closed = ::close(fd_);
  fd_ = -1;
  if (closed != 0) return cannot_write(path_, std::strerror(errno));
  if (temp_.empty()) return Ok{};
  if (::rename(temp_.c_str(), target_.c_str()) != 0)
    return cannot_write(path_, std::strerror(errno));
  temp_.clear();
  return Ok{};
}

Status write_file_safely(const std::string& path, std::string_view data) {
  // Not around a device or FIFO's open, which may wait for a reader for ever: a signal must
  // still end that wait. A regular file's temporary is written and renamed with them held.
  std::optional<HeldStopSignals> held;
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || S_ISREG(st.st_mode)) held.emplace();
  auto file = OutputFile::open(path);
  if (!file) return file.error();
  if (Status s = (*file)->write(data); !s) return s;
  return (*file)->finish();
}

bool same_file(const std::string& a, const std::string& b) {
  struct stat sa {};
  struct stat sb {};
  if (::stat(a.c_str(), &sa) != 0 || ::stat(b.c_str(), &sb) != 0) return false;
  return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

std::string same_file_among(const std::string& output, const std::vector<std::string>& inputs) {
  for (const std::string& input : inputs) {
    if (same_file(output, input)) return input;
  }
  return "";
}

std::string tagged_path(const std::string& path, const std::string& tag) {
  const std::size_t slash = path.find_last_of('/');
  const std::size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) {
    return path + "-" + tag;
  }
  return path.substr(0, dot) + "-" + tag + path.substr(dot);
}

}  // namespace seqc::io
