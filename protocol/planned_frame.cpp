#include "protocol/planned_frame.hpp"

#include <utility>

#include "protocol/lsc/group_download.hpp"

namespace seqc {
namespace {

std::string join_counts(const std::vector<std::uint8_t>& counts) {
  std::string s;
  for (std::uint8_t c : counts) {
    if (!s.empty()) s += ' ';
    s += std::to_string(c);
  }
  return s;
}

std::string n(unsigned value) { return std::to_string(value); }

// The labelled fields of a GroupDownload step, as a listing shows them.
struct FieldsOf {
  std::string operator()(const lsc::GroupDownloadOpen& m) const {
    return "step 1 open | group " + n(m.group) + " | block counts " + join_counts(m.block_counts);
  }
  std::string operator()(const lsc::GroupDownloadSize& m) const {
    return "step 2 size | group " + n(m.group) + " | block " + n(m.block) + " | count " +
           n(m.count) + " | pad 00";
  }
  std::string operator()(const lsc::GroupDownloadBlocks& m) const {
    return "step 3 blocks | group " + n(m.group) + " | pad 00 | blocks used " + n(m.block_count);
  }
  std::string operator()(const lsc::GroupDownloadAction& m) const {
    return "step 4 action | group " + n(m.group) + " | block " + n(m.block) + " | index " +
           n(m.index) + " | marker 0b | time " + n(m.time_ms) + " ms | servos " +
           std::to_string(m.servos.size());
  }
  std::string operator()(const lsc::GroupDownloadClose& m) const {
    return "step 5 close | group " + n(m.group);
  }
  template <class Other>
  std::string operator()(const Other& other) const {
    return lsc::describe(lsc::Request{other});
  }
};

// What the uploader calls the frame in its notes and errors.
std::string step_what(const lsc::Request& r, int step, std::size_t action, std::size_t actions) {
  switch (step) {
    case 1:
      return "step 1 (open group " + n(std::get<lsc::GroupDownloadOpen>(r).group) + ")";
    case 2:
      return "step 2 (size of block " + n(std::get<lsc::GroupDownloadSize>(r).block) + ")";
    case 3:
      return "step 3 (block list)";
    case 4: {
      const auto& a = std::get<lsc::GroupDownloadAction>(r);
      return "step 4 (action " + std::to_string(action) + " of " + std::to_string(actions) +
             ": block " + n(a.block) + ", index " + n(a.index) + ")";
    }
    case 5:
      return "step 5 (close)";
    default:
      return lsc::describe(r);
  }
}

}  // namespace

Result<std::vector<PlannedFrame>> plan_frames(const std::vector<lsc::Request>& steps) {
  std::size_t actions = 0;
  for (const lsc::Request& r : steps) {
    if (lsc::group_download_step(r) == 4) ++actions;
  }
  std::vector<PlannedFrame> out;
  out.reserve(steps.size());
  std::size_t action = 0;
  for (const lsc::Request& r : steps) {
    auto bytes = lsc::encode_serial(r);
    if (!bytes) return bytes.error();
    PlannedFrame f;
    f.request = r;
    f.dialect = &kXarmDialect;
    f.bytes = std::move(bytes).value();
    f.index = out.size();
    f.step = lsc::group_download_step(r);
    f.is_action = f.step == 4;
    if (f.is_action) {
      f.keyframe = action;
      ++action;
      f.short_what = "step 4 (action " + std::to_string(action) + ")";
    } else {
      f.short_what = "step " + std::to_string(f.step);
    }
    f.what = step_what(r, f.step, action, actions);
    f.fields = std::visit(FieldsOf{}, r);
    out.push_back(std::move(f));
  }
  return out;
}

Result<std::vector<PlannedFrame>> plan_frames(const std::vector<lsc6::DownloadAction>& actions) {
  std::vector<PlannedFrame> out;
  out.reserve(actions.size());
  for (const lsc6::DownloadAction& a : actions) {
    lsc6::Request request{a};
    auto bytes = lsc6::encode_serial(request);
    if (!bytes) return bytes.error();
    PlannedFrame f;
    f.request = std::move(request);
    f.dialect = &kLsc6Dialect;
    f.bytes = std::move(bytes).value();
    f.index = out.size();
    f.is_action = true;
    f.keyframe = out.size();
    f.what = "action " + std::to_string(out.size() + 1) + " of " + std::to_string(actions.size());
    f.short_what = "action " + n(a.index + 1u);
    f.fields = "download action | group " + n(a.group) + " | total " + n(a.total) + " | index " +
               n(a.index) + " | time " + n(a.time_ms) + " ms | servos " +
               std::to_string(a.servos.size());
    out.push_back(std::move(f));
  }
  return out;
}

}  // namespace seqc
