// The system's scheduler: raise() puts the calling thread under SCHED_FIFO at priority 10 with a
// 1 ns timer slack, and lower() gives back exactly the policy, priority and slack it had. Where
// the process may not use SCHED_FIFO (no CAP_SYS_NICE, no rtprio limit) the refusal is checked
// instead: an error that leaves the thread as it was.
#include <gtest/gtest.h>
#include <pthread.h>
#include <sched.h>
#include <sys/prctl.h>

#include <thread>

#include "runtime/io/realtime.hpp"

namespace seqc::io {
namespace {

struct ThreadState {
  int policy = -1;
  int priority = -1;
  int slack = -1;
};

ThreadState state_now() {
  ThreadState s;
  sched_param param{};
  EXPECT_EQ(pthread_getschedparam(pthread_self(), &s.policy, &param), 0);
  s.priority = param.sched_priority;
  s.slack = prctl(PR_GET_TIMERSLACK, 0UL, 0UL, 0UL, 0UL);
  return s;
}

// On a thread of its own, so the test runner's thread is never left raised.
template <class F>
void on_own_thread(F f) {
  std::thread t(f);
  t.join();
}

TEST(Realtime, SystemSchedulerRaisesThenGivesBackWhatTheThreadHad) {
  on_own_thread([] {
    // A slack the default (50 000 ns) is not, so giving it back is seen.
    ASSERT_EQ(prctl(PR_SET_TIMERSLACK, 70000UL, 0UL, 0UL, 0UL), 0);
    const ThreadState before = state_now();
    ASSERT_EQ(before.policy, SCHED_OTHER);
    ASSERT_EQ(before.slack, 70000);
    SystemScheduler scheduler;
    const Status raised = scheduler.raise();
    if (!raised) {
      const ThreadState after = state_now();
      EXPECT_EQ(after.policy, SCHED_OTHER);
      EXPECT_EQ(after.slack, 70000);
      EXPECT_EQ(raised.error().message.rfind("cannot use real-time scheduling: ", 0), 0u);
      GTEST_SKIP() << "SCHED_FIFO refused here: " << raised.error().message;
    }
    const ThreadState during = state_now();
    EXPECT_EQ(during.policy, SCHED_FIFO);
    EXPECT_EQ(during.priority, 10);
    // 1 ns as set, or 0 where the kernel gives real-time threads no slack at all (recent kernels).
    EXPECT_LE(during.slack, 1);
    scheduler.lower();
    const ThreadState after = state_now();
    EXPECT_EQ(after.policy, SCHED_OTHER);
    EXPECT_EQ(after.priority, 0);
    EXPECT_EQ(after.slack, 70000);
  });
}

TEST(Realtime, ScopeLowersOnlyWhatItRaised) {
  struct Counting final : Scheduler {
    bool grant = true;
    int raises = 0, lowers = 0;
    Status raise() override {
      ++raises;
      if (!grant) return make_error("refused");
      return Ok{};
    }
    void lower() override { ++lowers; }
  };
  Counting c;
  {
    RealtimeScope unwanted(&c, false);
    EXPECT_TRUE(unwanted.status().ok());
  }
  EXPECT_EQ(c.raises, 0);
  EXPECT_EQ(c.lowers, 0);
  {
    RealtimeScope granted(&c, true);
    EXPECT_TRUE(granted.status().ok());
    EXPECT_EQ(c.lowers, 0);  // still raised inside the scope
  }
  EXPECT_EQ(c.raises, 1);
  EXPECT_EQ(c.lowers, 1);
  c.grant = false;
  {
    RealtimeScope refused(&c, true);
    ASSERT_FALSE(refused.status().ok());
    EXPECT_EQ(refused.status().error().message, "refused");
  }
  EXPECT_EQ(c.raises, 2);
  EXPECT_EQ(c.lowers, 1);  // a refusal left nothing to give back
}

}  // namespace
}  // namespace seqc::io
