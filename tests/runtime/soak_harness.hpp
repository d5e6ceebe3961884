// The upload soak's fault model and one run of it, shared by the soak test (ctest, label
// `soak`) and soak_bench (10,000 uploads at x1 and x4). Every upload is a full 1,020-action
// download with GroupRun through the real uploader to the in-process emulator, in emulated
// time; every fault is drawn from seeds, so a run is the same on every machine.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "protocol/lsc/group_download.hpp"
#include "runtime/emulator/emulator_transport.hpp"
#include "runtime/emulator/fault_injector.hpp"
#include "runtime/emulator/xarm_emulator.hpp"
#include "runtime/upload/uploader.hpp"

namespace seqc::soak {

using namespace std::chrono_literals;

// Per-frame rates at scale 1 (each multiplied by the scale), and per-upload chances.
inline constexpr double kFrameRate = 0.0005;   // drop, corrupt, late, duplicate, busy
inline constexpr double kResetRate = 0.00002;  // controller reset, per frame
inline constexpr double kHangupChance = 0.02;  // an upload whose port hangs up once

inline std::string fault_model(double scale) {
  char buf[1400];
  const double frame = 100 * kFrameRate * scale;
  std::snprintf(
      buf, sizeof buf,
      "fault model (x%.2f), drawn per upload from its own seed:\n"
      "  per request frame the controller receives:\n"
      "    lost %.4f%%; a byte flipped %.4f%%: in 55 55 LEN the frame is ignored, anywhere\n"
      "      else it is taken as it arrived (there is no checksum);\n"
      "    busy %.4f%%: processed 400 ms longer (700 ms in a quarter of the uploads), frames\n"
      "      arriving meanwhile are dropped;\n"
      "    controller reset %.5f%%: the frame is lost, the download in progress forgotten,\n"
      "      deaf for 300 ms, then answers as after power-on\n"
      "  per frame the controller sends:\n"
      "    a byte flipped %.4f%%; late %.4f%% (by 400 ms, or 700 ms -- beyond the 500 ms reply\n"
      "      margin -- in a quarter of the uploads); sent twice %.4f%%\n"
      "  per upload: the port hangs up at a random frame (1-1030) in %.2f%% of the uploads;\n"
      "    the same device comes back 2 s later\n"
      "  link: half the uploads unpaced, half paced at 115200 baud; reply margin 0.5 s (3 s\n"
      "    for step 1); 4 re-sends per frame, 3 restarts per upload; GroupRun after each\n",
      scale, frame, frame, frame, 100 * kResetRate * scale, frame, frame, frame,
      100 * kHangupChance * scale);
  return buf;
}

inline std::vector<lsc::GroupAction> soak_actions(std::uint64_t seed) {
  emu::SplitMix64 rng(seed);
  std::vector<lsc::GroupAction> actions(1020);
  for (auto& a : actions) {
    a.time_ms = static_cast<std::uint16_t>(20 + rng.next() % 2000);
    for (std::uint8_t s = 1; s <= 6; ++s) {
      a.servos.push_back({s, static_cast<std::uint16_t>(rng.next() % 1001)});
    }
  }
  return actions;
}

// A restart's reason, in one of a few classes for the report.
inline std::string restart_cause(const std::string& reason) {
  if (reason.find("came back") != std::string::npos) return "port hung up and came back";
  if (reason.find("did not acknowledge") != std::string::npos) return "no ack after re-sends";
  if (reason.find("refused") != std::string::npos) {
    return reason.find("taken for the wrong frame") != std::string::npos
               ? "refused twice after a re-send or an extra ack"
               : "refused twice (controller reset?)";
  }
  if (reason.find("while waiting for") != std::string::npos) return "ack of an earlier step taken";
  if (reason.find("before the barrier") != std::string::npos) return "extra ack at a barrier";
  if (reason.find("between frames") != std::string::npos) return "extra ack between frames";
  return "other";
}

// A note, as the recovery it reports, or "" for notes that are no recovery.
inline std::string note_recovery(const std::string& note) {
  if (note.find("discarded a late acknowledgement") != std::string::npos) return "late-ack guard";
  if (note.find("sooner than the wire allows (") != std::string::npos) return "early ack held";
  if (note.find("discarded a stale acknowledgement") != std::string::npos) {
    return "stale ack absorbed by a barrier";
  }
  if (note.find("discarded an extra acknowledgement") != std::string::npos) {
    return "extra ack drained";
  }
  if (note.find("of a step not sent") != std::string::npos) return "ack of a step not sent ignored";
  if (note.find("sending it once more") != std::string::npos) return "refusal re-sent once";
  if (note.find("no known reply") != std::string::npos) return "unknown frame skipped";
  if (note.find("of an unfinished reply") != std::string::npos) return "partial reply dropped";
  return "";
}

// Keeps the last notes of an upload, to show how a failure came about, and counts the
// recoveries it saw.
class LastNotes final : public upload::UploadObserver {
 public:
  void on_retry(const upload::RetryEvent& e) override {
    add("re-send " + e.what + ": " + e.reason);
    ++recoveries[e.what.rfind("barrier", 0) == 0 ? "barrier re-sent"
                 : e.what.rfind("probe", 0) == 0 ? "probe re-sent"
                                                 : "frame re-sent"];
  }
  void on_restart(const upload::RestartEvent& e) override {
    add("RESTART: " + e.reason);
    causes.push_back(restart_cause(e.reason));
    ++recoveries["restart: " + causes.back()];
  }
  void on_note(const std::string& n) override {
    add(n);
    if (const std::string r = note_recovery(n); !r.empty()) ++recoveries[r];
  }
  std::map<std::string, std::size_t> recoveries;
  void add(std::string n) {
    if (notes.size() == 12) notes.erase(notes.begin());
    notes.push_back(std::move(n));
  }
  std::vector<std::string> notes;
  std::vector<std::string> causes;
};

// The kinds of fault the soak injects, as the tally names them.
inline const std::vector<std::string>& fault_kinds() {
  static const std::vector<std::string> kinds{
      "lost request",    "request framing flipped", "request byte flipped",
      "busy controller", "controller reset",        "port hang-up",
      "reply late",      "reply sent twice",        "reply byte flipped"};
  return kinds;
}

// The faults the emulator injected in one upload, per kind: the injector's decisions replayed
// from the same seed over the frames the emulator received and sent (every frame draws the
// same values whatever the outcome, fault_injector.hpp), keeping only those that took effect
// (a busy period is counted when its frame was processed). nullopt if the replay does not
// match what the emulator counted.
inline std::optional<std::map<std::string, std::size_t>> injected_faults(
    const emu::XArmEmulator& emulator, const emu::XArmFaults& faults) {
  std::map<std::string, std::size_t> n;
  emu::FaultInjector replay(faults);
  std::size_t framed = 0;
  for (const emu::ReceivedFrame& rec : emulator.received()) {
    if (!rec.frame && !rec.dropped_fault) continue;  // unframed bytes draw nothing
    ++framed;
    const emu::IncomingFault in = replay.on_request();
    if (in.hangup) {
      ++n["port hang-up"];
    } else if (in.silent) {
      continue;
    } else if (in.drop) {
      ++n["lost request"];
    } else if (in.corrupt && emu::FaultInjector::flip_index(rec.raw.size(), in.corrupt_where) < 3) {
      ++n["request framing flipped"];
    } else if (in.reset) {
      ++n["controller reset"];
    } else if (in.busy && rec.frame && !rec.dropped_busy) {
      ++n["busy controller"];
    }
    if (in.corrupt && !in.hangup && !in.drop &&
        emu::FaultInjector::flip_index(rec.raw.size(), in.corrupt_where) >= 3) {
      ++n["request byte flipped"];
    }
  }
  if (framed != emulator.frames_received()) return std::nullopt;
  for (std::size_t i = 0; i < emulator.frames_sent(); ++i) {
    const emu::OutgoingFault out = replay.on_reply();
    if (out.late) ++n["reply late"];
    if (out.duplicate) ++n["reply sent twice"];
    if (out.corrupt) ++n["reply byte flipped"];
  }
  return n;
}

// Where a request byte flipped past 55 55 LEN landed (rec.raw holds the flipped byte, so
// raw[3] is the command as the controller saw it).
inline std::string flip_place(const emu::ReceivedFrame& rec) {
  const std::size_t at = *rec.flipped_at;
  if (at == 3) return "command byte";
  if (rec.raw[3] == static_cast<std::uint8_t>(lsc::Command::GroupDownload)) {
    if (at == 4) return "download step byte";
    if (at == 5) return "download group byte";
    if (rec.raw[4] == 4) return at <= 7 ? "action block or index" : "action time, ids, positions";
    return "other download step data";
  }
  if (rec.raw[3] == static_cast<std::uint8_t>(lsc::Command::GroupRun)) return "GroupRun data";
  return "other request data";
}

// Request bytes flipped past 55 55 LEN, by where they landed, and what came of them.
struct FlipTally {
  std::size_t flips = 0;
  std::size_t stored_wrong = 0;    // uploads reporting success with the flipped action stored
  std::size_t run_unreported = 0;  // uploads whose GroupRun was flipped and not reported started
};

// The actions of `stored` that differ from `planned` and that a flipped step-4 frame the
// controller received carries, byte for byte: what no reply can reveal. False when some
// difference has no such frame (a fault of the uploader, not of the wire).
inline bool wrong_actions_explained_by_flips(const emu::XArmEmulator& emulator,
                                             const std::vector<lsc::GroupAction>& stored,
                                             const std::vector<lsc::GroupAction>& planned) {
  if (stored.size() != planned.size()) return false;
  std::vector<lsc::GroupAction> flipped;
  for (const emu::ReceivedFrame& rec : emulator.received()) {
    if (!rec.flipped_at || !rec.frame) continue;
    auto request = lsc::decode_group_download(*rec.frame);
    if (!request) continue;
    if (const auto* a = std::get_if<lsc::GroupDownloadAction>(&*request)) {
      flipped.push_back(lsc::GroupAction{a->time_ms, a->servos});
    }
  }
  for (std::size_t k = 0; k < stored.size(); ++k) {
    if (stored[k] == planned[k]) continue;
    if (std::find(flipped.begin(), flipped.end(), stored[k]) == flipped.end()) return false;
  }
  return true;
}

// One kind of fault over the mixed soak: how often it happened, in how many uploads.
struct FaultTally {
  std::size_t injected = 0;
  std::size_t uploads = 0;  // uploads with at least one
};

// The soak's fault knobs, each of which a pass can inject alone (soak_one's `only`), so that
// every recovery seen in that pass is that fault's: drop, corrupt (requests and replies), late,
// duplicate, busy, reset (one per upload, at a random frame), hang-up (one per upload).
inline const std::vector<std::string>& fault_knobs() {
  static const std::vector<std::string> knobs{"drop", "corrupt", "late",   "duplicate",
                                              "busy", "reset",   "hang-up"};
  return knobs;
}

// One knob injected alone: the faults that happened and the recoveries that handled them.
struct IsolatedTally {
  std::size_t uploads = 0;
  std::size_t injected = 0;
  std::size_t quiet = 0;   // uploads that needed no recovery (e.g. late within the margin)
  std::size_t failed = 0;  // uploads that did not complete
  std::map<std::string, std::size_t> recoveries;
};

struct Totals {
  std::size_t uploads = 0, completed = 0, failed = 0;
  // Reported success while the stored group differs from the plan, where no flipped byte
  // explains it: the uploader's fault.
  std::size_t wrong_success = 0;
  // Reported success with an action stored as a flipped step-4 frame carried it: the protocol
  // has no checksum and no read-back, so nothing on the wire can reveal it.
  std::size_t undetectable_flip = 0;
  std::map<std::string, FlipTally> flips;  // every upload, by flip_place
  std::size_t run_after_failure = 0;       // GroupRun reached the controller after a failure
  std::size_t with_hangup = 0, with_reset = 0;
  std::size_t retries = 0, restarts = 0, reopens = 0;
  std::map<std::string, std::size_t> failures;  // status: first words of the message -> count
  std::map<std::string, std::size_t> restart_causes;
  std::vector<std::string> first_failures;        // with their last notes (at most 3)
  std::map<std::string, FaultTally> faults;       // mixed uploads, by kind (fault_kinds())
  std::map<std::string, IsolatedTally> isolated;  // uploads with one knob alone, by knob
  std::size_t tally_mismatches = 0;               // uploads whose faults could not be replayed

