// seqc on a real terminal: the binary runs under forkpty with a window of known width, and the
// test reads what the terminal would show. Colour appears on a terminal unless NO_COLOR is set;
// the upload and play progress lines are redrawn in place and never wider than the window.
#include <gtest/gtest.h>
#include <pty.h>
#include <sys/ioctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

namespace {

struct TerminalRun {
  std::string screen;  // every byte written to the terminal (stdout and stderr)
  int status = -1;
};

// Runs seqc with `args` on a new pseudo-terminal `columns` wide, in the source tree, with
// `env` added to the environment (NO_COLOR is removed first, as in a plain login).
TerminalRun on_terminal(const std::vector<std::string>& args, int columns,
                        const std::vector<std::string>& env = {}, const std::string& typed = "") {
  struct winsize ws {};
  ws.ws_col = static_cast<unsigned short>(columns);
  ws.ws_row = 24;
  int master = -1;
  const pid_t pid = forkpty(&master, nullptr, nullptr, &ws);
  if (pid == 0) {
    if (chdir(SEQC_SOURCE_DIR) != 0) _exit(126);
    unsetenv("NO_COLOR");
    for (const std::string& e : env) putenv(const_cast<char*>(e.c_str()));
    std::vector<char*> argv{const_cast<char*>(SEQC_BIN)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(SEQC_BIN, argv.data());
    _exit(127);
  }
  // What the person types: the terminal holds it until the program reads a line.
  if (!typed.empty() && write(master, typed.data(), typed.size()) < 0) ADD_FAILURE() << "write";
  TerminalRun r;
  char buf[4096];
  for (;;) {
    const ssize_t n = read(master, buf, sizeof buf);
    if (n > 0) {
      r.screen.append(buf, static_cast<std::size_t>(n));
    } else if (n < 0 && errno == EINTR) {
      continue;
    } else {
      break;  // EIO: the child closed the terminal
    }
  }
  int raw = 0;
  waitpid(pid, &raw, 0);
  close(master);
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return r;
}

// The visible width of a piece of terminal output: escape sequences take no column.
std::size_t visible_width(const std::string& s) {
  std::size_t width = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '\033') {
      while (i < s.size() && !(s[i] >= '@' && s[i] <= '~' && s[i] != '[')) ++i;
      continue;
    }
    if ((static_cast<unsigned char>(s[i]) & 0xC0) != 0x80) ++width;
  }
  return width;
}

// Every redraw of a line ("\r...") and every line.
std::vector<std::string> drawn_lines(const std::string& screen) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : screen) {
    if (c == '\r' || c == '\n') {
      if (!cur.empty()) out.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  if (!cur.empty()) out.push_back(cur);
  return out;
}

TEST(Terminal, DiagnosticsAreColouredUnlessNoColor) {
  const TerminalRun coloured = on_terminal({"check", "tests/golden/bad-unknown-pose.yaml"}, 100);
  EXPECT_EQ(coloured.status, 1);
  EXPECT_NE(coloured.screen.find("\033[31merror: "), std::string::npos) << coloured.screen;
  const TerminalRun plain =
      on_terminal({"check", "tests/golden/bad-unknown-pose.yaml"}, 100, {"NO_COLOR=1"});
  EXPECT_EQ(plain.screen.find('\033'), std::string::npos) << plain.screen;
  EXPECT_NE(plain.screen.find("error: unknown pose 'raech'"), std::string::npos);
  // An empty NO_COLOR does not count (no-color.org), and --color=always beats NO_COLOR.
  EXPECT_NE(on_terminal({"check", "tests/golden/bad-unknown-pose.yaml"}, 100, {"NO_COLOR="})
                .screen.find('\033'),
            std::string::npos);
  EXPECT_NE(on_terminal({"--color=always", "check", "tests/golden/bad-unknown-pose.yaml"}, 100,
                        {"NO_COLOR=1"})
                .screen.find('\033'),
            std::string::npos);
}

TEST(Terminal, UploadProgressFitsTheWindow) {
  for (int columns : {60, 100}) {
    const TerminalRun r =
        on_terminal({"upload", "tests/data/walk-joints.yaml", "--port", "emu:xarm"}, columns);
    ASSERT_EQ(r.status, 0) << r.screen;
    std::size_t bars = 0;
    for (const std::string& line : drawn_lines(r.screen)) {
      // The bar lines (messages may wrap like any text; a bar redrawn in place must not).
      if (line.find("actions") == std::string::npos || line.find('[') == std::string::npos) {
        continue;
      }
      ++bars;
      EXPECT_LT(visible_width(line), static_cast<std::size_t>(columns)) << line;
    }
    EXPECT_GT(bars, 1u) << "the bar is redrawn in place: " << r.screen;
    EXPECT_NE(r.screen.find("] 27/27 actions"), std::string::npos) << r.screen;
  }
}

TEST(Terminal, PlayShowsProgress) {
  const TerminalRun r =
      on_terminal({"play", "tests/golden/raspblock/small.yaml", "--port", "emu:raspblock"}, 70);
  ASSERT_EQ(r.status, 0) << r.screen;
  EXPECT_NE(r.screen.find(" s  frame "), std::string::npos) << r.screen;
  for (const std::string& line : drawn_lines(r.screen)) {
    if (line.find(" s  frame ") != std::string::npos) {
      EXPECT_LT(visible_width(line), 70u) << line;
    }
  }
  // --quiet: no progress at all.
  const TerminalRun quiet = on_terminal(
      {"-q", "play", "tests/golden/raspblock/small.yaml", "--port", "emu:raspblock"}, 70);
  EXPECT_EQ(quiet.screen.find("frame"), std::string::npos) << quiet.screen;
}

TEST(Terminal, TeachOnATerminal) {
  const std::string path =
      ::testing::TempDir() + "teach-pty-" + std::to_string(::getpid()) + ".yaml";
  std::ofstream(path) << "robot: xarm\nsequence:\n  - move: home\n    time: 1s\n";
  const TerminalRun r =
      on_terminal({"teach", path, "--port", "emu:xarm?1=250,5=420"}, 80, {}, "\nlift\nq\n");
  ASSERT_EQ(r.status, 0) << r.screen;
  EXPECT_NE(r.screen.find("press Enter to record the pose, q to finish"), std::string::npos)
      << r.screen;
  EXPECT_NE(r.screen.find("name [pose1]"), std::string::npos) << r.screen;
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text,
            "robot: xarm\n"
            "poses:\n"
            "  lift: {claw: 250, wrist_roll: 500, wrist_pitch: 500, elbow: 500, shoulder: 420, "
            "base: 500}\n"
            "sequence:\n"
            "  - move: home\n"
            "    time: 1s\n");
  std::remove(path.c_str());
}

}  // namespace
