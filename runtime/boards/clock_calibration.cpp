#include "runtime/boards/clock_calibration.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "base/units.hpp"
#include "protocol/lsc/group_download.hpp"
#include "runtime/boards/xarm_queries.hpp"
#include "runtime/boards/xarm_session.hpp"
#include "runtime/upload/controller_link.hpp"

namespace seqc::boards {
namespace {

constexpr std::uint32_t kMaxActionMs = 30000;
constexpr std::uint32_t kFewestActions = 4;

// Where the servos are, when the board can say; the fallback position otherwise.
std::vector<lsc::ServoTarget> hold_positions(const Board& board, const Line& line,
                                             const ClockSettings& settings, bool& read) {
  read = false;
  if (board.queries) {
    upload::ControllerLink link(line.transport, line.clock, line.interrupted);
    XarmSession session(link, line.timeout);
    if (auto answered = read_positions(session, settings.servos); answered && !answered->empty()) {
      read = true;
      return *answered;
    }
  }
  // A board that cannot say where its servos are gets actions that name none (they move
  // nothing); a controller with queries that did not answer gets the fallback.
  std::vector<lsc::ServoTarget> out;
  if (!board.queries) return out;
  for (const std::uint8_t id : settings.servos) out.push_back({id, settings.fallback_position});
  return out;
}

}  // namespace

double clock_error_ppm(std::uint32_t board_ms, io::Duration host) {
  const double board_ns = static_cast<double>(board_ms) * 1e6;
  return (board_ns / static_cast<double>(host.count()) - 1.0) * 1e6;
}

std::vector<compiler::Keyframe> holding_keyframes(const std::vector<lsc::ServoTarget>& targets,
                                                  std::uint32_t run_ms) {
  const std::uint32_t count = std::max(kFewestActions, (run_ms + kMaxActionMs - 1) / kMaxActionMs);
  std::vector<compiler::Keyframe> out;
  std::uint32_t start = 0;
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::uint32_t time = i + 1 == count ? run_ms - start : run_ms / count;
    compiler::Keyframe k;
    k.start_ms = start;
    k.time_ms = static_cast<std::uint16_t>(time);
    k.targets = targets;
    out.push_back(std::move(k));
    start += time;
  }
  return out;
}

ClockMeasurement measure_clock(const Board& board, const Line& line,
                               const ClockSettings& settings) {
  ClockMeasurement m;
  m.held = hold_positions(board, line, settings, m.positions_read);
  std::sort(m.held.begin(), m.held.end(),
            [](const lsc::ServoTarget& a, const lsc::ServoTarget& b) { return a.id < b.id; });

  compiler::CompileOutput output;
  compiler::ServoProgram program;
  program.keyframes = holding_keyframes(m.held, settings.run_ms);
  output.program = std::move(program);
  output.board = std::string(board.key);
  auto plan = plan_for(board, output, settings.group);
  if (!plan) {
    m.upload.status = upload::UploadStatus::BadPlan;
    m.upload.message = plan.error().message;
    return m;
  }
  upload::UploadOptions options;
  options.group = settings.group;
  m.upload = upload(board, line, *plan, options, nullptr);
  if (!m.upload.ok()) return m;

  // A clock 20 % slow still ends within this.
  const io::Duration longest = std::chrono::milliseconds(settings.run_ms) * 5 / 4;
  for (std::size_t i = 0; i < settings.runs; ++i) {
    const TimedRun run = board.time_run(line, settings.group, longest);
    if (!run.ok()) {
      m.failure = run;
      return m;
    }
    m.lasted.push_back(run.lasted);
    m.ppm.push_back(clock_error_ppm(settings.run_ms, run.lasted));
  }
  const double n = static_cast<double>(m.ppm.size());
  m.mean_ppm = std::accumulate(m.ppm.begin(), m.ppm.end(), 0.0) / n;
  if (m.ppm.size() > 1) {
    double sq = 0;
    for (const double e : m.ppm) sq += (e - m.mean_ppm) * (e - m.mean_ppm);
    m.spread_ppm = std::sqrt(sq / (n - 1));
  }
  return m;
}

Result<std::uint32_t> parse_run_length(const std::string& text) {
  const std::optional<double> clock_ms = seqc::parse_clock_ms(text);
  if (!clock_ms) return make_error("--length: give ms or s, e.g. 20s");
  const double ms = *clock_ms;
  if (ms < 1000 || ms > 600000 || ms != std::floor(ms)) {
    return make_error("--length must be whole milliseconds from 1s to 10 minutes, got '" + text +
                      "'");
  }
  return static_cast<std::uint32_t>(ms);
}

}  // namespace seqc::boards
