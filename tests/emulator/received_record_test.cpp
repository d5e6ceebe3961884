// The --record CSV (received_record.hpp): every frame an emulator dropped on purpose is marked
// `dropped:<reason>`, and `seqc decode` of the record reports each such line, and each piece
// that was never a frame, as an issue. The expected lines are written by hand.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "compiler/formats/decode_formats.hpp"
#include "runtime/emulator/raspblock_emulator.hpp"
#include "runtime/emulator/received_record.hpp"
#include "tests/emulator/emu_test_util.hpp"

namespace seqc::emu::test {
namespace {

constexpr const char* kHeader = "time_s,status,bytes,message\n";

TEST(ReceivedRecord, XArmMarksABusyDropAndUnframedBytes) {
  XArmConfig config;
  config.command_time = 5ms;  // a frame keeps the controller busy for 5 ms
  XArmEmulator emu(config);
  emu.receive(hex("55 55 02 0f"), at_ms(0));
  emu.receive(hex("55 55 02 0f"), at_ms(1));
  emu.receive(hex("55 55 01"), at_ms(10));
  emu.receive(hex("aa"), at_ms(20));
  emu.receive(hex("55 55 02 07"), at_ms(30));
  const std::string csv = xarm_record_csv(emu);
  EXPECT_EQ(csv, std::string(kHeader) +
                     "0.000000,ok,55 55 02 0f,GetBatteryVoltage\n"
                     "0.001000,dropped:busy,55 55 02 0f,GetBatteryVoltage\n"
                     "0.010000,unframed,55 55 01,\n"
                     "0.020000,unframed,aa,\n"
                     "0.030000,ok,55 55 02 07,GroupStop\n");

  const compiler::DecodeResult d = compiler::decode_text(csv, compiler::DecodeFormat::Auto);
  EXPECT_EQ(d.issues, (std::vector<std::string>{
                          "line 3: dropped by the emulator (busy)",
                          "line 4: not a frame: the emulator ignored these bytes",
                          "line 5: not a frame: the emulator ignored these bytes",
                      }));
  EXPECT_NE(d.table.find("0.001000 dropped:busy GetBatteryVoltage\n"
                         "! line 3: dropped by the emulator (busy)\n"),
            std::string::npos)
      << d.table;
  EXPECT_NE(d.table.find("# 5 record(s), 3 issue(s)\n"), std::string::npos) << d.table;
}

// One emulator per fault, each fed the same two battery requests, 100 ms apart.
std::string record_with(const char* faults) {
  XArmConfig config;
  auto parsed = parse_faults(faults);
  EXPECT_TRUE(parsed.ok()) << faults;
  if (parsed) config.faults = *parsed;
  XArmEmulator emu(config);
  emu.receive(hex("55 55 02 0f"), at_ms(0));
  emu.receive(hex("55 55 02 0f"), at_ms(100));
  return xarm_record_csv(emu);
}

TEST(ReceivedRecord, XArmNamesTheFaultThatDroppedEachFrame) {
  EXPECT_EQ(record_with("drop=1"),
            std::string(kHeader) +
                "0.000000,dropped:fault-drop,55 55 02 0f,GetBatteryVoltage\n"
                "0.100000,dropped:fault-drop,55 55 02 0f,GetBatteryVoltage\n");
  EXPECT_EQ(record_with("silent-after=1"),
            std::string(kHeader) +
                "0.000000,ok,55 55 02 0f,GetBatteryVoltage\n"
                "0.100000,dropped:fault-silent,55 55 02 0f,GetBatteryVoltage\n");
  EXPECT_EQ(record_with("reset-at=2"),
            std::string(kHeader) +
                "0.000000,ok,55 55 02 0f,GetBatteryVoltage\n"
                "0.100000,dropped:fault-reset,55 55 02 0f,GetBatteryVoltage\n");
  // The frame that hangs up is recorded; nothing after it reaches the controller.
  EXPECT_EQ(record_with("hangup-at=1"),
            std::string(kHeader) + "0.000000,dropped:fault-hangup,55 55 02 0f,GetBatteryVoltage\n");

  const compiler::DecodeResult d =
      compiler::decode_text(record_with("silent-after=1"), compiler::DecodeFormat::Record);
  EXPECT_EQ(d.issues, (std::vector<std::string>{"line 3: dropped by the emulator (fault-silent)"}));
}

TEST(ReceivedRecord, Lsc6MarksAFrameLostWhileTheBufferWasFull) {
  Lsc6Config config;
  config.baud = 0;
  Lsc6Emulator emu(config);
  // EraseAll keeps the board busy about 46 ms; the first Stop waits in the buffer, the second
  // finds it full.
  emu.receive(hex("55 55 02 08"), at_ms(0));
  emu.receive(hex("55 55 02 07"), at_ms(1));
  emu.receive(hex("55 55 02 07"), at_ms(2));
  const std::string csv = lsc6_record_csv(emu);
  EXPECT_EQ(csv, std::string(kHeader) +
                     "0.000000,ok,55 55 02 08,EraseAll\n"
                     "0.001000,ok,55 55 02 07,Stop\n"
                     "0.002000,dropped:busy,55 55 02 07,Stop\n");
  const compiler::DecodeResult d = compiler::decode_text(csv, compiler::DecodeFormat::Auto);
  EXPECT_EQ(d.issues, (std::vector<std::string>{"line 4: dropped by the emulator (busy)"}));
}

TEST(ReceivedRecord, Lsc6MarksAFrameLostOnTheLine) {
  Lsc6Config config;
  config.baud = 0;
  config.drop = 1.0;
  Lsc6Emulator emu(config);
  emu.receive(hex("55 55 05 06 01 01 00"), at_ms(250));
  EXPECT_EQ(lsc6_record_csv(emu),
            std::string(kHeader) +
                "0.250000,dropped:fault-drop,55 55 05 06 01 01 00,Run group=1 times=1\n");
}

TEST(ReceivedRecord, DecodeStillFlagsTheOlderStatuses) {
  // Records written before drops carried a reason said `busy` and `fault`.
  const std::string csv = std::string(kHeader) +
                          "0.100000,ok,55 55 02 0f,GetBatteryVoltage\n"
                          "0.200000,busy,55 55 02 0f,GetBatteryVoltage\n"
                          "0.300000,fault,55 55 02 0f,\n";
  const compiler::DecodeResult d = compiler::decode_text(csv, compiler::DecodeFormat::Auto);
  EXPECT_EQ(d.issues, (std::vector<std::string>{"line 3: dropped by the emulator (busy)",
                                                "line 4: dropped by the emulator (fault)"}));
}

// The car emulator's record is its state, change by change; `seqc decode` reads it back as a
// table and finds nothing wrong in what the emulator wrote.
TEST(ReceivedRecord, TheCarRecordDecodesBack) {
  RaspblockEmulator board;
  board.receive(hex("ff fe 02 04 05 dc 03 e8 d2"), at_ms(0));               // gimbal 1500, 1000
  board.receive(hex("ff fe 03 08 01 00 0a 00 00 00 00 05 1b"), at_ms(20));  // X=-10
  board.receive(hex("ff fe 02 04 06 40 03 e8 37"), at_ms(60));              // pan 1600
  const std::string csv = timeline_csv(board.timeline());
  const compiler::DecodeResult d = compiler::decode_text(csv, compiler::DecodeFormat::Auto);
  EXPECT_TRUE(d.issues.empty());
  EXPECT_EQ(d.table,
            "# Raspblock emulator record: each change of the board's state\n"
            "0.000000 gimbal.horizontal  = 1500\n"
            "0.000000 gimbal.vertical    = 1000\n"
            "0.020000 rocker.x           = -10\n"
            "0.020000 rocker.y           = 0\n"
            "0.020000 rocker.z           = 0\n"
            "0.060000 gimbal.horizontal  1500 -> 1600\n"
            "# 6 change(s), 0 issue(s)\n");
}

// A record cut or edited by hand no longer adds up: each line whose previous value is not the
// field's last one, time running backwards, and a line that is not a record line.
TEST(ReceivedRecord, AnEditedCarRecordShowsWhereItStopsAddingUp) {
  const std::string csv =
      "time_s,field,previous,value\n"
      "0.000000,servo.1,,1500\n"
      "0.100000,servo.1,1400,1600\n"  // servo.1 was 1500
      "0.050000,servo.2,,900\n"       // before the line above
      "0.200000,servo.3,700,800\n"    // servo.3 had no value
      "0.300000,servo.1,,1700\n"      // servo.1 was 1600
      "0.4,servo.1\n";
  const compiler::DecodeResult d = compiler::decode_text(csv, compiler::DecodeFormat::Auto);
  EXPECT_EQ(d.issues, (std::vector<std::string>{
                          "line 3: servo.1 was 1500, not 1400",
                          "line 4: time runs backwards (0.050000 after 0.100000)",
                          "line 5: servo.3 had no value before, yet the record says it was 700",
                          "line 6: servo.1 was 1600, yet the record gives no previous value",
                          "line 7: not a record line (time_s,field,previous,value)",
                      }));
  EXPECT_EQ(compiler::detect_format(csv), compiler::DecodeFormat::Record);
}

}  // namespace
}  // namespace seqc::emu::test
