// Loading a file of either kind (compiler/load.hpp): the file given is read once whichever it
// turns out to be, one over the loader's size limit is refused unread, and a stored group
// carries the capacity its lowering kept it within; a compile names every file it read.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "compiler/frontend/profiles.hpp"
#include "compiler/load.hpp"

namespace seqc::compiler {
namespace {

// In-memory files that count how often each is read.
class CountingFiles final : public FileReader {
 public:
  std::map<std::string, std::string> files;
  std::map<std::string, int> reads;
  std::map<std::string, std::uint64_t> sizes;  // what size() says, where it says anything
  Result<std::string> read(const std::string& path) override {
    ++reads[path];
    auto it = files.find(path);
    if (it == files.end()) return make_error(path + ": No such file or directory");
    return it->second;
  }
  std::optional<std::uint64_t> size(const std::string& path) override {
    auto it = sizes.find(path);
    if (it == sizes.end()) return std::nullopt;
    return it->second;
  }
};

constexpr const char* kArm = R"(name: arm
robot:
  profile: xarm
sequence:
  - move: {claw: 200}
    time: 500ms
)";

TEST(Load, AChoreographyIsReadOnceAndCompiled) {
  CountingFiles files;
  files.files["arm.yaml"] = kArm;
  const Loaded loaded = load("arm.yaml", files);
  ASSERT_FALSE(loaded.is_show());
  ASSERT_NE(loaded.program().servo_program(), nullptr);
  EXPECT_EQ(files.reads["arm.yaml"], 1);
  EXPECT_FALSE(loaded.read_error());
  EXPECT_EQ(loaded.sources().path(0), "arm.yaml");
  EXPECT_EQ(loaded.program().servo_program()->group_capacity,
            group_capacity(find_profile("xarm")));
}

TEST(Load, AShowIsReadOnceAndItsPerformersCompiled) {
  CountingFiles files;
  files.files["dances/duet.yaml"] =
      "show: duet\nperformers:\n  arm: {file: arm.yaml, port: emu:xarm, group: 3}\n";
  files.files["dances/arm.yaml"] = kArm;
  const Loaded loaded = load("dances/duet.yaml", files);
  ASSERT_TRUE(loaded.is_show());
  EXPECT_EQ(files.reads["dances/duet.yaml"], 1);
  EXPECT_EQ(files.reads["dances/arm.yaml"], 1);
  const ShowOutput& show = loaded.show();
  EXPECT_TRUE(show.ok());
  EXPECT_EQ(show.name, "duet");
  ASSERT_EQ(show.performers.size(), 1u);
  EXPECT_EQ(show.performers[0].group, 3);
  EXPECT_EQ(&loaded.diagnostics(), &show.diagnostics);
}

TEST(Load, AShowsPerformersGetTheirOwnOptions) {
  CountingFiles files;
  files.files["duet.yaml"] = "show: duet\nperformers:\n  arm: {file: arm.yaml}\n";
  // 300 units in 500 ms is over the shoulder's 375/s: a warning.
  files.files["arm.yaml"] = R"(robot:
  profile: xarm
  servos:
    shoulder: {max_speed: 90deg/s}
sequence:
  - move: home
    time: 1s
  - move: {shoulder: 800}
    time: 500ms
)";
  LoadOptions options;
  options.performers.strict = true;
  const Loaded strict = load("duet.yaml", files, options);
  ASSERT_TRUE(strict.is_show());
  EXPECT_FALSE(strict.show().ok(true));
  options.performers.strict = false;
  options.program.strict = true;
  const Loaded lenient = load("duet.yaml", files, options);
  EXPECT_TRUE(lenient.show().ok());
  const Loaded alone = load("arm.yaml", files, options);
  ASSERT_FALSE(alone.is_show());
  EXPECT_FALSE(alone.program().program);
}

TEST(Load, AFileOverTheLimitIsRefusedUnread) {
  CountingFiles files;
  files.files["huge.yaml"] = "show: never read\n";
  files.sizes["huge.yaml"] = 30u << 20;
  const Loaded loaded = load("huge.yaml", files);
  ASSERT_FALSE(loaded.is_show());
  EXPECT_EQ(files.reads["huge.yaml"], 0);
  EXPECT_TRUE(loaded.diagnostics().has_errors());
  EXPECT_FALSE(loaded.program().program);
}

TEST(Load, AnUnreadableFileSaysWhy) {
  CountingFiles files;
  const Loaded loaded = load("missing.yaml", files);
  ASSERT_FALSE(loaded.is_show());
  ASSERT_TRUE(loaded.read_error());
  EXPECT_EQ(*loaded.read_error(), "missing.yaml: No such file or directory");
  EXPECT_EQ(files.reads["missing.yaml"], 1);
}

TEST(Load, InputsAreEveryFileReadInOrder) {
  CountingFiles files;
  files.files["dances/duet.yaml"] =
      "show: duet\nperformers:\n  arm: {file: arm.yaml}\n  other: {file: two.yaml}\n";
  files.files["dances/arm.yaml"] = kArm;
  files.files["dances/two.yaml"] =
      "robot:\n  profile: xarm\nsequence:\n  - include: parts/bit.yaml\n";
  files.files["dances/parts/bit.yaml"] = "sequence:\n  - move: {claw: 300}\n    time: 1s\n";
  const Loaded show = load("dances/duet.yaml", files);
  ASSERT_TRUE(show.is_show());
  EXPECT_EQ(show.inputs(), (std::vector<std::string>{"dances/duet.yaml", "dances/arm.yaml",
                                                     "dances/two.yaml", "dances/parts/bit.yaml"}));
  const Loaded two = load("dances/two.yaml", files);
  ASSERT_FALSE(two.is_show());
  EXPECT_EQ(two.inputs(), (std::vector<std::string>{"dances/two.yaml", "dances/parts/bit.yaml"}));
  EXPECT_EQ(load("missing.yaml", files).inputs(), std::vector<std::string>{});
}

TEST(Load, AReadOnceReaderServesItsTextAndPassesTheRestOn) {
  CountingFiles files;
  files.files["<stdin>"] = "never read";
  files.files["parts/bit.yaml"] = "sequence: []\n";
  files.sizes["<stdin>"] = 30u << 20;
  files.sizes["parts/bit.yaml"] = 14;
  ReadOnceReader once("<stdin>", "given text", files);
  EXPECT_EQ(*once.read("<stdin>"), "given text");
  EXPECT_EQ(*once.read("parts/bit.yaml"), "sequence: []\n");
  EXPECT_EQ(files.reads["<stdin>"], 0);
  EXPECT_EQ(once.size("<stdin>"), std::nullopt);  // its text is in hand: the loader checks it
  EXPECT_EQ(once.size("parts/bit.yaml"), 14u);
}

}  // namespace
}  // namespace seqc::compiler
