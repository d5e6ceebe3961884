#include "compiler/targets/servo_controller/chain.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "base/units.hpp"
#include "protocol/lsc/group_download.hpp"

namespace seqc::compiler {
namespace {

// A place the dance may be cut: a bar line (or, without bar lines, an action's start).
struct Candidate {
  std::int64_t board_ms = 0;
  ExactMs host;
  std::int64_t bar = 0;  // counted from 1; 0 without bar lines
  bool section = false;  // a section starts here (only looked at without bar lines)
  // The first action starting at or after the cut; when the cut falls inside action
  // first_after - 1 it is split there.
  std::size_t first_after = 0;
  bool split = false;
};

// The two halves of an action cut at a bar line.
struct Halves {
  Keyframe before, after;
};

class Chainer {
 public:
  Chainer(const ServoProgram& program, std::size_t capacity, std::int32_t clock_ppm)
      : p_(program),
        kf_(program.keyframes),
        capacity_(capacity),
        scale_(ExactMs::ratio(1000000 + std::int64_t{clock_ppm}, 1000000)) {}

  Result<ChainCut> run() {
    collect_candidates();
    ChainCut cut;
    Candidate from;  // the dance's start: action 0, not split
    cut.bars.push_back(cands_.empty() || cands_.front().bar == 0 ? 0 : 1);
    std::optional<Halves> carried;  // the second half of the action the last cut split
    std::size_t next = 0;           // the first candidate after `from`
    while (true) {
      const std::size_t held = count(from, kf_.size());
      if (held <= capacity_) {
        add_piece(cut, from, carried, kf_.size(), std::nullopt);
        break;
      }
      // The last candidate the group can reach, then back to the first that can be cut.
      std::size_t last = next;
      while (last < cands_.size() && count(from, cands_[last]) <= capacity_) ++last;
      std::optional<std::size_t> chosen;
      std::optional<Halves> halves;
      const std::size_t preferred = prefer_section(next, last);
      for (std::size_t c = preferred; c-- > next;) {
        if (!cands_[c].split) {
          chosen = c;
          break;
        }
        if (auto h = split(cands_[c])) {
          chosen = c;
          halves = std::move(h);
          break;
        }
      }
      if (!chosen) return too_long(from, last);
      const Candidate& c = cands_[*chosen];
      add_piece(cut, from, carried, c.first_after - (c.split ? 1 : 0), halves);
      cut.split_actions += c.split ? 1 : 0;
      cut.bars.push_back(c.bar);
      carried = halves;
      from = c;
      next = *chosen + 1;
    }
    return cut;
  }

 private:
  // Actions a group holds from cut `a` to cut `b` (the second half of a split counts in the
  // group after the cut, the first half in the one before).
  std::size_t count(const Candidate& a, const Candidate& b) const {
    return count(a, b.first_after);
  }
  std::size_t count(const Candidate& a, std::size_t until) const {
    return (a.split ? 1 : 0) + until - a.first_after;
  }

  void collect_candidates() {
    const TempoMap& map = p_.timeline.tempo_map;
    const std::int64_t end = kf_.empty() ? 0 : kf_.back().start_ms + kf_.back().time_ms;
    for (std::int64_t k = 1;; ++k) {
      const auto beat = map.beat_of_bar(ExactMs(k));
      const auto at = beat ? map.time_of_beat(*beat) : std::nullopt;
      if (!at || *at >= p_.timeline.end) break;
      add_candidate((*at * scale_).round(), *at, k + 1, end);
    }
    if (!cands_.empty()) return;
    // No bar lines: every action's start, sections' starts marked.
    std::vector<std::int64_t> sections;
    for (const TimelineMarker& m : p_.timeline.markers) {
      if (m.label.rfind("section ", 0) == 0) sections.push_back((m.at * scale_).round());
    }
    std::sort(sections.begin(), sections.end());
    for (std::size_t i = 1; i < kf_.size(); ++i) {
      Candidate c;
      c.board_ms = kf_[i].start_ms;
      c.host = ExactMs(c.board_ms) / scale_;
      c.first_after = i;
      c.section = std::binary_search(sections.begin(), sections.end(), c.board_ms);
      cands_.push_back(c);
    }
  }

  void add_candidate(std::int64_t board_ms, ExactMs host, std::int64_t bar, std::int64_t end) {
    if (board_ms <= 0 || board_ms >= end) return;
    Candidate c;
    c.board_ms = board_ms;
    c.host = host;
    c.bar = bar;
    const auto it = std::lower_bound(
        kf_.begin(), kf_.end(), board_ms,
        [](const Keyframe& f, std::int64_t t) { return std::int64_t{f.start_ms} < t; });
    c.first_after = static_cast<std::size_t>(it - kf_.begin());
    c.split = it == kf_.end() || std::int64_t{it->start_ms} != board_ms;
    // Between actions (a gap no action covers cannot happen: actions are back to back).
    if (!cands_.empty() && cands_.back().board_ms >= board_ms) return;
    cands_.push_back(c);
  }

  // Without bar lines, the latest section start in the later half of the reach, if any.
  std::size_t prefer_section(std::size_t next, std::size_t last) const {
    if (last == 0 || cands_[last - 1].bar != 0) return last;
    for (std::size_t c = last; c-- > next;) {
      if (cands_[c].section && 2 * (cands_[c].first_after - cands_[next].first_after) >=
                                   (cands_[last - 1].first_after - cands_[next].first_after)) {
        return c + 1;
      }
    }
    return last;
  }

