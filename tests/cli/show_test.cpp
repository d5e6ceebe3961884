// seqc show end to end: in one process on both built-in emulators (a manual clock, so the start
// is exact and instant), and across processes with `seqc emulate xarm` and `seqc emulate
// raspblock` on pseudo-terminals, as a person would run a show without hardware.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "runtime/audio/manual_output.hpp"
#include "tests/cli/device_test_util.hpp"
#include "tests/cli/quiet_songs.hpp"

namespace seqc::cli::test {
namespace {

namespace fs = std::filesystem;

std::string slurp_file(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(Show, InProcessOnBothEmulatorsUploadsThenStartsTogether) {
  DeviceHarness h;
  const std::string dir = std::string(SEQC_SOURCE_DIR) + "/";
  h.files.add("duet.yaml",
              "show: duet\n"
              "performers:\n"
              "  arm: {file: " +
                  dir +
                  "tests/data/walk-joints.yaml, port: emu:xarm, group: 2}\n"
                  "  car: {file: " +
                  dir + "tests/golden/raspblock/small.yaml, port: emu:raspblock}\n");
  h.files.add(dir + "tests/data/walk-joints.yaml", slurp_file(dir + "tests/data/walk-joints.yaml"));
  h.files.add(dir + "tests/golden/raspblock/small.yaml",
              slurp_file(dir + "tests/golden/raspblock/small.yaml"));
  const io::TimePoint before = h.clock.now();
  const RunResult r = h.run({"show", "duet.yaml"});
  ASSERT_EQ(r.code, 0) << r.err;
  // The arm's group was stored before anything started, then run.
  ASSERT_TRUE(h.emu.stored_group(2).has_value());
  EXPECT_EQ(h.emu.stored_group(2)->size(), 27u);
  EXPECT_EQ(h.emu.playing_group(), std::optional<std::uint8_t>(2));
  const std::string& err = r.err;
  const auto uploaded = err.find("seqc: arm: the controller acknowledged 27 actions");
  const auto started = err.find("seqc: show duet: starting 2 performers at one instant");
  ASSERT_NE(uploaded, std::string::npos) << err;
  ASSERT_NE(started, std::string::npos) << err;
  EXPECT_LT(uploaded, started);
  // On a manual clock every frame leaves exactly at its deadline.
  EXPECT_NE(err.find("seqc: arm: GroupRun 2 arrived 0.00 ms after the start (written 0.00 ms "
                     "after it, 0.00 ms on the wire)"),
            std::string::npos)
      << err;
  EXPECT_NE(err.find("seqc: car: "), std::string::npos) << err;
  EXPECT_NE(err.find("seqc: start skew between performers: 0.00 ms"), std::string::npos) << err;
  EXPECT_GT(h.clock.now() - before, std::chrono::seconds(2));  // the car's stream was played
}

TEST(Show, WithMusicEveryoneStartsOnTheDownbeatAsHeard) {
  emu::XArmConfig at_9600;
  at_9600.baud = 9600;
  DeviceHarness h(at_9600);
  QuietSongs songs;
  audio::ManualAudioOutputFactory speakers(h.clock, std::chrono::milliseconds(50));
  h.audio_files = &songs;
  h.audio_output = &speakers;
  const std::string dir = std::string(SEQC_SOURCE_DIR) + "/";
  h.files.add("duet.yaml",
              "show: duet\nperformers:\n  arm: {file: arm.yaml, port: emu:xarm, group: 2}\n"
              "  car: {file: " +
                  dir + "tests/golden/raspblock/small.yaml, port: emu:raspblock}\n");
  h.files.add("arm.yaml",
              "robot: xarm\nmusic:\n  file: song.wav\n  downbeat: 0.750s\n  tempo: 120\n"
              "  meter: 4/4\nsequence:\n  - move: {base: 400}\n    time: 1b\n");
  h.files.add(dir + "tests/golden/raspblock/small.yaml",
              slurp_file(dir + "tests/golden/raspblock/small.yaml"));
  const RunResult r = h.run({"show", "duet.yaml", "--music"});
  ASSERT_EQ(r.code, 0) << r.err;
  ASSERT_NE(speakers.last(), nullptr);
  ASSERT_TRUE(speakers.last()->started_at().has_value());
  // 50 ms of latency + the downbeat at 750 ms: GroupRun 2 finishes arriving 800 ms after the
  // song's start, written 7.29 ms (7 bytes at 9600 baud) before.
  std::optional<io::TimePoint> arrived;
  for (const emu::ReceivedFrame& f : h.emu.received()) {
    if (to_hex(f.raw) == hex("55 55 05 06 02 01 00")) arrived = f.at;
  }
  ASSERT_TRUE(arrived.has_value()) << r.err;
  const double arrived_ms =
      std::chrono::duration<double, std::milli>(*arrived - *speakers.last()->started_at()).count();
  EXPECT_NEAR(arrived_ms, 800.0, 1e-5);
  EXPECT_NE(r.err.find("seqc: music: downbeat heard at +0.800 s (output latency 50.0 ms)"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("seqc: arm: GroupRun 2 arrived 0.00 ms after the start (written 7.29 ms "
                       "before it, 7.29 ms on the wire)"),
            std::string::npos)
      << r.err;
  EXPECT_TRUE(speakers.last()->stopped());
}

// A downbeat sooner than the song's start can be timed (0.2 s) gets a lead-in of silence; the show
// says it in the same words as `upload --run --music` and `play --music` (heard_text).
TEST(Show, WithMusicSaysTheLeadInOfSilence) {
  DeviceHarness h;
  QuietSongs songs;
  audio::ManualAudioOutputFactory speakers(h.clock, std::chrono::milliseconds(50));
  h.audio_files = &songs;
  h.audio_output = &speakers;
  h.files.add("solo.yaml", "show: solo\nperformers:\n  arm: {file: arm.yaml, port: emu:xarm}\n");
  h.files.add("arm.yaml",
              "robot: xarm\nmusic:\n  file: song.wav\n  downbeat: 0.200s\n  tempo: 120\n"
              "  meter: 4/4\nsequence:\n  - move: {base: 400}\n    time: 1b\n");
  const RunResult r = h.run({"show", "solo.yaml", "--music"});
  ASSERT_EQ(r.code, 0) << r.err;
  // 0.3 s of silence, 50 ms of latency, the downbeat 0.2 s into the song: heard at 0.550 s.
  EXPECT_NE(r.err.find("seqc: music: downbeat heard at +0.550 s (output latency 50.0 ms, after "
                       "0.300 s of silence); each performer's start below is from it\n"),
            std::string::npos)
      << r.err;
}

// A stop signal during the uploads is an interruption like any other (exit 130), not a failing
// device: nothing was stored and nothing started.
TEST(Show, InterruptedDuringItsUploadsExits130) {
  DeviceHarness h;
  const std::string dir = std::string(SEQC_SOURCE_DIR) + "/";
  h.files.add("duet.yaml",
              "show: duet\nperformers:\n  arm: {file: arm.yaml, port: emu:xarm, group: 2}\n"
              "  car: {file: " +
                  dir + "tests/golden/raspblock/small.yaml, port: emu:raspblock}\n");
  h.files.add("arm.yaml", "robot: xarm\nsequence:\n  - move: home\n    time: 1s\n");
  h.files.add(dir + "tests/golden/raspblock/small.yaml",
              slurp_file(dir + "tests/golden/raspblock/small.yaml"));
  h.interrupted = true;  // arrived before the first frame of the arm's download
  const RunResult r = h.run({"show", "duet.yaml"});
  EXPECT_EQ(r.code, 130) << r.err;
  EXPECT_NE(r.err.find("seqc: nothing was started\n"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("error"), std::string::npos) << r.err;
  EXPECT_FALSE(h.emu.stored_group(2).has_value());
  EXPECT_EQ(h.emu.playing_group(), std::nullopt);
}

TEST(Show, NothingStartsWhenAPerformerIsBroken) {
  DeviceHarness h;
  h.files.add("bad.yaml",
              "show: broken\nperformers:\n  arm: {file: arm.yaml, port: emu:xarm}\n"
              "  car: {file: car.yaml}\n");
  h.files.add("arm.yaml", "robot: xarm\nsequence:\n  - move: home\n    time: 1s\n");
  h.files.add("car.yaml", "robot: raspblock\nsequence:\n  - drive: {y: 99}\n    time: 1s\n");
  const RunResult r = h.run({"show", "bad.yaml"});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("car.yaml:3:16: error: 'y' must be -25 to 25, not 99"), std::string::npos)
      << r.err;
  EXPECT_EQ(h.received(), "");  // not even the arm was touched
}

// --trace PREFIX writes one trace per performer, PREFIX-NAME.trace, each in its board's dialect,
// and `seqc decode` reads both: the arm's shows the first-move read just before its GroupRun,
// the car's its two Rocker packets one second apart (drive y 10 for 1 s, then the stop).
TEST(Show, TracesEveryPerformerInItsOwnDialect) {
  DeviceHarness h;
  h.files.add("duo.yaml",
              "show: duo\nperformers:\n  arm: {file: arm.yaml, port: emu:xarm}\n"
              "  car: {file: car.yaml, port: emu:raspblock}\n");
  h.files.add("arm.yaml", "robot: xarm\nsequence:\n  - move: {claw: 300}\n    time: 1s\n");
  h.files.add("car.yaml", "robot: raspblock\nsequence:\n  - drive: {y: 10}\n    time: 1s\n");
  const fs::path dir = fs::temp_directory_path() / "seqc-show-trace-test";
  fs::create_directories(dir);
  const std::string prefix = (dir / "duo").string();
  fs::remove(prefix + "-arm.trace");
  fs::remove(prefix + "-car.trace");
  const RunResult r = h.run({"show", "duo.yaml", "--trace", prefix});
  ASSERT_EQ(r.code, 0) << r.err;

  const std::string arm = slurp_file(prefix + "-arm.trace");
  const std::string car = slurp_file(prefix + "-car.trace");
  EXPECT_NE(arm.find("# dialect: xArm / LSC-16 / LSC-32\n"), std::string::npos) << arm;
  EXPECT_NE(car.find("# dialect: Raspblock\n"), std::string::npos) << car;
  // The car's packets by hand (docs/protocol/raspblock.md, 0x03 rocker): FF FE 03 08, mode 01,
  // X 00 00, Y 00 0a (then 00 00 for the stop), Z 00 00, direction 01 (Z >= 0), and the checksum
  // 03 + 08 + 01 + 0a + 01 = 0x17 (0x0d for the stop).
  EXPECT_NE(car.find(" > ff fe 03 08 01 00 00 00 0a 00 00 01 17\n"), std::string::npos) << car;
  EXPECT_NE(car.find(" > ff fe 03 08 01 00 00 00 00 00 00 01 0d\n"), std::string::npos) << car;

  h.files.add(prefix + "-arm.trace", arm);
  h.files.add(prefix + "-car.trace", car);
  const RunResult da = h.run({"decode", prefix + "-arm.trace"});
  ASSERT_EQ(da.code, 0) << da.err;
  const auto read = da.out.find("> ServoPositionRead servos=[1]\n");
  const auto run = da.out.find("> GroupRun group=0 times=1\n");
  ASSERT_NE(read, std::string::npos) << da.out;
  ASSERT_NE(run, std::string::npos) << da.out;
  EXPECT_LT(read, run);
  const RunResult dc = h.run({"decode", prefix + "-car.trace"});
  ASSERT_EQ(dc.code, 0) << dc.err;
  EXPECT_NE(dc.out.find("# trace, Raspblock packets\n"), std::string::npos) << dc.out;
  const auto go = dc.out.find(" > Rocker x=0 y=10 z=0\n");
  const auto stop = dc.out.find(" > Rocker x=0 y=0 z=0\n");
  ASSERT_NE(go, std::string::npos) << dc.out;
  ASSERT_NE(stop, std::string::npos) << dc.out;
  // "t=S.SSSSSS > ...": the stop leaves exactly 1 s after the drive on the manual clock.
  const auto time_before = [&](std::size_t at) {
    const std::size_t line = dc.out.rfind("t=", at);
    return std::stod(dc.out.substr(line + 2, at - line - 2));
  };
  EXPECT_NEAR(time_before(stop) - time_before(go), 1.0, 1e-6);
}

// `seqc emulate DEVICE ARGS...` in the background; returns its pid and the pty it printed.
pid_t emulate(const std::vector<std::string>& args, const fs::path& err, std::string& pty) {
  int pipefd[2];
  if (::pipe(pipefd) != 0) return -1;
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::dup2(pipefd[1], STDOUT_FILENO);
    if (std::freopen(err.c_str(), "w", stderr) == nullptr) std::_Exit(126);
    ::close(pipefd[0]);
    std::vector<char*> argv{const_cast<char*>("seqc"), const_cast<char*>("emulate")};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(SEQC_BIN, argv.data());
    std::_Exit(127);
  }
  ::close(pipefd[1]);
  char c = 0;
  while (::read(pipefd[0], &c, 1) == 1 && c != '\n') pty += c;
  ::close(pipefd[0]);
  return pid;
}

TEST(Show, AcrossProcessesOnPseudoTerminals) {
  const fs::path tmp =
      fs::path(SEQC_BINARY_DIR) / "tests/cli/tmp" / ("show-" + std::to_string(::getpid()));
  fs::create_directories(tmp);
  std::string arm_pty, car_pty;
  const pid_t arm = emulate({"xarm", "--dump-groups", (tmp / "groups.txt").string()},
                            tmp / "arm.stderr", arm_pty);
  const pid_t car =
      emulate({"raspblock", "--record", (tmp / "car.csv").string()}, tmp / "car.stderr", car_pty);
  ASSERT_FALSE(arm_pty.empty());
  ASSERT_FALSE(car_pty.empty());
  const std::string src = SEQC_SOURCE_DIR;
  std::ofstream(tmp / "duet.yaml")
      << "show: duet\nperformers:\n  arm: {file: " << src
      << "/tests/data/walk-joints.yaml, port: " << arm_pty << "}\n  car: {file: " << src
      << "/tests/golden/raspblock/small.yaml, port: " << car_pty << "@115200}\n";
  const std::string cmd = "'" SEQC_BIN "' show '" + (tmp / "duet.yaml").string() + "' 2>'" +
                          (tmp / "show.stderr").string() + "'";
  const int raw = std::system(cmd.c_str());
  // Stop the emulators once the car's last packet (the stop) is logged.
  for (int i = 0; i < 2000 && slurp_file(tmp / "car.stderr").find("rocker") == std::string::npos;
       ++i) {
    ::usleep(5000);
  }
  ::kill(arm, SIGINT);
  ::kill(car, SIGINT);
  int status = 0;
  ::waitpid(arm, &status, 0);
  ::waitpid(car, &status, 0);
  const std::string report = slurp_file(tmp / "show.stderr");
  ASSERT_TRUE(WIFEXITED(raw) && WEXITSTATUS(raw) == 0) << report;
  EXPECT_NE(report.find("seqc: start skew between performers: "), std::string::npos) << report;
  // The arm's controller stored group 0 (walk.yaml: 27 actions); the car board got packets.
  const std::string groups = slurp_file(tmp / "groups.txt");
  std::vector<std::string> actions;
  std::istringstream lines(groups);
  for (std::string line; std::getline(lines, line);) {
    if (!line.empty() && line[0] != '#') actions.push_back(line);
  }
  ASSERT_EQ(actions.size(), 27u) << groups;
  EXPECT_EQ(actions[0].rfind("0 0 1000 ", 0), 0u) << groups;  // move: home, time: 1s
  EXPECT_NE(slurp_file(tmp / "car.csv").find("gimbal"), std::string::npos);
  std::printf("[ measured ] %s", report.substr(report.find("seqc: arm: GroupRun")).c_str());
  fs::remove_all(tmp);
}

}  // namespace
}  // namespace seqc::cli::test
