#include "runtime/cli/group_dialect.hpp"

#include <fmt/format.h>

#include "runtime/cli/session_text.hpp"
#include "runtime/protocol/group_download.hpp"
#include "runtime/upload/controller_link.hpp"
#include "runtime/upload/lsc6_link.hpp"
#include "runtime/upload/lsc6_uploader.hpp"

namespace seqc::cli {
namespace {

class XarmDialect final : public GroupDialect {
 public:
  explicit XarmDialect(std::vector<lsc::Request> plan) : plan_(std::move(plan)) {
    std::size_t action = 0;
    for (const lsc::Request& r : plan_) {
      const int step = lsc::group_download_step(r);
      const std::string what = step == 4 ? "step 4 (action " + std::to_string(++action) + ")"
                                         : "step " + std::to_string(step);
      frame_sizes_.emplace_back(lsc::encode_serial(r).value().size(), what);
    }
  }
  std::string board() const override { return "xArm / LSC-16 / LSC-32"; }
  std::string session_hex(std::uint8_t group, bool run, std::uint16_t times) const override {
    return upload_session_hex(plan_, group, run, times);
  }
  upload::UploadResult upload(io::Transport& transport, io::Clock& clock,
                              const std::atomic<bool>* interrupted,
                              const upload::UploadOptions& options,
                              upload::UploadObserver* observer) const override {
    upload::ControllerLink link(transport, clock, interrupted);
    return upload::Uploader(link, options, observer).upload(plan_);
  }
  std::string unconfirmed_run() const override { return "it did not report starting it"; }

 private:
  std::vector<lsc::Request> plan_;
};

class Lsc6Dialect final : public GroupDialect {
 public:
  explicit Lsc6Dialect(std::vector<lsc6::DownloadAction> plan) : plan_(std::move(plan)) {
    for (const lsc6::DownloadAction& a : plan_) {
      frame_sizes_.emplace_back(lsc6::encode_serial(lsc6::Request{a}).value().size(),
                                "action " + std::to_string(a.index + 1));
    }
  }
  std::string board() const override { return "LSC-6"; }
  std::string session_hex(std::uint8_t group, bool run, std::uint16_t times) const override {
    return lsc6_session_hex(plan_, group, run, times);
  }
  upload::UploadResult upload(io::Transport& transport, io::Clock& clock,
                              const std::atomic<bool>* interrupted,
                              const upload::UploadOptions& options,
                              upload::UploadObserver* observer) const override {
    upload::Lsc6Link link(transport, clock, interrupted);
    return upload::upload_lsc6(link, plan_, options, observer);
  }
  std::string unconfirmed_run() const override {
    return "it did not answer Run, as some copies of the LSC-6 firmware never do: started, "
           "unconfirmed";
  }

 private:
  std::vector<lsc6::DownloadAction> plan_;
};

}  // namespace

std::string GroupDialect::too_big_for(const io::Transport& transport) const {
  const std::size_t limit = transport.max_frame_bytes();
  if (limit == 0) return "";
  for (const auto& [size, what] : frame_sizes_) {
    if (size > limit) {
      return what + " is a " + std::to_string(size) + "-byte frame, and " + transport.describe() +
             " carries at most " + std::to_string(limit) +
             " bytes in one report; nothing was sent (a serial port takes any frame)";
    }
  }
  return "";
}

std::unique_ptr<GroupDialect> dialect_for(std::vector<backend::PlannedFrame> plan) {
  if (!plan.empty() && std::holds_alternative<lsc6::Request>(plan.front().request)) {
    std::vector<lsc6::DownloadAction> actions;
    for (backend::PlannedFrame& f : plan) {
      actions.push_back(std::get<lsc6::DownloadAction>(std::get<lsc6::Request>(f.request)));
    }
    return std::make_unique<Lsc6Dialect>(std::move(actions));
  }
  std::vector<lsc::Request> requests;
  for (backend::PlannedFrame& f : plan) requests.push_back(std::get<lsc::Request>(f.request));
  return std::make_unique<XarmDialect>(std::move(requests));
}

}  // namespace seqc::cli
