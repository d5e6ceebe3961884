#!/usr/bin/env python3
"""Writes the SMPTE timecode test signals, encoded by libltc (LGPL, loaded through ctypes here
and never linked into seqc), as 16-bit mono WAV files in the folder given.

Each file's content is stated here and again, by hand, in the tests that read it
(tests/follow/ltc_*_test.cpp): a start label and a number of frames, silence where a segment is
silent. Exits 77 (a skipped test) when libltc.so.11 is not installed (Debian libltc11).
"""
import ctypes
import os
import struct
import sys
import wave

TV_525_60, TV_625_50, TV_FILM_24 = 0, 1, 3
RATES = {  # name: (frames a second given to libltc, TV standard)
    "24": (24.0, TV_FILM_24),
    "25": (25.0, TV_625_50),
    "2997df": (30000.0 / 1001.0, TV_525_60),
    "30": (30.0, TV_525_60),
}


class SMPTETimecode(ctypes.Structure):
    _fields_ = [("timezone", ctypes.c_char * 6), ("years", ctypes.c_ubyte),
                ("months", ctypes.c_ubyte), ("days", ctypes.c_ubyte), ("hours", ctypes.c_ubyte),
                ("mins", ctypes.c_ubyte), ("secs", ctypes.c_ubyte), ("frame", ctypes.c_ubyte)]


def load():
    try:
        lib = ctypes.CDLL("libltc.so.11")
    except OSError:
        print("ltc_signal: libltc.so.11 is not installed (apt install libltc-dev)", file=sys.stderr)
        sys.exit(77)
    lib.ltc_encoder_create.restype = ctypes.c_void_p
    lib.ltc_encoder_create.argtypes = [ctypes.c_double, ctypes.c_double, ctypes.c_int, ctypes.c_int]
    lib.ltc_encoder_free.argtypes = [ctypes.c_void_p]
    lib.ltc_encoder_set_timecode.argtypes = [ctypes.c_void_p, ctypes.POINTER(SMPTETimecode)]
    lib.ltc_encoder_set_user_bits.argtypes = [ctypes.c_void_p, ctypes.c_ulong]
    lib.ltc_encoder_encode_frame.argtypes = [ctypes.c_void_p]
    lib.ltc_encoder_inc_timecode.argtypes = [ctypes.c_void_p]
    lib.ltc_encoder_get_buffersize.restype = ctypes.c_size_t
    lib.ltc_encoder_get_buffersize.argtypes = [ctypes.c_void_p]
    lib.ltc_encoder_copy_buffer.argtypes = [ctypes.c_void_p, ctypes.POINTER(ctypes.c_ubyte)]
    lib.ltc_encoder_buffer_flush.argtypes = [ctypes.c_void_p]
    return lib


class Encoder:
    def __init__(self, lib, sample_rate, rate):
        fps, standard = RATES[rate]
        self.lib = lib
        self.e = lib.ltc_encoder_create(sample_rate, fps, standard, 0)
        self.buf = (ctypes.c_ubyte * (lib.ltc_encoder_get_buffersize(self.e) + 16))()
        self.samples = []

    def set(self, label):
        h, m, s, f = (int(x) for x in label.replace(";", ":").split(":"))
        tc = SMPTETimecode(b"+0000", 0, 1, 1, h, m, s, f)
        self.lib.ltc_encoder_set_timecode(self.e, ctypes.byref(tc))

    def frames(self, n, silent=False, advance=True):
        """n frames from the current label: heard, or as silence of the same length."""
        for _ in range(n):
            self.lib.ltc_encoder_encode_frame(self.e)
            got = self.lib.ltc_encoder_copy_buffer(self.e, self.buf)
            self.lib.ltc_encoder_buffer_flush(self.e)
            if silent:
                self.samples.extend([0] * got)
            else:
                self.samples.extend((self.buf[i] - 128) * 256 for i in range(got))
            if advance:
                self.lib.ltc_encoder_inc_timecode(self.e)

    def write(self, path, sample_rate):
        with wave.open(path, "wb") as w:
            w.setnchannels(1)
            w.setsampwidth(2)
            w.setframerate(sample_rate)
            w.writeframes(struct.pack("<%dh" % len(self.samples), *self.samples))
        self.lib.ltc_encoder_free(self.e)


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    lib = load()
    # Frames counted by the decoder tests: a start label, a number of frames.
    plain = [("24", "01:02:03:00", 72), ("25", "10:00:00:00", 75),
             ("2997df", "00:00:58;00", 90), ("2997df-tenth", "00:09:58;00", 90),
             ("30", "00:59:59:00", 60)]
    for sample_rate in (48000, 44100):
        for name, start, count in plain:
            e = Encoder(lib, sample_rate, name.split("-")[0])
            if name == "25":
                e.lib.ltc_encoder_set_user_bits(e.e, 0x12345678)
            e.set(start)
            e.frames(count)
            e.write(os.path.join(out, f"ltc-{name}-{sample_rate}.wav"), sample_rate)
    # The show clock's run: one second before --start 01:00:00:00, four seconds after it, a
    # one-second dropout (the timecode runs on, unheard), two seconds, a jump to 01:10:00:00,
    # two seconds, three seconds of silence. In frames of the rate.
    for rate, fps in (("25", 25), ("2997df", 30)):
        e = Encoder(lib, 48000, rate)
        e.set("00:59:59:00")
        e.frames(5 * fps)
        e.frames(fps, silent=True)
        e.frames(2 * fps)
        e.set("01:10:00:00")
        e.frames(2 * fps)
        e.frames(3 * fps, silent=True)
        e.write(os.path.join(out, f"ltc-show-{rate}-48000.wav"), 48000)
    # Two seconds from 10:00:00:00, then its last frame again for four seconds (a paused deck).
    e = Encoder(lib, 48000, "25")
    e.set("10:00:00:00")
    e.frames(49)
    e.frames(101, advance=False)
    e.write(os.path.join(out, "ltc-still-25-48000.wav"), 48000)
    return 0


if __name__ == "__main__":
    sys.exit(main())
