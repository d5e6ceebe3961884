// What `seqc upload` shows while it works: a progress bar redrawn in place on a terminal,
// plain lines (one per tenth of the actions) otherwise; with --verbose also every re-send,
// restart and skipped frame. Formatting is kept apart from the uploader so it can be
// golden-tested.
#pragma once

#include <cstddef>
#include <iosfwd>
#include <string>

#include "runtime/upload/uploader.hpp"

namespace seqc::upload {

// "[##########..........]  510/1020 actions  1.2 kB/s  0:12 left" (width = bar cells).
std::string format_progress_bar(const UploadProgress& p, int width = 30);
// The bar's cells so that the whole line fits in `columns` (30 when columns is 0).
int bar_cells_for(const UploadProgress& p, int columns);
// "510/1020 actions acknowledged (50%), 1.2 kB/s, about 0:12 left".
std::string format_progress_line(const UploadProgress& p);
// "re-sending step 4 (action 17 of 1020: block 0, index 16), attempt 2 of 5: no ..."
std::string format_retry(const RetryEvent& e);
// "restarting the download from step 1 (attempt 2 of 4): the controller refused ..."
std::string format_restart(const RestartEvent& e);

class ProgressPrinter final : public UploadObserver {
 public:
  // verbosity: -1 prints nothing, 0 progress, 1 also re-sends and notes. columns: the
  // terminal's width (0 = unknown), so the bar fits on one line.
  ProgressPrinter(std::ostream& err, bool terminal, int verbosity, int columns = 0);
  ~ProgressPrinter() override;

  void on_progress(const UploadProgress& progress) override;
  void on_retry(const RetryEvent& event) override;
  // Shown at every verbosity but --quiet: the user should know the upload started over.
  void on_restart(const RestartEvent& event) override;
  void on_note(const std::string& note) override;
  // Ends the bar's line (call before printing the result).
  void finish();

 private:
  void message_line(const std::string& text);

  std::ostream& err_;
  bool terminal_;
  int verbosity_;
  int columns_;
  bool bar_shown_ = false;
  std::string last_bar_;
  std::size_t last_tenth_ = 0;
  int last_attempt_ = 1;
};

}  // namespace seqc::upload
