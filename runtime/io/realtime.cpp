#include "runtime/io/realtime.hpp"

#include <pthread.h>
#include <sched.h>
#include <sys/prctl.h>
#include <cerrno>
#include <cstring>
#include <string>

namespace seqc::io {

Status request_realtime_scheduling() {
  // Low in the FIFO range: above every normal thread, below the kernel's own RT work.
  sched_param param{};
  param.sched_priority = 10;
  const int rc = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
  if (rc != 0) {
    std::string message = std::string("cannot use real-time scheduling: ") + std::strerror(rc);
    if (rc == EPERM) {
      message +=
          " (grant it with `sudo setcap cap_sys_nice+ep $(command -v seqc)`, or an rtprio limit "
          "in /etc/security/limits.conf)";
    }
    return make_error(std::move(message));
  }
  // The default 50 us slack would be added to every wake-up.
  (void)prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
  return Ok{};
}

Status SystemScheduler::raise() {
  sched_param param{};
  if (const int rc = pthread_getschedparam(pthread_self(), &policy_, &param); rc != 0) {
    return make_error(std::string("cannot use real-time scheduling: ") + std::strerror(rc));
  }
  priority_ = param.sched_priority;
  // PR_GET_TIMERSLACK returns the slack itself.
  const int slack = prctl(PR_GET_TIMERSLACK, 0UL, 0UL, 0UL, 0UL);
  slack_ns_ = slack > 0 ? static_cast<unsigned long>(slack) : 0UL;
  return request_realtime_scheduling();
}

void SystemScheduler::lower() {
  sched_param param{};
  param.sched_priority = priority_;
  // Leaving SCHED_FIFO needs no privilege; a slack of 0 (not read) restores the default.
  (void)pthread_setschedparam(pthread_self(), policy_, &param);
  (void)prctl(PR_SET_TIMERSLACK, slack_ns_, 0UL, 0UL, 0UL);
}

RealtimeScope::RealtimeScope(Scheduler* scheduler, bool wanted) {
  if (!wanted) return;
  if (scheduler == nullptr) {
    system_ = std::make_unique<SystemScheduler>();
    scheduler = system_.get();
  }
  scheduler_ = scheduler;
  status_ = scheduler_->raise();
  raised_ = status_.ok();
}

RealtimeScope::~RealtimeScope() {
  if (raised_) scheduler_->lower();
}

}  // namespace seqc::io
