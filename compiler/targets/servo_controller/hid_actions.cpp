#include "compiler/targets/servo_controller/hid_actions.hpp"

#include <cstddef>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "protocol/lsc/group_download.hpp"
#include "protocol/lsc/lsc_frame.hpp"

namespace seqc::compiler {

void check_hid_actions(const ServoProgram& program, Reporter& reporter) {
  // A step performed many times (a repeat, a section) yields many wide actions; the step is
  // said once, with its first action and a count of the rest.
  struct Wide {
    Location step;
    std::size_t first = 0;  // 1-based action number
    std::size_t servos = 0;
    std::size_t more = 0;
  };
  std::vector<Wide> wide;
  for (std::size_t i = 0; i < program.keyframes.size(); ++i) {
    const Keyframe& k = program.keyframes[i];
    if (k.targets.size() <= lsc::kHidMaxActionServos) continue;
    bool seen = false;
    for (Wide& w : wide) {
      if (w.step == k.source) {
        ++w.more;
        seen = true;
        break;
      }
    }
    if (!seen) wide.push_back({k.source, i + 1, k.targets.size(), 0});
  }
  for (const Wide& w : wide) {
    std::string message = fmt::format(
        "action {} carries {} servos, a {}-byte frame; over USB HID a frame holds at most {} "
        "bytes, its {}-byte header included (at most {} servos per action)",
        w.first, w.servos, lsc::action_frame_bytes(w.servos), lsc::kHidReportData, lsc::kHeaderSize,
        lsc::kHidMaxActionServos);
    if (w.more > 0) {
      message += fmt::format("; {} more action{} of this step {} too wide", w.more,
                             w.more == 1 ? "" : "s", w.more == 1 ? "is" : "are");
    }
    reporter.error(w.step, std::move(message));
  }
}

}  // namespace seqc::compiler
