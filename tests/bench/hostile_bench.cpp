// hostile_bench: the hostile-input catalogue through seqc's commands, as a user would meet them.
// Every input must end as documented -- by default `seqc check FILE` with exit 1 and a located
// error ("FILE:LINE:COL: error: ...") -- within 1 s and 64 MiB, and leave unchanged every file
// the command was not asked to write.
//
// The catalogue: every file in tests/compiler/hostile/ (NUL bytes, invalid UTF-8, !!binary,
// duplicate keys, a lone ',', cycles, tags, ...), and generated here: an alias bomb, a cyclic
// alias, 200,000-deep flow nesting, 3,000-deep block nesting (compact sequences; and nested maps
// as deep as 1 MiB allows), a 30 MB line, 200,000 steps (too big for a file) and as many steps
// as 1 MiB holds (a size probe, reported apart), repeat 65535 nested six deep, numbers of 5,000
// digits (position, time, tempo, repeat count), a file that includes itself, two that include each
// other, an include chain deeper than the limit, what the check fuzzer found (a slow tempo that
// makes fitting walk a long curve, in a file with a mistake); files that are not files (an
// include of /dev/zero, of a FIFO nobody writes to, of one that never ends; standard input that
// never ends), and outputs aimed at inputs (`-o` naming the choreography, a link to it, or an
// include; `-o /dev/null`); sections performing sections 40 wide and 14,000 deep, wrappers
// 15,000 deep, includes 15 x 10 wide; moves of 1,000 s to 100 minutes through check and every
// view; songs at 655 kHz and of 8 channels at 192 kHz, /dev/zero and an endless FIFO as songs;
// .d6a files holding a recursive view, a trigger, a million rows; names with markup and control
// characters through the preview, the plot and the terminal.
//
// Method: the files are written to --dir (default /tmp/seqc-hostile). Each case runs its
// command in a separate seqc process (fork + exec, stdout and stderr to a file); wall time is
// CLOCK_MONOTONIC around fork..wait4 (process start-up included), memory is wait4's ru_maxrss
// (peak RSS of that process alone). Best wall of --runs runs (default 3), largest RSS. The exit
// status and the output must be the case's; the inputs are hashed before and after. Prints one
// row per input, the worst time and memory, and whether every input met the targets; exits 1
// when one did not (a wrong exit, a missing message, an input changed).
//
// Usage: hostile_bench [--runs N] [--dir DIR] [--only SUBSTRING]
#include <fcntl.h>
#include <sqlite3.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <regex>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

// Texts are made when the case runs, in a child of their own (see main).
struct Case {
  std::string name;  // the file checked: DIR/name + ext
  std::function<std::string()> text;
  std::vector<std::pair<std::string, std::string>> extra;  // other files it needs
  // Not a hostile shape but the price of the size limit itself: reported apart from the
  // catalogue's verdict.
  bool size_probe = false;
  std::string ext = ".yaml";
  // The command line after `seqc`; {file} is the case's file, {dir} the folder.
  std::vector<std::string> args = {"check", "{file}"};
  int exit = 1;  // -1: any
  // A regular expression the output must match; empty: a located error.
  std::string expect;
  // Standard input: a path ("" = /dev/null).
  std::string stdin_path;
  // Before each run, in the folder (mkfifo, a writer, a link); returns a process to kill after
  // the run, or 0.
  std::function<pid_t(const std::string& dir)> setup;
  // After the run: "" when what the command left is right, else what is wrong.
  std::function<std::string(const std::string& dir)> verify;
};

Case lazy(std::string name, std::function<std::string()> text, bool size_probe = false) {
  Case c;
  c.name = std::move(name);
  c.text = std::move(text);
  c.size_probe = size_probe;
  return c;
}

Case fixed(std::string name, std::string text,
           std::vector<std::pair<std::string, std::string>> extra = {}) {
  Case c = lazy(std::move(name), [t = std::move(text)] { return t; });
  c.extra = std::move(extra);
  return c;
}

std::string repeat(const std::string& s, std::size_t n) {
  std::string out;
  out.reserve(s.size() * n);
  for (std::size_t i = 0; i < n; ++i) out += s;
  return out;
}

std::string read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

const std::string kHead = "name: hostile\nrobot: xarm\n";

