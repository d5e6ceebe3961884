// The compiled goldens checked against what they claim, with no seqc code.
// tests/golden/examples/*.hex and *.listing (`seqc compile --emit hex|listing`): a decoder
// written here from docs/protocol/servo-controller.md (55 55 LEN CMD DATA, LEN = DATA + 2;
// GroupDownload steps 1 open, 2 size, 3 blocks, 4 action `04 G b i 0B tLo tHi {id posLo
// posHi}...`, 5 close) reads every frame; the listing's header, frame and action lines are
// checked against the decoded bytes; and a few actions per file are compared with values worked
// out by hand from the choreography. tests/golden/raspblock/small.hex: every packet read by the
// rules of docs/protocol/raspblock.md and compared with the stream worked out by hand. A golden
// rewritten with a wrong time or position fails here even where the byte-for-byte golden test
// would take the rewrite.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <ostream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace seqc::golden_frames {
namespace {

namespace fs = std::filesystem;

const fs::path kExamples = fs::path(SEQC_SOURCE_DIR) / "tests/golden/examples";

std::vector<std::string> lines_of(const fs::path& p) {
  std::ifstream in(p);
  std::vector<std::string> out;
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

// "55 55 05 ..." to bytes; nullopt on anything but two-digit hex words.
std::optional<std::vector<std::uint8_t>> bytes_of(const std::string& hex) {
  std::istringstream in(hex);
  std::vector<std::uint8_t> out;
  for (std::string word; in >> word;) {
    if (word.size() != 2) return std::nullopt;
    std::size_t used = 0;
    const unsigned long v = std::stoul(word, &used, 16);
    if (used != 2) return std::nullopt;
    out.push_back(static_cast<std::uint8_t>(v));
  }
  return out;
}

struct Target {
  int id;
  int position;
  bool operator==(const Target&) const = default;
};

struct Action {
  int block = 0;
  int index = 0;
  int time_ms = 0;
  std::vector<Target> servos;
  int end_ms = 0;  // the sum of this and every earlier action's time
};

// A whole GroupDownload, decoded and checked step by step (failures name the frame).
struct Download {
  int group = -1;
  std::vector<int> block_counts;  // step 1's n_0, n_1, ...
  std::vector<Action> actions;
};

// Fills `d` (a fatal failure stops at the frame that broke the layout).
void decode_download(const std::vector<std::vector<std::uint8_t>>& frames, Download& d) {
  // The step each frame must be, in order: 1, 2 per block, 3, 4 per action, 5.
  std::size_t next_block = 0;  // the block whose step 2 comes next
  int stage = 1;
  int block = 0, index = 0;
  for (std::size_t f = 0; f < frames.size(); ++f) {
    SCOPED_TRACE("frame " + std::to_string(f + 1));
    const std::vector<std::uint8_t>& b = frames[f];
    ASSERT_GE(b.size(), 6u);
    EXPECT_EQ(b[0], 0x55);
    EXPECT_EQ(b[1], 0x55);
    EXPECT_EQ(static_cast<std::size_t>(b[2]), b.size() - 2) << "LEN counts itself, CMD and DATA";
    ASSERT_EQ(b[3], 0x05) << "GroupDownload";
    const int step = b[4];
    const int group = b[5];
    if (d.group < 0) d.group = group;
    EXPECT_EQ(group, d.group);
    const std::vector<std::uint8_t> p(b.begin() + 6, b.end());  // after step and group
    if (stage == 1) {
      ASSERT_EQ(step, 1);
      ASSERT_GE(p.size(), 1u);
      ASSERT_LE(p.size(), 4u);
      for (std::uint8_t n : p) d.block_counts.push_back(n);
      stage = 2;
    } else if (stage == 2) {
      ASSERT_EQ(step, 2);
      ASSERT_EQ(p.size(), 3u);
      EXPECT_EQ(p[0], next_block);
      EXPECT_EQ(p[1], d.block_counts[next_block]);
      EXPECT_EQ(p[2], 0);
      if (++next_block == d.block_counts.size()) stage = 3;
    } else if (stage == 3) {
      ASSERT_EQ(step, 3);
      // 00, then the number of every used block.
      ASSERT_EQ(p.size(), 1 + d.block_counts.size());
      EXPECT_EQ(p[0], 0);
      for (std::size_t k = 0; k < d.block_counts.size(); ++k) EXPECT_EQ(p[1 + k], k);
      stage = 4;
    } else if (stage == 4 && step == 4) {
      ASSERT_GE(p.size(), 5u);
      EXPECT_EQ((p.size() - 5) % 3, 0u) << "whole servo entries";
      Action a;
      a.block = p[0];
      a.index = p[1];
      EXPECT_EQ(a.block, block);
      EXPECT_EQ(a.index, index) << "indices run 0, 1, 2, ... within a block";
      EXPECT_EQ(p[2], 0x0b) << "marker";
      a.time_ms = p[3] | (p[4] << 8);
      EXPECT_GE(a.time_ms, 20);
      EXPECT_LE(a.time_ms, 30000);
      for (std::size_t s = 5; s + 2 < p.size(); s += 3) {
        a.servos.push_back({p[s], p[s + 1] | (p[s + 2] << 8)});
      }
      a.end_ms = (d.actions.empty() ? 0 : d.actions.back().end_ms) + a.time_ms;
      d.actions.push_back(std::move(a));
      if (++index == d.block_counts[static_cast<std::size_t>(block)]) {
        ++block;
        index = 0;
      }
    } else {
      ASSERT_EQ(step, 5) << "only step 5 closes";
      EXPECT_TRUE(p.empty());
      EXPECT_EQ(f + 1, frames.size()) << "step 5 is the last frame";
      EXPECT_EQ(static_cast<std::size_t>(block), d.block_counts.size()) << "every block sent";
      stage = 5;
    }
  }
  EXPECT_EQ(stage, 5) << "the download ends with step 5";
}

// "# robot xarm, group 0: 27 actions in 1 block, 31 frames, 8 s".
struct Header {
  std::string robot;
  int group = -1, actions = -1, blocks = -1, frames = -1;
  int length_ms = -1;  // the seconds, read as a decimal with up to three places
};

std::optional<Header> header_of(const std::string& line) {
  Header h;
  char robot[32] = {};
  char seconds[32] = {};
  std::string text = line;  // "1 block" or "2 blocks": read both alike
  if (const std::size_t at = text.find(" blocks,"); at != std::string::npos) {
    text.erase(at + 6, 1);
  }
  if (std::sscanf(text.c_str(),
                  "# robot %31[^,], group %d: %d actions in %d block, %d frames, %31s s", robot,
                  &h.group, &h.actions, &h.blocks, &h.frames, seconds) != 6) {
    return std::nullopt;
  }
  h.robot = robot;
  const std::string s = seconds;
  const std::size_t dot = s.find('.');
  const std::string whole = s.substr(0, dot);
  std::string frac = dot == std::string::npos ? "" : s.substr(dot + 1);
  if (frac.size() > 3) return std::nullopt;
  frac.resize(3, '0');
  h.length_ms = std::stoi(whole) * 1000 + std::stoi(frac);
  return h;
}

// What one golden pair must satisfy: its robot and the limits of every servo it may name,
// written by hand from the profile table of docs/language.md and the file's own `servos:`.
struct Golden {
  const char* name;
  const char* robot;
  std::map<int, std::pair<int, int>> limits;  // id -> min, max
};

std::map<int, std::pair<int, int>> xarm(int claw_min = 0, int claw_max = 1000) {
  // xArm bus ids 1-6 (claw, wrist_roll, wrist_pitch, elbow, shoulder, base), 0..1000.
  return {{1, {claw_min, claw_max}},
          {2, {0, 1000}},
          {3, {0, 1000}},
          {4, {0, 1000}},
          {5, {0, 1000}},
          {6, {0, 1000}}};
}

std::vector<Golden> goldens() {
  return {
      // examples/dance.yaml: claw {min: 150, max: 700}.
      {"dance", "xarm", xarm(150, 700)},
      // tests/data/walk-joints.yaml (the walk golden's source): the profile's limits.
      {"walk", "xarm", xarm()},
      {"waltz", "xarm", xarm()},
      // examples/wave.yaml on the LSC-16 (500-2500 us): shoulders 600..2400, elbows 700..2300,
      // wrists the profile's, head 1000..2000.
      {"wave",
       "lsc-16",
       {{0, {600, 2400}},
        {1, {700, 2300}},
        {2, {500, 2500}},
        {3, {600, 2400}},
        {4, {700, 2300}},
        {5, {500, 2500}},
        {6, {1000, 2000}}}},
  };
}

// Everything a golden pair says about itself, read back.
struct Read {
  Header header;
  Download download;
};

void read_into(const Golden& g, Read& r) {
  const std::vector<std::string> hex = lines_of(kExamples / (std::string(g.name) + ".hex"));
  const std::vector<std::string> listing = lines_of(kExamples / (std::string(g.name) + ".listing"));
  EXPECT_FALSE(hex.empty());
  EXPECT_FALSE(listing.empty());
  if (hex.empty() || listing.empty()) return;
  std::vector<std::vector<std::uint8_t>> frames;
  for (const std::string& line : hex) {
    auto b = bytes_of(line);
    EXPECT_TRUE(b.has_value()) << line;
    if (b) frames.push_back(*b);
  }
  decode_download(frames, r.download);
  if (::testing::Test::HasFatalFailure()) return;
  const auto header = header_of(listing[0]);
  EXPECT_TRUE(header.has_value()) << listing[0];
  if (header) r.header = *header;

  // The listing's frame lines are the hex file's, in order; its `time` and `servos` fields and
  // each `action K at T ms` line agree with the decoded action.
  std::size_t frame = 0, action = 0;
  for (std::size_t i = 1; i < listing.size(); ++i) {
    const std::string& line = listing[i];
    const std::string frame_tag = "frame " + std::to_string(frame + 1) + ": ";
    if (line.rfind("frame ", 0) == 0) {
      EXPECT_EQ(line.rfind(frame_tag, 0), 0u) << line;
      EXPECT_LT(frame, hex.size());
      if (frame < hex.size()) {
        EXPECT_EQ(line.substr(frame_tag.size()), hex[frame]);
      }
      ++frame;
    } else if (line.rfind("  action ", 0) == 0) {
      int k = 0, at = 0;
      ASSERT_EQ(std::sscanf(line.c_str(), "  action %d at %d ms", &k, &at), 2) << line;
      EXPECT_EQ(k, static_cast<int>(action + 1)) << line;
      EXPECT_LT(action, r.download.actions.size());
      if (action < r.download.actions.size()) {
        const Action& a = r.download.actions[action];
        EXPECT_EQ(at, a.end_ms - a.time_ms) << line;
        // The header line just before names the time and the count.
        const std::string& fields = listing[i - 1];
        EXPECT_NE(fields.find("| time " + std::to_string(a.time_ms) + " ms |"), std::string::npos)
            << fields;
        EXPECT_NE(fields.find("| servos " + std::to_string(a.servos.size())), std::string::npos)
            << fields;
        // Each `name(id)=position` in the order of the frame.
        std::size_t from = 0;
        for (const Target& t : a.servos) {
          const std::string want = "(" + std::to_string(t.id) + ")=" + std::to_string(t.position);
          const std::size_t at_pos = line.find(want, from);
          EXPECT_NE(at_pos, std::string::npos) << want << " in " << line;
          if (at_pos != std::string::npos) from = at_pos + want.size();
        }
      }
      ++action;
    }
  }
  EXPECT_EQ(frame, hex.size());
  EXPECT_EQ(action, r.download.actions.size());
}

Read read_golden(const Golden& g) {
  Read r;
  read_into(g, r);
  return r;
}

class CompiledGolden : public ::testing::TestWithParam<Golden> {};

TEST_P(CompiledGolden, EveryFrameDecodesAndAgreesWithTheListing) {
  const Golden& g = GetParam();
  const Read r = read_golden(g);
  const Header& h = r.header;
  const Download& d = r.download;
  EXPECT_EQ(h.robot, g.robot);
  EXPECT_EQ(h.group, d.group);
  EXPECT_EQ(h.actions, static_cast<int>(d.actions.size()));
  EXPECT_EQ(h.blocks, static_cast<int>(d.block_counts.size()));
  // Step 1, a step 2 per block, step 3, the actions, step 5.
  EXPECT_EQ(h.frames, 1 + h.blocks + 1 + h.actions + 1);
  int counted = 0;
  for (int n : d.block_counts) counted += n;
  EXPECT_EQ(counted, static_cast<int>(d.actions.size()));
  // The actions' times add up to the length the header states.
  ASSERT_FALSE(d.actions.empty());
  EXPECT_EQ(d.actions.back().end_ms, h.length_ms);
  for (std::size_t k = 0; k < d.actions.size(); ++k) {
    SCOPED_TRACE("action " + std::to_string(k + 1));
    int last_id = -1;
    for (const Target& t : d.actions[k].servos) {
      EXPECT_GT(t.id, last_id) << "ascending ids, each once";
      last_id = t.id;
      const auto limit = g.limits.find(t.id);
      ASSERT_NE(limit, g.limits.end()) << "servo " << t.id << " is not the robot's";
      EXPECT_GE(t.position, limit->second.first) << "servo " << t.id;
      EXPECT_LE(t.position, limit->second.second) << "servo " << t.id;
    }
  }
}

void PrintTo(const Golden& g, std::ostream* os) { *os << g.name; }

INSTANTIATE_TEST_SUITE_P(Examples, CompiledGolden, ::testing::ValuesIn(goldens()),
                         [](const auto& param_info) { return std::string(param_info.param.name); });

// ---- values worked out by hand from each choreography ------------------------------------------

const Golden& golden(const std::string& name) {
  static const std::vector<Golden> all = goldens();
  for (const Golden& g : all) {
    if (name == g.name) return g;
  }
  ADD_FAILURE() << name;
  return all.front();
}

// The action ending at `end_ms` (a failure when no action boundary falls there).
const Action* ending_at(const Download& d, int end_ms) {
  for (const Action& a : d.actions) {
    if (a.end_ms == end_ms) return &a;
  }
  ADD_FAILURE() << "no action ends at " << end_ms << " ms";
  return nullptr;
}

std::vector<Target> all_six(int position) {
  return {{1, position}, {2, position}, {3, position}, {4, position}, {5, position}, {6, position}};
}

TEST(CompiledGoldenByHand, Walk) {
  // tests/data/walk-joints.yaml: home (every servo 500) in 1 s; `ready` in 800 ms; base to
  // 60deg = 60 x 1000/240 = 250 in 600 ms; `reach` with ease in-out (quad: 2t^2, then
  // 1 - 2(1 - t)^2) in 4 steps of 700/4 = 175 ms: at t = 1/4, 1/2, 3/4, 1 the ease is 0.125,
  // 0.5, 0.875, 1, so wrist_pitch 300 -> 250 reads 293.75, 275, 256.25, 250 (294, 275, 256,
  // 250), elbow 650 -> 750: 662.5, 700, 737.5, 750 (663, 700, 738, 750), shoulder 400 -> 300:
  // 387.5, 350, 312.5, 300 (388, 350, 313, 300); claw to 650 in 300 ms; the wait (200 ms)
  // re-sends all six; `lift` in 500 ms. Then base to 180deg = 750 over 1.2 s (fitted), ending
  // at 1000 + 800 + 600 + 700 + 300 + 200 + 500 + 1200 = 5300; reach (600 ms, 5900); the claw
  // -350 from 650 = 300 (6200); ready (800 ms, 7000); home (1 s, 8000).
  const Read r = read_golden(golden("walk"));
  const std::vector<Action>& a = r.download.actions;
  ASSERT_EQ(a.size(), 27u);
  const std::vector<std::pair<int, std::vector<Target>>> first = {
      {1000, all_six(500)},
      {800, {{1, 300}, {2, 500}, {3, 300}, {4, 650}, {5, 400}, {6, 500}}},
      {600, {{6, 250}}},
      {175, {{3, 294}, {4, 663}, {5, 388}}},
      {175, {{3, 275}, {4, 700}, {5, 350}}},
      {175, {{3, 256}, {4, 738}, {5, 313}}},
      {175, {{3, 250}, {4, 750}, {5, 300}}},
      {300, {{1, 650}}},
      {200, {{1, 650}, {2, 500}, {3, 250}, {4, 750}, {5, 300}, {6, 250}}},
      {500, {{4, 600}, {5, 450}}},
  };
  for (std::size_t k = 0; k < first.size(); ++k) {
    SCOPED_TRACE("action " + std::to_string(k + 1));
    EXPECT_EQ(a[k].time_ms, first[k].first);
    EXPECT_EQ(a[k].servos, first[k].second);
  }
  if (const Action* swing = ending_at(r.download, 5300)) {
    EXPECT_EQ(swing->servos, (std::vector<Target>{{6, 750}}));
  }
  if (const Action* let_go = ending_at(r.download, 6200)) {
    EXPECT_EQ(let_go->servos, (std::vector<Target>{{1, 300}}));
  }
  EXPECT_EQ(a.back().time_ms, 1000);
  EXPECT_EQ(a.back().servos, all_six(500));
  EXPECT_EQ(a.back().end_ms, 8000);
}

TEST(CompiledGoldenByHand, Dance) {
  // examples/dance.yaml at 96 bpm: a beat is 625 ms. `stand` (five servos, the claw not named)
  // over 2 beats: 1250 ms. The dance is 34 beats, 21,250 ms; it ends with the claw to 650, 200,
  // 650, 200, half a beat (312.5 ms) each from 20,000 ms: boundaries 20312.5, 20625, 20937.5
  // and 21250 rounded once (halves away from zero): 20313, 20625, 20938, 21250, so the actions
  // last 313, 312, 313 and 312 ms.
  const Read r = read_golden(golden("dance"));
  const std::vector<Action>& a = r.download.actions;
  ASSERT_GE(a.size(), 5u);
  EXPECT_EQ(a[0].time_ms, 1250);
  EXPECT_EQ(a[0].servos, (std::vector<Target>{{2, 500}, {3, 500}, {4, 500}, {5, 500}, {6, 500}}));
  const std::size_t n = a.size();
  EXPECT_EQ(a[n - 5].end_ms, 20000);
  const int times[4] = {313, 312, 313, 312};
  const int claw[4] = {650, 200, 650, 200};
  for (std::size_t k = 0; k < 4; ++k) {
    SCOPED_TRACE(k);
    EXPECT_EQ(a[n - 4 + k].time_ms, times[k]);
    EXPECT_EQ(a[n - 4 + k].servos, (std::vector<Target>{{1, claw[k]}}));
  }
  EXPECT_EQ(a.back().end_ms, 21250);
}

TEST(CompiledGoldenByHand, Waltz) {
  // examples/waltz.yaml at 84 bpm in 3/4: a bar is 3 x 60000/84 = 15000/7 ms. home over bar 1
  // ends at 2142.857 -> 2143 (all six at 500). The move at 7bar (base 600, elbow 600) ends at
  // bar 9's line, 8 x 15000/7 = 17142.857 -> 17143. Then tempo 72: home over a bar of 3 x
  // 60000/72 = 2500 ms, ending at 17142.857 + 2500 = 19642.857 -> 19643, every servo at 500.
  const Read r = read_golden(golden("waltz"));
  const std::vector<Action>& a = r.download.actions;
  ASSERT_FALSE(a.empty());
  EXPECT_EQ(a[0].time_ms, 2143);
  EXPECT_EQ(a[0].servos, all_six(500));
  if (const Action* bar8 = ending_at(r.download, 17143)) {
    EXPECT_EQ(bar8->servos, (std::vector<Target>{{4, 600}, {6, 600}}));
  }
  EXPECT_EQ(a.back().end_ms, 19643);
  EXPECT_EQ(a.back().servos, all_six(500));
}

TEST(CompiledGoldenByHand, Wave) {
  // examples/wave.yaml on the LSC-16 (home 1500): home over 1 s names all seven channels;
  // arm_up (eased, 600 ms) ends at 1600 with left_shoulder 2200, left_elbow 1100, head 1700;
  // the wrist +400 (1900) and back (1500), 250 ms each, three times: boundaries 1850, 2100, ...
  // 3100; arm_down (500 ms) to 3600. Mirrored, positions reflect around home 1500:
  // right_shoulder 1500 - 700 = 800, right_elbow 1500 + 400 = 1900, head 1500 - 200 = 1300 at
  // 3600 + 600 = 4200, and the right wrist moves the other way, -400 to 1100 at 4450. The wait
  // (1 s) re-sends all seven: 7200 ms in all.
  const Read r = read_golden(golden("wave"));
  const std::vector<Action>& a = r.download.actions;
  ASSERT_FALSE(a.empty());
  const std::vector<Target> home = {{0, 1500}, {1, 1500}, {2, 1500}, {3, 1500},
                                    {4, 1500}, {5, 1500}, {6, 1500}};
  EXPECT_EQ(a[0].time_ms, 1000);
  EXPECT_EQ(a[0].servos, home);
  if (const Action* up = ending_at(r.download, 1600)) {
    EXPECT_EQ(up->servos, (std::vector<Target>{{0, 2200}, {1, 1100}, {6, 1700}}));
  }
  for (int k = 0; k < 3; ++k) {
    SCOPED_TRACE(k);
    const Action* out = ending_at(r.download, 1850 + 500 * k);
    const Action* back = ending_at(r.download, 2100 + 500 * k);
    ASSERT_NE(out, nullptr);
    ASSERT_NE(back, nullptr);
    EXPECT_EQ(out->time_ms, 250);
    EXPECT_EQ(out->servos, (std::vector<Target>{{2, 1900}}));
    EXPECT_EQ(back->servos, (std::vector<Target>{{2, 1500}}));
  }
  if (const Action* right_up = ending_at(r.download, 4200)) {
    EXPECT_EQ(right_up->servos, (std::vector<Target>{{3, 800}, {4, 1900}, {6, 1300}}));
  }
  if (const Action* right_wave = ending_at(r.download, 4450)) {
    EXPECT_EQ(right_wave->servos, (std::vector<Target>{{5, 1100}}));
  }
  EXPECT_EQ(a.back().time_ms, 1000);
  EXPECT_EQ(a.back().servos, home);
  EXPECT_EQ(a.back().end_ms, 7200);
}

// ---- tests/golden/raspblock/small.hex: the car's stream ------------------------------------

// One "   T ms  ff fe ..." line: its send time and packet. From docs/protocol/raspblock.md:
// FF FE FUNC LEN DATA CHK, LEN = DATA bytes, CHK = (FUNC + LEN + sum(DATA)) & 0xFF, 16-bit
// values big-endian.
struct CarPacket {
  int at_ms = -1;
  int func = -1;
  std::vector<int> data;
  bool operator==(const CarPacket&) const = default;
};

void read_car_line(const std::string& line, CarPacket& out) {
  int at = -1;
  char rest[256] = {};
  ASSERT_EQ(std::sscanf(line.c_str(), " %d ms %255[^\n]", &at, rest), 2) << line;
  const auto b = bytes_of(rest);
  ASSERT_TRUE(b.has_value()) << line;
  ASSERT_GE(b->size(), 5u) << line;
  EXPECT_EQ((*b)[0], 0xff);
  EXPECT_EQ((*b)[1], 0xfe);
  const std::size_t len = (*b)[3];
  ASSERT_EQ(b->size(), 4 + len + 1) << "LEN counts the data only: " << line;
  unsigned sum = (*b)[2] + (*b)[3];
  for (std::size_t k = 0; k < len; ++k) sum += (*b)[4 + k];
  EXPECT_EQ(sum & 0xffu, b->back()) << "checksum of " << line;
  out.at_ms = at;
  out.func = (*b)[2];
  out.data.assign(b->begin() + 4, b->end() - 1);
}

TEST(CompiledGoldenByHand, RaspblockSmall) {
  // tests/golden/raspblock/small.yaml (resolution 100ms):
  //   0     the PID settings: mode 1 (position), then 10, 11, ... 17;
  //   0     the gimbal with no position yet goes straight to pan 1500 (05 dc), tilt 1000 (03 e8);
  //   100   pan to 1700 over 200 ms = 2 steps: 1600 (06 40) at 100, 1700 (06 a4) at 200;
  //   300   drive y 20, z -150 for 1 s: magnitudes 0, 20, 150, direction 0 (Y >= 0, Z < 0);
  //   1300  drive x 5, z 30: 5, 0, 30, direction 01 (Z >= 0), replacing the speeds;
  //   2300  the drive ends (all zero, direction 01) and servo3 with no position goes straight
  //         to 2000 (07 d0); 2400 the stream's closing stop.
  const std::vector<std::string> lines =
      lines_of(fs::path(SEQC_SOURCE_DIR) / "tests/golden/raspblock/small.hex");
  std::vector<CarPacket> got;
  for (const std::string& line : lines) {
    CarPacket p;
    read_car_line(line, p);
    if (HasFatalFailure()) return;
    got.push_back(p);
  }
  const std::vector<int> stop = {1, 0, 0, 0, 0, 0, 0, 1};
  const std::vector<CarPacket> want = {
      {0, 0x01, {1, 10, 11, 12, 13, 14, 15, 16, 17}},
      {0, 0x02, {0x05, 0xdc, 0x03, 0xe8}},
      {100, 0x02, {0x06, 0x40, 0x03, 0xe8}},
      {200, 0x02, {0x06, 0xa4, 0x03, 0xe8}},
      {300, 0x03, {1, 0, 0, 0, 20, 0, 150, 0}},
      {1300, 0x03, {1, 0, 5, 0, 0, 0, 30, 1}},
      {2300, 0x03, stop},
      {2300, 0x02, {3, 0x07, 0xd0}},
      {2400, 0x03, stop},
  };
  EXPECT_EQ(got, want);
}

}  // namespace
}  // namespace seqc::golden_frames
