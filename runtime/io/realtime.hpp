// Real-time scheduling for the calling thread, for players that must hit deadlines on a busy
// machine. Opt-in (`seqc play --realtime`, `seqc upload --run --realtime`, `seqc show
// --realtime`): a SCHED_FIFO thread pre-empts everything else, which is what a live stream or a
// start on a downbeat wants and what a batch tool must not do uninvited. The scheduler is an
// interface, so a test can refuse it; RealtimeScope holds real-time priority over the stretch of
// a command that keeps time and gives it back after.
#pragma once

#include <memory>

#include "base/result.hpp"

namespace seqc::io {

// Puts the calling thread under SCHED_FIFO at a modest priority and sets its timer slack to
// the minimum, so sleeps end when asked. Fails (leaving the thread as it was) where the process
// lacks CAP_SYS_NICE or an RLIMIT_RTPRIO allowance; the message says how to grant one.
Status request_realtime_scheduling();

// The calling thread's scheduling class.
class Scheduler {
 public:
  virtual ~Scheduler() = default;
  // Real-time for the calling thread; an Error (the thread as it was) when refused.
  virtual Status raise() = 0;
  // The calling thread back as it was before the last raise() that succeeded.
  virtual void lower() = 0;
};

// The system's: request_realtime_scheduling(), after keeping the thread's policy, priority and
// timer slack for lower().
class SystemScheduler final : public Scheduler {
 public:
  Status raise() override;
  void lower() override;

 private:
  int policy_ = 0;
  int priority_ = 0;
  unsigned long slack_ns_ = 0;
};

// Real-time for the calling thread from construction to destruction when `wanted` (a thread
// that is refused stays as it was; status() says why). `scheduler` null: the system's.
class RealtimeScope {
 public:
  RealtimeScope(Scheduler* scheduler, bool wanted);
  ~RealtimeScope();
  RealtimeScope(const RealtimeScope&) = delete;
  RealtimeScope& operator=(const RealtimeScope&) = delete;
  const Status& status() const { return status_; }

 private:
  std::unique_ptr<SystemScheduler> system_;
  Scheduler* scheduler_ = nullptr;
  Status status_ = Ok{};
  bool raised_ = false;
};

}  // namespace seqc::io
