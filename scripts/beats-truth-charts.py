#!/usr/bin/env python3
"""Beat truth for the rock and metal recordings that Debian's Frets on Fire song packages ship
(fretsonfire-songs-muldjord, fretsonfire-songs-sectoid): each song folder holds the band's own
backing track (song.ogg) and the note chart its makers wrote for it (notes.mid), whose tempo
events and time signature place every beat and bar line of the recording (the game scrolls
the notes on them). Standard library only.

Usage: scripts/beats-truth-charts.py OUT_DIR [SONGS_DIR ...]
Writes OUT_DIR/fof-NAME.ogg (a link to the recording), OUT_DIR/fof-NAME.truth (TIME<TAB>PLACE IN
BAR) and OUT_DIR/fof-NAME.json.
"""
import json
import os
import re
import struct
import sys

DEFAULT_DIRS = ['/usr/share/games/fretsonfire/data/songs/muldjord',
                '/usr/share/games/fretsonfire/data/songs/sectoid']


def variable_length(data, at):
    value = 0
    while True:
        byte = data[at]
        at += 1
        value = (value << 7) | (byte & 0x7F)
        if not byte & 0x80:
            return value, at


def read_midi(path):
    """(ticks per quarter note, tempo events [(tick, us per quarter)], time signatures
    [(tick, beats, unit)], note-on ticks) of a standard MIDI file."""
    data = open(path, 'rb').read()
    if data[:4] != b'MThd':
        raise ValueError(path + ': not a standard MIDI file')
    _, tracks, division = struct.unpack('>HHH', data[8:14])
    if division & 0x8000:
        raise ValueError(path + ': SMPTE time division is not read')
    at = 8 + struct.unpack('>I', data[4:8])[0]
    tempos, signatures, notes = [], [], []
    for _ in range(tracks):
        if data[at:at + 4] != b'MTrk':
            raise ValueError(path + ': malformed track')
        end = at + 8 + struct.unpack('>I', data[at + 4:at + 8])[0]
        at += 8
        tick, status = 0, 0
        while at < end:
            delta, at = variable_length(data, at)
            tick += delta
            byte = data[at]
            if byte == 0xFF:
                kind = data[at + 1]
                length, at = variable_length(data, at + 2)
                body = data[at:at + length]
                at += length
                if kind == 0x51:
                    tempos.append((tick, int.from_bytes(body, 'big')))
                elif kind == 0x58:
                    signatures.append((tick, body[0], 2 ** body[1]))
            elif byte in (0xF0, 0xF7):
                length, at = variable_length(data, at + 1)
                at += length
            else:
                if byte & 0x80:
                    status = byte
                    at += 1
                size = 1 if status & 0xF0 in (0xC0, 0xD0) else 2
                if status & 0xF0 == 0x90 and data[at + 1] > 0:
                    notes.append(tick)
                at += size
        at = end
    return division, sorted(tempos), sorted(signatures), sorted(notes)


def seconds_at(tick, division, tempos):
    """The time of `tick` under the tempo events (120 BPM before the first, as MIDI says)."""
    seconds, last_tick, per_quarter = 0.0, 0, 500000
    for event_tick, micros in tempos:
        if event_tick >= tick:
            break
        seconds += (event_tick - last_tick) * per_quarter / division / 1e6
        last_tick, per_quarter = event_tick, micros
    return seconds + (tick - last_tick) * per_quarter / division / 1e6


def ogg_vorbis_seconds(path):
    """The length of an Ogg Vorbis file: the last page's granule position (samples) over the
    sample rate of the identification header."""
    data = open(path, 'rb').read()
    header = data.find(b'\x01vorbis')
    if not data.startswith(b'OggS') or header < 0:
        raise ValueError(path + ': not Ogg Vorbis')
    rate = struct.unpack('<I', data[header + 12:header + 16])[0]
    last = data.rfind(b'OggS')
    granule = struct.unpack('<q', data[last + 6:last + 14])[0]
    return granule / rate


def chart_truth(folder):
    division, tempos, signatures, notes = read_midi(os.path.join(folder, 'notes.mid'))
    if not notes:
        raise ValueError(folder + ': the chart has no notes')
    distinct = sorted({micros for _, micros in tempos})
    if len(distinct) > 1:
        raise ValueError(folder + ': the tempo changes; only steady songs are scored')
    beats_per_bar = signatures[0][1] if signatures else 4
    if signatures and (len({(b, u) for _, b, u in signatures}) > 1 or signatures[0][2] != 4):
        raise ValueError(folder + ': the meter changes or is not in quarters')
    bpm = 60e6 / distinct[0] if distinct else 120.0
    # The recording is played from the chart's tick 0; the truth runs from bar 1 to the bar
    # after the last note (the backing track ends with the chart).
    last_beat = notes[-1] // division + beats_per_bar
    lines = []
    for beat in range(0, last_beat + 1):
        lines.append('%.4f\t%d' % (seconds_at(beat * division, division, tempos),
                                   beat % beats_per_bar + 1))
    return bpm, beats_per_bar, lines


def main():
    out = sys.argv[1]
    dirs = sys.argv[2:] or DEFAULT_DIRS
    os.makedirs(out, exist_ok=True)
    for parent in dirs:
        if not os.path.isdir(parent):
            print('beats-truth-charts: %s not installed' % parent, file=sys.stderr)
            continue
        for name in sorted(os.listdir(parent)):
            folder = os.path.join(parent, name)
            if not os.path.isfile(os.path.join(folder, 'notes.mid')):
                continue
            slug = 'fof-' + re.sub(r'[^a-z0-9]+', '-', name.lower()).strip('-')
            try:
                bpm, meter, lines = chart_truth(folder)
            except ValueError as err:
                print('beats-truth-charts: excluded: %s' % err, file=sys.stderr)
                continue
            link = os.path.join(out, slug + '.ogg')
            if os.path.lexists(link):
                os.remove(link)
            os.symlink(os.path.join(folder, 'song.ogg'), link)
            with open(os.path.join(out, slug + '.truth'), 'w') as f:
                f.write('\n'.join(lines) + '\n')
            source = os.path.join(folder, 'notes.mid')
            licence = 'CC-BY-SA-3.0' if 'muldjord' in folder else 'MIT (Expat)'
            seconds = ogg_vorbis_seconds(os.path.join(folder, 'song.ogg'))
            with open(os.path.join(out, slug + '.json'), 'w') as f:
                json.dump({'bpm': bpm, 'meter': '%d/4' % meter, 'project': source,
                           'licence': licence, 'seconds': seconds,
                           'audio': 'band recording (backing track)'}, f, indent=1)
            print('%s: %.3f BPM, %d/4, %d beats' % (slug, bpm, meter, len(lines)))


if __name__ == '__main__':
    main()
