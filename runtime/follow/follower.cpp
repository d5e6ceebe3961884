#include "runtime/follow/follower.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <span>
#include <variant>

#include <fmt/format.h>

#include "protocol/raspblock/raspblock.hpp"
#include "runtime/boards/resync_run.hpp"
#include "runtime/boards/upload_run.hpp"

namespace seqc::follow {
namespace {

double ms_of(io::Duration d) { return std::chrono::duration<double, std::milli>(d).count(); }

io::Duration from_ms(double ms) {
  return io::Duration{static_cast<std::int64_t>(std::llround(ms * 1e6))};
}

// What a streamed frame sets on the car: a later frame of the same key replaces it (a gimbal
// frame and a single servo's overlap, and are replayed in their order, so the later still wins).
// The car is the only board that takes a stream; a frame that does not decode is its own key.
std::string state_key(ByteView frame) {
  const Result<raspblock::Packet> p = raspblock::decode(frame);
  if (!p) return to_hex(frame);
  if (const auto* one = std::get_if<raspblock::SingleServo>(&*p)) {
    return "servo " + std::to_string(one->index);
  }
  return std::to_string(p->index());
}

}  // namespace

OffsetSummary summarize_offsets(std::vector<double> offsets_ms) {
  OffsetSummary s;
  if (offsets_ms.empty()) return s;
  for (double& v : offsets_ms) v = std::fabs(v);
  std::sort(offsets_ms.begin(), offsets_ms.end());
  const auto rank = [&](double q) {
    const auto k = static_cast<std::size_t>(std::ceil(q * static_cast<double>(offsets_ms.size())));
    return offsets_ms[std::max<std::size_t>(k, 1) - 1];
  };
  s.median = rank(0.5);
  s.p99 = rank(0.99);
  s.max = offsets_ms.back();
  return s;
}

Follower::Follower(const boards::Board& board, const compiler::CompileOutput& output,
                   const boards::Line& line, io::Clock& host, FollowerOptions options,
                   FollowerHooks hooks)
    : board_(board),
      output_(output),
      line_(line),
      host_(host),
      options_(options),
      hooks_(std::move(hooks)),
      stream_(board.plan == nullptr) {}

void Follower::say(const std::string& line) const {
  if (hooks_.note) hooks_.note(line);
}

bool Follower::prepare() {
  if (report_.prepared) return true;
  if (stream_) {
    if (board_.live_frames == nullptr) {
      report_.error = std::string(board_.name) + " can neither store a group nor take a stream";
      return false;
    }
    auto frames = board_.live_frames(output_);
    if (!frames) {
      report_.error = frames.error().message;
      return false;
    }
    schedule_ = std::move(*frames);
    for (const player::ScheduledFrame& f : schedule_) keys_.push_back(state_key(f.bytes));
    report_.prepared = true;
    say(fmt::format("planned {} frames over {:.1f} s", schedule_.size(),
                    schedule_.empty() ? 0.0 : ms_of(schedule_.back().at) / 1000));
    return true;
  }
  const compiler::ServoProgram* program = output_.servo_program();
  if (program == nullptr || board_.run_frame == nullptr) {
    report_.error = "internal: a servo controller's dance without a servo program";
    return false;
  }
  upload::UploadOptions upload_options;
  upload_options.group = options_.group;
  upload_options.retries = options_.retries;
  if (options_.resync_bars > 0 || boards::needs_chain(*program)) {
    const boards::ResyncCut cut =
        boards::cut_for_resync(*program, options_.resync_bars, options_.clock_ppm, options_.group);
    if (!cut.fits()) {
      report_.error = cut.error;
      return false;
    }
    const boards::ResyncRun stored = boards::store_pieces(board_, line_, output_, cut.pieces,
                                                          options_.group, upload_options, nullptr);
    if (!stored.stored()) {
      report_.error = stored.uploads.empty() ? "nothing stored" : stored.uploads.back().message;
      return false;
    }
    schedule_ = boards::resync_starts(board_, cut.pieces, options_.group);
    report_.groups = cut.pieces.size();
    say(fmt::format("stored {} in groups {}-{}", boards::pieces_text(cut, options_.resync_bars),
                    options_.group, cut.last_group));
  } else {
    auto plan = boards::plan_for(board_, output_, options_.group);
    if (!plan) {
      report_.error = plan.error().message;
      return false;
    }
    const upload::UploadResult r = boards::upload(board_, line_, *plan, upload_options, nullptr);
    if (!r.ok()) {
      report_.error = r.message;
      return false;
    }
    Bytes start = board_.stop_frame != nullptr ? board_.stop_frame() : Bytes{};
    const Bytes run = board_.run_frame(options_.group, 1);
    start.insert(start.end(), run.begin(), run.end());
    schedule_ = {{io::Duration{0}, std::move(start)}};
    report_.groups = 1;
    say(fmt::format("stored {} actions in group {}", plan->actions, options_.group));
  }
  report_.prepared = true;
  return true;
}

io::TimePoint Follower::due(std::size_t i) const {
  const player::ScheduledFrame& f = schedule_[i];
  const double wire_s = static_cast<double>(f.bytes.size()) * line_.transport.seconds_per_byte();
  return *anchor_ + f.at - board_.start_delay -
         io::Duration{static_cast<std::int64_t>(std::llround(wire_s * 1e9))};
}

std::optional<io::TimePoint> Follower::next_due() const {
  if (!anchor_ || next_ >= schedule_.size()) return std::nullopt;
  return due(next_);
}

bool Follower::within_limit(io::Duration off) const {
  const io::Duration limit = stream_ ? options_.reanchor_after : options_.restart_after;
  return off <= limit && off >= -limit;
}

void Follower::anchor_at(io::TimePoint master_anchor, bool starting) {
  anchor_ = master_anchor;
  const io::Duration dance_now = host_.now() - master_anchor;
  // The first frame still ahead on the new anchor.
  const auto ahead =
      std::upper_bound(schedule_.begin(), schedule_.end(), dance_now,
                       [](io::Duration t, const player::ScheduledFrame& f) { return t < f.at; });
  auto first = static_cast<std::size_t>(ahead - schedule_.begin());
  catch_up_.clear();
  if (stream_) {
    // What the car should be doing now goes at once: the latest frame of each kind before now,
    // in their order, leaving out what the car already has.
    std::map<std::string, std::size_t> latest;
    for (std::size_t i = 0; i < first; ++i) latest[keys_[i]] = i;
    for (const auto& [key, i] : latest) {
      const auto had = sent_.find(key);
      if (had == sent_.end() || schedule_[had->second].bytes != schedule_[i].bytes) {
        catch_up_.push_back(i);
      }
    }
    std::sort(catch_up_.begin(), catch_up_.end());
    robot_anchor_ = anchor_;
  } else if (first > 0 && (dance_now - schedule_[first - 1].at <= options_.restart_after ||
                           (starting && first == schedule_.size()))) {
    // A piece whose start passed only just now still starts, that little late; so does the last
    // on a Start (a dance of one group stored when the master started), since no later piece
    // would start the robot at all.
    --first;
  }
  next_ = first;
}

bool Follower::handle(const ShowClockEvent& e) {
  const auto prepared = [&] {
    if (prepare()) return true;
    report_.end = FollowEnd::PrepareFailed;
    return false;
  };
  const io::TimePoint master_anchor = e.at - from_ms(e.dance_ms) + options_.offset;
  switch (e.kind) {
    case ShowClockKind::Open:
      if (!prepared()) return false;
      return true;
    case ShowClockKind::Start:
      if (!prepared()) return false;
      ++report_.starts;
      // A second start of the same run (the entry's media after its sequence) moves nothing.
      if (anchor_ && within_limit(master_anchor - *anchor_)) return true;
      anchor_at(master_anchor, true);
      say(fmt::format("start at {:.3f} s ({})", e.dance_ms / 1000, e.detail));
      return true;
    case ShowClockKind::Sync: {
      if (!anchor_) {
        // Joined a show already playing: its position is as good as a start.
        if (!prepared()) return false;
        ++report_.starts;
        anchor_at(master_anchor, false);
        say(fmt::format("joined at {:.3f} s ({})", e.dance_ms / 1000, e.detail));
        return true;
      }
      ++report_.syncs;
      const io::TimePoint robot = robot_anchor_.value_or(*anchor_);
      const io::Duration off = master_anchor - robot;  // robot's dance time minus the master's
      if (report_.offsets_ms.size() < kMaxOffsets) report_.offsets_ms.push_back(ms_of(off));
      // A stored group re-anchored already waits for its next piece: only a master that moved
      // again since is corrected again.
      if (!within_limit(off) && !within_limit(master_anchor - *anchor_)) {
        ++report_.corrections;
        anchor_at(master_anchor, false);
        if (stream_) {
          say(fmt::format("{:+.1f} ms off at {:.3f} s: re-anchored the stream", ms_of(off),
                          e.dance_ms / 1000));
        } else if (next_ < schedule_.size()) {
          say(
              fmt::format("{:+.1f} ms off at {:.3f} s: the next piece starts at {:.3f} s on the "
                          "master's time",
                          ms_of(off), e.dance_ms / 1000, ms_of(schedule_[next_].at) / 1000));
        } else {
          say(
              fmt::format("{:+.1f} ms off at {:.3f} s: no piece left to restart on (--resync "
                          "BARS cuts the dance into pieces)",
                          ms_of(off), e.dance_ms / 1000));
        }
      }
      return true;
    }
    case ShowClockKind::Stop:
      ++report_.stops;
      stop_robot();
      say(fmt::format("stop ({})", e.detail));
      return true;
  }
  return true;
}

bool Follower::write(std::size_t i, io::TimePoint due_at) {
  const io::TimePoint now = host_.now();
  if (Status w = line_.transport.write(schedule_[i].bytes); !w) {
    report_.error = w.error().message;
    return false;
  }
  if (report_.frames == 0) report_.first_late = now - due_at;
  ++report_.frames;
  if (stream_) sent_[keys_[i]] = i;
  // A start written late (a master's start cannot be foreseen by the start's own wire time)
  // puts the robot's dance that much behind.
  if (!stream_) robot_anchor_ = *anchor_ + std::max(io::Duration{0}, now - due_at);
  return true;
}

bool Follower::send_due() {
  if (anchor_) {
    const io::TimePoint now = host_.now();
    for (const std::size_t i : catch_up_) {
      if (!write(i, std::min(now, due(i)))) return false;
    }
  }
  catch_up_.clear();
  while (anchor_ && next_ < schedule_.size()) {
    const io::TimePoint at = due(next_);
    const io::TimePoint now = host_.now();
    if (now < at) return true;
    if (!write(next_, at)) return false;
    if (!stream_) {
      say(fmt::format("started group {} ({:.1f} ms after its time)", options_.group + next_,
                      ms_of(now - at)));
    }
    ++next_;
  }
  return true;
}

void Follower::stop_robot() {
  // Once stopped and not started since, there is nothing to stop.
  if (!report_.prepared || (report_.stop_sent && !anchor_)) return;
  Bytes stop;
  if (stream_ && board_.safe_stop != nullptr) stop = board_.safe_stop();
  if (!stream_ && board_.stop_frame != nullptr) stop = board_.stop_frame();
  anchor_.reset();
  robot_anchor_.reset();
  catch_up_.clear();
  sent_.clear();  // the next start sends the car everything again
  if (stop.empty()) return;
  if (Status w = line_.transport.write(stop); w) {
    report_.stop_sent = true;
  } else {
    report_.stop_error = w.error().message;
  }
}

void Follower::finish(FollowEnd end) {
  stop_robot();
  report_.end = end;
}

FollowReport Follower::run(ShowClock& clock) {
  Follower* self = this;
  (void)follow_all(std::span<Follower* const>(&self, 1), clock, host_, options_.interrupted,
                   options_.poll, options_.once);
  return report_;
}

FollowAll follow_all(std::span<Follower* const> followers, ShowClock& clock, io::Clock& host,
                     const std::atomic<bool>* interrupted, io::Duration poll, bool once) {
  const auto finish = [&](FollowEnd end, std::optional<std::size_t> failed) {
    // The one that failed first keeps its reason; every robot is stopped.
    for (std::size_t i = 0; i < followers.size(); ++i) {
      followers[i]->finish(failed && i != *failed ? FollowEnd::Stopped : end);
    }
    return FollowAll{end, failed};
  };
  for (;;) {
    if (interrupted != nullptr && interrupted->load()) return finish(FollowEnd::Interrupted, {});
    io::TimePoint deadline = host.now() + poll;
    for (const Follower* f : followers) {
      if (const auto d = f->next_due()) deadline = std::min(deadline, *d);
    }
    if (const auto e = clock.next(deadline)) {
      for (std::size_t i = 0; i < followers.size(); ++i) {
        if (!followers[i]->handle(*e)) return finish(FollowEnd::PrepareFailed, i);
      }
      if (once && e->kind == ShowClockKind::Stop) return finish(FollowEnd::Stopped, {});
    } else if (clock.ended()) {
      return finish(FollowEnd::SourceEnded, {});
    }
    for (std::size_t i = 0; i < followers.size(); ++i) {
      if (!followers[i]->send_due()) return finish(FollowEnd::WriteFailed, i);
    }
  }
}

}  // namespace seqc::follow
