// FPP control packets against bytes written by hand from FPP's docs/ControlProtocol.txt, and
// the decoder's refusals: it never reads past the datagram.
#include <gtest/gtest.h>

#include <variant>

#include "protocol/fpp_multisync.hpp"

namespace seqc::fpp {
namespace {

// A master's sync of show.fseq at frame 400, 10.0 s in.
const Bytes kSyncShow10s = {
    'F',  'P',  'P',  'D',                               // buf[0-3]: the header
    0x01,                                                // buf[4]: packet type MultiSync
    0x14, 0x00,                                          // buf[5-6]: 20 = 10 + 9 + 1, LE
    0x02,                                                // buf[7]: action 2, sync
    0x00,                                                // buf[8]: file type 0, sequence
    0x90, 0x01, 0x00, 0x00,                              // buf[9-12]: frame 400, LE
    0x00, 0x00, 0x20, 0x41,                              // buf[13-16]: 10.0f, LE
    's',  'h',  'o',  'w',  '.', 'f', 's', 'e', 'q', 0,  // buf[17+]: the name and its NUL
};

TEST(FppMultiSync, ASyncPacketIsWrittenAsTheDocumentLaysItOut) {
  SyncPacket p;
  p.action = SyncAction::Sync;
  p.file = SyncFile::Sequence;
  p.frame = 400;
  p.seconds = 10.0f;
  p.file_name = "show.fseq";
  EXPECT_EQ(to_hex(encode_sync(p)), to_hex(kSyncShow10s));
}

TEST(FppMultiSync, ASyncPacketIsReadAsTheDocumentLaysItOut) {
  const Result<Packet> r = decode(kSyncShow10s);
  ASSERT_TRUE(r.ok()) << r.error().message;
  const auto* p = std::get_if<SyncPacket>(&*r);
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(p->action, SyncAction::Sync);
  EXPECT_EQ(p->file, SyncFile::Sequence);
  EXPECT_EQ(p->frame, 400u);
  EXPECT_EQ(p->seconds, 10.0f);
  EXPECT_EQ(p->file_name, "show.fseq");
}

TEST(FppMultiSync, TheActionCodesAreTheDocumentsStartStopSyncOpen) {
  const auto action_of = [](std::uint8_t code) {
    Bytes b = kSyncShow10s;
    b[7] = code;
    return std::get<SyncPacket>(*decode(b)).action;
  };
  EXPECT_EQ(action_of(0), SyncAction::Start);
  EXPECT_EQ(action_of(1), SyncAction::Stop);
  EXPECT_EQ(action_of(2), SyncAction::Sync);
  EXPECT_EQ(action_of(3), SyncAction::Open);
  Bytes media = kSyncShow10s;
  media[8] = 1;
  EXPECT_EQ(std::get<SyncPacket>(*decode(media)).file, SyncFile::Media);
}

TEST(FppMultiSync, DecodeErrorsNameWhatIsWrong) {
  const auto error_of = [](const Bytes& b) {
    const Result<Packet> r = decode(b);
    return r.ok() ? std::string("decoded") : r.error().message;
  };
  EXPECT_EQ(error_of({'F', 'P', 'P'}), "not an FPP packet (no FPPD header)");
  EXPECT_EQ(error_of({'F', 'P', 'P', 'X', 1, 0, 0}), "not an FPP packet (no FPPD header)");
  Bytes cut(kSyncShow10s.begin(), kSyncShow10s.end() - 3);  // the length says 3 more
  EXPECT_EQ(error_of(cut), "extra length 20 but 17 bytes follow the header");
  Bytes no_nul = kSyncShow10s;
  no_nul.back() = 'x';
  EXPECT_EQ(error_of(no_nul), "sync packet: file name without its NUL");
  // The length stops before the NUL: the NUL beyond it is not read.
  Bytes short_len = kSyncShow10s;
  short_len[5] = 19;
  EXPECT_EQ(error_of(short_len), "sync packet: file name without its NUL");
  Bytes bad_action = kSyncShow10s;
  bad_action[7] = 4;
  EXPECT_EQ(error_of(bad_action), "sync packet: unknown action 4");
  Bytes bad_type = kSyncShow10s;
  bad_type[8] = 2;
  EXPECT_EQ(error_of(bad_type), "sync packet: unknown file type 2");
  EXPECT_EQ(error_of({'F', 'P', 'P', 'D', 1, 5, 0, 2, 0, 0, 0, 0}),
            "sync packet: 5 bytes of data, fewer than the 11 of an empty file name");
  Bytes nan = kSyncShow10s;
  nan[15] = 0xc0;  // 0x7fc00000 with its top byte's sign: a NaN
  nan[16] = 0x7f;
  EXPECT_EQ(error_of(nan), "sync packet: seconds elapsed out of range");
  EXPECT_EQ(error_of(Bytes(kMaxPacketBytes + 1, 'F')), "packet of 2049 bytes, longer than 2048");
  EXPECT_EQ(error_of({'F', 'P', 'P', 'D', 4, 10, 0, 3, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0}),
            "ping packet: 10 bytes of data, fewer than the 98 of the first version");
}

TEST(FppMultiSync, OtherPacketTypesAreOnlyNamed) {
  const Result<Packet> r = decode(Bytes{'F', 'P', 'P', 'D', 3, 0, 0});  // blanking
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(std::get<OtherPacket>(*r).type, 3);
}

TEST(FppMultiSync, APingRoundTripsAndSitsAtTheDocumentsOffsets) {
  PingPacket p;
  p.discover = false;
  p.system_type = kSystemOther;
  p.major = 1;
  p.minor = 2;
  p.mode = kModeRemote;
  p.hostname = "robot";
  p.version_text = "1.2.0";
  p.hardware = "seqc";
  const Bytes b = encode_ping(p);
  ASSERT_EQ(b.size(), 7u + 294u);
  EXPECT_EQ(to_hex(ByteView(b).first(19)),
            "46 50 50 44 04 26 01 03 00 c0 00 01 00 02 08 00 00 00 00");
  EXPECT_EQ(b[19], 'r');   // hostname at buf[19]
  EXPECT_EQ(b[84], '1');   // version at buf[84]
  EXPECT_EQ(b[125], 's');  // hardware at buf[125]
  const Result<Packet> back = decode(b);
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(std::get<PingPacket>(*back), p);
}

}  // namespace
}  // namespace seqc::fpp
