// The one table of wire dialects: one row per dialect seqc speaks (the xArm / LSC-16 / LSC-32
// servo controller, the LSC-6 / LeArm board, the Raspblock car). Everything that must tell the
// dialects apart without a board at hand reads a row: the trace header names a row (`name`,
// written byte for byte as "# dialect: NAME"), `seqc decode` finds a trace's or a file's row from
// that header or by sniffing the bytes, and each planned download frame carries the row it is
// encoded in. A row knows how one frame or packet of its dialect travels (encode/decode of a
// Unit), how to describe one in a line, and whether a byte stream looks like its own; the typed
// messages stay in each dialect's files (lsc_messages, lsc6_messages, raspblock).
//
// Adding a dialect: its files in protocol/, one row in dialects.cpp, and the board row that
// names it (docs/architecture.md, "Adding a board").
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "base/bytes.hpp"
#include "base/result.hpp"

namespace seqc {

// How a dialect cuts its bytes: `55 55 LEN CMD DATA` frames (lsc_frame.hpp), shared by the
// servo controllers, or the Raspblock's checksummed `FF FE FUNC LEN DATA CHK` packets.
enum class Framing { Frames, Packets };

// One frame or packet: its command (CMD, or the Raspblock's FUNC) and its data.
struct Unit {
  std::uint8_t command = 0;
  Bytes data;
  friend bool operator==(const Unit&, const Unit&) = default;
};

struct Dialect {
  // "xarm", "lsc6", "raspblock": what code and tests name the row by.
  std::string_view key;
  // "xArm / LSC-16 / LSC-32", "LSC-6", "Raspblock": the trace header's "# dialect: NAME" (traces
  // already written are read back by it, so it never changes) and what tables call the dialect.
  std::string_view name;
  // The `seqc decode --from` choice for its hex frames or packets: "hex" (the first dialect's,
  // which was the only one once), "lsc6", "raspblock".
  std::string_view decode_name;
  Framing framing = Framing::Frames;

  // One unit's serial bytes; an error when its data does not fit the framing.
  Result<Bytes> (*encode)(const Unit& unit) = nullptr;
  // Exactly one whole unit (no bytes before or after), checksum and length checked.
  Result<Unit> (*decode)(ByteView bytes) = nullptr;
  // One line naming a unit sent to the board, e.g. "GroupRun group=0 times=1"; an error when the
  // dialect has no such request.
  Result<std::string> (*describe_request)(const Unit& unit) = nullptr;
  // The same for a unit the board sends; null: the board never answers (the Raspblock).
  Result<std::string> (*describe_reply)(const Unit& unit) = nullptr;
  // Whether `bytes` (what was written and read, concatenated) show this dialect. Rows of one
  // framing never both accept the same bytes, so sniff_dialect() has one answer.
  bool (*sniff)(ByteView bytes) = nullptr;
};

extern const Dialect kXarmDialect;
extern const Dialect kLsc6Dialect;
extern const Dialect kRaspblockDialect;

// Every row, in the order `seqc decode --from` lists them.
std::span<const Dialect* const> all_dialects();
const Dialect* find_dialect(std::string_view key);
// The row a trace header names ("# dialect: LSC-6" -> LSC-6); null for a name no row has.
const Dialect* dialect_named(std::string_view name);
// The row whose `decode_name` is `decode_name`; null for none.
const Dialect* dialect_decoded_as(std::string_view decode_name);
// How `bytes` are framed: packets when they open with the Raspblock's header, else frames.
Framing framing_of(ByteView bytes);
// The row of `framing` whose sniff accepts `bytes`, else that framing's first row (frames
// without a download of the LSC-6 are read as the xArm dialect's).
const Dialect& sniff_dialect(ByteView bytes, Framing framing);
// sniff_dialect(bytes, framing_of(bytes)).
const Dialect& sniff_dialect(ByteView bytes);

}  // namespace seqc
