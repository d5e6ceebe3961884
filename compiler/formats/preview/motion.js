// The controller's motion at t ms, as formats/simulate.cpp computes it: every action that has
// ended by t has put its servos at their targets; the current one moves its servos in a straight
// line from there.
function servoPositions(p, t) {
  const from = p.servos.map((s) => s.home);
  const actions = p.actions;
  let k = 0;
  while (k < actions.length && actions[k][0] + actions[k][1] <= t) {
    for (const [i, v] of actions[k][2]) from[i] = v;
    ++k;
  }
  const now = from.slice();
  if (k < actions.length) {
    const [start, time, targets] = actions[k];
    const f = Math.max(0, (t - start) / time);
    for (const [i, v] of targets) now[i] = from[i] + (v - from[i]) * f;
  }
  return now;
}
