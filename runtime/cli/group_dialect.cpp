#include "runtime/cli/group_dialect.hpp"

#include <fmt/format.h>

#include "runtime/cli/session_text.hpp"
#include "runtime/upload/controller_link.hpp"
#include "runtime/upload/lsc6_link.hpp"
#include "runtime/upload/lsc6_uploader.hpp"

namespace seqc::cli {
namespace {

class XarmDialect final : public GroupDialect {
 public:
  explicit XarmDialect(std::vector<lsc::Request> plan) : plan_(std::move(plan)) {}
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
  explicit Lsc6Dialect(std::vector<lsc6::DownloadAction> plan) : plan_(std::move(plan)) {}
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
