// Real-time scheduling for the calling thread, for players that must hit deadlines on a busy
// machine. Opt-in (`seqc play --realtime`): a SCHED_FIFO thread pre-empts everything else, which
// is what a live stream wants and what a batch tool must not do uninvited.
#pragma once

#include "runtime/protocol/result.hpp"

namespace seqc::io {

// Puts the calling thread under SCHED_FIFO at a modest priority and sets its timer slack to
// the minimum, so sleeps end when asked. Fails (leaving the thread as it was) where the process
// lacks CAP_SYS_NICE or an RLIMIT_RTPRIO allowance; the message says how to grant one.
Status request_realtime_scheduling();

}  // namespace seqc::io
