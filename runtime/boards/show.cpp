#include "runtime/boards/show.hpp"

#include <algorithm>
#include <chrono>
#include <utility>

#include "runtime/audio/playback_sync.hpp"

namespace seqc::boards {
namespace {

// A short lead, beyond the earliest write, so the first deadline is in the future for every
// performer.
constexpr io::Duration kLead = std::chrono::milliseconds(20);

bool stores(const Board& board) { return board.run_frame != nullptr; }

}  // namespace

io::Duration ShowReport::start_skew() const {
  io::Duration earliest = io::Duration::max(), latest = io::Duration::min();
  for (const PerformerReport& p : performers) {
    const io::Duration first = p.started().value_or(io::Duration{0});
    earliest = std::min(earliest, first);
    latest = std::max(latest, first);
  }
  return latest - earliest;
}

ShowReport perform(std::vector<Performer>& performers, io::Clock& clock,
                   const std::atomic<bool>* interrupted, io::Duration reply_timeout,
                   std::optional<io::TimePoint> start_at) {
  ShowReport report;
  report.performers.resize(performers.size());
  std::vector<player::Track> tracks;
  for (Performer& p : performers) {
    player::Track track;
    track.transport = p.port->transport.get();
    if (stores(*p.board)) {
      // The stored group starts at the common start, with the board's own run command.
      track.frames.push_back({io::Duration{0}, p.board->run_frame(p.group, 1)});
      if (p.board->stop_frame != nullptr) track.safe_stop = p.board->stop_frame();
    } else {
      if (p.board->live_frames == nullptr) {
        report.error = p.name + ": " + std::string(p.board->name) + " plays nothing live";
        return report;
      }
      auto frames = p.board->live_frames(*p.output);
      if (!frames) {
        report.error = p.name + ": " + frames.error().message;
        return report;
      }
      track.frames = std::move(frames).value();
      if (p.board->safe_stop != nullptr) track.safe_stop = p.board->safe_stop();
    }
    PerformerReport& mine = report.performers[tracks.size()];
    if (!track.frames.empty()) {
      mine.wire =
          audio::wire_time(track.frames.front().bytes.size(), track.transport->seconds_per_byte());
    }
    mine.delay = p.board->start_delay;
    track.seconds_per_byte = track.transport->seconds_per_byte();
    track.early = mine.delay;
    tracks.push_back(std::move(track));
  }

  player::PlayOptions options;
  options.interrupted = interrupted;
  options.lead = kLead;  // the player adds what the frames written earliest need
  options.start_at = start_at;
  report.play = player::play(tracks, clock, options);

  for (std::size_t i = 0; i < performers.size(); ++i) {
    if (i < report.play.tracks.size()) report.performers[i].track = report.play.tracks[i];
  }
  if (report.play.end != player::PlayEnd::Completed) return report;
  // The replies to the run commands were kept by the transports while the streams played.
  for (std::size_t i = 0; i < performers.size(); ++i) {
    Performer& p = performers[i];
    if (!stores(*p.board) || p.board->confirm_run == nullptr) continue;
    const Line line{*p.port->transport, *p.port->clock, interrupted, reply_timeout};
    report.performers[i].run = p.board->confirm_run(line, p.group, 1);
  }
  return report;
}

StageOpen open_stage(const compiler::Performer& p, const std::string& trace_prefix,
                     io::Clock& clock, const Hooks& hooks, ShowStage& stage) {
  StageOpen r;
  stage.performer = &p;
  if (p.port.empty()) {
    r.problem = StageProblem::NoPort;
    return r;
  }
  if (!trace_prefix.empty()) {
    r.trace_path = trace_prefix + "-" + p.name + ".trace";
    if (!stage.trace.open(r.trace_path)) {
      r.problem = StageProblem::TraceUnwritable;
      return r;
    }
  }
  stage.board = &board_for(p.output);
  r.request = PortRequest{p.port, stage.board};
  OpenResult opened = open_port(r.request, clock, hooks);
  if (!opened.port) {
    r.problem = StageProblem::PortFailed;
    r.failure = std::move(opened.failure);
    return r;
  }
  stage.port = std::move(opened.port);
  stage.trace.wrap_in_place(stage.port->transport, *stage.port->clock, *stage.board);
  return r;
}

Result<Plan> stage_plan(const ShowStage& stage) {
  return plan_for(*stage.board, stage.performer->output,
                  static_cast<std::uint8_t>(stage.performer->group));
}

upload::UploadResult upload_stage(const ShowStage& stage, const Plan& plan,
                                  const std::atomic<bool>* interrupted,
                                  upload::UploadObserver* observer) {
  upload::UploadOptions options;
  options.group = static_cast<std::uint8_t>(stage.performer->group);
  const Line line{*stage.port->transport, *stage.port->clock, interrupted};
  return upload(*stage.board, line, plan, options, observer);
}

std::optional<UnsafeStage> first_unsafe_stage(std::vector<ShowStage>& stages,
                                              const std::atomic<bool>* interrupted) {
  for (std::size_t i = 0; i < stages.size(); ++i) {
    ShowStage& s = stages[i];
    const compiler::ServoProgram* program = s.performer->output.servo_program();
    if (program == nullptr) continue;
    const Line line{*s.port->transport, *s.port->clock, interrupted};
    if (auto fast = first_move_too_fast(*s.board, line, *program)) {
      return UnsafeStage{i, std::move(*fast)};
    }
  }
  return std::nullopt;
}

std::vector<Performer> performers_of(std::vector<ShowStage>& stages) {
  std::vector<Performer> performers;
  for (ShowStage& s : stages) {
    const compiler::Performer& p = *s.performer;
    performers.push_back(
        {p.name, s.board, &*s.port, &p.output, static_cast<std::uint8_t>(p.group)});
  }
  return performers;
}

void stop_stages(std::vector<ShowStage>& stages) {
  for (ShowStage& s : stages) {
    if (s.board->stop_frame != nullptr) (void)s.port->transport->write(s.board->stop_frame());
  }
}

}  // namespace seqc::boards