std::vector<Case> generated() {
  std::vector<Case> c;
  {
    std::string bomb = kHead + "poses:\n  l0: &l0 {base: 1}\n";
    for (int i = 1; i <= 9; ++i) {
      bomb += "  l" + std::to_string(i) + ": &l" + std::to_string(i) + " [" +
              repeat("*l" + std::to_string(i - 1) + ", ", 8) + "*l" + std::to_string(i - 1) + "]\n";
    }
    c.push_back(fixed("alias_bomb", bomb + "sequence:\n  - move: l0\n    time: 1s\n"));
  }
  c.push_back(fixed("cyclic_alias", kHead + "poses: &p\n  a: *p\nsequence: []\n"));
  c.push_back(lazy("flow_200k_deep", [] {
    return kHead + "sequence: " + repeat("[", 200000) + repeat("]", 200000) + "\n";
  }));
  c.push_back(fixed("block_3k_deep", kHead + "sequence:\n  " + repeat("- ", 3000) + "x\n"));
  {
    std::string maps = kHead + "poses:\n";
    for (int d = 0; d < 1400; ++d)
      maps += std::string(static_cast<std::size_t>(d + 1), ' ') + "a:\n";
    c.push_back(fixed("block_maps_1400_deep", maps));
  }
  c.push_back(lazy("line_30mb", [] { return "name: " + std::string(30u << 20, 'x') + "\n"; }));
  c.push_back(lazy("steps_200k", [] {
    return kHead + "sequence:\n" + repeat("  - {move: home, time: 20ms}\n", 200000);
  }));
  {
    // 35,000 steps of one action each: with no bar lines, 35 chained groups of at most 1,020.
    Case probe = lazy(
        "probe_steps_1mib",
        [] { return kHead + "sequence:\n" + repeat("  - {move: home, time: 20ms}\n", 35000); },
        true);
    probe.exit = 0;
    probe.expect = R"(35000 actions in 35 groups of at most 1020)";
    c.push_back(probe);
  }
  {
    // Six nested repeats around: valid moves (the action budget), relative moves from an
    // unknown position (an error in every pass), and for the car, waits (the 24-hour limit).
    const auto nest = [](const std::string& head, const std::string& body) {
      std::string out = head + "sequence:\n";
      std::string indent = "  ";
      for (int d = 0; d < 6; ++d) {
        out += indent + "- repeat: 65535\n" + indent + "  do:\n";
        indent += "    ";
      }
      std::string b = body;
      for (std::size_t at = 0; (at = b.find('|', at)) != std::string::npos;)
        b.replace(at, 1, indent);
      return out + b;
    };
    c.push_back(fixed("repeat_65535_six_deep",
                      nest(kHead,
                           "|- move: {base: 100}\n|  time: 20ms\n|- move: {base: 200}\n"
                           "|  time: 20ms\n")));
    c.push_back(fixed("repeat_65535_six_deep_errors",
                      nest(kHead,
                           "|- move: {base: +1}\n|  time: 20ms\n|- move: {base: -1}\n"
                           "|  time: 20ms\n")));
    c.push_back(fixed("repeat_65535_six_deep_car",
                      nest("name: hostile\nrobot: raspblock\n", "|- wait: 1ms\n")));
  }
  const std::string digits = "1" + std::string(4999, '7');
  c.push_back(fixed("number_5000_digits_position",
                    kHead + "sequence:\n  - move: {base: " + digits + "}\n    time: 1s\n"));
  c.push_back(fixed("number_5000_digits_time",
                    kHead + "sequence:\n  - move: home\n    time: " + digits + "ms\n"));
  c.push_back(fixed("number_5000_digits_tempo",
                    kHead + "tempo: " + digits + "\nsequence:\n  - move: home\n    time: 1b\n"));
  c.push_back(
      fixed("number_5000_digits_repeat", kHead + "sequence:\n  - repeat: " + digits +
                                             "\n    do:\n      - move: home\n        time: 1s\n"));
  c.push_back(fixed("self_include", kHead + "sequence:\n  - include: self_include.yaml\n"));
  c.push_back(fixed("mutual_include", kHead + "sequence:\n  - include: mutual_b.yaml\n",
                    {{"mutual_b.yaml", "sequence:\n  - include: mutual_include.yaml\n"}}));
  {
    Case chain = fixed("include_chain_20", kHead + "sequence:\n  - include: chain1.yaml\n");
    for (int i = 1; i < 20; ++i) {
      chain.extra.push_back({"chain" + std::to_string(i) + ".yaml",
                             "sequence:\n  - include: chain" + std::to_string(i + 1) + ".yaml\n"});
    }
    chain.extra.push_back({"chain20.yaml", "sequence:\n  - move: home\n    time: 1s\n"});
    c.push_back(chain);
  }
  // Slow tempo: ten bars of eased moves at 1 beat per minute (about 33 minutes of curve).
  // Found by the check fuzzer: half an hour of eased curves (tempo 1) with one mistake at the
  // end. Fitting them took seconds; a file with mistakes is no longer fitted.
  c.push_back(fixed("slow_tempo_curves_and_a_mistake",
                    kHead + "tempo: 1\nsequence:\n  - move: {base: 500}\n    time: 1s\n" +
                        repeat("  - move: {base: +100}\n    time: 1b\n    ease: sine-in-out\n"
                               "  - move: {base: -100}\n    time: 1b\n    ease: sine-in-out\n",
                               15) +
                        "  - move: {bsae: 10}\n    time: 1s\n"));
  return c;
}

