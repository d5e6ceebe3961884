// `seqc decode` for everything seqc writes or records: hex frames (`compile --emit hex`, the
// commented `--dry-run` listing), in either servo-controller dialect (xArm / LSC-16 / LSC-32, or
// LSC-6), the Raspblock's timed hex packets, `--trace` files (both directions, each reply
// decoded) and the emulators' `--record` CSV (the controllers' received frames, the car's state
// changes). detect_format() tells them apart from the text; `--from` forces one. Which dialect
// bytes are in comes from the dialect table (protocol/dialects.hpp): a trace's header names its
// row, and the rows' sniffs tell hex frames and headerless traces apart.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "base/result.hpp"
#include "compiler/formats/decode.hpp"
#include "protocol/dialects.hpp"

namespace seqc::compiler {

enum class DecodeFormat { Auto, Hex, Lsc6, Raspblock, Trace, Record };

// Every `--from` choice, in the order help lists them: "auto", each dialect's decode_name in
// table order ("hex", "lsc6", "raspblock"), "trace", "record".
std::vector<std::string> decode_format_names();
Result<DecodeFormat> parse_decode_format(std::string_view name);
std::string_view to_string(DecodeFormat format);
// The dialect whose hex frames or packets `format` reads; null for Auto, Trace and Record.
const Dialect* dialect_of(DecodeFormat format);

// What `text` is, never Auto: a trace starts its lines with t=, a record with one of the two
// CSV headers; other text is hex, in the dialect its bytes sniff as (sniff_dialect: Raspblock
// packets open with ff fe, frames holding an LSC-6 download (CMD 25) are that dialect's, and other
// frames the xArm dialect's).
DecodeFormat detect_format(std::string_view text);

// Decodes `text` as `format` (Auto: detect_format). Bytes that are not frames, frames that do
// not decode and downloads that do not add up are issues, marked '!' in the table; so is every
// record line whose status is not `ok` (a frame the emulator dropped, bytes it could not frame),
// and every car record line whose previous value is not the field's last one.
DecodeResult decode_text(std::string_view text, DecodeFormat format);

// The LSC-6 dialect's frames: each request, and for a download the group it builds, checked
// (indices in order from 0, one total, one group, the last index closing it).
DecodeResult decode_lsc6_frames(ByteView bytes);

}  // namespace seqc::compiler
