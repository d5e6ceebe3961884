// The robot that follows the studio page's playhead: a PlayheadSink (playhead.hpp) that moves
// one board, through the live frames of its row (boards/board.hpp), to the dance's positions at
// the page's instant, on the Clock it is given.
//
// Servo controllers (xArm family, LSC-6). While the page plays, each keyframe's move is sent so
// that it finishes arriving when its step starts, carrying only the servos whose target changes
// (as `seqc play` sends them); playing from inside a step sends the rest of that step's move.
// The line is never given more than it carries: nothing is written while the previous frame is
// still on the wire, and frames that fell due meanwhile are merged into one move to the latest
// targets (intermediate targets are dropped, the dance is not fallen behind). Where the robot is
// comes from what was sent; before that, from reading the servos where they can say
// (FollowerOptions::read_positions), else a servo is taken to be at its home.
//
// A jump (a scrub, the page's loop wrapping, playing from a place the robot is not at) is slewed:
// one move to the positions the controller's motion has at the instant (compiler/formats/
// simulate.hpp, pose_at) lasting max over servos of |target - where it is| / max_speed (at least
// the controller's shortest action); while the page plays, to where the dance will be when the
// slew ends, from which the keyframes go on. Paused sends nothing: the move under way finishes.
//
// The Raspblock car. Its packets are sent at their times, and on a jump its state at the
// instant. The gimbal and servos slew in steps of `car_slew_step_ms`, never faster than
// `car_servo_speed` (the program names no max_speed for them). The drive cannot go back in
// time: a scrub stops it (the board's stop frame) and says so in FollowerState::notices; it
// drives again when the page plays. A pause stops the drive too (a held car stands still).
//
// stop() ends every move as `seqc play` does on Ctrl-C: the car gets its stop frame; a servo
// controller gets nothing more (its servos finish the move they were given).
//
// RobotFollower itself never sleeps and has no thread: service() sends what is due by the clock's
// now, so tests drive it on io::ManualClock. make_robot_follower() adds the thread that calls
// service() on time, for a clock that runs by itself.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "compiler/compile.hpp"
#include "compiler/formats/raspblock_simulate.hpp"
#include "protocol/raspblock/raspblock.hpp"
#include "protocol/servo_target.hpp"
#include "runtime/boards/board.hpp"
#include "runtime/io/clock.hpp"
#include "runtime/io/transport.hpp"
#include "runtime/studio/playhead.hpp"

namespace seqc::studio {

struct FollowerOptions {
  // A Playing report this far (ms) from where the follower's clock puts the dance is a jump.
  double jump_tolerance_ms = 100;
  // The car's gimbal and servos, in microseconds per second: the stock hobby servo's rated
  // 60 degrees in 0.16 s at 2000 us per 180 degrees (the servo profiles' default max_speed).
  double car_servo_speed = 60.0 / 0.16 * 2000.0 / 180.0;
  // Between two steps of a car's slew (its programs' default resolution).
  std::uint32_t car_slew_step_ms = 20;
  // Where servos that report their positions (the xArm family's bus servos) stand is read
  // (ServoPositionRead) before their first move, so the first slew is timed from there; this
  // long for the answer. Unread, a servo is taken to be at its home.
  bool read_positions = true;
  io::Duration read_timeout = std::chrono::milliseconds(300);
};

class RobotFollower final : public PlayheadSink {
 public:
  // `board`, `transport` and `clock` outlive the follower.
  RobotFollower(const boards::Board& board, io::Transport& transport, io::Clock& clock,
                FollowerOptions options = {});

  void set_program(const compiler::CompileOutput& output) override;
  FollowerState report(const PlayheadReport& playhead) override;
  void stop() override;

  // Sends what is due by the clock's now; returns when something next falls due (nullopt:
  // nothing is scheduled).
  std::optional<io::TimePoint> service();

  // Bytes written so far, and the frames they were (for measurements).
  std::size_t bytes_written() const { return bytes_written_; }
  std::size_t frames_written() const { return frames_written_; }

