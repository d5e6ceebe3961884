// What `seqc upload` prints while it works: bar, plain lines, retries.
#include <gtest/gtest.h>

#include <chrono>
#include <sstream>

#include "runtime/upload/progress_text.hpp"

namespace seqc::upload {
namespace {

using namespace std::chrono_literals;

UploadProgress at(std::size_t done, io::Duration elapsed) {
  UploadProgress p;
  p.actions_done = done;
  p.actions_total = 1020;
  p.frames_done = done + 6;
  p.frames_total = 1027;
  p.bytes_sent = done * 29;
  p.bytes_received = done * 6;
  p.elapsed = elapsed;
  return p;
}

TEST(ProgressText, Bar) {
  EXPECT_EQ(format_progress_bar(at(510, 18s), 20),
            "[##########..........] 510/1020 actions  992 B/s  0:18 left");
  EXPECT_EQ(format_progress_bar(at(0, 0s), 4), "[....] 0/1020 actions");
}

TEST(ProgressText, Line) {
  EXPECT_EQ(format_progress_line(at(102, 4s)),
            "102/1020 actions acknowledged (10%), 892 B/s, about 0:34 left");
}

TEST(ProgressText, Retry) {
  EXPECT_EQ(format_retry({"step 4 (action 17 of 1020: block 0, index 16)", 2, 5,
                          "no acknowledgement within 0.536 s"}),
            "re-sending step 4 (action 17 of 1020: block 0, index 16), attempt 2 of 5: no "
            "acknowledgement within 0.536 s");
}

TEST(ProgressPrinter, RestartsAreShownUnlessQuiet) {
  std::ostringstream normal, quiet;
  ProgressPrinter n(normal, false, 0), q(quiet, false, -1);
  const RestartEvent e{2, 4, "the port hung up; the device came back on /dev/ttyUSB0"};
  n.on_restart(e);
  q.on_restart(e);
  EXPECT_EQ(normal.str(),
            "upload: restarting the download from step 1 (attempt 2 of 4): the port hung up; the "
            "device came back on /dev/ttyUSB0\n");
  EXPECT_EQ(quiet.str(), "");
}

TEST(ProgressPrinter, PlainLinesEveryTenthAndRetriesOnlyWhenVerbose) {
  std::ostringstream quiet, verbose;
  ProgressPrinter q(quiet, false, 0), v(verbose, false, 1);
  for (std::size_t i = 0; i <= 1020; i += 51) {
    q.on_progress(at(i, std::chrono::milliseconds(i * 36)));
    v.on_progress(at(i, std::chrono::milliseconds(i * 36)));
    if (i == 102) {
      q.on_retry({"barrier (battery voltage)", 2, 5, "no reply within 0.506 s"});
      v.on_retry({"barrier (battery voltage)", 2, 5, "no reply within 0.506 s"});
    }
  }
  const std::string qs = quiet.str();
  EXPECT_EQ(std::count(qs.begin(), qs.end(), '\n'), 10);
  EXPECT_EQ(qs.find("re-sending"), std::string::npos);
  EXPECT_NE(verbose.str().find("upload: re-sending barrier (battery voltage), attempt 2 of 5"),
            std::string::npos);
  EXPECT_NE(qs.find("upload: 1020/1020 actions acknowledged (100%)"), std::string::npos);
}

TEST(ProgressPrinter, TerminalRedrawsOneLine) {
  std::ostringstream err;
  {
    ProgressPrinter p(err, true, 0);
    p.on_progress(at(1, 1s));
    p.on_progress(at(2, 2s));
  }
  const std::string s = err.str();
  EXPECT_EQ(std::count(s.begin(), s.end(), '\n'), 1);  // the final newline only
  EXPECT_EQ(std::count(s.begin(), s.end(), '\r'), 2);
}

}  // namespace
}  // namespace seqc::upload
