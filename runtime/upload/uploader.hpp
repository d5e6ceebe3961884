// Uploads a GroupDownload plan (lsc::plan_group_download) into the servo controller and,
// when asked, starts the group with GroupRun.
//
// Sequence
//   1. probe: GetBatteryVoltage until it is answered (retried). Nothing answers: one LSC-6
//      DownloadAction into slot 255 with a total of 1 (below), and its answer 55 55 02 19 ->
//      OtherDialect (an LSC-6 board, which ignores GetBatteryVoltage); else NoAnswer.
//   2. GroupStop (no reply), then a barrier, so a running group is stopped before flash is
//      erased and the controller has finished with the stop before step 1 arrives.
//   3. steps 1-5, stop-and-wait: one frame, its acknowledgement, then the next. Each wait has
//      a deadline of (frame + ack bytes) x seconds_per_byte + a margin; step 1 gets a longer
//      margin because the controller erases flash first. A frame is re-sent at most
//      `retries` times; every re-send is reported to the observer.
//   4. a final barrier after step 5's acknowledgement (see below).
//   5. GroupRun, only if the download and the final barrier succeeded and `run` is set.
//
// A barrier is GetBatteryVoltage: the controller answers in the order it receives, so once
// its reply arrives, every acknowledgement of an earlier frame has arrived too. Acks that
// arrive before the barrier's reply are discarded. A dropped barrier is re-sent.
//
// Why acknowledgements cannot be mis-paired (an ack "<step> 00" does not say which action
// it is for, and a shifted upload is the worst outcome):
//   (a) Every ack's step number is checked; an ack for another step is never accepted.
//   (b) Before each frame is sent, replies that have already arrived are drained; an extra
//       ack found there (a duplicate) is discarded. The ack of the previous frame was already
//       taken, so nothing the controller still owes us is outstanding.
//   (c) After any re-send, the next frame is sent only after a barrier: a late ack of an
//       earlier attempt is absorbed by the barrier and cannot be taken for the next frame.
//   (d) If anything shows that pairing was off -- an ack for an earlier step while waiting
//       outside a barrier, an ack for another step inside a barrier, or any extra ack before
//       the final barrier's reply that a re-send of step 5 does not explain -- the attempt is
//       abandoned and the whole download restarts at step 1 (which erases: restarting is
//       idempotent). Success is reported only after an attempt with no such evidence.
// Restarts: mis-pairing (d), a frame that no re-send got through, a refusal that may come
// from a controller reset, and a port that hung up and came back all restart the download
// from step 1, at most `restarts` times in all; each restart is reported to the observer
// (on_restart) with its reason. When the budget is spent the upload fails with the status of
// the last cause (Inconsistent, NoAck or Refused).
//
// Against each fault:
//   drop        the frame (or its ack) is lost: deadline, re-send, barrier (c).
//   corrupt     a request with broken framing is ignored by the controller = drop. A corrupted
//               reply is skipped as garbage (decoder resync) = drop; if it still decodes as an
//               ack, a step that was never sent in this attempt is ignored, an earlier step
//               restarts (d), and a refusal is confirmed (below), so a flipped status byte does
//               not end the upload.
//   late ack    arrives after the deadline: the re-sent frame is either stored or, for step 4,
//               re-acked by the controller as a repeat; whichever ack comes first is taken
//               (same step, same frame). The other is absorbed by the late-ack guard (acks of
//               that step are discarded until late_guard after the frame was first sent) and
//               the barrier (c) after it.
//   duplicate   drained before the next send (b); if it arrives later and is taken for the
//               next frame, the real ack of that frame is left over and shows up as a
//               wrong-step ack, a drained extra ack, or an extra ack at the final barrier (d).
//               Whatever was sent early and dropped by the busy controller leaves a gap in
//               the sequence, which the controller refuses.
//   busy-drop   only happens if a frame is sent before the previous one was processed, i.e.
//               after a mis-paired ack; it is then seen as in "duplicate".
//   silence     every re-send of a frame times out: after `retries` the download restarts
//               from step 1 (a busy or briefly deaf controller); a controller that stays
//               silent then fails the restart's first barrier (NoAck).
//   hang-up     the link reports HangUp: the transport is asked to reopen the same device
//               (Transport::reopen, waiting up to `reopen_wait`); if it comes back the
//               download restarts from the probe, else the upload ends (HangUp).
//   refusal     "<step> xx" with xx != 00 for the frame being waited on: after a barrier the
//               same frame is sent once more. Accepted then: the first was a corrupted ack.
//               Refused again: for step 1, or for a frame already refused twice in an earlier
//               attempt, that is the controller's answer (Refused). Otherwise the refusal may
//               be our own doing (a mis-paired ack let a frame go out while the controller was
//               busy; it was dropped and the next one is refused for the gap) or a controller
//               reset (below), so the download restarts.
//   reset       a power dip mid-download: the controller forgets the download in progress and
//               answers as after boot, so it refuses the next step 2-5 frame (no download is
//               open). That is the refusal above: the download restarts from step 1.
//   reordering  the emulator (and perhaps a real board) may send a late ack after a later
//               reply, so a barrier cannot absorb it; it is then taken as a later frame's
//               ack and shows up as the gap refusal above -> restart. Reply margins are
//               chosen longer than ordinary lateness, so this needs a very late ack.
//   Ctrl-C      the interrupt flag is polled between frames and in every wait slice (<= 100 ms
//               of the link's clock): Interrupted. Before returning, the controller is put in a
//               known state: GroupStop if a group may be playing (GroupRun was sent, or the
//               upload had not yet stopped the group that was playing), and GroupErase of the
//               group if step 5 was sent but its storing was not confirmed, so a group written
//               only in part is never left looking complete (UploadResult says which was sent).
//               The erase is confirmed only by its reply (55 55 02 08), awaited for step 1's
//               deadline (the controller erases flash before it answers) on the link's clock,
//               whatever the interrupt flag says; a controller still busy with step 5 drops
//               the erase, so without the reply the group counts as Uncertain, not Empty.
// Group state when an upload ends early: before step 1 was acknowledged the group is
// unchanged (or, if step 1 was sent, possibly erased); after it, the group is empty: the
// controller only makes it valid at step 5.
//
// The LSC-6 question. The LSC-6 answers nothing but Run, EraseAll and DownloadAction; the first
// two would start or wipe groups. A DownloadAction with index 255 and total 1 writes slot 255
// of the group about to be replaced, which no group plays (a group holds at most 255 actions,
// indices 0-254), neither erases the group (index 0 does) nor writes its action count (the last
// index does), and the xArm dialect has no command 25 (docs/protocol/lsc-6.md). It is sent only
// after the battery question went unanswered every time, so a working xArm never sees it.
//
// The uploader never sleeps or reads the wall clock: time comes from the link's Clock.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "runtime/io/clock.hpp"
#include "protocol/lsc/lsc_messages.hpp"
#include "protocol/planned_frame.hpp"
#include "runtime/upload/controller_link.hpp"