// Files that are not files, and outputs aimed at inputs: the cases of the file-system classes.
std::vector<Case> file_cases() {
  std::vector<Case> c;
  const std::string walk = kHead + "sequence:\n  - move: {base: 600}\n    time: 1s\n";
  c.push_back(fixed("include_dev_zero", kHead + "sequence:\n  - include: /dev/zero\n"));
  {
    Case fifo = fixed("include_fifo_no_writer", kHead + "sequence:\n  - include: nobody.fifo\n");
    fifo.setup = [](const std::string& dir) {
      fs::remove(dir + "/nobody.fifo");
      mkfifo((dir + "/nobody.fifo").c_str(), 0600);
      return pid_t{0};
    };
    fifo.expect = "no process opened this FIFO for writing";
    c.push_back(fifo);
  }
  {
    Case fifo = fixed("include_fifo_endless", kHead + "sequence:\n  - include: endless.fifo\n");
    fifo.setup = [](const std::string& dir) {
      fs::remove(dir + "/endless.fifo");
      mkfifo((dir + "/endless.fifo").c_str(), 0600);
      const pid_t writer = fork();
      if (writer == 0) {
        const int fd = ::open((dir + "/endless.fifo").c_str(), O_WRONLY);
        const std::string line(4096, ' ');
        while (::write(fd, line.data(), line.size()) > 0) {
        }
        _exit(0);
      }
      return writer;
    };
    fifo.expect = "file is too large";
    c.push_back(fifo);
  }
  {
    Case in = fixed("stdin_endless", "");
    in.args = {"check", "-"};
    in.stdin_path = "/dev/zero";
    in.exit = 5;
    in.expect = "seqc: error: <stdin>: file is too large";
    c.push_back(in);
  }
  const auto unchanged = [](std::string file, std::string text) {
    return [file = std::move(file), text = std::move(text)](const std::string& dir) {
      return read(dir + "/" + file) == text ? std::string() : file + " was changed";
    };
  };
  {
    Case self = fixed("output_is_the_input", walk);
    self.args = {"compile", "{file}", "-o", "{file}"};
    self.exit = 2;
    self.expect = "seqc: error: .*output_is_the_input.yaml.*";
    self.verify = unchanged("output_is_the_input.yaml", walk);
    c.push_back(self);
  }
  {
    Case link = fixed("output_links_to_the_input", walk);
    link.setup = [](const std::string& dir) {
      fs::remove(dir + "/link_to_input.hex");
      fs::create_symlink(dir + "/output_links_to_the_input.yaml", dir + "/link_to_input.hex");
      return pid_t{0};
    };
    link.args = {"compile", "{file}", "-o", "{dir}/link_to_input.hex"};
    link.exit = 2;
    link.expect = "seqc: error: ";
    link.verify = unchanged("output_links_to_the_input.yaml", walk);
    c.push_back(link);
  }
  {
    const std::string part = "sequence:\n  - move: {base: 700}\n    time: 1s\n";
    Case inc = fixed("output_is_an_include", kHead + "sequence:\n  - include: part.yaml\n",
                     {{"part.yaml", part}});
    inc.args = {"compile", "{file}", "-o", "{dir}/part.yaml"};
    inc.exit = 2;
    inc.expect = "seqc: error: ";
    inc.verify = unchanged("part.yaml", part);
    c.push_back(inc);
  }
  {
    Case null = fixed("output_dev_null", walk);
    null.args = {"compile", "{file}", "-o", "/dev/null"};
    null.exit = 0;
    null.expect = ".*";
    null.verify = [](const std::string&) {
      struct stat st {};
      return ::stat("/dev/null", &st) == 0 && S_ISCHR(st.st_mode)
                 ? std::string()
                 : std::string("/dev/null is no longer a character device");
    };
    c.push_back(null);
  }
  return c;
}

