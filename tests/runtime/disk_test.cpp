// The file system boundary on files a stranger prepared: the safe writer (a planted link is not
// followed, a device stays a device, a full disk is an error, nothing half written is left),
// the same-file test (hard and symbolic links), and reads bounded whatever the file is.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <future>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "runtime/io/disk.hpp"

namespace {

namespace fs = std::filesystem;
using seqc::io::DiskFileReader;
using seqc::io::read_input;
using seqc::io::read_stream;
using seqc::io::same_file;
using seqc::io::same_file_among;
using seqc::io::write_file_safely;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class Disk : public ::testing::Test {
 protected:
  void SetUp() override {
    char tmpl[] = "/tmp/seqc-disk-XXXXXX";
    ASSERT_NE(::mkdtemp(tmpl), nullptr);
    dir_ = tmpl;
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  // Every name in the folder, sorted: what a write left behind.
  std::string listing() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_)) names.push_back(e.path().filename());
    std::sort(names.begin(), names.end());
    std::string all;
    for (const auto& n : names) all += n + " ";
    return all;
  }
  fs::path dir_;
};

TEST_F(Disk, WritesANewFileWithAnOrdinaryModeAndLeavesNoTemporary) {
  const mode_t old = ::umask(022);
  ASSERT_TRUE(write_file_safely(path("out.hex"), "55 55\n").ok());
  ::umask(old);
  EXPECT_EQ(slurp(path("out.hex")), "55 55\n");
  struct stat st {};
  ASSERT_EQ(::stat(path("out.hex").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0644u);  // 0666 less the umask 022
  EXPECT_EQ(listing(), "out.hex ");
}

TEST_F(Disk, ReplacesARegularFileWhole) {
  std::ofstream(path("out.hex")) << "a much longer old content\n";
  ASSERT_TRUE(write_file_safely(path("out.hex"), "new\n").ok());
  EXPECT_EQ(slurp(path("out.hex")), "new\n");
  EXPECT_EQ(listing(), "out.hex ");
}

// A file written as seqc runs (a trace): the old file stays whole until finish() renames the
// temporary over it, and an OutputFile dropped unfinished leaves the old file and no temporary.
TEST_F(Disk, AnOutputFileReplacesTheOldFileOnlyWhenFinished) {
  std::ofstream(path("trace.txt")) << "old trace\n";
  {
    auto file = seqc::io::OutputFile::open(path("trace.txt"));
    ASSERT_TRUE(file.ok());
    ASSERT_TRUE((*file)->write("t=0.000000 > 55 55\n").ok());
    ASSERT_TRUE((*file)->write("t=0.010000 < 55 55\n").ok());
    EXPECT_EQ(slurp(path("trace.txt")), "old trace\n");
    ASSERT_TRUE((*file)->finish().ok());
  }
  EXPECT_EQ(slurp(path("trace.txt")), "t=0.000000 > 55 55\nt=0.010000 < 55 55\n");
  EXPECT_EQ(listing(), "trace.txt ");
  {
    auto file = seqc::io::OutputFile::open(path("trace.txt"));
    ASSERT_TRUE(file.ok());
    ASSERT_TRUE((*file)->write("half").ok());
  }
  EXPECT_EQ(slurp(path("trace.txt")), "t=0.000000 > 55 55\nt=0.010000 < 55 55\n");
  EXPECT_EQ(listing(), "trace.txt ");
  EXPECT_FALSE(seqc::io::OutputFile::open(dir_.string()).ok());  // a folder
}

TEST_F(Disk, ALinkPlantedAtTheOldTemporaryNameIsNotFollowed) {
  // Another user plants OUT.seqc-tmp (the name a former version wrote through) pointing at a
  // file of the victim's: the write must neither follow nor remove it.
  std::ofstream(path("precious")) << "keep me\n";
  fs::create_symlink(path("precious"), path("out.hex.seqc-tmp"));
  fs::create_symlink(path("precious"), path("out.hex.part"));
  ASSERT_TRUE(write_file_safely(path("out.hex"), "frames\n").ok());
  EXPECT_EQ(slurp(path("precious")), "keep me\n");
  EXPECT_EQ(slurp(path("out.hex")), "frames\n");
  EXPECT_TRUE(fs::is_symlink(path("out.hex.seqc-tmp")));
  EXPECT_EQ(listing(), "out.hex out.hex.part out.hex.seqc-tmp precious ");
}

TEST_F(Disk, ASymlinkedTargetIsFollowedAndTheFileItNamesReplaced) {
  // The rule: a link is followed as open() follows it; the file at its end is replaced and the
  // link stays a link.
  fs::create_directory(path("real"));
  std::ofstream(path("real/out.hex")) << "old\n";
  fs::create_symlink("real/out.hex", path("link.hex"));
  ASSERT_TRUE(write_file_safely(path("link.hex"), "new\n").ok());
  EXPECT_TRUE(fs::is_symlink(path("link.hex")));
  EXPECT_EQ(slurp(path("real/out.hex")), "new\n");
  // A dangling link: its end is created, in its own folder.
  fs::create_symlink("real/made.hex", path("dangling.hex"));
  ASSERT_TRUE(write_file_safely(path("dangling.hex"), "made\n").ok());
  EXPECT_TRUE(fs::is_symlink(path("dangling.hex")));
  EXPECT_EQ(slurp(path("real/made.hex")), "made\n");
  EXPECT_EQ(listing(), "dangling.hex link.hex real ");
  // A loop of links is an error, not a hang.
  fs::create_symlink("loop-b", path("loop-a"));
  fs::create_symlink("loop-a", path("loop-b"));
  EXPECT_FALSE(write_file_safely(path("loop-a"), "x").ok());
}

TEST_F(Disk, ACharacterDeviceIsWrittenDirectlyAndStaysADevice) {
  ASSERT_TRUE(write_file_safely("/dev/null", "frames\n").ok());
  struct stat st {};
  ASSERT_EQ(::stat("/dev/null", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));
  // Nothing was created in /dev beside it.
  EXPECT_FALSE(fs::exists("/dev/null.seqc-tmp"));
}

TEST_F(Disk, AFifoIsWrittenDirectlyToItsReader) {
  ASSERT_EQ(::mkfifo(path("pipe").c_str(), 0600), 0);
  auto reader = std::async(std::launch::async, [this] { return slurp(path("pipe")); });
  ASSERT_TRUE(write_file_safely(path("pipe"), "through the pipe\n").ok());
  ASSERT_EQ(reader.wait_for(std::chrono::seconds(5)), std::future_status::ready);
  EXPECT_EQ(reader.get(), "through the pipe\n");
  struct stat st {};
  ASSERT_EQ(::lstat(path("pipe").c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));
  EXPECT_EQ(listing(), "pipe ");
}

TEST_F(Disk, AFileHeldOpenAndNamedThroughProcIsWrittenWhereItIs) {
  // /dev/fd/N (as /dev/stdout) names a file a process holds open: it is written in place, so
  // the holder sees the data, not a new file renamed over the name.
  std::ofstream(path("held")) << "old content, longer\n";
  const int fd = ::open(path("held").c_str(), O_RDWR);
  ASSERT_GE(fd, 0);
  struct stat before {};
  ASSERT_EQ(::fstat(fd, &before), 0);
  ASSERT_TRUE(write_file_safely("/dev/fd/" + std::to_string(fd), "new\n").ok());
  struct stat after {};
  ASSERT_EQ(::stat(path("held").c_str(), &after), 0);
  EXPECT_EQ(after.st_ino, before.st_ino);
  EXPECT_EQ(slurp(path("held")), "new\n");
  ::close(fd);
  EXPECT_EQ(listing(), "held ");
}

TEST_F(Disk, AFullDiskIsAnErrorNamingThePath) {
  const auto full = write_file_safely("/dev/full", std::string(100000, 'x'));
  ASSERT_FALSE(full.ok());
  EXPECT_EQ(full.error().message, "/dev/full: cannot write: No space left on device");
}

TEST_F(Disk, AFolderOrAMissingFolderIsAnErrorAndNothingIsLeft) {
  const auto folder = write_file_safely(dir_.string(), "x");
  ASSERT_FALSE(folder.ok());
  EXPECT_EQ(folder.error().message, dir_.string() + ": cannot write: is a directory");
  const auto missing = write_file_safely(path("no/such/out.hex"), "x");
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().message.rfind(path("no/such/out.hex") + ": cannot write: ", 0), 0u);
  EXPECT_EQ(listing(), "");
}

