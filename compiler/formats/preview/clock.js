"use strict";
const page = JSON.parse(document.getElementById("seqc-data").textContent);
let endMs = Math.max(page.end, 1);
const $ = (id) => document.getElementById(id);

// The one time source. Everything drawn follows clock() (seconds). With a song the <audio>
// element is the clock: while it plays, the sequence's time is its currentTime minus the
// downbeat, so the picture follows what is heard; seeking, pausing and the rate go to it too. The
// wall clock carries on where the audio cannot (before it has loaded, past its end).
const timeSource = { playing: false, at: 0, origin: 0, rate: 1 };
const wall = () => performance.now() / 1000;
const audio = $("song");
let lead = page.song ? page.song.downbeat : 0;
const audioRuns = () => audio && !audio.paused && !audio.ended && audio.readyState >= 2;
function audioTo(seconds) {
  if (!audio) return;
  const at = seconds + lead;
  if (!isNaN(audio.duration) && at >= audio.duration) {
    audio.pause();
    return;
  }
  audio.currentTime = Math.max(at, 0);
}
function clock() {
  const s = timeSource;
  if (s.playing && audioRuns()) return audio.currentTime - lead;
  return s.playing ? s.at + (wall() - s.origin) * s.rate : s.at;
}
function seek(seconds) {
  timeSource.at = Math.min(Math.max(seconds, 0), endMs / 1000);
  timeSource.origin = wall();
  audioTo(timeSource.at);
}
function play() {
  if (clock() >= endMs / 1000) seek(loopRange() ? loopRange()[0] / 1000 : 0);
  timeSource.at = clock();
  timeSource.origin = wall();
  timeSource.playing = true;
  if (audio && (isNaN(audio.duration) || timeSource.at + lead < audio.duration)) {
    audioTo(timeSource.at);
    audio.playbackRate = timeSource.rate;
    audio.play().catch(() => {});  // no sound allowed: the wall clock plays on
  }
}
function pause() {
  timeSource.at = clock();
  timeSource.playing = false;
  if (audio) audio.pause();
}
function setRate(rate) {
  timeSource.at = clock();
  timeSource.origin = wall();
  timeSource.rate = rate;
  if (audio) {
    audio.preservesPitch = true;
    audio.playbackRate = rate;
  }
}
if (audio) {
  // The audio's clock moved by someone else (its own controls, a test driving it): follow it.
  audio.addEventListener("seeked", () => {
    if (!timeSource.playing) {
      timeSource.at = audio.currentTime - lead;
      draw(clock());
    }
  });
  // Past the song's end the dance goes on on the wall clock, from where the audio stopped.
  audio.addEventListener("ended", () => {
    timeSource.at = audio.duration - lead;
    timeSource.origin = wall();
  });
}

const round2 = (v) => Math.round(v * 100) / 100 + 0;
const fmt = (v) => String(round2(v));

// The studio (live.js) swaps in the data of the file as it was saved: the same object, so every
// function reading `page` sees the new dance; the clock itself (playing, its time, its rate) stays.
function replaceData(data) {
  for (const key of Object.keys(page)) delete page[key];
  Object.assign(page, data);
  endMs = Math.max(page.end, 1);
  lead = page.song ? page.song.downbeat : 0;
}