  // The servo index (into robot.servos) of bus id `id`.
  std::optional<std::size_t> servo_of(std::uint8_t id) const {
    for (std::size_t s = 0; s < p_.robot.servos.size(); ++s) {
      if (p_.robot.servos[s].id == id) return s;
    }
    return std::nullopt;
  }

  // Where servo `id` is when action i starts (its last target before), if any action named it.
  std::optional<int> position_before(std::size_t i, std::uint8_t id) const {
    for (std::size_t j = i; j-- > 0;) {
      for (const lsc::ServoTarget& t : kf_[j].targets) {
        if (t.id == id) return t.position;
      }
    }
    return std::nullopt;
  }

  // The worst distance beyond tolerance (<= 0: within) of servo s moving on a straight line from
  // p0 at board ms a to p1 at b, under the controller model, at every millisecond.
  double excess(std::size_t s, std::int64_t a, std::int64_t b, double p0, double p1) const {
    double most = -1e300;
    for (std::int64_t t = a; t <= b; ++t) {
      const double line = controller_output(
          p_.controller, p0 + (p1 - p0) * static_cast<double>(t - a) / static_cast<double>(b - a));
      const double host = (ExactMs(t) / scale_).value();
      const auto i = p_.timeline.index_at(s, host);
      if (!i) continue;  // not known yet: nothing to keep to
      const Segment seg = p_.timeline.segment(s, *i);
      most = std::max(most, std::abs(line - seg.value(host)) - seg.tolerance);
    }
    return most;
  }

  // Action first_after - 1 cut at the candidate's instant, or nullopt when it cannot be.
  std::optional<Halves> split(const Candidate& c) const {
    const std::size_t i = c.first_after - 1;
    const Keyframe& k = kf_[i];
    const std::int64_t s = k.start_ms, e = s + k.time_ms, at = c.board_ms;
    if (at - s < lsc::kMinActionMs || e - at < lsc::kMinActionMs) return std::nullopt;
    Halves h{k, k};
    h.before.time_ms = static_cast<std::uint16_t>(at - s);
    h.after.start_ms = static_cast<std::uint32_t>(at);
    h.after.time_ms = static_cast<std::uint16_t>(e - at);
    for (std::size_t n = 0; n < k.targets.size(); ++n) {
      const lsc::ServoTarget target = k.targets[n];
      const auto from = position_before(i, target.id);
      const auto servo = servo_of(target.id);
      if (!from || !servo) return std::nullopt;  // a first move: only its end can be told
      const double p0 = *from, p1 = target.position;
      const double mid = p0 + (p1 - p0) * static_cast<double>(at - s) / static_cast<double>(e - s);
      // No worse than the action was: within tolerance, or no further out than it already is.
      const double allowed = std::max(0.0, excess(*servo, s, e, p0, p1)) + 1e-9;
      std::optional<int> best;
      double best_excess = 1e300;
      for (const double m : {std::round(mid), std::floor(mid), std::ceil(mid)}) {
        const double x = std::max(excess(*servo, s, at, p0, m), excess(*servo, at, e, m, p1));
        if (x < best_excess) {
          best_excess = x;
          best = static_cast<int>(m);
        }
      }
      if (!best || best_excess > allowed || *best < 0 || *best > 65535) return std::nullopt;
      h.before.targets[n].position = static_cast<std::uint16_t>(*best);
    }
    return h;
  }

  // Actions [from cut, until) as a piece (with the carried second half first and `halves`' first
  // half last).
  void add_piece(ChainCut& cut, const Candidate& from, const std::optional<Halves>& carried,
                 std::size_t until, const std::optional<Halves>& halves) const {
    ResyncPiece piece;
    piece.board_start_ms = static_cast<std::uint32_t>(from.board_ms);
    piece.host_start = from.host;
    auto push = [&](Keyframe k) {
      k.start_ms -= piece.board_start_ms;
      piece.keyframes.push_back(std::move(k));
    };
    if (carried) push(carried->after);
    for (std::size_t i = from.first_after; i < until; ++i) push(kf_[i]);
    if (halves) push(halves->before);
    cut.pieces.push_back(std::move(piece));
  }

  Error too_long(const Candidate& from, std::size_t last) const {
    const std::size_t until = last < cands_.size() ? cands_[last].first_after : kf_.size();
    const Keyframe& k = kf_[std::min(until, kf_.size()) - 1];
    std::string where = format_seconds(k.start_ms);
    if (last < cands_.size() && cands_[last].bar > 0) {
      where += " (before bar " + std::to_string(cands_[last].bar) + ")";
    }
    return Error{"from " + format_seconds(static_cast<std::uint64_t>(from.board_ms)) + " to " +
                 where + " the dance needs " +
                 format_grouped(static_cast<long long>(count(from, until))) +
                 " actions with no bar line between them where a group can end; a group holds " +
                 format_grouped(static_cast<long long>(capacity_))};
  }

  const ServoProgram& p_;
  const std::vector<Keyframe>& kf_;
  std::size_t capacity_;
  ExactMs scale_;
  std::vector<Candidate> cands_;
};

}  // namespace

Result<ChainCut> chain_groups(const ServoProgram& program, std::size_t capacity,
                              std::int32_t clock_ppm) {
  if (capacity == 0) return make_error("a group must hold at least one action");
  if (program.keyframes.empty()) return make_error("the program has no actions");
  return Chainer(program, capacity, clock_ppm).run();
}

}  // namespace seqc::compiler