namespace seqc::upload {

struct UploadOptions {
  std::uint8_t group = 0;  // must match the plan's group
  int retries = 4;         // re-sends of one frame after its first attempt
  int restarts = 3;        // whole-download restarts, all causes together (see above)
  // How long a port that hung up is given to come back (Transport::reopen).
  io::Duration reopen_wait = std::chrono::seconds(10);
  // The late-ack guard: after a frame was re-sent for want of an acknowledgement, its first
  // sending may still be acknowledged late, after the barrier's reply, where it would be
  // taken for the next frame's. Until this long after the first sending, acknowledgements of
  // that step are discarded before the next frame goes out.
  io::Duration late_guard = std::chrono::seconds(1);
  // Added to the wire time of a frame and its reply to give the reply's deadline.
  io::Duration reply_margin = std::chrono::milliseconds(500);
  // Step 1's margin: the controller erases the group's flash before it acknowledges.
  io::Duration open_margin = std::chrono::seconds(3);
  bool run = false;             // send GroupRun after a successful download
  std::uint16_t run_times = 1;  // GroupRun's count; 0 = loop until stopped
  // Asked over the upload's own transport and clock after the download, just before the run is
  // sent: false leaves the group stored and not started (UploadResult::run_refused). Commands
  // read the servos here so that a first move too fast from where the robot is never starts.
  std::function<bool(io::Transport&, io::Clock&)> may_run;
};

enum class UploadStatus {
  Completed,     // every step acknowledged and the final barrier clean (GroupRun sent if asked)
  BadPlan,       // the plan is not a GroupDownload for options.group; nothing was sent
  NoAnswer,      // the probe was never answered
  NoAck,         // a frame was not acknowledged after all re-sends
  Refused,       // the controller refused a frame twice
  Inconsistent,  // acknowledgements stayed mis-paired after every restart
  HangUp,        // the device went away
  Interrupted,   // Ctrl-C
  LinkError,     // a write or read failed
  // The board answered in the family's other storing dialect (an LSC-6 to the xArm uploader,
  // an xArm-family controller to the LSC-6 uploader); nothing was stored.
  OtherDialect,
};
const char* to_string(UploadStatus status);

// What is known about the group on the controller when the upload ended.
enum class GroupState {
  Unchanged,    // no step 1 was sent
  MaybeErased,  // step 1 was sent but never acknowledged
  Empty,        // step 1 was acknowledged; the group is erased until a step 5 arrives
  Uncertain,    // step 5 was acknowledged, but pairing was not confirmed afterwards
  Stored,       // Completed: the controller acknowledged every action
  OldCount,     // LSC-6: the group's actions were erased, its old action count stays
};

// One sentence about the group's state, e.g. "group 0 is now empty".
std::string describe_group_state(GroupState state, std::uint8_t group);

struct UploadProgress {
  std::size_t actions_done = 0;  // step-4 acks taken in the current attempt
  std::size_t actions_total = 0;
  std::size_t frames_done = 0;  // steps 1-5 acknowledged in the current attempt
  std::size_t frames_total = 0;
  std::size_t bytes_sent = 0;  // on the link since the upload began (all attempts)
  std::size_t bytes_received = 0;
  io::Duration elapsed{0};  // since the upload began, on the link's clock
  int attempt = 1;          // 1 + restarts so far
};

struct RestartEvent {
  int attempt = 2;  // the attempt about to be made
  int max_attempts = 0;
  std::string reason;  // "the controller refused step 4 (...) twice"
};

struct RetryEvent {
  // "step 4 (action 17 of 1020: block 0, index 16)", "probe (battery voltage)",
  // "barrier (battery voltage)"
  std::string what;
  int attempt = 2;  // the attempt about to be made (2 = first re-send)
  int max_attempts = 0;
  std::string reason;  // "no acknowledgement within 0.536 s"
};

class UploadObserver {
 public:
  virtual ~UploadObserver() = default;
  virtual void on_progress(const UploadProgress& /*progress*/) {}
  virtual void on_retry(const RetryEvent& /*event*/) {}
  // The download starts again from step 1 (or from the probe, after the port came back).
  virtual void on_restart(const RestartEvent& /*event*/) {}
  // Restarts, stale acks discarded, notifications, skipped frames: for verbose output.
  virtual void on_note(const std::string& /*note*/) {}
};

struct UploadResult {
  UploadStatus status = UploadStatus::BadPlan;
  std::string message;  // for the user when status != Completed
  GroupState group_state = GroupState::Unchanged;
  std::size_t actions_total = 0;
  std::size_t actions_acknowledged = 0;     // in the last attempt
  std::optional<std::uint16_t> battery_mv;  // from the probe
  int retries = 0;                          // re-sends of frames and barriers, all attempts
  int restarts = 0;                         // whole-download restarts
  int reopens = 0;                          // times the port hung up and came back
  std::size_t stale_acks = 0;               // acks discarded by barriers and drains
  bool run_sent = false;
  bool run_reported = false;  // the controller announced the group started
  bool run_refused = false;   // options.may_run said no: stored, not started
  // Interrupted: what was sent to leave the controller in a known state.
  bool stop_sent = false;        // GroupStop: no group is playing
  bool erase_sent = false;       // GroupErase of the group: step 5 was sent but not confirmed
  bool erase_confirmed = false;  // the controller answered that GroupErase (group empty)
  io::Duration elapsed{0};
  LinkStats link;

  bool ok() const { return status == UploadStatus::Completed; }
};

class Uploader {
 public:
  Uploader(ControllerLink& link, UploadOptions options, UploadObserver* observer = nullptr);

  // Runs the whole sequence for `plan` (steps 1..5 as plan_frames() encodes them).
  UploadResult upload(const std::vector<PlannedFrame>& plan);
  // The same for steps 1..5 as plan_group_download returns them (encoded with plan_frames()).
  UploadResult upload(const std::vector<lsc::Request>& plan);

  // Reply deadline for a frame of `frame_bytes` whose reply is `reply_bytes` long.
  io::Duration reply_timeout(std::size_t frame_bytes, std::size_t reply_bytes, bool open) const;

 private:
  class Run;
  ControllerLink& link_;
  UploadOptions options_;
  UploadObserver* observer_;
};

}  // namespace seqc::upload