TEST_F(Disk, SameFileSeesThroughHardAndSymbolicLinks) {
  std::ofstream(path("dance.yaml")) << "name: d\n";
  std::ofstream(path("other.yaml")) << "name: d\n";  // same text, another file
  fs::create_hard_link(path("dance.yaml"), path("hard.yaml"));
  fs::create_symlink("dance.yaml", path("soft.yaml"));
  EXPECT_TRUE(same_file(path("dance.yaml"), path("hard.yaml")));
  EXPECT_TRUE(same_file(path("soft.yaml"), path("dance.yaml")));
  EXPECT_TRUE(same_file(path("./dance.yaml"),
                        dir_.string() + "/../" + dir_.filename().string() + "/dance.yaml"));
  EXPECT_FALSE(same_file(path("dance.yaml"), path("other.yaml")));
  EXPECT_FALSE(same_file(path("dance.yaml"), path("absent.yaml")));
  EXPECT_FALSE(same_file(path("absent.yaml"), path("absent.yaml")));
  EXPECT_EQ(same_file_among(path("hard.yaml"), {path("other.yaml"), path("soft.yaml")}),
            path("soft.yaml"));
  EXPECT_EQ(same_file_among(path("new.hex"), {path("dance.yaml")}), "");
}

TEST_F(Disk, ReadsAreBoundedWhateverTheFileIs) {
  DiskFileReader reader(1000);
  std::ofstream(path("small")) << std::string(1000, 'a');
  std::ofstream(path("big")) << std::string(1001, 'a');
  EXPECT_EQ(reader.read(path("small")).value(), std::string(1000, 'a'));
  const auto big = reader.read(path("big"));
  ASSERT_FALSE(big.ok());
  EXPECT_EQ(big.error().message, path("big") + ": file is too large (more than 1000 bytes)");
  // A device of endless bytes: refused after the limit, not read forever.
  const auto zero = reader.read("/dev/zero");
  ASSERT_FALSE(zero.ok());
  EXPECT_EQ(zero.error().message, "/dev/zero: file is too large (more than 1000 bytes)");
  EXPECT_EQ(reader.read("/dev/null").value(), "");
  const auto folder = reader.read(dir_.string());
  ASSERT_FALSE(folder.ok());
  EXPECT_EQ(folder.error().message, dir_.string() + ": is a directory");
}

