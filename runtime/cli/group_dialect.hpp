// How a controller firmware stores and starts a group, as a strategy the upload commands are
// given: they never ask which board they talk to. The xArm / LSC-16 / LSC-32 dialect stores a
// group with GroupDownload steps 1-5 (upload::Uploader); the LSC-6 dialect with one
// DownloadAction per action (upload::upload_lsc6). Which one a plan needs is decided where the
// plan is made (backend::plan_download, by the robot's profile).
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "compiler/backend/servo_backend.hpp"
#include "runtime/io/clock.hpp"
#include "runtime/io/transport.hpp"
#include "runtime/upload/uploader.hpp"

namespace seqc::cli {

class GroupDialect {
 public:
  virtual ~GroupDialect() = default;
  // For messages: "xArm / LSC-16 / LSC-32", "LSC-6".
  virtual std::string board() const = 0;
  // Every frame the upload sends, as commented hex, one a line (`--dry-run`; `seqc decode`
  // reads it back). run_times: 0 = until stopped; ignored without run.
  virtual std::string session_hex(std::uint8_t group, bool run, std::uint16_t run_times) const = 0;
  virtual upload::UploadResult upload(io::Transport& transport, io::Clock& clock,
                                      const std::atomic<bool>* interrupted,
                                      const upload::UploadOptions& options,
                                      upload::UploadObserver* observer) const = 0;
  // What a run that the board did not confirm means on it.
  virtual std::string unconfirmed_run() const = 0;
  // Why the plan cannot go over `transport` (a frame larger than one write can carry, as over
  // USB HID), or "" when it can: checked before anything is sent.
  std::string too_big_for(const io::Transport& transport) const;

 protected:
  // Each frame of the download in send order, with what it is ("step 4 (action 3)").
  std::vector<std::pair<std::size_t, std::string>> frame_sizes_;
};

// The dialect `plan` (from backend::plan_download) is written in, holding the plan.
std::unique_ptr<GroupDialect> dialect_for(std::vector<backend::PlannedFrame> plan);

}  // namespace seqc::cli
