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

}  // namespace seqc::io