TEST_F(Disk, AFifoThatNeverEndsIsRefusedAtTheLimit) {
  ASSERT_EQ(::mkfifo(path("pipe").c_str(), 0600), 0);
  std::signal(SIGPIPE, SIG_IGN);  // the writer learns the reader is gone from EPIPE
  std::thread writer([this] {
    const int fd = ::open(path("pipe").c_str(), O_WRONLY);
    const std::string block(4096, 'z');
    // Until the reader closes its end.
    while (::write(fd, block.data(), block.size()) > 0) {
    }
    ::close(fd);
  });
  const auto read = DiskFileReader(100000).read(path("pipe"));
  writer.join();
  ASSERT_FALSE(read.ok());
  EXPECT_EQ(read.error().message, path("pipe") + ": file is too large (more than 100000 bytes)");
}

TEST_F(Disk, AFifoNoOneWritesToIsAnErrorNotAWaitForever) {
  ASSERT_EQ(::mkfifo(path("pipe").c_str(), 0600), 0);
  const auto read =
      DiskFileReader(1000, std::chrono::milliseconds(20), std::chrono::milliseconds(20))
          .read(path("pipe"));
  ASSERT_FALSE(read.ok());
  EXPECT_EQ(read.error().message, path("pipe") + ": no process opened this FIFO for writing");
}

TEST_F(Disk, AFifoWhoseWriterComesLateOrFallsSilentIsReadOrRefused) {
  ASSERT_EQ(::mkfifo(path("pipe").c_str(), 0600), 0);
  // The writer opens it after the reader, writes, and ends: read whole.
  std::thread late([this] {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    const int fd = ::open(path("pipe").c_str(), O_WRONLY);
    (void)!::write(fd, "name: x\n", 8);
    ::close(fd);
  });
  const auto whole = DiskFileReader(1000, std::chrono::seconds(5)).read(path("pipe"));
  late.join();
  EXPECT_EQ(whole.value(), "name: x\n");
  // A writer that holds it open and says nothing more: refused after the idle wait.
  int writer_fd = -1;
  std::thread silent([&] {
    writer_fd = ::open(path("pipe").c_str(), O_WRONLY);
    (void)!::write(writer_fd, "abc", 3);
  });
  const auto stalled =
      DiskFileReader(1000, std::chrono::seconds(5), std::chrono::milliseconds(1000))
          .read(path("pipe"));
  silent.join();
  ::close(writer_fd);
  ASSERT_FALSE(stalled.ok());
  EXPECT_EQ(stalled.error().message, path("pipe") + ": nothing arrived for 1 s");
}

TEST(ReadStream, StopsAtTheLimitOnAStreamWithoutEnd) {
  std::istringstream small(std::string(10, 'x'));
  EXPECT_EQ(read_stream(small, "<stdin>", 10).value(), std::string(10, 'x'));
  std::istringstream big(std::string(11, 'x'));
  const auto refused = read_stream(big, "<stdin>", 10);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().message, "<stdin>: file is too large (more than 10 bytes)");
}

TEST(ReadInput, DashIsStandardInputAndAnythingElseAFile) {
  class OneFile final : public seqc::FileReader {
   public:
    seqc::Result<std::string> read(const std::string& path) override {
      if (path == "a.yaml") return std::string("from the file");
      return seqc::make_error(path + ": No such file or directory");
    }
  } files;
  std::istringstream in("from stdin");
  EXPECT_EQ(read_input("-", files, &in, "<stdin>").value(), "from stdin");
  EXPECT_EQ(read_input("-", files, nullptr, "<stdin>").value(), "");  // no stream: empty
  EXPECT_EQ(read_input("a.yaml", files, &in, "<stdin>").value(), "from the file");
  EXPECT_EQ(read_input("b.yaml", files, &in, "<stdin>").error().message,
            "b.yaml: No such file or directory");
}

TEST(TaggedPath, TheTagGoesBeforeTheExtension) {
  EXPECT_EQ(seqc::io::tagged_path("out.csv", "arm"), "out-arm.csv");
  EXPECT_EQ(seqc::io::tagged_path("out", "arm"), "out-arm");
  EXPECT_EQ(seqc::io::tagged_path("runs.d/out", "arm"), "runs.d/out-arm");
  EXPECT_EQ(seqc::io::tagged_path("runs.d/out.v2.csv", "car"), "runs.d/out.v2-car.csv");
}

}  // namespace
