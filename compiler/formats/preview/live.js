// The studio's page (`seqc studio`, runtime/studio/server.hpp): the preview page, live. It runs
// after the preview's script, in a <script> of its own that carries the version of the dance the
// page was served with (data-version). The server pushes every compile of the file as an event
// (/events): a good one's whole page, of which the data, the lanes, the title and the song are
// swapped into this one in place (the clock, the loop, the speed and the scroll stay); a bad
// one's diagnostics, shown in a box while the last good dance stays. The playhead goes back to
// the server (/playhead) when it plays, pauses, jumps or wraps round a loop, and what the robot
// following it says comes back under the controls. Every request carries the page's token.
const studio = {
  token: new URLSearchParams(location.search).get("token") || "",
  version: +document.currentScript.dataset.version,
};
const studioUrl = (path) => `${path}?token=${encodeURIComponent(studio.token)}`;

// The diagnostics and the robot's words float over the bottom of the page, so that the picture
// (whose place on the page is part of its contract) does not move when they come and go.
function studioBox(id, css) {
  const box = document.createElement(id === "studio-errors" ? "pre" : "div");
  box.id = id;
  box.hidden = true;
  box.style.cssText = "position:fixed;left:0;right:0;margin:0;padding:6px 8px;" +
    "font:12px monospace;white-space:pre-wrap;overflow:auto;z-index:1;" + css;
  document.body.appendChild(box);
  return box;
}
const errorBox = studioBox("studio-errors",
  "bottom:0;max-height:45vh;background:#fef2f2;color:#991b1b;border-top:2px solid #dc2626;");
const followerLine = studioBox("studio-follower",
  "top:48px;background:#fffbeb;color:#92400e;border-bottom:1px solid #f59e0b;");

// The file's diagnostics as text (textContent: nothing in them is read as markup), red while the
// file has errors and the page shows the last good dance, amber for warnings alone.
function showDiagnostics(text, ok) {
  errorBox.textContent = ok ? text : "the page shows the last good version of the file\n\n" + text;
  errorBox.style.color = ok ? "#92400e" : "#991b1b";
  errorBox.style.background = ok ? "#fffbeb" : "#fef2f2";
  errorBox.hidden = text === "";
}

// A page the data cannot be swapped into (a song came or went): reload it at the same instant.
function reloadAt(seconds) {
  location.hash = `t=${seconds.toFixed(3)}`;
  location.reload();
}

function applyUpdate(update) {
  if (update.version < studio.version) return;
  showDiagnostics(update.errors, update.ok);
  if (update.version === studio.version || !update.page) return;
  studio.version = update.version;
  const doc = new DOMParser().parseFromString(update.page, "text/html");
  const song = doc.getElementById("song"), old = $("song");
  const t = clock();
  if (!song !== !old) {
    reloadAt(t);
    return;
  }
  replaceData(JSON.parse(doc.getElementById("seqc-data").textContent));
  $("all-lanes").innerHTML = doc.getElementById("all-lanes").innerHTML;
  $("scrub").max = doc.getElementById("scrub").max;
  $("title").textContent = doc.getElementById("title").textContent;
  document.title = doc.title;
  rebuild();
  const newSong = song && song.getAttribute("src") !== old.getAttribute("src");
  if (newSong) old.src = song.getAttribute("src");
  if (!timeSource.playing || newSong) seek(Math.min(t, endMs / 1000));
  if (newSong && timeSource.playing) play();
  draw(clock());
  document.body.dataset.studioVersion = studio.version;
}

// ---- the playhead, to the server and the robot following it.
function showFollower(state) {
  const words = [];
  if (state.slewing) {
    words.push(`the robot is catching up (until ${(state.slew_until_ms / 1000).toFixed(2)} s)`);
  }
  for (const notice of state.notices || []) words.push(notice);
  followerLine.textContent = words.join("\n");
  followerLine.hidden = words.length === 0;
}

function report(ms, mode, looped) {
  fetch(studioUrl("/playhead"), {
    method: "POST",
    headers: { "Content-Type": "application/json" },
    body: JSON.stringify({ ms: Math.round(ms * 10) / 10, mode, looped }),
  }).then((r) => (r.ok ? r.json() : {})).then(showFollower).catch(() => {});
}

// Watched every 50 ms rather than hooked into each control, so that every way the clock moves
// (the buttons, the keys, the slider, the lanes, the song's own controls, a loop) is seen alike:
// a change of playing is a play or a pause; a time away from where the clock should be is a jump
// (a scrub), or the loop's wrap when it lands on the loop's start while playing.
const last = { playing: timeSource.playing, ms: clock() * 1000, at: performance.now() };
function watchPlayhead() {
  const ms = clock() * 1000, now = performance.now(), playing = timeSource.playing;
  const expected = last.playing ? last.ms + (now - last.at) * timeSource.rate : last.ms;
  if (playing !== last.playing) {
    report(ms, playing ? "playing" : "paused", false);
  } else if (Math.abs(ms - expected) > 150) {
    const range = loopRange();
    if (playing && range && ms < expected && Math.abs(ms - range[0]) < 200) {
      report(ms, "playing", true);
    } else {
      report(ms, "scrubbed", false);
      if (playing) report(ms, "playing", false);
    }
  }
  Object.assign(last, { playing, ms, at: now });
}
setInterval(watchPlayhead, 50);
// While the page is open it says so; the server also counts its open event stream, which a
// hidden tab's slowed timers cannot hold up.
setInterval(() => fetch(studioUrl("/heartbeat"), { method: "POST" }).catch(() => {}), 2000);
window.addEventListener("beforeunload", () => navigator.sendBeacon(studioUrl("/stop")));

const events = new EventSource(studioUrl("/events"));
events.onmessage = (e) => applyUpdate(JSON.parse(e.data));
document.body.dataset.studioVersion = studio.version;
