// The only list of boards, and the lookups every caller goes through. Order matters: it is the
// order of `seqc emulate`'s choices, and the first discoverable board is what a device command
// talks to when neither --robot nor --port names one.
#include <algorithm>

#include "compiler/frontend/profiles.hpp"
#include "runtime/boards/board.hpp"
#include "runtime/transport/port_spec.hpp"

namespace seqc::boards {

extern const Board kXarmBoard;
extern const Board kLsc6Board;
extern const Board kRaspblockBoard;

namespace {

constexpr const Board* kBoards[] = {&kXarmBoard, &kLsc6Board, &kRaspblockBoard};

// "emu:lsc6?baud=0" -> "lsc6"; "" when `port` is not an emulator port.
std::string emulator_name(std::string_view port) {
  auto spec = transport::parse_port(port);
  if (!spec || spec->kind != transport::PortKind::Emulator) return {};
  return spec->emulator;
}

}  // namespace

std::span<const Board* const> all_boards() { return kBoards; }

const Board* find_board(std::string_view key) {
  for (const Board* b : kBoards) {
    if (b->key == key) return b;
  }
  return nullptr;
}

const Board& board_for(const compiler::CompileOutput& output) {
  if (const Board* b = find_board(output.board)) return *b;
  // Every profile names a board (board_table_test); an output without a program names none.
  return *kBoards[0];
}

const Board* board_for_emulator(std::string_view emulator) {
  for (const Board* b : kBoards) {
    if (std::find(b->emulators.begin(), b->emulators.end(), emulator) != b->emulators.end()) {
      return b;
    }
  }
  return nullptr;
}

const Board& board_for_device(std::string_view profile, std::string_view port) {
  if (const Board* b = board_for_emulator(emulator_name(port))) return *b;
  if (const compiler::RobotProfile* p = compiler::find_profile(profile)) {
    if (const Board* b = find_board(p->board)) return *b;
  }
  for (const Board* b : kBoards) {
    if (b->discoverable) return *b;
  }
  return *kBoards[0];
}

bool same_family(const Board& a, const Board& b) { return a.family == b.family; }

bool port_over_hid(std::string_view port) {
  const auto spec = transport::parse_port(port);
  if (!spec) return false;
  return spec->kind == transport::PortKind::Hid ||
         (spec->kind == transport::PortKind::Emulator && spec->emulator == "xarm-hid");
}

std::vector<std::string_view> family_emulators(const Board& board) {
  std::vector<std::string_view> names;
  for (const Board* b : kBoards) {
    if (same_family(*b, board) && !b->emulators.empty()) names.push_back(b->emulators.front());
  }
  return names;
}

OtherDialect other_dialect(const Board& board) {
  OtherDialect out;
  for (const Board* b : kBoards) {
    if (b != &board && b->plan != nullptr && same_family(*b, board)) out.answered = b;
  }
  if (out.answered == nullptr) return out;
  for (const std::string& name : compiler::profile_names()) {
    if (compiler::find_profile(name)->board == out.answered->key) out.profiles.push_back(name);
  }
  return out;
}

std::vector<std::string_view> served_emulators() {
  std::vector<std::string_view> names;
  for (const Board* b : kBoards) {
    if (b->serve != nullptr && !b->emulators.empty()) names.push_back(b->emulators.front());
  }
  return names;
}

const Board& board_for_command(std::string_view profile, std::string_view port) {
  const Board& reached = board_for_device(profile, port);
  const Board& discovered = board_for_device("", "");
  return same_family(reached, discovered) ? reached : discovered;
}

Result<Plan> plan_for(const Board& board, const compiler::CompileOutput& output,
                      std::uint8_t group) {
  if (board.plan == nullptr) return make_error(std::string(board.name) + " stores no groups");
  return board.plan(output, group);
}

std::optional<std::size_t> first_too_big(const Plan& plan, const io::Transport& transport) {
  const std::size_t limit = transport.max_frame_bytes();
  if (limit == 0) return std::nullopt;
  for (std::size_t i = 0; i < plan.frames.size(); ++i) {
    if (plan.frames[i].bytes.size() > limit) return i;
  }
  return std::nullopt;
}

upload::UploadResult upload(const Board& board, const Line& line, const Plan& plan,
                            const upload::UploadOptions& options,
                            upload::UploadObserver* observer) {
  if (board.upload == nullptr) {
    upload::UploadResult r;
    r.status = upload::UploadStatus::BadPlan;
    r.message = std::string(board.name) + " stores no groups";
    return r;
  }
  return board.upload(line, plan, options, observer);
}

RunOutcome run_group(const Board& board, const Line& line, std::uint8_t group,
                     std::uint16_t times) {
  RunOutcome out;
  // What a failed write names: the run request as the board's dialect describes it.
  out.request = std::string(board.run_name) + " group=" + std::to_string(group) +
                " times=" + std::to_string(times);
  if (board.run_frame == nullptr || board.confirm_run == nullptr) {
    out.failure = Failure::SendFailed;
    out.detail = std::string(board.name) + " stores no groups";
    return out;
  }
  if (line.interrupted != nullptr && line.interrupted->load()) {
    out.failure = Failure::Interrupted;
    return out;
  }
  // A reply left from before the run must not be taken for its confirmation.
  line.transport.discard_input();
  if (auto written = line.transport.write(board.run_frame(group, times)); !written) {
    out.failure = Failure::SendFailed;
    out.detail = written.error().message;
    return out;
  }
  RunOutcome confirmed = board.confirm_run(line, group, times);
  // The row's confirmation does not know the count; the failure names the request as sent.
  if (!confirmed.ok()) confirmed.request = out.request;
  return confirmed;
}

RefusedOption refused_emulator_option(const Board& board, unsigned given) {
  for (const unsigned option : {kFaults, kSeed, kDumpGroups, kPositions}) {
    if ((given & option) == 0 || (board.emulator_options & option) != 0) continue;
    const std::string_view reason = option == kFaults || option == kSeed ? board.no_faults_reason
                                    : option == kDumpGroups              ? board.no_groups_reason
                                                                         : std::string_view();
    return {option, reason};
  }
  return {};
}

}  // namespace seqc::boards