 private:
  // One servo as the follower last commanded it, on the follower's clock.
  struct Servo {
    std::uint8_t id = 0;
    double home = 0;
    double max_speed = 0;  // units per second; 0: unchecked
    bool known = false;    // sent anything yet
    double from = 0, to = 0;
    io::TimePoint t0{0}, t1{0};
    double at(io::TimePoint now) const;
  };
  struct Timed {
    io::TimePoint at{0};
    raspblock::Packet packet;
  };

  void read_where_servos_stand(const compiler::RobotInfo& robot);
  double dance_ms(io::TimePoint now) const;
  bool line_busy(io::TimePoint now) const { return now < line_free_at_; }
  bool write(Bytes bytes, io::TimePoint now);
  void note(std::string text);

  // Servo controllers.
  std::optional<io::TimePoint> service_servos(io::TimePoint now);
  void slew_servos(io::TimePoint now);
  // The move to `targets` (those that change) taking `time_ms`, at least as long as every
  // servo's max_speed needs from where it is when the move arrives; the move's time, nullopt
  // when nothing was sent.
  std::optional<double> send_move(std::vector<lsc::ServoTarget> targets, double time_ms,
                                  io::TimePoint now);
  // The longest any servo of `targets` needs at its max_speed from where it is at `at` (or a
  // little later, when it is farther then).
  double slew_ms(const std::vector<lsc::ServoTarget>& targets, io::TimePoint at) const;
  Servo* find_servo(std::uint8_t id);
  std::size_t first_keyframe_after(double ms) const;
  io::TimePoint keyframe_due(std::size_t k) const;

  // The car.
  std::optional<io::TimePoint> service_car(io::TimePoint now);
  void slew_car(io::TimePoint now);
  compiler::CarState car_state_at(double ms) const;
  void send_car(const std::vector<raspblock::Packet>& packets, io::TimePoint now);
  // The packets that take the car from car_ to `target` (the drive too when `drive`).
  std::vector<raspblock::Packet> car_changes_to(const compiler::CarState& target, bool drive) const;
  void stop_drive(io::TimePoint now);
  double car_slew_ms(const compiler::CarState& target) const;

  const boards::Board& board_;
  io::Transport& transport_;
  io::Clock& clock_;
  FollowerOptions options_;

  std::optional<compiler::ServoProgram> servo_;
  std::optional<compiler::RaspblockProgram> car_program_;
  std::vector<compiler::CarSimulation::Sample> car_changes_;
  std::vector<Servo> servos_;             // the program's servos, ascending id
  compiler::CarState car_;                // the car's outputs as last sent
  compiler::CompileOutput frame_output_;  // one move or a few packets, for the row's live_frames
  std::vector<io::Duration> leads_;       // per keyframe: its whole frame's wire time

  bool stopped_ = false;
  bool read_tried_ = false;
  bool drive_refused_ = false;  // the page was told, since it last played
  bool playing_ = false;
  bool slew_pending_ = false;  // a jump waits for the line
  double held_ms_ = 0;         // where the page holds, while not playing
  io::TimePoint anchor_host_{0};
  double anchor_ms_ = 0;
  double resume_ms_ = 0;       // the keyframes (packets) go on from this dance time
  bool resume_state_ = false;  // the car: its state at resume_ms_ is still to be sent
  std::size_t next_ = 0;       // the next keyframe (or packet) to send
  io::TimePoint slew_end_{0};  // on the follower's clock
  double slew_until_ms_ = 0;
  std::vector<Timed> ramp_;        // the car's slew steps not yet sent
  io::TimePoint line_free_at_{0};  // when the last byte written has left
  std::vector<std::string> notices_;
  std::size_t bytes_written_ = 0;
  std::size_t frames_written_ = 0;
};

// A RobotFollower behind a mutex, with a thread that calls service() on time; its destructor
// stops the thread (not the robot: call stop() for that). For a clock that runs by itself
// (io::SteadyClock): on a ManualClock the thread would run emulated time away.
std::unique_ptr<PlayheadSink> make_robot_follower(const boards::Board& board,
                                                  io::Transport& transport, io::Clock& clock,
                                                  FollowerOptions options = {});

}  // namespace seqc::studio