  // The kinds of fault the mixed soak injects, and the knobs of the isolated passes run, that
  // never produced a fault in this run.
  std::vector<std::string> faults_never_seen() const {
    std::vector<std::string> out;
    if (uploads > 0) {
      for (const std::string& kind : fault_kinds()) {
        auto it = faults.find(kind);
        if (it == faults.end() || it->second.injected == 0) out.push_back(kind);
      }
    }
    for (const auto& [knob, x] : isolated) {
      if (x.injected == 0) out.push_back(knob + " (alone)");
    }
    return out;
  }

  double completion() const {
    return uploads == 0 ? 0 : static_cast<double>(completed) / static_cast<double>(uploads);
  }
};

// Upload number i of a soak at `scale`, added to `t`. With `only` (one of fault_knobs()),
// that fault alone is injected, at four times the rate (reset and hang-up: once per upload),
// and its faults and recoveries are tallied in t.isolated[only] instead of t.faults.
inline void soak_one(std::size_t i, double scale, Totals& t, const std::string& only = "") {
  emu::SplitMix64 plan_rng(20240611 + i);
  emu::XArmConfig config;
  config.baud = (i % 2 == 0) ? 0 : 115200;
  config.faults.seed = 1000 + i;
  const double rate = kFrameRate * scale;
  config.faults.drop = rate;
  config.faults.corrupt = rate;
  // Corrupted LEN bytes are part of the soak's fault mix; the figures were measured with the
  // inter-byte gap that lets the emulator drop such a frame, so the soak keeps it on.
  config.faults.frame_gap = 20ms;
  config.faults.late_ack = rate;
  config.faults.late_by = (i % 4 == 1) ? 700ms : 400ms;
  config.faults.duplicate_ack = rate;
  config.faults.busy = rate;
  config.faults.busy_for = (i % 4 == 3) ? 700ms : 400ms;
  config.faults.reset = kResetRate * scale;
  bool hangup = plan_rng.unit() < kHangupChance * scale;
  const std::size_t at_frame = 1 + plan_rng.next() % 1030;
  if (!only.empty()) {
    emu::XArmFaults alone;
    alone.seed = config.faults.seed;
    alone.frame_gap = config.faults.frame_gap;
    alone.late_by = config.faults.late_by;
    alone.busy_for = config.faults.busy_for;
    const double more = 4 * rate;
    if (only == "drop") alone.drop = more;
    if (only == "corrupt") alone.corrupt = more;
    if (only == "late") alone.late_ack = more;
    if (only == "duplicate") alone.duplicate_ack = more;
    if (only == "busy") alone.busy = more;
    if (only == "reset") alone.reset_at = at_frame;
    config.faults = alone;
    hangup = only == "hang-up";
  }
  if (hangup) {
    config.faults.hangup_at = at_frame;
    config.faults.back_after = 2s;
  }

  emu::XArmEmulator emulator(config);
  io::ManualClock clock;
  emu::EmulatorTransport transport(emulator, clock);
  upload::ControllerLink link(transport, clock);
  upload::UploadOptions options;
  options.group = static_cast<std::uint8_t>(i % 8);
  options.run = true;
  LastNotes notes;
  upload::Uploader uploader(link, options, &notes);
  const auto actions = soak_actions(i);
  const auto plan = lsc::plan_group_download(options.group, actions);
  if (!plan.ok()) {
    ++t.failed;
    ++t.failures["bad plan"];
    return;
  }
  const upload::UploadResult r = uploader.upload(*plan);

  const auto injected = injected_faults(emulator, config.faults);
  if (!injected) ++t.tally_mismatches;
  if (!only.empty()) {
    IsolatedTally& x = t.isolated[only];
    ++x.uploads;
    if (injected) {
      for (const auto& [kind, count] : *injected) x.injected += count;
    }
    if (notes.recoveries.empty()) ++x.quiet;
    if (!r.ok()) ++x.failed;
    for (const auto& [what, count] : notes.recoveries) x.recoveries[what] += count;
  } else if (injected) {
    for (const auto& [kind, count] : *injected) {
      t.faults[kind].injected += count;
      ++t.faults[kind].uploads;
    }
  }

  ++t.uploads;
  t.retries += static_cast<std::size_t>(r.retries);
  t.restarts += static_cast<std::size_t>(r.restarts);
  t.reopens += static_cast<std::size_t>(r.reopens);
  for (const auto& c : notes.causes) ++t.restart_causes[c];
  if (hangup && emulator.frames_received() >= *config.faults.hangup_at) ++t.with_hangup;
  if (emulator.resets() > 0) ++t.with_reset;
  const auto stored = emulator.stored_group(options.group);
  std::map<std::string, std::size_t> flipped_here;
  for (const emu::ReceivedFrame& rec : emulator.received()) {
    if (rec.flipped_at) ++flipped_here[flip_place(rec)];
  }
  for (const auto& [place, n] : flipped_here) t.flips[place].flips += n;
  if (flipped_here.count("GroupRun data") && !r.run_reported) {
    ++t.flips["GroupRun data"].run_unreported;
  }
  if (r.ok()) {
    ++t.completed;
    if (stored && *stored != actions &&
        wrong_actions_explained_by_flips(emulator, *stored, actions)) {
      ++t.undetectable_flip;
      ++t.flips["action time, ids, positions"].stored_wrong;
    } else if (!stored || *stored != actions) {
      ++t.wrong_success;
    }
    return;
  }
  ++t.failed;
  for (const emu::ReceivedFrame& f : emulator.received()) {
    if (f.frame && f.frame->cmd == static_cast<std::uint8_t>(lsc::Command::GroupRun)) {
      ++t.run_after_failure;
      break;
    }
  }
  // Grouped by status and cause (the message up to its first parenthesis: which frame differs).
  ++t.failures[std::string(upload::to_string(r.status)) + ": " +
               r.message.substr(0, r.message.find(" ("))];
  if (t.first_failures.size() < 3) {
    std::string s = "upload " + std::to_string(i) + " (baud " + std::to_string(config.baud) +
                    ", faults " + emu::describe_faults(config.faults) + ") failed: " + r.message;
    for (const auto& n : notes.notes) s += "\n    " + n;
    t.first_failures.push_back(s);
  }
}

// Per kind of fault: how often it happened in the mixed soak; per knob injected alone, the
// recoveries that handled it.
inline std::string fault_table(const Totals& t) {
  std::string out;
  char buf[200];
  if (t.uploads > 0) {
    out += "faults injected in the mixed soak:\n";
    for (const std::string& kind : fault_kinds()) {
      auto it = t.faults.find(kind);
      const FaultTally f = it == t.faults.end() ? FaultTally{} : it->second;
      std::snprintf(buf, sizeof buf, "  %-24s %6zu in %5zu uploads%s\n", kind.c_str(), f.injected,
                    f.uploads, f.injected == 0 ? "  <-- NEVER HAPPENED" : "");
      out += buf;
    }
  }
  if (!t.isolated.empty()) out += "each fault alone, and the recoveries that handled it:\n";
  for (const auto& [knob, x] : t.isolated) {
    std::snprintf(buf, sizeof buf,
                  "  %-10s %5zu faults in %4zu uploads (%zu needed no recovery, %zu failed)%s\n",
                  knob.c_str(), x.injected, x.uploads, x.quiet, x.failed,
                  x.injected == 0 ? "  <-- NEVER HAPPENED" : "");
    out += buf;
    for (const auto& [what, n] : x.recoveries) {
      out += "      " + what + " x" + std::to_string(n) + "\n";
    }
  }
  if (!t.flips.empty()) {
    out += "request bytes flipped past 55 55 LEN (taken as they arrived), by where they landed:\n";
  }
  for (const auto& [place, f] : t.flips) {
    std::snprintf(buf, sizeof buf, "  %-30s %6zu", place.c_str(), f.flips);
    out += buf;
    if (f.stored_wrong > 0) {
      out += ", " + std::to_string(f.stored_wrong) +
             " uploads reported success with a flipped action stored (undetectable)";
    }
    if (f.run_unreported > 0) {
      out += ", " + std::to_string(f.run_unreported) + " uploads saw no start reported";
    }
    out += "\n";
  }
  if (t.tally_mismatches > 0) {
    out += "  uploads whose faults could not be replayed: " + std::to_string(t.tally_mismatches) +
           "\n";
  }
  return out;
}

// Each knob alone, `per_knob` uploads each (numbered after the mixed soak's `first`).
inline void soak_isolated(std::size_t first, std::size_t per_knob, double scale, Totals& t) {
  std::size_t i = first;
  for (const std::string& knob : fault_knobs()) {
    for (std::size_t k = 0; k < per_knob; ++k) soak_one(i++, scale, t, knob);
  }
}

inline std::string report(const Totals& t, double scale) {
  char buf[600];
  std::snprintf(buf, sizeof buf,
                "soak x%.2f: %zu uploads of 1020 actions: %zu completed (%.3f%%), %zu failed; "
                "%zu reported success with a wrong group no flipped byte explains, %zu with "
                "an action a flipped byte changed; %zu GroupRun after a failed "
                "download; %zu met a hang-up, %zu a controller reset; %zu re-sends, %zu "
                "restarts, %zu reconnects\n",
                scale, t.uploads, t.completed, 100 * t.completion(), t.failed, t.wrong_success,
                t.undetectable_flip, t.run_after_failure, t.with_hangup, t.with_reset, t.retries,
                t.restarts, t.reopens);
  std::string out = buf;
  for (const auto& [what, n] : t.restart_causes) {
    out += "  restarts x" + std::to_string(n) + ": " + what + "\n";
  }
  for (const auto& [what, n] : t.failures) {
    out += "  failure x" + std::to_string(n) + ": " + what + "\n";
  }
  for (const auto& f : t.first_failures) out += "  " + f + "\n";
  out += fault_table(t);
  return out;
}

}  // namespace seqc::soak
