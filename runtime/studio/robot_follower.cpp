#include "runtime/studio/robot_follower.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <map>
#include <mutex>
#include <thread>
#include <type_traits>
#include <utility>
#include <variant>

#include "compiler/formats/simulate.hpp"
#include "compiler/targets/servo_controller/servo_wire.hpp"
#include "protocol/lsc/group_download.hpp"
#include "runtime/boards/first_move.hpp"

namespace seqc::studio {
namespace {

io::Duration ms_duration(double ms) {
  return std::chrono::duration_cast<io::Duration>(std::chrono::duration<double, std::milli>(ms));
}

double to_ms(io::Duration d) { return std::chrono::duration<double, std::milli>(d).count(); }

std::uint64_t whole_ms(double ms) { return ms <= 0 ? 0 : static_cast<std::uint64_t>(ms); }

bool driving(const compiler::CarState& s) { return s.x != 0 || s.y != 0 || s.z != 0; }

// The packets that take the car from `from` to `to` (its drive too when `drive`).
std::vector<raspblock::Packet> car_packets(const compiler::CarState& from,
                                           const compiler::CarState& to, bool drive) {
  std::vector<raspblock::Packet> out;
  if (drive && (to.x != from.x || to.y != from.y || to.z != from.z)) {
    out.push_back(raspblock::Rocker{to.x, to.y, to.z});
  }
  if (to.pan && to.tilt && (to.pan != from.pan || to.tilt != from.tilt)) {
    out.push_back(raspblock::GimbalServos{static_cast<std::uint16_t>(*to.pan),
                                          static_cast<std::uint16_t>(*to.tilt)});
  }
  for (std::size_t i = 0; i < to.servos.size(); ++i) {
    if (to.servos[i] && to.servos[i] != from.servos[i]) {
      out.push_back(raspblock::SingleServo{static_cast<std::uint8_t>(i + 1),
                                           static_cast<std::uint16_t>(*to.servos[i])});
    }
  }
  return out;
}

// Notices kept for the page between two of its reports.
constexpr std::size_t kMostNotices = 16;

}  // namespace

double RobotFollower::Servo::at(io::TimePoint now) const {
  if (!known) return home;
  if (now >= t1 || t1 <= t0) return to;
  if (now <= t0) return from;
  return from + (to - from) * to_ms(now - t0) / to_ms(t1 - t0);
}

RobotFollower::RobotFollower(const boards::Board& board, io::Transport& transport, io::Clock& clock,
                             FollowerOptions options)
    : board_(board), transport_(transport), clock_(clock), options_(options) {}

void RobotFollower::note(std::string text) {
  // Said to the page at its next report; a page that stopped asking is not told more.
  if (notices_.size() < kMostNotices) notices_.push_back(std::move(text));
}

double RobotFollower::dance_ms(io::TimePoint now) const {
  return anchor_ms_ + to_ms(now - anchor_host_);
}

bool RobotFollower::write(Bytes bytes, io::TimePoint now) {
  if (bytes.empty()) return false;
  const Status written = transport_.write(bytes);
  if (!written) {
    note("sending to " + transport_.describe() + " failed: " + written.error().message);
    return false;
  }
  bytes_written_ += bytes.size();
  ++frames_written_;
  // A serial write returns once the bytes are queued: the line is busy until they have left.
  const io::TimePoint after = clock_.now();
  const double wire = transport_.seconds_per_byte() * static_cast<double>(bytes.size());
  line_free_at_ = std::max(after, std::max(now, line_free_at_) + ms_duration(wire * 1000));
  return true;
}

void RobotFollower::set_program(const compiler::CompileOutput& output) {
  const bool had = servo_.has_value() || car_program_.has_value();
  servo_.reset();
  car_program_.reset();
  car_changes_.clear();
  ramp_.clear();
  leads_.clear();
  next_ = 0;
  if (!output.program) {
    note("no program to follow: the file does not compile");
    return;
  }
  if (output.board != board_.key) {
    note("the program is for the " + output.board + " board, and the port reaches the " +
         std::string(board_.name) + ": the robot does not follow it");
    return;
  }
  frame_output_.board = output.board;
  if (const compiler::ServoProgram* p = output.servo_program()) {
    servo_ = *p;
    // The robot stays where it is: servos already commanded keep what was sent.
    std::vector<Servo> servos;
    for (const std::uint8_t id : compiler::used_servo_ids(*p)) {
      Servo s;
      s.id = id;
      if (const compiler::ServoInfo* info = p->robot.find_id(id)) {
        s.home = info->home;
        s.max_speed = info->max_speed.value_or(0);
      }
      if (const Servo* old = find_servo(id)) {
        s.known = old->known;
        s.from = old->from;
        s.to = old->to;
        s.t0 = old->t0;
        s.t1 = old->t1;
      }
      servos.push_back(s);
    }
    servos_ = std::move(servos);
    read_where_servos_stand(p->robot);
    compiler::ServoProgram frame;
    frame.robot = p->robot;
    frame.controller = p->controller;
    frame_output_.program = std::move(frame);
    // Each keyframe's move is written its wire time before its step starts, so that it has
    // arrived by then; its whole frame is the longest the move can be.
    const double spb = transport_.seconds_per_byte();
    for (const compiler::Keyframe& k : p->keyframes) {
      std::get<compiler::ServoProgram>(*frame_output_.program).keyframes = {
          compiler::Keyframe{0, k.time_ms, k.targets, {}}};
      auto frames = board_.live_frames(frame_output_);
      const std::size_t size = frames && !frames->empty() ? frames->front().bytes.size() : 0;
      leads_.push_back(ms_duration(spb * 1000 * static_cast<double>(size)));
    }
  } else if (const compiler::RaspblockProgram* car = output.raspblock_program()) {
    car_program_ = *car;
    car_changes_ = compiler::car_changes(*car).samples;
    frame_output_.program = compiler::RaspblockProgram{};
  }
  if (!had && !playing_) return;
  // The dance changed under the robot: it goes to the new one's positions at the playhead.
  const io::TimePoint now = clock_.now();
  if (playing_) {
    anchor_ms_ = dance_ms(now);
    anchor_host_ = now;
  }
  slew_pending_ = true;
  service();
}

void RobotFollower::read_where_servos_stand(const compiler::RobotInfo& robot) {
  if (read_tried_ || !options_.read_positions || !board_.queries ||
      !compiler::servos_report_positions(robot)) {
    return;
  }
  std::vector<std::uint8_t> ids;
  for (const Servo& s : servos_) {
    if (!s.known) ids.push_back(s.id);
  }
  if (ids.empty()) return;
  const boards::Line line{transport_, clock_, nullptr, options_.read_timeout};
  const auto read = boards::read_start(board_, line, ids);
  const io::TimePoint now = clock_.now();
  if (!read) {
    read_tried_ = true;  // not again: a board that does not answer would hold every save up
    note("the servos did not say where they stand: their first move is timed from home");
    return;
  }
  for (const auto& [id, position] : *read) {
    Servo* s = find_servo(id);
    if (s == nullptr) continue;
    s->known = true;
    s->from = s->to = position;
    s->t0 = s->t1 = now;
  }
}

FollowerState RobotFollower::report(const PlayheadReport& playhead) {
  const io::TimePoint now = clock_.now();
  stopped_ = false;
  FollowerState state;
  if (!servo_ && !car_program_) {
    state.notices = std::move(notices_);
    notices_.clear();
    return state;
  }
  const double ms = std::max(0.0, playhead.ms);
  switch (playhead.mode) {
    case PlayheadMode::Paused:
      playing_ = false;
      held_ms_ = ms;
      if (car_program_) stop_drive(now);
      break;
    case PlayheadMode::Scrubbed:
      playing_ = false;
      held_ms_ = ms;
      slew_pending_ = true;
      // Said once a drag, when the drive is running or the dance drives there.
      if (car_program_ && !drive_refused_ && (driving(car_) || driving(car_state_at(ms)))) {
        drive_refused_ = true;
        note(
            "the car's drive does not follow a scrub: it cannot drive backwards in time, so it "
            "stands until the page plays; the gimbal and servos follow");
        stop_drive(now);
      }
      break;
    case PlayheadMode::Playing: {
      const bool jump =
          playhead.looped || slew_pending_ ||
          (playing_ ? std::abs(ms - dance_ms(now)) > options_.jump_tolerance_ms
                    : std::abs(ms - held_ms_) > options_.jump_tolerance_ms || now < slew_end_);
      if (!playing_ || jump) {
        anchor_host_ = now;
        anchor_ms_ = ms;
      }
      if (jump) {
        slew_pending_ = true;
      } else if (!playing_) {
        resume_ms_ = ms;
        resume_state_ = true;
        next_ = first_keyframe_after(ms);
      }
      playing_ = true;
      drive_refused_ = false;
      break;
    }
  }
  service();
  state.slewing = clock_.now() < slew_end_;
  state.slew_until_ms = state.slewing ? slew_until_ms_ : ms;
  state.notices = std::move(notices_);
  notices_.clear();
  return state;
}

void RobotFollower::stop() {
  playing_ = false;
  slew_pending_ = false;
  ramp_.clear();
  stopped_ = true;
  // As `seqc play` on Ctrl-C: the board's stop after an early end where it has one (the car's
  // speeds to 0); a servo controller gets no more moves and finishes the one it was given.
  if (board_.safe_stop != nullptr) {
    if (write(board_.safe_stop(), clock_.now())) car_.x = car_.y = car_.z = 0;
  }
}

std::optional<io::TimePoint> RobotFollower::service() {
  if (stopped_) return std::nullopt;
  const io::TimePoint now = clock_.now();
  if (servo_) return service_servos(now);
  if (car_program_) return service_car(now);
  return std::nullopt;
}

// ---- servo controllers -------------------------------------------------------------------------

RobotFollower::Servo* RobotFollower::find_servo(std::uint8_t id) {
  for (Servo& s : servos_) {
    if (s.id == id) return &s;
  }
  return nullptr;
}

// How far from the line's arithmetic a move may take effect (the line's, the kernel's and the
// scheduler's jitter), for the slew's length.
constexpr io::Duration kArrivalSlack = std::chrono::milliseconds(15);

double RobotFollower::slew_ms(const std::vector<lsc::ServoTarget>& targets,
                              io::TimePoint now) const {
  double longest = 0;
  for (const lsc::ServoTarget& t : targets) {
    for (const Servo& s : servos_) {
      if (s.id != t.id || s.max_speed <= 0) continue;
      // Where the servo is when the move takes effect, kArrivalSlack either side: a servo still
      // moving away from the target is farther if the move arrives late, one coming towards it
      // if the move before arrived late (so the servo is behind where the arithmetic puts it),
      // and the move must not be faster than max_speed from there either. A servo's path is a
      // line and then a stop, so the farthest point of the stretch is one of its ends.
      const double early = std::abs(t.position - s.at(now - kArrivalSlack));
      const double late = std::abs(t.position - s.at(now + kArrivalSlack));
      longest = std::max(longest, std::max(early, late) / s.max_speed * 1000);
    }
  }
  return longest;
}

std::size_t RobotFollower::first_keyframe_after(double ms) const {
  if (!servo_) return 0;
  const auto& keys = servo_->keyframes;
  std::size_t k = 0;
  while (k < keys.size() && keys[k].start_ms + double(keys[k].time_ms) <= ms) ++k;
  return k;
}

io::TimePoint RobotFollower::keyframe_due(std::size_t k) const {
  const double start = std::max(double(servo_->keyframes[k].start_ms), resume_ms_);
  const io::Duration lead = k < leads_.size() ? leads_[k] : io::Duration{0};
  return anchor_host_ + ms_duration(start - anchor_ms_) - lead;
}

std::optional<double> RobotFollower::send_move(std::vector<lsc::ServoTarget> targets,
                                               double time_ms, io::TimePoint now) {
  // Changed servos only: one already heading for its target is left to get there.
  std::erase_if(targets, [&](const lsc::ServoTarget& t) {
    const Servo* s = find_servo(t.id);
    return s == nullptr || (s->known && std::lround(s->to) == t.position);
  });
  if (targets.empty()) return std::nullopt;
  auto frames_for = [&](std::uint16_t time) {
    std::get<compiler::ServoProgram>(*frame_output_.program).keyframes = {
        compiler::Keyframe{0, time, targets, {}}};
    return board_.live_frames(frame_output_);
  };
  auto frames = frames_for(lsc::kMinActionMs);
  if (!frames || frames->empty()) {
    note("internal: no move could be made for the board: " +
         (frames ? std::string("none") : frames.error().message));
    return std::nullopt;
  }
  // The move takes effect as its last byte arrives (after the frame before it has left, and its
  // own wire time), so its length is measured from where the servos will be then: measured from
  // now, a servo still moving away from the new target would be given too little time.
  const double wire_ms =
      transport_.seconds_per_byte() * static_cast<double>(frames->front().bytes.size()) * 1000;
  const io::TimePoint arrives = std::max(now, line_free_at_) + ms_duration(wire_ms);
  const double needed =
      std::ceil(std::max({time_ms, slew_ms(targets, arrives), double(lsc::kMinActionMs)}));
  const auto time = static_cast<std::uint16_t>(std::min(needed, double(lsc::kMaxActionMs)));
  frames = frames_for(time);
  if (!frames || frames->empty()) {
    note("internal: no move could be made for the board: " +
         (frames ? std::string("none") : frames.error().message));
    return std::nullopt;
  }
  const std::vector<double> where = [&] {
    std::vector<double> w;
    for (const lsc::ServoTarget& t : targets) w.push_back(find_servo(t.id)->at(arrives));
    return w;
  }();
  if (!write(std::move(frames->front().bytes), now)) return std::nullopt;
  // The move starts as its last byte arrives.
  const io::TimePoint start = line_free_at_;
  for (std::size_t i = 0; i < targets.size(); ++i) {
    Servo& s = *find_servo(targets[i].id);
    s.known = true;
    s.from = where[i];
    s.to = targets[i].position;
    s.t0 = start;
    s.t1 = start + std::chrono::milliseconds(time);
  }
  return double(time);
}

void RobotFollower::slew_servos(io::TimePoint now) {
  const compiler::ServoProgram& program = *servo_;
  std::optional<double> took;
  if (playing_) {
    // Where the dance will be when the slew ends: a few rounds from the time the positions
    // now need to the time the later ones need.
    const double from = dance_ms(now);
    double span = lsc::kMinActionMs;
    for (int round = 0; round < 4; ++round) {
      const double need = slew_ms(compiler::pose_at(program, whole_ms(from + span)), now);
      if (need <= span) break;
      span = std::ceil(need);
    }
    took = send_move(compiler::pose_at(program, whole_ms(from + span)), span, now);
  } else {
    took = send_move(compiler::pose_at(program, whole_ms(held_ms_)), 0, now);
  }
  // The move starts once it has arrived: the robot is on the playhead when it ends, and the
  // keyframes go on from the dance's time then.
  slew_end_ = took ? line_free_at_ + ms_duration(*took) : now;
  const double lasts = to_ms(slew_end_ - now);
  if (playing_) {
    resume_ms_ = dance_ms(slew_end_);
    next_ = first_keyframe_after(resume_ms_);
  }
  slew_until_ms_ = (playing_ ? dance_ms(now) : held_ms_) + lasts;
}

std::optional<io::TimePoint> RobotFollower::service_servos(io::TimePoint now) {
  if (slew_pending_) {
    if (line_busy(now)) return line_free_at_;
    slew_pending_ = false;
    slew_servos(now);
    now = clock_.now();
  }
  if (!playing_) return std::nullopt;
  const auto& keys = servo_->keyframes;
  if (next_ >= keys.size()) return std::nullopt;
  if (line_busy(now)) return std::max(line_free_at_, keyframe_due(next_));
  // Every move due by now, merged into one to the latest targets: the line carries one frame
  // at a time, and a move that could only leave late is dropped rather than queued.
  std::map<std::uint8_t, std::uint16_t> merged;
  std::optional<std::size_t> last;
  while (next_ < keys.size() && keyframe_due(next_) <= now) {
    for (const lsc::ServoTarget& t : keys[next_].targets) merged[t.id] = t.position;
    last = next_++;
  }
  if (last) {
    std::vector<lsc::ServoTarget> targets;
    for (const auto& [id, position] : merged) targets.push_back({id, position});
    const double end = double(keys[*last].start_ms) + keys[*last].time_ms;
    // It arrives as the step starts (or at once, inside the step): the rest of the step.
    const double arrives = std::max(dance_ms(now) + to_ms(leads_[*last]),
                                    std::max(resume_ms_, double(keys[*last].start_ms)));
    (void)send_move(std::move(targets), end - arrives, now);
  }
  if (next_ >= keys.size()) return std::nullopt;
  return std::max(line_free_at_, keyframe_due(next_));
}

// ---- the car -----------------------------------------------------------------------------------

compiler::CarState RobotFollower::car_state_at(double ms) const {
  compiler::CarState state;
  for (const compiler::CarSimulation::Sample& s : car_changes_) {
    if (double(s.time_ms) > ms) break;
    state = s.state;
  }
  return state;
}

std::vector<raspblock::Packet> RobotFollower::car_changes_to(const compiler::CarState& target,
                                                             bool drive) const {
  return car_packets(car_, target, drive);
}

void RobotFollower::send_car(const std::vector<raspblock::Packet>& packets, io::TimePoint now) {
  if (packets.empty()) return;
  compiler::RaspblockProgram frame;
  for (const raspblock::Packet& p : packets) frame.packets.push_back({0, p, {}});
  frame_output_.program = std::move(frame);
  auto frames = board_.live_frames(frame_output_);
  if (!frames) {
    note("internal: no packet could be made for the board: " + frames.error().message);
    return;
  }
  Bytes bytes;
  for (const player::ScheduledFrame& f : *frames)
    bytes.insert(bytes.end(), f.bytes.begin(), f.bytes.end());
  if (!write(std::move(bytes), now)) return;
  for (const raspblock::Packet& p : packets) compiler::apply_packet(car_, p);
}

void RobotFollower::stop_drive(io::TimePoint now) {
  if (!driving(car_) || board_.safe_stop == nullptr) return;
  if (write(board_.safe_stop(), now)) car_.x = car_.y = car_.z = 0;
}

double RobotFollower::car_slew_ms(const compiler::CarState& target) const {
  double longest = 0;
  const auto far = [&](const std::optional<int>& from, const std::optional<int>& to) {
    if (from && to)
      longest = std::max(longest, std::abs(*to - *from) * 1000.0 / options_.car_servo_speed);
  };
  far(car_.pan, target.pan);
  far(car_.tilt, target.tilt);
  for (std::size_t i = 0; i < target.servos.size(); ++i) far(car_.servos[i], target.servos[i]);
  return longest;
}

void RobotFollower::slew_car(io::TimePoint now) {
  // The car stands while its gimbal and servos slew: a scrub never drives it, and a jump
  // while playing drives again from where the dance is when the slew ends.
  stop_drive(now);
  ramp_.clear();
  const double from = playing_ ? dance_ms(now) : held_ms_;
  double span = car_slew_ms(car_state_at(from));
  if (playing_) {
    for (int round = 0; round < 4; ++round) {
      const double need = car_slew_ms(car_state_at(from + span));
      if (need <= span) break;
      span = need;
    }
  }
  const compiler::CarState target = car_state_at(playing_ ? from + span : from);
  const double step = std::max<std::uint32_t>(1, options_.car_slew_step_ms);
  const int n = std::max(1, static_cast<int>(std::ceil(span / step)));
  // Step k of n carries k/n of the way and is sent at (k-1)/n of the time, as a car program's
  // moves are, so each step is no faster than the speed allows.
  for (int k = 1; k <= n; ++k) {
    const double f = double(k) / n;
    const auto part = [&](const std::optional<int>& a, const std::optional<int>& b) {
      if (!a || !b || k == n) return b;
      return std::optional<int>(static_cast<int>(std::lround(*a + (*b - *a) * f)));
    };
    compiler::CarState s = car_;
    s.pan = part(car_.pan, target.pan);
    s.tilt = part(car_.tilt, target.tilt);
    for (std::size_t i = 0; i < s.servos.size(); ++i)
      s.servos[i] = part(car_.servos[i], target.servos[i]);
    const io::TimePoint at = now + ms_duration(span * (k - 1) / n);
    // Every output of the step is sent, so a step that arrives late still lands where it should.
    const std::vector<raspblock::Packet> packets = car_packets(compiler::CarState{}, s, false);
    for (const raspblock::Packet& p : packets) ramp_.push_back({at, p});
  }
  slew_end_ = now + ms_duration(span);
  slew_until_ms_ = from + span;
  if (playing_) {
    resume_ms_ = from + span;
    resume_state_ = true;
  }
}

std::optional<io::TimePoint> RobotFollower::service_car(io::TimePoint now) {
  if (slew_pending_) {
    if (line_busy(now)) return line_free_at_;
    slew_pending_ = false;
    slew_car(now);
  }
  if (line_busy(now)) return line_free_at_;
  // The slew's steps due by now; of several, the latest of each output.
  if (!ramp_.empty() && ramp_.front().at <= now) {
    compiler::CarState wanted = car_;
    while (!ramp_.empty() && ramp_.front().at <= now) {
      compiler::apply_packet(wanted, ramp_.front().packet);
      ramp_.erase(ramp_.begin());
    }
    send_car(car_changes_to(wanted, false), now);
  }
  std::optional<io::TimePoint> next;
  if (!ramp_.empty()) next = ramp_.front().at;
  if (!playing_) return next;
  const auto host = [&](double ms) { return anchor_host_ + ms_duration(ms - anchor_ms_); };
  const auto& packets = car_program_->packets;
  if (resume_state_) {
    if (now < host(resume_ms_)) return next ? std::min(*next, host(resume_ms_)) : host(resume_ms_);
    resume_state_ = false;
    // The board's settings first (the last PID packet at or before the instant), then its
    // state there.
    std::vector<raspblock::Packet> out;
    next_ = 0;
    while (next_ < packets.size() && packets[next_].at_ms <= resume_ms_) {
      if (std::holds_alternative<raspblock::PidAdjust>(packets[next_].packet)) {
        out = {packets[next_].packet};
      }
      ++next_;
    }
    const std::vector<raspblock::Packet> state = car_changes_to(car_state_at(resume_ms_), true);
    out.insert(out.end(), state.begin(), state.end());
    send_car(out, now);
  } else {
    compiler::CarState wanted = car_;
    std::vector<raspblock::Packet> pid;
    while (next_ < packets.size() && host(packets[next_].at_ms) <= now) {
      if (std::holds_alternative<raspblock::PidAdjust>(packets[next_].packet)) {
        pid = {packets[next_].packet};
      }
      compiler::apply_packet(wanted, packets[next_].packet);
      ++next_;
    }
    std::vector<raspblock::Packet> out = pid;
    const std::vector<raspblock::Packet> state = car_changes_to(wanted, true);
    out.insert(out.end(), state.begin(), state.end());
    send_car(out, now);
  }
  if (next_ < packets.size()) {
    const io::TimePoint due = std::max(line_free_at_, host(packets[next_].at_ms));
    next = next ? std::min(*next, due) : due;
  }
  return next;
}

// ---- the thread
// ----------------------------------------------------------------------------------

namespace {

// The longest the thread sleeps between two looks at the schedule: a report may have changed it.
constexpr io::Duration kTick = std::chrono::milliseconds(5);

class FollowerThread final : public PlayheadSink {
 public:
  FollowerThread(const boards::Board& board, io::Transport& transport, io::Clock& clock,
                 FollowerOptions options)
      : follower_(board, transport, clock, options), clock_(clock), worker_([this] { run(); }) {}
  ~FollowerThread() override {
    quit_ = true;
    worker_.join();
  }
  FollowerThread(const FollowerThread&) = delete;
  FollowerThread& operator=(const FollowerThread&) = delete;

  void set_program(const compiler::CompileOutput& output) override {
    const std::lock_guard lock(mutex_);
    follower_.set_program(output);
  }
  FollowerState report(const PlayheadReport& playhead) override {
    const std::lock_guard lock(mutex_);
    return follower_.report(playhead);
  }
  void stop() override {
    const std::lock_guard lock(mutex_);
    follower_.stop();
  }

 private:
  void run() {
    while (!quit_) {
      std::optional<io::TimePoint> next;
      {
        const std::lock_guard lock(mutex_);
        next = follower_.service();
      }
      const io::TimePoint wake = clock_.now() + kTick;
      clock_.sleep_until(next ? std::min(*next, wake) : wake);
    }
  }

  std::mutex mutex_;
  RobotFollower follower_;
  io::Clock& clock_;
  std::atomic<bool> quit_{false};
  std::thread worker_;  // last: it starts once everything it uses is made
};

}  // namespace

std::unique_ptr<PlayheadSink> make_robot_follower(const boards::Board& board,
                                                  io::Transport& transport, io::Clock& clock,
                                                  FollowerOptions options) {
  return std::make_unique<FollowerThread>(board, transport, clock, options);
}

}  // namespace seqc::studio
