// fit_bench: how few actions fitting needs for a curve, against two references.
//
// Curves: every easing family as -in, -out and -in-out, two cubic-beziers and two Hermite
// splines (`through`-style, zero end velocity, one with a fast middle), each over 0.5, 1, 2 and
// 5 s, as a small move (60 units) and a full-range one (900 units), at tolerance 2 (--tolerance).
// Curves that overshoot (back, elastic) start at 300 so they stay within 0..1000.
//
// For each curve:
//   fitted    actions fit_timeline() makes for it (one servo, the curve alone).
//   uniform   actions of sampling the curve every 20 ms, the controller's shortest action:
//             ceil(duration / 20). The ratio fitted / uniform is the figure of merit.
//   minimum   the exact minimum under the same rules (boundaries on whole milliseconds,
//             targets rounded to whole units, every action 20 ms to 30 s, the straight line
//             within tolerance of the curve at every millisecond), by dynamic programming over
//             all boundaries on the 1 ms grid. Written here independently of the fitter.
//   error     the largest distance between the motion rebuilt from the fitted actions and the
//             curve, at every millisecond (where the tolerance is promised).
// Targets: mean ratio <= 0.2, no curve above its tolerance, every fitted count within 10 % of
// the minimum.
//
// Usage: fit_bench [--tolerance U] [--quick]   (--quick: 0.5 and 1 s only, for ctest)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "compiler/fitting/fitter.hpp"
#include "compiler/timeline/easing.hpp"

using namespace seqc::compiler;

namespace {

// The exact minimum number of actions from 0 to D (ms, relative to the curve's start), by
// dynamic programming over every pair of boundaries on the 1 ms grid. The line from a (at the
// rounded curve) to b is within tolerance at every millisecond t between them exactly when its
// slope lies in [(c(t) - tol - p0) / (t - a), (c(t) + tol - p0) / (t - a)] for each such t, so
// for a fixed a the windows of t = a+1, a+2, ... are intersected as b grows; once empty, no
// later b can work. Exact, not a heuristic: every pair is decided.
int dp_minimum(const Segment& seg, double start_ms, int duration, double tol) {
  std::vector<double> c(duration + 1);
  for (int t = 0; t <= duration; ++t) c[t] = seg.value(start_ms + t);
  std::vector<int> best(duration + 1, 1 << 30);
  best[0] = 0;
  for (int a = 0; a < duration; ++a) {
    if (best[a] >= (1 << 30)) continue;
    const double p0 = std::round(c[a]);
    double lo = -1e300, hi = 1e300;
    for (int b = a + 1; b <= std::min(duration, a + 30000); ++b) {
      const double slope = (std::round(c[b]) - p0) / (b - a);
      if (b - a >= 20 && slope >= lo - 1e-12 && slope <= hi + 1e-12 && best[a] + 1 < best[b]) {
        best[b] = best[a] + 1;
      }
      lo = std::max(lo, (c[b] - tol - 1e-9 - p0) / (b - a));
      hi = std::min(hi, (c[b] + tol + 1e-9 - p0) / (b - a));
      if (lo > hi) break;
    }
  }
  return best[duration];
}

struct Row {
  std::string name;
  int ms = 0;
  double amplitude = 0;
  int fitted = 0, uniform = 0, minimum = 0;
  double error = 0;
};

}  // namespace

