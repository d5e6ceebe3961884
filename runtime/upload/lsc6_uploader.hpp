// Stores a group in an LSC-6 board (docs/protocol/lsc-6.md, "Storing a group") and, when
// asked, starts it.
//
// Sequence
//   1. Stop (no answer): a playing group reads the flash that is about to be rewritten.
//   2. one DownloadAction per action, stop-and-wait: a frame, its 55 55 02 19, the next. The
//      board holds a single frame while it writes flash and drops one more, so nothing is sent
//      ahead. Deadlines are the wire time of the frame and its answer plus a margin; index 0
//      gets a longer one (the board erases the group's four flash sectors first) and so does
//      the last (it rewrites the count table).
//   3. Run (with `run`), waiting briefly for 55 55 02 06: copies of the firmware that never
//      answer Run leave the start unconfirmed, which is reported as such, not as a failure.
//      Run is sent only after every action was answered. Ctrl-C while waiting for its answer
//      ends the upload Interrupted and sends Stop: the group is stored, the robot must not move.
// The board has no battery or any other command with an answer that could serve as a probe or
// a barrier, so the first frame is the probe: no answer to it after every re-send means no
// board (NoAnswer). When index 0's first sending goes unanswered, GetBatteryVoltage follows
// once: the LSC-6 ignores it, while a controller of the xArm dialect (which has no command 25)
// answers with its voltage, and the upload ends at once (OtherDialect, group unchanged) rather
// than re-sending for every attempt.
//
// Pairing. An answer names no index. Every frame carries its own group, total and index, so
// sending one again is harmless (the same bytes land in the same flash slot; index 0 erases the
// group again). What must not happen is a late answer being taken for the next frame's: after a
// frame needed more than one sending, the uploader waits one more deadline for the answers it
// may still be owed before sending on. An answer that arrives when none is owed shows that
// pairing was off: the download restarts from index 0 (at most `restarts` times).
//
// Never sent: EraseAll (it wipes every group on the board).
// Group state when an upload ends early: the board erases the group's actions at index 0 but
// writes its action count only with the last index, so from index 0 on the group keeps its old
// count over erased or partly rewritten actions (running it stops at the first erased one).
//
// The uploader never sleeps or reads the wall clock: time comes from the link's clock.
#pragma once

#include <vector>

#include "protocol/lsc6/lsc6_messages.hpp"
#include "protocol/planned_frame.hpp"
#include "runtime/upload/lsc6_link.hpp"
#include "runtime/upload/uploader.hpp"

namespace seqc::upload {

// Margins for the LSC-6 beyond UploadOptions::reply_margin: index 0 waits for four sector
// erases (400 ms each at the slowest parts' datasheet maximum), the last index for one more and
// the count table's write.
inline constexpr io::Duration kLsc6EraseMargin = std::chrono::milliseconds(2000);
inline constexpr io::Duration kLsc6CommitMargin = std::chrono::milliseconds(1000);

// `plan` holds DownloadActions as plan_frames() encodes them.
UploadResult upload_lsc6(Lsc6Link& link, const std::vector<PlannedFrame>& plan,
                         const UploadOptions& options, UploadObserver* observer = nullptr);
// The same for lsc6::plan_download's actions (encoded with plan_frames()).
UploadResult upload_lsc6(Lsc6Link& link, const std::vector<lsc6::DownloadAction>& plan,
                         const UploadOptions& options, UploadObserver* observer = nullptr);

}  // namespace seqc::upload
