// `seqc emulate --help` and the emulators' option parsers read one table each (emu::fault_keys,
// emu::lsc6_option_keys): every key of a table parses with a value of its kind, a key outside it
// is refused, and the help names every fault key (split and frame-gap among them), so the help
// and the parsers cannot drift apart.
#include <gtest/gtest.h>

#include <string>

#include "runtime/emulator/emulator_serve.hpp"
#include "runtime/emulator/lsc6_emulator.hpp"
#include "runtime/emulator/xarm_config.hpp"

namespace seqc::emu {
namespace {

// A value of each kind, by hand: a rate, a time, a frame count, a seed.
std::string sample(FaultValue value) {
  switch (value) {
    case FaultValue::Rate:
      return "0.25";
    case FaultValue::Duration:
      return "20ms";
    case FaultValue::Count:
      return "3";
    case FaultValue::Seed:
      return "7";
    case FaultValue::ClockError:
      return "+0.8%";
  }
  return "";
}

TEST(FaultKeys, EveryXarmKeyParsesAndIsInTheHelp) {
  const std::string help = faults_help();
  ASSERT_FALSE(fault_keys().empty());
  for (const FaultKey& k : fault_keys()) {
    SCOPED_TRACE(std::string(k.key));
    const std::string item = std::string(k.key) + "=" + sample(k.value);
    auto parsed = parse_faults(item);
    ASSERT_TRUE(parsed) << parsed.error().message;
    EXPECT_NE(help.find("\n  " + std::string(k.key) + "="), std::string::npos) << help;
  }
  // The two the help used to leave out, by name.
  EXPECT_NE(help.find("\n  split=P: "), std::string::npos) << help;
  EXPECT_NE(help.find("\n  frame-gap=TIME: "), std::string::npos) << help;
  // split=0.25 and frame-gap=20ms land in their fields.
  auto f = parse_faults("split=0.25,frame-gap=20ms");
  ASSERT_TRUE(f);
  EXPECT_EQ(f->split, 0.25);
  EXPECT_EQ(f->frame_gap, std::chrono::milliseconds(20));
  EXPECT_FALSE(parse_faults("splits=0.25"));
}

TEST(FaultKeys, EveryLsc6KeyParsesAndEveryFaultIsInTheHelp) {
  const std::string help = faults_help();
  for (const Lsc6OptionKey& k : lsc6_option_keys()) {
    SCOPED_TRACE(std::string(k.key));
    const std::string item = std::string(k.key) + (k.value == "P"     ? "=0.5"
                                                   : k.value == "N"   ? "=9600"
                                                   : k.value == "ERR" ? "=-1%"
                                                                      : "");
    Lsc6Config config;
    auto ok = apply_lsc6_options(item, config);
    EXPECT_TRUE(ok) << ok.error().message;
    EXPECT_EQ(help.find("\n  " + std::string(k.key)) != std::string::npos, k.fault) << help;
  }
  Lsc6Config config;
  EXPECT_FALSE(apply_lsc6_options("no-finnish", config));
}

}  // namespace
}  // namespace seqc::emu
