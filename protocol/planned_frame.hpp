// One frame of a download plan, encoded once. plan_frames() is the only place a download frame
// is encoded and labelled: the uploaders, the dry run, listings and size checks all read these
// fields, so what is shown, checked and sent cannot differ. The plan is either GroupDownload
// steps 1-5 (xArm / LSC-16 / LSC-32) or one DownloadAction per action (LSC-6); plan_frames()
// rejects a request that does not belong to a download, or a value its encoder refuses. Each
// frame names its row of the dialect table (dialects.hpp), so what reads a plan asks the row, not
// the request's type, which dialect the bytes are in.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "base/bytes.hpp"
#include "base/result.hpp"
#include "protocol/dialects.hpp"
#include "protocol/lsc6/lsc6_messages.hpp"
#include "protocol/lsc/lsc_messages.hpp"

namespace seqc {

// A request of either servo-controller dialect: the xArm / LSC-16 / LSC-32 one or the LSC-6 one.
using DialectRequest = std::variant<lsc::Request, lsc6::Request>;

struct PlannedFrame {
  DialectRequest request;
  Bytes bytes;                          // 55 55 LEN CMD DATA, the only encoding
  const Dialect* dialect = nullptr;     // kXarmDialect or kLsc6Dialect, as `request` is
  std::size_t index = 0;                // position in the plan
  int step = 0;                         // GroupDownload step 1-5; 0 on the LSC-6
  bool is_action = false;               // stores one action (step 4, DownloadAction)
  std::optional<std::size_t> keyframe;  // the action's index in the program's keyframes
  std::string what;        // "step 4 (action 3 of 29: block 0, index 2)", "action 3 of 42"
  std::string short_what;  // "step 4 (action 3)", "action 3"
  std::string fields;      // listing text, e.g. "step 4 action | group 0 | block 0 | ..."
};

// GroupDownload steps as lsc::plan_group_download returns them.
Result<std::vector<PlannedFrame>> plan_frames(const std::vector<lsc::Request>& steps);
// DownloadActions as lsc6::plan_download returns them.
Result<std::vector<PlannedFrame>> plan_frames(const std::vector<lsc6::DownloadAction>& actions);

}  // namespace seqc
