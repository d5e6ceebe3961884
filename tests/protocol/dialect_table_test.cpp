// The dialect table (protocol/dialects.hpp) against hand-written bytes: one frame or packet of
// each dialect, copied from docs/protocol/, is sniffed as its own row's and no other's, and a
// trace whose header names a row is decoded in that row's dialect. The names are the text
// traces already carry in "# dialect: NAME", so they are written out here, not read back.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <string_view>

#include "compiler/formats/decode_formats.hpp"
#include "protocol/dialects.hpp"
#include "wire_test_util.hpp"

namespace seqc {
namespace {

using test::hex;

// docs/protocol/servo-controller.md, Framing: MultiServoMove, servo 1 to 2000 in 1000 ms.
constexpr std::string_view kXarmMove = "55 55 08 03 01 e8 03 01 d0 07";
// docs/protocol/lsc-6.md, command 25: group 0, 1 action, index 0, 1 servo, 1000 ms, channel 1
// to 1500 µs (LEN 11 = 9 data bytes + 2).
constexpr std::string_view kLsc6Download = "55 55 0b 19 00 01 00 01 e8 03 01 dc 05";
// docs/protocol/raspblock.md, the worked Rocker example: X = -10, Y = 0, Z = 0.
constexpr std::string_view kRaspblockRocker = "ff fe 03 08 01 00 0a 00 00 00 00 05 1b";

struct Sample {
  const Dialect* dialect;
  std::string_view bytes;
};
const Sample kSamples[] = {
    {&kXarmDialect, kXarmMove},
    {&kLsc6Dialect, kLsc6Download},
    {&kRaspblockDialect, kRaspblockRocker},
};

TEST(DialectTable, HoldsTheThreeDialectsUnderTheNamesTracesCarry) {
  ASSERT_EQ(all_dialects().size(), 3u);
  EXPECT_EQ(all_dialects()[0]->name, "xArm / LSC-16 / LSC-32");
  EXPECT_EQ(all_dialects()[1]->name, "LSC-6");
  EXPECT_EQ(all_dialects()[2]->name, "Raspblock");
  EXPECT_EQ(all_dialects()[0]->decode_name, "hex");
  EXPECT_EQ(all_dialects()[1]->decode_name, "lsc6");
  EXPECT_EQ(all_dialects()[2]->decode_name, "raspblock");
  EXPECT_EQ(all_dialects()[2]->framing, Framing::Packets);
  EXPECT_EQ(all_dialects()[2]->describe_reply, nullptr) << "the Raspblock never answers";
}

TEST(DialectTable, KeysNamesAndDecodeNamesAreUniqueAndFoundAgain) {
  std::set<std::string_view> keys, names, decode_names;
  for (const Dialect* d : all_dialects()) {
    EXPECT_FALSE(d->key.empty());
    EXPECT_TRUE(keys.insert(d->key).second) << d->key;
    EXPECT_TRUE(names.insert(d->name).second) << d->name;
    EXPECT_TRUE(decode_names.insert(d->decode_name).second) << d->decode_name;
    EXPECT_EQ(find_dialect(d->key), d);
    EXPECT_EQ(dialect_named(d->name), d);
    EXPECT_EQ(dialect_decoded_as(d->decode_name), d);
    EXPECT_NE(d->encode, nullptr);
    EXPECT_NE(d->decode, nullptr);
    EXPECT_NE(d->describe_request, nullptr);
    EXPECT_NE(d->sniff, nullptr);
  }
  EXPECT_EQ(find_dialect("LSC-6"), nullptr) << "a name is not a key";
  EXPECT_EQ(dialect_named("lsc6"), nullptr) << "a key is not a name";
  EXPECT_EQ(dialect_named(""), nullptr);
}

TEST(DialectTable, EachSniffAcceptsItsOwnBytesAndRejectsTheOthers) {
  for (const Sample& own : kSamples) {
    for (const Sample& other : kSamples) {
      EXPECT_EQ(own.dialect->sniff(hex(other.bytes)), own.dialect == other.dialect)
          << own.dialect->key << " sniffing " << other.bytes;
    }
    EXPECT_EQ(&sniff_dialect(hex(own.bytes)), own.dialect) << own.bytes;
  }
}

TEST(DialectTable, FramesWithoutAnLsc6DownloadAreTheXarmDialects) {
  // Stop (55 55 02 07) is a frame both servo-controller dialects send: only a download tells
  // the LSC-6 apart, so the first row of the frames is the answer.
  EXPECT_EQ(&sniff_dialect(hex("55 55 02 07")), &kXarmDialect);
  EXPECT_EQ(&sniff_dialect(hex("")), &kXarmDialect);
  EXPECT_EQ(&sniff_dialect(hex("55 55 02 07 55 55 0b 19 00 01 00 01 e8 03 01 dc 05")),
            &kLsc6Dialect);
  EXPECT_EQ(framing_of(hex("ff fe")), Framing::Packets);
  EXPECT_EQ(framing_of(hex("ff")), Framing::Frames);
}

TEST(DialectTable, EachRowDecodesEncodesAndDescribesItsOwnUnit) {
  for (const Sample& s : kSamples) {
    const Dialect& d = *s.dialect;
    auto unit = d.decode(hex(s.bytes));
    ASSERT_TRUE(unit.ok()) << d.key << ": " << unit.error().message;
    auto again = d.encode(*unit);
    ASSERT_TRUE(again.ok()) << d.key;
    EXPECT_EQ(to_hex(*again), test::norm(s.bytes)) << d.key;
    EXPECT_TRUE(d.describe_request(*unit).ok()) << d.key;
  }
  const Unit rocker = kRaspblockDialect.decode(hex(kRaspblockRocker)).value();
  EXPECT_EQ(rocker.command, 0x03);
  EXPECT_EQ(to_hex(rocker.data), test::norm("01 00 0a 00 00 00 00 05"));
  EXPECT_FALSE(kRaspblockDialect.decode(hex("ff fe 03 08 01 00 0a 00 00 00 00 05 1c")).ok())
      << "bad checksum";
  const Unit stop = kLsc6Dialect.decode(hex("55 55 02 07")).value();
  EXPECT_EQ(kLsc6Dialect.describe_request(stop).value(), "Stop");
  EXPECT_EQ(kXarmDialect.describe_request(stop).value(), "GroupStop");
  EXPECT_FALSE(kXarmDialect.describe_request(kLsc6Dialect.decode(hex(kLsc6Download)).value()).ok())
      << "the xArm dialect has no command 25";
}

// The first line of `seqc decode`'s table for a trace with `header` and one frame sent.
std::string decoded_title(std::string_view header, std::string_view sent) {
  std::string trace = "# seqc trace of emu:test; t in seconds, > to the device, < from it\n";
  if (!header.empty()) trace += "# dialect: " + std::string(header) + "\n";
  trace += "t=0.000000 > " + std::string(sent) + "\n";
  const compiler::DecodeResult r = compiler::decode_text(trace, compiler::DecodeFormat::Auto);
  return r.table.substr(0, r.table.find('\n'));
}

TEST(DialectTable, ATracesHeaderPicksTheRowItsFramesAreReadIn) {
  EXPECT_EQ(decoded_title("xArm / LSC-16 / LSC-32", "55 55 02 07"),
            "# trace, xArm / LSC-16 / LSC-32 dialect");
  EXPECT_EQ(decoded_title("LSC-6", "55 55 02 07"), "# trace, LSC-6 dialect");
  EXPECT_EQ(decoded_title("Raspblock", kRaspblockRocker), "# trace, Raspblock packets");
  // Without a header the frames decide: a download is the LSC-6's, anything else the xArm's.
  EXPECT_EQ(decoded_title("", kLsc6Download), "# trace, LSC-6 dialect");
  EXPECT_EQ(decoded_title("", "55 55 02 07"), "# trace, xArm / LSC-16 / LSC-32 dialect");

  const std::string lsc6 = "# dialect: LSC-6\nt=0.000000 > 55 55 02 07\n";
  EXPECT_NE(compiler::decode_text(lsc6, compiler::DecodeFormat::Trace).table.find("> Stop\n"),
            std::string::npos);
  const std::string xarm = "# dialect: xArm / LSC-16 / LSC-32\nt=0.000000 > 55 55 02 07\n";
  EXPECT_NE(compiler::decode_text(xarm, compiler::DecodeFormat::Trace).table.find("> GroupStop\n"),
            std::string::npos);
}

TEST(DialectTable, DecodeFromChoicesAreTheRowsBetweenAutoAndTheFileFormats) {
  const std::vector<std::string> expected{"auto", "hex", "lsc6", "raspblock", "trace", "record"};
  EXPECT_EQ(compiler::decode_format_names(), expected);
  for (const Dialect* d : all_dialects()) {
    auto format = compiler::parse_decode_format(d->decode_name);
    ASSERT_TRUE(format.ok()) << d->decode_name;
    EXPECT_EQ(compiler::dialect_of(*format), d);
  }
  EXPECT_EQ(compiler::parse_decode_format("xml").error().message,
            "unknown format 'xml'; expected auto, hex, lsc6, raspblock, trace or record");
}

TEST(DecodeHex, ALineThatIsNotHexIsAnIssueListedAndCountedBeforeTheSummary) {
  // 55 55 02 0f is GetBatteryVoltage; line 2 is not hex and holds ESC [ 2 J (clear screen).
  const std::string text = "55 55 02 0f\n\x1b[2Jzz\n";
  const compiler::DecodeResult r = compiler::decode_text(text, compiler::DecodeFormat::Hex);
  EXPECT_EQ(r.table,
            "frame  group block index time_ms  servos\n"
            "1      GetBatteryVoltage\n"
            "! input: line 2: not a hex byte: '\\x1b[2Jzz' in '\\x1b[2Jzz'\n"
            "# 1 frame(s), 0 action(s), 0 s total, 1 issue(s)\n");
  EXPECT_EQ(r.issues.size(), 1u);
  // A binary "line" is quoted in part.
  const compiler::DecodeResult bin =
      compiler::decode_text(std::string(500, 'q'), compiler::DecodeFormat::Hex);
  EXPECT_EQ(bin.table,
            "frame  group block index time_ms  servos\n"
            "! input: line 1: not a hex byte: '" +
                std::string(40, 'q') + "...' in '" + std::string(60, 'q') +
                "...'\n"
                "# 0 frame(s), 0 action(s), 0 s total, 1 issue(s)\n");
}

}  // namespace
}  // namespace seqc