// Fan-out and depth: sections performing sections, wrappers, includes. Each ends with one
// located error at the first budget passed, however much work the file describes.
std::vector<Case> walk_cases() {
  std::vector<Case> c;
  const auto sections = [](int n, const std::function<std::string(int)>& body,
                           const std::string& last, const std::string& sequence) {
    std::string text = kHead + "sections:\n";
    for (int i = 0; i + 1 < n; ++i) text += "  s" + std::to_string(i) + ": " + body(i + 1) + "\n";
    return text + "  s" + std::to_string(n - 1) + ": " + last + "\nsequence:\n" + sequence;
  };
  const std::string move = "[{move: {claw: 600}, time: 20ms}]";
  const auto twice = [](int next) {
    const std::string s = "{section: s" + std::to_string(next) + "}";
    return "[" + s + ", " + s + "]";
  };
  Case fan =
      lazy("section_fanout_40", [=] { return sections(40, twice, move, "  - section: s0\n"); });
  // Every group the board stores is 260,100 actions: the walk's step budget stops it first.
  fan.expect = R"(error: the sequence walks more than 200,000 steps)";
  c.push_back(fan);
  Case quiet = lazy("section_fanout_40_no_actions",
                    [=] { return sections(40, twice, "[]", "  - section: s0\n"); });
  quiet.expect = R"(error: the sequence walks more than 200,000 steps)";
  c.push_back(quiet);
  Case pow = lazy("performances_2pow20", [=] {
    return sections(21, twice, move, "  - move: {claw: 600}\n    time: 1s\n  - section: s0\n");
  });
  pow.expect = R"(error: the sequence walks more than 200,000 steps)";
  c.push_back(pow);
  const std::string deep = R"(error: sections perform sections more than 64 deep)";
  Case chain = lazy("section_chain_14000", [=] {
    return sections(
        14000, [](int next) { return "[{section: s" + std::to_string(next) + "}]"; }, move,
        "  - section: s0\n");
  });
  chain.expect = deep;
  c.push_back(chain);
  Case together = lazy("together_15000_deep", [=] {
    return sections(
        15000,
        [](int next) { return "[{together: {a: [{section: s" + std::to_string(next) + "}]}}]"; },
        move, "  - section: s0\n");
  });
  together.expect = deep;
  c.push_back(together);
  Case repeats = lazy("repeat1_15000_deep", [=] {
    return sections(
        15000,
        [](int next) { return "[{repeat: 1, do: [{section: s" + std::to_string(next) + "}]}]"; },
        move, "  - section: s0\n");
  });
  repeats.expect = deep;
  c.push_back(repeats);
  {
    std::string main = kHead + "sequence:\n";
    for (int k = 0; k < 10; ++k) main += "  - include: inc1.yaml\n";
    Case inc = fixed("include_fanout_15x10", main);
    for (int i = 1; i < 15; ++i) {
      std::string text = "sequence:\n";
      for (int k = 0; k < 10; ++k) text += "  - include: inc" + std::to_string(i + 1) + ".yaml\n";
      inc.extra.push_back({"inc" + std::to_string(i) + ".yaml", text});
    }
    inc.extra.push_back({"inc15.yaml", "sequence: []\n"});
    inc.expect = R"(error: the sequence includes files more than 10,000 times)";
    c.push_back(inc);
  }
  return c;
}

// A PCM WAV file (16-bit) of `seconds` at `rate` Hz with `channels` channels: a click every
// half second (120 bpm) on silence, written here byte by byte (RIFF layout).
std::string click_wav(std::uint32_t rate, std::uint16_t channels, double seconds) {
  const auto frames = static_cast<std::uint32_t>(rate * seconds);
  const std::uint32_t data = frames * channels * 2;
  std::string out;
  const auto u32 = [&](std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out += static_cast<char>((v >> (8 * i)) & 0xff);
  };
  const auto u16 = [&](std::uint16_t v) {
    out += static_cast<char>(v & 0xff);
    out += static_cast<char>(v >> 8);
  };
  out += "RIFF";
  u32(36 + data);
  out += "WAVEfmt ";
  u32(16);
  u16(1);
  u16(channels);
  u32(rate);
  u32(rate * channels * 2);
  u16(static_cast<std::uint16_t>(channels * 2));
  u16(16);
  out += "data";
  u32(data);
  out.reserve(out.size() + data);
  const std::uint32_t click = rate / 100;  // 10 ms of sound every half second
  for (std::uint32_t f = 0; f < frames; ++f) {
    const bool on = f % (rate / 2) < click;
    const auto v = static_cast<std::int16_t>(on ? ((f / 20) % 2 == 0 ? 20000 : -20000) : 0);
    for (std::uint16_t ch = 0; ch < channels; ++ch) u16(static_cast<std::uint16_t>(v));
  }
  return out;
}

// A .d6a file (an SQLite database) made by running `sql` on a new database at `path`.
std::string make_d6a(const std::string& path, const std::string& sql) {
  fs::remove(path);
  sqlite3* db = nullptr;
  if (sqlite3_open(path.c_str(), &db) != SQLITE_OK) return "cannot create " + path;
  char* error = nullptr;
  const int rc = sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &error);
  std::string why = rc == SQLITE_OK ? "" : std::string(error != nullptr ? error : "?");
  sqlite3_free(error);
  sqlite3_close(db);
  return why;
}

