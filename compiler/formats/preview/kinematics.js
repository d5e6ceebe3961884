// Forward kinematics (program/arm_kinematics.hpp): a joint angle is sign * (position - zero) *
// degrees_per_unit; all angles 0 points straight up; the base turns about the vertical axis.
function armPoints(arm, position) {
  const rad = (j) => j.sign * (position(j.servo) - j.zero) * arm.degrees_per_unit * Math.PI / 180;
  const base = rad(arm.joints.base);
  const s = rad(arm.joints.shoulder);
  const se = s + rad(arm.joints.elbow);
  const sew = se + rad(arm.joints.wrist);
  const plane = [[0, arm.base_height]];
  let r = 0, z = arm.base_height;
  for (const [length, angle] of [[arm.upper_arm, s], [arm.forearm, se], [arm.hand, sew]]) {
    r += length * Math.sin(angle);
    z += length * Math.cos(angle);
    plane.push([r, z]);
  }
  return { plane, base, hand: sew, tip: [r * Math.cos(base), r * Math.sin(base), z] };
}
