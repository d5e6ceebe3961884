#include "runtime/upload/progress_text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>

namespace seqc::upload {
namespace {

std::string rate_text(const UploadProgress& p) {
  const double secs = std::chrono::duration<double>(p.elapsed).count();
  if (secs <= 0) return "";
  const double rate = static_cast<double>(p.bytes_sent + p.bytes_received) / secs;
  char buf[32];
  if (rate >= 1000) {
    std::snprintf(buf, sizeof buf, "%.1f kB/s", rate / 1000);
  } else {
    std::snprintf(buf, sizeof buf, "%.0f B/s", rate);
  }
  return buf;
}

// Time left from the rate so far; "" until there is something to go on.
std::string left_text(const UploadProgress& p) {
  if (p.frames_done == 0 || p.frames_done >= p.frames_total || p.elapsed <= io::Duration{0}) {
    return "";
  }
  const double secs = std::chrono::duration<double>(p.elapsed).count();
  const double left = secs * static_cast<double>(p.frames_total - p.frames_done) /
                      static_cast<double>(p.frames_done);
  const long s = std::lround(left);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%ld:%02ld left", s / 60, s % 60);
  return buf;
}

}  // namespace

std::string format_progress_bar(const UploadProgress& p, int width) {
  const std::size_t total = p.actions_total == 0 ? 1 : p.actions_total;
  const auto filled = static_cast<int>(p.actions_done * static_cast<std::size_t>(width) / total);
  std::string out = "[";
  out.append(static_cast<std::size_t>(filled), '#');
  out.append(static_cast<std::size_t>(width - filled), '.');
  out += "] ";
  char count[48];
  std::snprintf(count, sizeof count, "%zu/%zu actions", p.actions_done, p.actions_total);
  out += count;
  if (const std::string r = rate_text(p); !r.empty()) out += "  " + r;
  if (const std::string l = left_text(p); !l.empty()) out += "  " + l;
  return out;
}

int bar_cells_for(const UploadProgress& p, int columns) {
  if (columns <= 0) return 30;
  // The text after the bar, at its widest; one column spare so the cursor never wraps.
  const int text = static_cast<int>(format_progress_bar(p, 0).size()) - 3;
  return std::clamp(columns - text - 4, 5, 50);
}

std::string format_progress_line(const UploadProgress& p) {
  const std::size_t total = p.actions_total == 0 ? 1 : p.actions_total;
  char head[80];
  std::snprintf(head, sizeof head, "%zu/%zu actions acknowledged (%zu%%)", p.actions_done,
                p.actions_total, p.actions_done * 100 / total);
  std::string out = head;
  if (const std::string r = rate_text(p); !r.empty()) out += ", " + r;
  if (const std::string l = left_text(p); !l.empty()) out += ", about " + l;
  return out;
}

std::string format_retry(const RetryEvent& e) {
  return "re-sending " + e.what + ", attempt " + std::to_string(e.attempt) + " of " +
         std::to_string(e.max_attempts) + ": " + e.reason;
}

std::string format_restart(const RestartEvent& e) {
  return "restarting the download from step 1 (attempt " + std::to_string(e.attempt) + " of " +
         std::to_string(e.max_attempts) + "): " + e.reason;
}

ProgressPrinter::ProgressPrinter(std::ostream& err, bool terminal, int verbosity, int columns)
    : err_(err), terminal_(terminal), verbosity_(verbosity), columns_(columns) {}

ProgressPrinter::~ProgressPrinter() { finish(); }

void ProgressPrinter::finish() {
  if (bar_shown_) {
    err_ << '\n';
    err_.flush();
    bar_shown_ = false;
  }
}

void ProgressPrinter::message_line(const std::string& text) {
  if (bar_shown_) {
    err_ << "\r\033[K";  // clear the bar; it is redrawn on the next update
    bar_shown_ = false;
    last_bar_.clear();
  }
  err_ << "upload: " << text << '\n';
  err_.flush();
}

void ProgressPrinter::on_progress(const UploadProgress& p) {
  if (p.attempt != last_attempt_) {
    last_attempt_ = p.attempt;
    last_tenth_ = 0;
  }
  if (verbosity_ < 0) return;
  if (terminal_) {
    std::string bar = format_progress_bar(p, bar_cells_for(p, columns_));
    if (bar == last_bar_) return;
    last_bar_ = bar;
    err_ << "\r\033[K" << bar;
    err_.flush();
    bar_shown_ = true;
    return;
  }
  if (p.actions_total == 0) return;
  const std::size_t tenth = p.actions_done * 10 / p.actions_total;
  if (tenth <= last_tenth_ || p.actions_done == 0) return;
  last_tenth_ = tenth;
  message_line(format_progress_line(p));
}

void ProgressPrinter::on_retry(const RetryEvent& event) {
  if (verbosity_ > 0) message_line(format_retry(event));
}

void ProgressPrinter::on_restart(const RestartEvent& event) {
  if (verbosity_ >= 0) message_line(format_restart(event));
}

void ProgressPrinter::on_note(const std::string& note) {
  if (verbosity_ > 0) message_line(note);
}

}  // namespace seqc::upload