// Songs and .d6a files: limited in samples and rows, whatever their header or schema says.
std::vector<Case> song_and_d6a_cases() {
  std::vector<Case> c;
  {
    Case k = lazy("song_655khz_wav", [] { return click_wav(655350, 1, 10); });
    k.ext = ".wav";
    k.args = {"beats", "{file}"};
    k.exit = 0;
    k.expect = R"(tempo: 120\n)";
    c.push_back(k);
  }
  {
    Case k = lazy("song_192khz_8_channels_wav", [] { return click_wav(192000, 8, 10); });
    k.ext = ".wav";
    k.args = {"beats", "{file}"};
    k.exit = 0;
    k.expect = R"(tempo: 120\n)";
    c.push_back(k);
  }
  {
    Case k = fixed("song_dev_zero", "");
    k.args = {"beats", "/dev/zero"};
    k.exit = 5;
    k.expect = R"(seqc: error: .*/dev/zero)";
    c.push_back(k);
  }
  {
    Case k = fixed("song_fifo_endless", "");
    k.setup = [](const std::string& dir) {
      fs::remove(dir + "/song.fifo");
      mkfifo((dir + "/song.fifo").c_str(), 0600);
      const pid_t writer = fork();
      if (writer == 0) {
        const int fd = ::open((dir + "/song.fifo").c_str(), O_WRONLY);
        const std::string zeros(65536, '\0');
        while (::write(fd, zeros.data(), zeros.size()) > 0) {
        }
        _exit(0);
      }
      return writer;
    };
    k.args = {"beats", "{dir}/song.fifo"};
    k.exit = 5;
    k.expect = R"(seqc: error: .*song\.fifo)";
    c.push_back(k);
  }
  {
    // A dance whose song is /dev/zero: the check says so where the file names it.
    Case k = fixed(
        "music_dev_zero",
        kHead +
            "music:\n  file: /dev/zero\n  tempo: 120\n  meter: 4/4\nsequence:\n  - move: home\n"
            "    time: 1b\n");
    k.expect = R"(music_dev_zero\.yaml:[0-9]+:[0-9]+: (error|warning): )";
    k.exit = -1;  // any exit: what matters is the located word and the bounds
    c.push_back(k);
  }
  const auto d6a = [](std::string name, std::string sql, std::string expect) {
    Case k = fixed(name, "");
    k.ext = ".d6a";
    k.setup = [name, sql](const std::string& dir) {
      const std::string why = make_d6a(dir + "/" + name + ".d6a", sql);
      if (!why.empty()) std::fprintf(stderr, "%s: %s\n", name.c_str(), why.c_str());
      return pid_t{0};
    };
    k.args = {"import", "{file}", "-o", "{dir}/" + name + ".yaml"};
    k.expect = std::move(expect);
    return k;
  };
  c.push_back(d6a("d6a_with_view",
                  "CREATE VIEW ActionGroup([Index], Time, Servo1) AS WITH RECURSIVE n(i) AS "
                  "(SELECT 1 UNION ALL SELECT i + 1 FROM n) SELECT i, 100, 500 FROM n;",
                  "holds a view, ActionGroup"));
  c.push_back(d6a("d6a_with_trigger",
                  "CREATE TABLE ActionGroup([Index] INTEGER PRIMARY KEY AUTOINCREMENT, Time INT, "
                  "Servo1 INT); CREATE TRIGGER grow AFTER INSERT ON ActionGroup BEGIN INSERT INTO "
                  "ActionGroup (Time, Servo1) VALUES (1, 1); END;",
                  "holds a trigger, grow"));
  c.push_back(d6a("d6a_million_rows",
                  "CREATE TABLE ActionGroup([Index] INTEGER PRIMARY KEY, Time INT, Servo1 INT); "
                  "WITH RECURSIVE n(i) AS (SELECT 1 UNION ALL SELECT i + 1 FROM n WHERE i < "
                  "1000000) INSERT INTO ActionGroup SELECT i, 100, 500 FROM n;",
                  "more than 65536 rows"));
  return c;
}

