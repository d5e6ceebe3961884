#!/usr/bin/env python3
"""Writes the seed corpus of each fuzz target (tests/fuzz/corpus/<target>/).

The seeds are the hand-written golden frames of tests/protocol plus a few broken ones.
Run from anywhere: python3 tests/fuzz/make_corpus.py
"""
import pathlib

HERE = pathlib.Path(__file__).resolve().parent

LSC_FRAMES = {
    "move": "55 55 08 03 01 E8 03 01 D0 07",
    "move_nomove": "55 55 0B 03 02 F4 01 01 DC 05 02 00 FF",
    "gd_open": "55 55 06 05 01 00 FF 01",
    "gd_size": "55 55 07 05 02 00 01 01 00",
    "gd_blocks": "55 55 07 05 03 00 00 00 01",
    "gd_action": "55 55 0C 05 04 00 01 00 0B E8 03 01 D0 07",
    "gd_close": "55 55 04 05 05 00",
    "gd_ack": "55 55 04 05 01 00",
    "gd_refusal": "55 55 04 05 04 01",
    "run": "55 55 05 06 02 01 00",
    "stop": "55 55 02 07",
    "stopped": "55 55 05 07 02 03 00",
    "erase": "55 55 03 08 FF",
    "erased": "55 55 02 08",
    "finished": "55 55 05 08 02 01 00",
    "speed": "55 55 05 0B 01 C8 00",
    "battery": "55 55 02 0F",
    "battery_reply": "55 55 04 0F 4C 1D",
    "servo_off": "55 55 06 14 03 01 02 03",
    "position_read": "55 55 05 15 02 01 02",
    "positions": "55 55 09 15 02 01 F4 01 02 E8 03",
    "offset_write": "55 55 04 16 01 06",
    "offset_read": "55 55 05 17 02 01 06",
    "offsets": "55 55 07 17 02 01 FD 02 05",
    "offset_adjust": "55 55 05 18 03 EC FF",
    "servo_speed": "55 55 06 1A 01 01 F4 01",
    "info_write": "55 55 0F 1B 01 00 00 E8 03 94 11 E0 2E 55 00 01 07",
    "info_read": "55 55 02 1C",
    "info": "55 55 15 1C 01 00 00 E8 03 94 11 E0 2E 55 00 01 07 FE F4 01 28 E8 1C",
}

LSC_BROKEN = {
    "len0": "55 55 00 55 55 02 0F",
    "len1": "55 55 01 0F",
    "triple55": "55 55 55 04 0F 4C 1D",
    "truncated": "55 55 09 15 02 01 F4",
    "garbage": "00 FF 55 13 AA 55",
    "bad_count": "55 55 06 14 04 01 02 03",
    "bad_marker": "55 55 0C 05 04 00 00 00 0C E8 03 01 D0 07",
}

RASPBLOCK = {
    "rocker": "FF FE 03 08 01 00 0A 00 00 00 00 05 1B",
    "rocker_edges": "FF FE 03 08 01 00 19 00 19 00 C8 02 08",
    "gimbal": "FF FE 02 04 05 DC 07 9E 8C",
    "single": "FF FE 02 03 02 09 C4 D4",
    "pid": "FF FE 01 09 01 01 02 03 04 05 06 07 08 2F",
    "bad_checksum": "FF FE 03 08 01 00 0A 00 00 00 00 05 1C",
    "bad_len": "FF FE 02 07 FF FE 02 03 02 09 C4 D4",
    "out_of_range": "FF FE 02 03 05 09 C4 D7",
    "garbage": "00 FF 12 FE FF",
}


def b(text):
    return bytes.fromhex(text)


def write(target, name, data):
    folder = HERE / "corpus" / target
    folder.mkdir(parents=True, exist_ok=True)
    (folder / name).write_bytes(data)


def main():
    # lsc_stream: byte 0 picks the chunk size, then the stream.
    for i, (name, text) in enumerate({**LSC_FRAMES, **LSC_BROKEN}.items()):
        write("lsc_stream", name, bytes([i % 16]) + b(text))
    everything = b"".join(b(t) for t in LSC_FRAMES.values())
    write("lsc_stream", "all_frames", bytes([0]) + everything)
    write("lsc_stream", "all_frames_garbage", bytes([5]) + b(LSC_BROKEN["garbage"]) + everything)

    # lsc_hid: 64-byte input reports.
    for name, text in LSC_FRAMES.items():
        frame = b(text)
        if len(frame) <= 64:
            write("lsc_hid", name, frame + bytes(64 - len(frame)))
    write("lsc_hid", "short_report", b(LSC_FRAMES["battery_reply"]))
    write("lsc_hid", "len_too_big", b("55 55 3F 14") + bytes([1]) * 60)
    write("lsc_hid", "no_header", bytes(64))

    # raspblock: byte 0 picks the chunk size, then the bytes.
    for i, (name, text) in enumerate(RASPBLOCK.items()):
        write("raspblock", name, bytes([i % 16]) + b(text))
    write("raspblock", "stream",
          bytes([3]) + b("".join(RASPBLOCK[k] + " " for k in RASPBLOCK)))


if __name__ == "__main__":
    main()