int main(int argc, char** argv) {
  double tol = 2;
  bool quick = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--tolerance" && i + 1 < argc) {
      tol = std::atof(argv[++i]);
    } else if (a == "--quick") {
      quick = true;
    } else {
      std::fprintf(stderr, "usage: fit_bench [--tolerance U] [--quick]\n");
      return 2;
    }
  }
  std::vector<std::string> names;
  for (const std::string& n : easing_names()) {
    if (n != "linear" && n != "in" && n != "out" && n != "in-out") names.push_back(n);
  }
  names.push_back("cubic-bezier(0.42, 0, 0.58, 1)");
  names.push_back("cubic-bezier(0.1, 0.7, 0.3, 1)");
  names.push_back("hermite");
  names.push_back("hermite-fast-middle");
  const std::vector<int> durations =
      quick ? std::vector<int>{500, 1000} : std::vector<int>{500, 1000, 2000, 5000};
  std::vector<Row> rows;
  for (const std::string& name : names) {
    for (int ms : durations) {
      for (double amplitude : {60.0, 900.0}) {
        const bool overshoots = name.rfind("back", 0) == 0 || name.rfind("elastic", 0) == 0;
        Segment seg;
        seg.start = ExactMs(0);
        seg.end = ExactMs(ms);
        seg.from = overshoots && amplitude > 100 ? 300 : 50;
        seg.to = seg.from + (overshoots && amplitude > 100 ? 400 : amplitude);
        seg.tolerance = tol;
        if (name.rfind("hermite", 0) == 0) {
          seg.kind = CurveKind::Hermite;
          seg.slope_from = 0;
          seg.slope_to = name == "hermite" ? 0 : 3 * (seg.to - seg.from) / ms;
        } else {
          seg.kind = CurveKind::Eased;
          seg.easing = *parse_easing(name).easing;
        }
        Timeline tl;
        tl.resize(1);
        tl.add(0, seg);
        tl.end = ExactMs(ms);
        const FitResult fit = fit_timeline(tl);
        Row r;
        r.name = name;
        r.ms = ms;
        r.amplitude = seg.to - seg.from;
        r.fitted = static_cast<int>(fit.actions.size());
        r.uniform = (ms + 19) / 20;
        r.minimum = dp_minimum(seg, 0, ms, tol);
        // The motion rebuilt from the actions: straight lines between their targets.
        double pos = std::round(seg.from);
        for (const FittedAction& a : fit.actions) {
          const double to = a.targets.empty() ? pos : a.targets[0].position;
          for (double t = a.start_ms; t <= a.start_ms + a.time_ms; t += 1) {
            const double line = pos + (to - pos) * (t - a.start_ms) / a.time_ms;
            r.error = std::max(r.error, std::abs(line - seg.value(t)));
          }
          pos = to;
        }
        rows.push_back(r);
      }
    }
  }
  std::printf(
      "fit_bench: tolerance %g units; fitted = fit_timeline(), uniform = every 20 ms, minimum = "
      "exact DP on the 1 ms grid, error = rebuilt motion vs curve at every ms\n",
      tol);
  std::printf("%-32s %6s %6s %7s %7s %7s %7s %8s\n", "curve", "ms", "units", "fitted", "uniform",
              "ratio", "minimum", "error");
  double ratio_sum = 0, feasible_sum = 0;
  int above_tol = 0, off_minimum = 0, impossible = 0, feasible = 0;
  double worst_over_min = 0;
  for (const Row& r : rows) {
    const double ratio = static_cast<double>(r.fitted) / r.uniform;
    ratio_sum += ratio;
    // No sequence of 20 ms actions meets the tolerance: the compiler warns where and by how
    // much (a shortfall) and uses its shortest actions there.
    const bool possible = r.minimum < (1 << 30);
    const bool over = possible && r.error > tol + 1e-6;
    const double over_min =
        possible ? static_cast<double>(r.fitted) / std::max(1, r.minimum) - 1 : 0;
    if (possible) {
      ++feasible;
      feasible_sum += ratio;
    } else {
      ++impossible;
    }
    above_tol += over ? 1 : 0;
    off_minimum += over_min > 0.1 ? 1 : 0;
    worst_over_min = std::max(worst_over_min, over_min);
    std::printf("%-32s %6d %6.0f %7d %7d %7.3f %7s %8.3f%s%s\n", r.name.c_str(), r.ms, r.amplitude,
                r.fitted, r.uniform, ratio, possible ? std::to_string(r.minimum).c_str() : "none",
                r.error, over ? "  ABOVE TOLERANCE" : "",
                over_min > 0.1 ? "  >10% above minimum" : "");
  }
  const double mean = ratio_sum / static_cast<double>(rows.size());
  const double mean_feasible = feasible > 0 ? feasible_sum / feasible : 0;
  std::printf(
      "summary: %zu curves; mean fitted/uniform %.3f over all (target <= 0.2: %s), %.3f over the "
      "%d that 20 ms actions can follow; %d that no 20 ms actions can follow within tolerance "
      "(warned as shortfalls); %d above tolerance where possible (target 0); %d more than 10%% "
      "above the minimum, worst %+.1f%% (target 0)\n",
      rows.size(), mean, mean <= 0.2 ? "met" : "MISSED", mean_feasible, feasible, impossible,
      above_tol, off_minimum, worst_over_min * 100);
  return 0;
}