// Names with markup and control characters, through every document and the terminal.
std::vector<Case> name_cases() {
  std::vector<Case> c;
  const auto piece = [](const std::string& name, const std::string& target) {
    return "robot: xarm\nname: " + name + "\nposes:\n  " + name + ": {claw: 300}\nsections:\n  " +
           name + ":\n    steps:\n      - move: " + target +
           "\n        time: 500ms\nsequence:\n  - section: " + name + "\n";
  };
  {
    const std::string n = R"("</script><!--<script>alert(1)//")";
    Case k = fixed("name_markup_preview", piece(n, n));
    k.args = {"preview", "{file}", "-o", "{dir}/markup.html"};
    k.exit = 0;
    k.expect = "markup.html: [0-9]+ bytes";
    k.verify = [](const std::string& dir) {
      const std::string page = read(dir + "/markup.html");
      std::size_t scripts = 0;
      for (std::size_t at = page.find("<script"); at != std::string::npos;
           at = page.find("<script", at + 1)) {
        ++scripts;
      }
      if (scripts != 2) return "the page has " + std::to_string(scripts) + " <script";
      return page.find("<!--") == std::string::npos ? std::string()
                                                    : std::string("the page has <!--");
    };
    c.push_back(k);
  }
  {
    const std::string n = R"("c\x01\e[31m\a\v<&>\"end")";
    Case k = fixed("name_control_plot", piece(n, n));
    k.args = {"plot", "{file}", "-o", "{dir}/control.svg"};
    k.exit = 0;
    k.expect = "control.svg: [0-9]+ bytes";
    k.verify = [](const std::string& dir) {
      // XML 1.0 allows no C0 control but tab, LF and CR, nor a raw '<' or '&' in text.
      const std::string svg = read(dir + "/control.svg");
      for (unsigned char ch : svg) {
        if (ch < 0x20 && ch != '\t' && ch != '\n' && ch != '\r') {
          return std::string("the SVG holds control byte ") + std::to_string(ch);
        }
      }
      return svg.find("<&>") == std::string::npos ? std::string()
                                                  : std::string("the SVG holds <&> raw");
    };
    c.push_back(k);
  }
  {
    const std::string n = R"("p\e]0;owned\a\e[2J\nx.yaml:1:1: error: forged\r")";
    std::string target = n;
    target.insert(target.size() - 1, "x");
    Case k =
        fixed("name_escape_terminal", "robot: xarm\nname: " + n + "\nposes:\n  " + n +
                                          ": {claw: 300}\nsequence:\n  - move: " + target +
                                          "\n    time: 1s\n  - move: {nosuch: 1}\n    time: 1s\n");
    k.expect =
        R"(error: unknown pose 'p\\x1b\]0;owned\\x07\\x1b\[2J\\nx\.yaml:1:1: error: forged\\rx')";
    k.verify = [](const std::string& dir) {
      return read(dir + "/name_escape_terminal.out").find('\x1b') == std::string::npos
                 ? std::string()
                 : std::string("an ESC byte reached the terminal");
    };
    c.push_back(k);
  }
  return c;
}

// Long moves: what they cost must follow their actions, not their milliseconds.
std::vector<Case> long_move_cases() {
  std::vector<Case> c;
  const auto valid = [](std::string name, std::string text, std::string expect) {
    Case k = fixed(std::move(name), std::move(text));
    k.exit = 0;
    k.expect = std::move(expect);
    return k;
  };
  c.push_back(valid("long_tip_line_6002s",
                    kHead +
                        "sequence:\n  - move: {tip: {x: 90mm, y: 156mm, z: 120mm}, pitch: 135deg, "
                        "claw: 300}\n    time: 1s\n  - move: {tip: {x: 90mm, y: 156mm, z: 40mm}}\n"
                        "    time: 6002s\n    path: line\n",
                    R"(actions, 6003\.000 s, fit within)"));
  c.push_back(valid("long_elastic_1000s",
                    kHead + "sequence:\n  - move: {base: 300}\n    time: 1s\n  - move: {base: "
                            "600}\n    time: 1000s\n    ease: elastic-out\n",
                    R"(actions, 1001\.000 s)"));
  c.push_back(valid("long_joint_100_minutes",
                    kHead + "sequence:\n  - move: {base: 300, elbow: 400}\n    time: 1s\n"
                            "  - move: {base: 700, elbow: 600}\n    time: 6000s\n"
                            "    ease: sine-in-out\n",
                    R"(actions, 6001\.000 s)"));
  c.push_back(valid("long_car_drive_6000s",
                    "name: hostile\nrobot: raspblock\nsequence:\n  - drive: {x: 15}\n"
                    "    time: 6000s\n  - drive: {x: 15, y: 10}\n    move: {pan: 2000, tilt: "
                    "1500}\n    time: 100s\n    ease: in-out\n",
                    R"(6100 s)"));
  {
    // Twelve 1,000 s curves of three servos at tolerance 0.1: more actions than a group holds,
    // chained into many groups, each long stretch fitted at a cost that follows its actions.
    const char* eases[] = {"elastic-out", "bounce-in-out",  "back-in-out", "sine-in-out",
                           "in-out",      "cubic-in",       "expo-out",    "circ-in-out",
                           "quart-out",   "elastic-in-out", "bounce-out",  "back-out"};
    std::string text = kHead +
                       "tolerance: 0.1\nsequence:\n  - move: {base: 300, shoulder: 350, "
                       "elbow: 400}\n    time: 1s\n";
    for (int i = 0; i < 12; ++i) {
      text += i % 2 == 0 ? "  - move: {base: 600, shoulder: 350, elbow: 600}\n"
                         : "  - move: {base: 300, shoulder: 550, elbow: 400}\n";
      text += std::string("    time: 1000s\n    ease: ") + eases[i] + "\n";
    }
    Case twelve = fixed("twelve_1000s_moves_tolerance_0_1", text);
    twelve.exit = 0;
    twelve.expect = R"(actions in [0-9]+ groups of at most 1020)";
    c.push_back(twelve);
  }
  {
    // The same long line through every view: each bounded in time, memory and output.
    const std::string line = kHead +
                             "sequence:\n  - move: {tip: {x: 90mm, y: 156mm, z: 120mm}, pitch: "
                             "135deg, claw: 300}\n    time: 1s\n  - move: {tip: {x: 90mm, y: "
                             "156mm, z: 40mm}}\n    time: 6002s\n    path: line\n";
    for (const auto& [view, args] :
         {std::pair<std::string, std::vector<std::string>>{
              "simulate_compare", {"simulate", "{file}", "--compare", "-o", "{dir}/view.csv"}},
          {"plot", {"plot", "{file}", "-o", "{dir}/view.svg"}},
          {"preview", {"preview", "{file}", "-o", "{dir}/view.html"}}}) {
      Case k = valid("long_tip_line_" + view, line, ".*");
      k.args = args;
      c.push_back(k);
    }
  }
  return c;
}

