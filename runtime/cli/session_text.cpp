#include "runtime/cli/session_text.hpp"

#include <fmt/format.h>

#include "runtime/protocol/bytes.hpp"

namespace seqc::cli {
namespace {

std::string line_for(const lsc::Request& r, const std::string& role) {
  auto bytes = lsc::encode_serial(r);
  return fmt::format("{:<40}  # {}{}\n", bytes ? to_hex(*bytes) : "?", role, lsc::describe(r));
}

std::string lsc6_line_for(const lsc6::Request& r, const std::string& role) {
  auto bytes = lsc6::encode_serial(r);
  return fmt::format("{:<40}  # {}{}\n", bytes ? to_hex(*bytes) : "?", role, lsc6::describe(r));
}

}  // namespace

std::string upload_session_hex(const std::vector<lsc::Request>& plan, std::uint8_t group, bool run,
                               std::uint16_t run_times) {
  std::string out = line_for(lsc::GetBatteryVoltage{}, "probe: ");
  out += line_for(lsc::GroupStop{}, "");
  out += line_for(lsc::GetBatteryVoltage{}, "barrier: ");
  for (const auto& r : plan) out += line_for(r, "");
  out += line_for(lsc::GetBatteryVoltage{}, "barrier: ");
  if (run) {
    out += line_for(lsc::GroupRun{group, run_times}, "");
    out += line_for(lsc::GetBatteryVoltage{}, "barrier: ");
  }
  return out;
}

std::string lsc6_session_hex(const std::vector<lsc6::DownloadAction>& plan, std::uint8_t group,
                             bool run, std::uint16_t run_times) {
  std::string out = lsc6_line_for(lsc6::Stop{}, "");
  for (const auto& a : plan) out += lsc6_line_for(a, "");
  if (run) out += lsc6_line_for(lsc6::Run{group, run_times}, "");
  return out;
}

}  // namespace seqc::cli
