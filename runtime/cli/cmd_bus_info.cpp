// `seqc bus-info read|write`: a bus servo's limits and state (BusServoInfoRead,
// BusServoInfoWrite).
//
// BusServoInfoWrite is not addressed: every servo on the bus takes what it carries, at once
// (docs/protocol/servo-controller.md). `write` therefore refuses to run unless the user states,
// with
// --i-have-one-servo-attached, that only the servo to configure is connected. Fields the user
// does not give are read from that servo first, so a write changes only what was asked for.
#include <memory>
#include <optional>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "runtime/cli/commands.hpp"
#include "runtime/cli/controller_session.hpp"
#include "runtime/cli/device_args.hpp"
#include "runtime/cli/device_table.hpp"

namespace seqc::cli {
namespace {

constexpr const char* kConfirmFlag = "--i-have-one-servo-attached";

// The led_warning bits, in bit order (docs/protocol/servo-controller.md).
const char* const kWarningNames[] = {"overheat", "overvoltage", "overposition"};

std::string warning_text(std::uint8_t bits) {
  std::string out;
  for (int b = 0; b < 3; ++b) {
    if ((bits >> b) & 1) out += (out.empty() ? "" : ",") + std::string(kWarningNames[b]);
  }
  if ((bits & ~0x07) != 0)
    out += (out.empty() ? "" : ",") + std::string("bits ") + std::to_string(bits);
  return out.empty() ? "none" : out;
}

Result<std::uint8_t> parse_warnings(const std::string& text) {
  if (text == "none") return std::uint8_t{0};
  std::uint8_t bits = 0;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    bool found = false;
    for (int b = 0; b < 3; ++b) {
      if (item == kWarningNames[b]) {
        bits = static_cast<std::uint8_t>(bits | (1 << b));
        found = true;
      }
    }
    if (!found) {
      return make_error("--led-warning: unknown warning '" + item +
                        "'; use a comma list of overheat, overvoltage, overposition, or none");
    }
  }
  return bits;
}

std::string limits_table(const lsc::BusServoLimits& l, std::vector<std::vector<std::string>> rows) {
  Table table({"field", "value"});
  for (auto& r : rows) table.add(std::move(r));
  table.add({"position-min", std::to_string(l.position_min)});
  table.add({"position-max", std::to_string(l.position_max)});
  table.add({"millivolts-min", std::to_string(l.millivolts_min)});
  table.add({"millivolts-max", std::to_string(l.millivolts_max)});
  table.add({"temp-max", std::to_string(l.temp_max)});
  table.add({"led", l.led_status == 0   ? "on"
                    : l.led_status == 1 ? "off"
                                        : std::to_string(l.led_status)});
  table.add({"led-warning", warning_text(l.led_warning)});
  return table.render();
}

// ---- read ----------------------------------------------------------------------------------

ExitCode read_info(Context& ctx, const DeviceOptions& device) {
  return run_on_controller(ctx, device, [&](ControllerSession& s) {
    auto info = s.ask<lsc::BusServoInfo>(lsc::BusServoInfoRead{}, "the bus servo info");
    if (!info) return ExitCode::DeviceFailure;
    ctx.out << limits_table(info->limits, {{"id", std::to_string(info->id)}});
    Table now({"state", "value"});
    now.add({"offset", std::to_string(info->offset)});
    now.add({"position", std::to_string(info->position)});
    now.add({"temp", std::to_string(info->temp)});
    now.add({"millivolts", std::to_string(info->millivolts)});
    ctx.out << "\n" << now.render();
    return ExitCode::Ok;
  });
}

// ---- write ---------------------------------------------------------------------------------

struct WriteOptions {
  DeviceOptions device;
  bool one_servo = false;
  std::optional<long long> servo;
  std::optional<long long> position_min;
  std::optional<long long> position_max;
  std::optional<long long> millivolts_min;
  std::optional<long long> millivolts_max;
  std::optional<long long> temp_max;
  std::optional<std::string> led;
  std::optional<std::string> led_warning;