struct Run {
  double ms = 0;
  long rss_kib = 0;
  int status = -1;
};

std::string expand(const std::string& arg, const std::string& file, const std::string& dir) {
  std::string out = arg;
  for (const auto& [key, value] : {std::pair<std::string, std::string>{"{file}", file},
                                   std::pair<std::string, std::string>{"{dir}", dir}}) {
    for (std::size_t at = 0; (at = out.find(key, at)) != std::string::npos;) {
      out.replace(at, key.size(), value);
      at += value.size();
    }
  }
  return out;
}

Run run_case(const char* seqc, const Case& c, const std::string& file, const std::string& dir,
             const std::string& out) {
  std::vector<std::string> args{seqc};
  for (const auto& a : c.args) args.push_back(expand(a, file, dir));
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t helper = c.setup ? c.setup(dir) : 0;
  timespec a{}, b{};
  clock_gettime(CLOCK_MONOTONIC, &a);
  const pid_t pid = fork();
  if (pid == 0) {
    const int fd = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, 1);
    dup2(fd, 2);
    const int in = ::open(c.stdin_path.empty() ? "/dev/null" : c.stdin_path.c_str(), O_RDONLY);
    dup2(in, 0);
    execv(seqc, argv.data());
    _exit(127);
  }
  int status = 0;
  rusage ru{};
  wait4(pid, &status, 0, &ru);
  clock_gettime(CLOCK_MONOTONIC, &b);
  if (helper > 0) {
    kill(helper, SIGKILL);
    waitpid(helper, nullptr, 0);
  }
  Run r;
  r.ms = static_cast<double>(b.tv_sec - a.tv_sec) * 1e3 +
         static_cast<double>(b.tv_nsec - a.tv_nsec) / 1e6;
  r.rss_kib = ru.ru_maxrss;
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  int runs = 3;
  std::string dir = "/tmp/seqc-hostile";
  std::string only;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--runs") == 0 && i + 1 < argc) {
      runs = std::max(1, std::atoi(argv[++i]));
    } else if (std::strcmp(argv[i], "--dir") == 0 && i + 1 < argc) {
      dir = argv[++i];
    } else if (std::strcmp(argv[i], "--only") == 0 && i + 1 < argc) {
      only = argv[++i];
    } else {
      std::fprintf(stderr, "usage: hostile_bench [--runs N] [--dir DIR] [--only SUBSTRING]\n");
      return 2;
    }
  }
  std::signal(SIGPIPE, SIG_IGN);
  fs::create_directories(dir);
  dir = fs::canonical(dir).string();
  std::vector<Case> cases;
  for (const auto& e :
       fs::directory_iterator(std::string(SEQC_SOURCE_DIR) + "/tests/compiler/hostile")) {
    if (e.path().extension() == ".yaml") {
      cases.push_back(fixed("file_" + e.path().stem().string(), read(e.path().string())));
    }
  }
  std::sort(cases.begin(), cases.end(),
            [](const Case& x, const Case& y) { return x.name < y.name; });
  for (Case& c : generated()) cases.push_back(std::move(c));
  for (Case& c : walk_cases()) cases.push_back(std::move(c));
  for (Case& c : long_move_cases()) cases.push_back(std::move(c));
  for (Case& c : song_and_d6a_cases()) cases.push_back(std::move(c));
  for (Case& c : name_cases()) cases.push_back(std::move(c));
  for (Case& c : file_cases()) cases.push_back(std::move(c));
  if (!only.empty()) {
    std::erase_if(cases, [&](const Case& c) { return c.name.find(only) == std::string::npos; });
  }

  const std::regex located(R"((^|\n)[^\n:]+\.yaml:[0-9]+:[0-9]+: error: )");
  constexpr double kTargetMs = 1000;
  constexpr long kTargetKib = 64 * 1024;
  double worst_ms = 0;
  long worst_kib = 0;
  std::string worst_ms_name, worst_kib_name;
  int failures = 0, wrong = 0;
  std::vector<std::string> probes;
  std::printf("%-36s %10s %9s %9s  %s\n", "input", "bytes", "ms", "MiB", "what it said");
  for (const Case& c : cases) {
    const std::string file = dir + "/" + c.name + c.ext;
    // Made and written in a child, so this process never holds the big texts (a child forked
    // from it would count them in its peak RSS).
    if (const pid_t maker = fork(); maker == 0) {
      std::ofstream(file, std::ios::binary) << c.text();
      _exit(0);
    } else {
      waitpid(maker, nullptr, 0);
    }
    const auto bytes = static_cast<std::size_t>(fs::file_size(file));
    for (const auto& [name, text] : c.extra)
      std::ofstream(dir + "/" + name, std::ios::binary) << text;
    const std::string out = dir + "/" + c.name + ".out";
    Run best;
    best.ms = 1e18;
    std::string left_wrong;
    for (int r = 0; r < runs; ++r) {
      const Run one = run_case(SEQC_BIN, c, file, dir, out);
      best.ms = std::min(best.ms, one.ms);
      best.rss_kib = std::max(best.rss_kib, one.rss_kib);
      best.status = one.status;
      if (c.verify && left_wrong.empty()) left_wrong = c.verify(dir);
    }
    const std::string text = read(out);
    std::smatch m;
    bool said = false;
    std::string first;
    if (c.expect.empty()) {
      said = std::regex_search(text, m, located);
      first =
          said ? text.substr(static_cast<std::size_t>(m.position(0)) + (m[1].length() > 0 ? 1 : 0))
               : text;
    } else {
      said = std::regex_search(text, m, std::regex(c.expect));
      first = text;
    }
    first = first.substr(0, first.find('\n'));
    if (first.size() > 90) first = first.substr(0, 87) + "...";
    const bool right = (c.exit < 0 || best.status == c.exit) && said && left_wrong.empty();
    const bool ok = right && best.ms <= kTargetMs && best.rss_kib <= kTargetKib;
    std::string verdict;
    if (!right) {
      verdict = "   <-- WRONG (exit " + std::to_string(best.status) + ", wanted " +
                std::to_string(c.exit) + (said ? "" : "; message missing") +
                (left_wrong.empty() ? "" : "; " + left_wrong) + ")";
    } else if (!ok) {
      verdict = "   <-- OVER THE TARGETS";
    }
    std::printf("%-36s %10zu %9.1f %9.1f  %s%s\n", c.name.c_str(), bytes, best.ms,
                static_cast<double>(best.rss_kib) / 1024.0, first.c_str(), verdict.c_str());
    if (c.size_probe) {
      char line[200];
      std::snprintf(line, sizeof line, "%s: %.1f ms, %.1f MiB, %s", c.name.c_str(), best.ms,
                    static_cast<double>(best.rss_kib) / 1024.0,
                    ok ? "within the targets" : "over the targets");
      probes.push_back(line);
      continue;
    }
    if (!right) ++wrong;
    if (!ok) ++failures;
    if (best.ms > worst_ms) {
      worst_ms = best.ms;
      worst_ms_name = c.name;
    }
    if (best.rss_kib > worst_kib) {
      worst_kib = best.rss_kib;
      worst_kib_name = c.name;
    }
  }
  std::printf(
      "\ncatalogue, %zu inputs; worst time %.1f ms (%s), worst peak RSS %.1f MiB (%s); targets "
      "(the documented exit and message, inputs unchanged, <= 1 s, <= 64 MiB): %s\n",
      cases.size() - probes.size(), worst_ms, worst_ms_name.c_str(),
      static_cast<double>(worst_kib) / 1024.0, worst_kib_name.c_str(),
      failures == 0 ? "met by every input" : "NOT met");
  for (const auto& p : probes) {
    std::printf(
        "size probe (a file at the 1 MiB limit, all of it steps; yaml-cpp's parse of the "
        "whole file dominates): %s\n",
        p.c_str());
  }
  std::printf(
      "method: one seqc process per run, best wall of %d runs "
      "(CLOCK_MONOTONIC around fork..wait4, start-up included), peak RSS from wait4\n",
      runs);
  // A wrong answer fails the run wherever it runs; a time over the target is a figure, since
  // the smoke run in ctest shares the machine with other tests.
  return wrong == 0 ? 0 : 1;
}
