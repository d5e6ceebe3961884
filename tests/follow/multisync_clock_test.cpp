// The MultiSync ShowClock over a fake socket: which packets become events and when, which are
// ignored, and the remote's answer to a master's discovery ping, byte for byte.
#include <gtest/gtest.h>

#include <chrono>

#include "protocol/fpp_multisync.hpp"
#include "runtime/follow/multisync_clock.hpp"
#include "runtime/io/udp_socket.hpp"

namespace seqc::follow {
namespace {

using std::chrono::milliseconds;

Bytes sync(fpp::SyncAction action, const std::string& name, float seconds, std::uint32_t frame = 0,
           fpp::SyncFile file = fpp::SyncFile::Sequence) {
  return fpp::encode_sync({action, file, frame, seconds, name});
}

TEST(MultisyncClock, NamesAreMatchedWithOrWithoutTheirExtension) {
  EXPECT_TRUE(names_followed("show", "show.fseq"));
  EXPECT_TRUE(names_followed("show", "show.mp3"));
  EXPECT_TRUE(names_followed("show.fseq", "show.fseq"));
  EXPECT_TRUE(names_followed("show", "/home/fpp/media/sequences/show.fseq"));
  EXPECT_FALSE(names_followed("show.fseq", "show.mp3"));
  EXPECT_FALSE(names_followed("show", "show2.fseq"));
  EXPECT_FALSE(names_followed("show", "other.fseq"));
  EXPECT_FALSE(names_followed("show", ""));
}

TEST(MultisyncClock, OpenStartSyncStopOfTheNamedFileBecomeEventsAndOthersAreIgnored) {
  io::ManualClock clock;
  io::FakeDatagramSocket socket(clock);
  socket.arrive(milliseconds(100), sync(fpp::SyncAction::Open, "show.fseq", 0));
  socket.arrive(milliseconds(150), sync(fpp::SyncAction::Start, "other.fseq", 0));
  socket.arrive(milliseconds(200), sync(fpp::SyncAction::Start, "show.fseq", 0));
  socket.arrive(milliseconds(210), sync(fpp::SyncAction::Start, "show.mp3", 0, 0,
                                        fpp::SyncFile::Media));  // the same entry's media
  socket.arrive(milliseconds(1200), sync(fpp::SyncAction::Sync, "show.fseq", 1.0f, 40));
  socket.arrive(milliseconds(1300), Bytes{'F', 'P', 'P'});                             // malformed
  socket.arrive(milliseconds(1400), sync(fpp::SyncAction::Sync, "show.fseq", 0, 48));  // frames
  socket.arrive(milliseconds(2000), sync(fpp::SyncAction::Stop, "show.fseq", 0));
  MultisyncClock ms(socket, clock, {.name = "show"});
  std::vector<ShowClockEvent> events;
  while (auto e = ms.next(milliseconds(5000))) events.push_back(*e);
  ASSERT_EQ(events.size(), 5u);
  EXPECT_EQ(events[0].kind, ShowClockKind::Open);
  EXPECT_EQ(events[0].at, milliseconds(100));
  EXPECT_EQ(events[1].kind, ShowClockKind::Start);
  EXPECT_EQ(events[1].at, milliseconds(200));
  EXPECT_EQ(events[1].dance_ms, 0);
  EXPECT_EQ(events[2].kind, ShowClockKind::Sync);
  EXPECT_EQ(events[2].at, milliseconds(1200));
  EXPECT_EQ(events[2].dance_ms, 1000);
  EXPECT_EQ(events[3].kind, ShowClockKind::Sync);
  EXPECT_EQ(events[3].dance_ms, 1200);  // frame 48 x 25 ms: the packet carried no seconds
  EXPECT_EQ(events[4].kind, ShowClockKind::Stop);
  EXPECT_EQ(events[4].detail, "sequence show.fseq from 192.168.1.10:32320");
  EXPECT_EQ(ms.counts().followed, 5u);
  EXPECT_EQ(ms.counts().other_names, 2u);
  EXPECT_EQ(ms.counts().malformed, 1u);
  EXPECT_EQ(ms.counts().last_error, "not an FPP packet (no FPPD header)");
  EXPECT_EQ(clock.now(), milliseconds(5000));  // waited to the deadline for more
  EXPECT_FALSE(ms.ended());
}

TEST(MultisyncClock, AMediaOnlyEntryIsFollowedByItsMediaPackets) {
  io::ManualClock clock;
  io::FakeDatagramSocket socket(clock);
  socket.arrive(milliseconds(10),
                sync(fpp::SyncAction::Start, "song.mp3", 2.5f, 0, fpp::SyncFile::Media));
  MultisyncClock ms(socket, clock, {.name = "song"});
  const auto e = ms.next(milliseconds(100));
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->kind, ShowClockKind::Start);
  EXPECT_EQ(e->dance_ms, 2500);
}

TEST(MultisyncClock, ADiscoveryPingIsAnsweredAsARemote) {
  io::ManualClock clock;
  io::FakeDatagramSocket socket(clock);
  fpp::PingPacket discover;
  discover.discover = true;
  discover.system_type = 0x13;  // a Pi 4 running FPP
  discover.mode = fpp::kModePlayer | fpp::kModeSendsMultiSync;
  discover.address = {192, 168, 1, 10};
  discover.hostname = "fpp-master";
  socket.arrive(milliseconds(5), fpp::encode_ping(discover), {{192, 168, 1, 10}, 32320});
  discover.discover = false;  // a plain ping is heard, not answered
  socket.arrive(milliseconds(6), fpp::encode_ping(discover), {{192, 168, 1, 10}, 32320});
  MultisyncClock ms(
      socket, clock,
      {.name = "show", .hostname = "robot", .version = "1.2.0", .major = 1, .minor = 2});
  EXPECT_FALSE(ms.next(milliseconds(100)).has_value());
  EXPECT_EQ(ms.counts().pings, 2u);
  EXPECT_EQ(ms.counts().answered, 1u);
  ASSERT_EQ(socket.sent.size(), 1u);
  EXPECT_EQ(socket.sent[0].from, (io::UdpAddress{{192, 168, 1, 10}, 32320}));
  const Bytes& b = socket.sent[0].bytes;
  ASSERT_EQ(b.size(), 301u);
  // FPPD, ping, 294 bytes; version 3, a ping (not a discover), system "other" (0xC0), version
  // 1.2 most significant byte first, mode remote (0x08), address 0.0.0.0 (the master takes the
  // one the answer came from).
  EXPECT_EQ(to_hex(ByteView(b).first(19)),
            "46 50 50 44 04 26 01 03 00 c0 00 01 00 02 08 00 00 00 00");
  EXPECT_EQ(std::string(b.begin() + 19, b.begin() + 25), std::string("robot\0", 6));
  EXPECT_EQ(std::string(b.begin() + 84, b.begin() + 90), std::string("1.2.0\0", 6));
  EXPECT_EQ(std::string(b.begin() + 125, b.begin() + 130), std::string("seqc\0", 5));
}

}  // namespace
}  // namespace seqc::follow