  bool complete() const {
    return servo && position_min && position_max && millivolts_min && millivolts_max && temp_max &&
           led && led_warning;
  }
};

// The fields the user gave, checked; `base` supplies the others.
struct Changes {
  std::optional<std::uint8_t> servo;
  std::optional<std::uint16_t> position_min, position_max, millivolts_min, millivolts_max, temp_max;
  std::optional<std::uint8_t> led_status, led_warning;
};

Result<Changes> check_changes(const WriteOptions& o) {
  Changes c;
  auto u16 = [](const std::optional<long long>& v, const char* field,
                std::optional<std::uint16_t>& out) -> Status {
    if (!v) return Ok{};
    auto r = lsc::checked_u16(*v, field);
    if (!r) return r.error();
    out = *r;
    return Ok{};
  };
  if (o.servo) {
    auto r = lsc::checked_u8(*o.servo, "--servo");
    if (!r) return r.error();
    c.servo = *r;
  }
  for (auto s : {u16(o.position_min, "--position-min", c.position_min),
                 u16(o.position_max, "--position-max", c.position_max),
                 u16(o.millivolts_min, "--millivolts-min", c.millivolts_min),
                 u16(o.millivolts_max, "--millivolts-max", c.millivolts_max),
                 u16(o.temp_max, "--temp-max", c.temp_max)}) {
    if (!s) return s.error();
  }
  if (o.led) c.led_status = *o.led == "on" ? 0 : 1;
  if (o.led_warning) {
    auto w = parse_warnings(*o.led_warning);
    if (!w) return w.error();
    c.led_warning = *w;
  }
  return c;
}

lsc::BusServoInfoWrite apply(const Changes& c, std::uint8_t id, lsc::BusServoLimits l) {
  l.position_min = c.position_min.value_or(l.position_min);
  l.position_max = c.position_max.value_or(l.position_max);
  l.millivolts_min = c.millivolts_min.value_or(l.millivolts_min);
  l.millivolts_max = c.millivolts_max.value_or(l.millivolts_max);
  l.temp_max = c.temp_max.value_or(l.temp_max);
  l.led_status = c.led_status.value_or(l.led_status);
  l.led_warning = c.led_warning.value_or(l.led_warning);
  return lsc::BusServoInfoWrite{c.servo.value_or(id), l};
}

std::optional<std::string> inconsistent(const lsc::BusServoLimits& l) {
  if (l.position_min > l.position_max) {
    return "position-min " + std::to_string(l.position_min) + " is above position-max " +
           std::to_string(l.position_max);
  }
  if (l.millivolts_min > l.millivolts_max) {
    return "millivolts-min " + std::to_string(l.millivolts_min) + " is above millivolts-max " +
           std::to_string(l.millivolts_max);
  }
  return std::nullopt;
}

ExitCode write_info(Context& ctx, const WriteOptions& o) {
  if (!o.one_servo) {
    return usage_error(ctx,
                       std::string("bus-info write is not addressed to one servo: every servo on "
                                   "the bus takes these settings at once. Disconnect all servos "
                                   "but the one to configure, then add ") +
                           kConfirmFlag);
  }
  auto changes = check_changes(o);
  if (!changes) return usage_error(ctx, changes.error().message);
  if (o.complete()) {
    auto whole = apply(*changes, 0, {});
    if (auto bad = inconsistent(whole.limits)) return usage_error(ctx, *bad);
  }
  return run_on_controller(ctx, o.device, [&](ControllerSession& s) {
    lsc::BusServoInfoWrite write = apply(*changes, 0, {});
    if (!o.complete()) {
      // Fields not given keep the servo's current values.
      auto info = s.ask<lsc::BusServoInfo>(lsc::BusServoInfoRead{}, "the bus servo info");
      if (!info) return ExitCode::DeviceFailure;
      write = apply(*changes, info->id, info->limits);
      if (auto bad = inconsistent(write.limits)) {
        ctx.err << "seqc: error: " << *bad << " (after merging with the servo's current "
                << "settings); nothing written\n";
        return ExitCode::Usage;
      }
    }
    if (!s.tell(write)) return ExitCode::DeviceFailure;
    summarize(ctx, "written to every servo on the bus (kept over power-off):");
    ctx.out << limits_table(write.limits, {{"id", std::to_string(write.servo)}});
    return ExitCode::Ok;
  });
}

}  // namespace

void add_bus_info_command(CLI::App& app, Context& ctx, Outcome& result) {
  CLI::App* bus = app.add_subcommand(
      "bus-info", "Read or write a bus servo's limits (id, position, voltage, temperature, LED)");
  bus->require_subcommand(1);

  auto read = std::make_shared<DeviceOptions>();
  CLI::App* read_cmd = bus->add_subcommand(
      "read",
      "Print the limits and state of the bus servo that answers (BusServoInfoRead; on a bus\n"
      "with several servos the controller answers for one of them)");
  add_device_options(*read_cmd, *read);
  read_cmd->callback([read, &ctx, &result] { result.code = read_info(ctx, *read); });

  auto w = std::make_shared<WriteOptions>();
  CLI::App* write_cmd = bus->add_subcommand(
      "write",
      "Set bus servo limits (BusServoInfoWrite; kept over power-off). It is not addressed:\n"
      "EVERY servo on the bus takes these values at once, so it runs only with\n"
      "--i-have-one-servo-attached. Fields not given keep the attached servo's values");
  write_cmd->add_flag(kConfirmFlag, w->one_servo,
                      "Confirm that exactly one servo is connected to the bus");
  write_cmd->add_option("--servo", w->servo, "Servo id field (0-255)");
  write_cmd->add_option("--position-min", w->position_min, "Lowest position (0-65535)");
  write_cmd->add_option("--position-max", w->position_max, "Highest position (0-65535)");
  write_cmd->add_option("--millivolts-min", w->millivolts_min, "Lowest supply voltage, mV");
  write_cmd->add_option("--millivolts-max", w->millivolts_max, "Highest supply voltage, mV");
  write_cmd->add_option("--temp-max", w->temp_max, "Highest temperature, degrees C");
  write_cmd->add_option("--led", w->led, "Status LED: on or off")
      ->check(CLI::IsMember({"on", "off"}));
  write_cmd->add_option("--led-warning", w->led_warning,
                        "Faults the LED flashes for: overheat,overvoltage,overposition "
                        "(any) or none");
  add_device_options(*write_cmd, w->device);
  write_cmd->callback([w, &ctx, &result] { result.code = write_info(ctx, *w); });
}

}  // namespace seqc::cli
