#!/usr/bin/python3
"""Writes schemas/seqc.schema.json, the JSON Schema editors use for seqc files.

The schema is written here as Python data because it is mostly repetition: every key needs a
title, a description and a markdownDescription; every profile needs its own id and limit ranges;
both robot kinds share keys with different rules. Edit this file, run it, commit both; the test
`schema_is_generated` fails when they differ.

Choices (and why):
- Per-robot branching with if/then/else on `robot`, so a Raspblock step in an xArm file (or the
  reverse) is an error at the step.
- Steps are one object type whose verb selects the allowed keys through if/then. No oneOf: a
  oneOf over step kinds makes editors report "matches more than one" or list every branch's
  errors; an unknown or misplaced key here is reported once, at the key.
- Values that are "a number or a string" use a type list plus a pattern (patterns only apply to
  strings), again without oneOf.
- What a schema cannot know is left to `seqc check`: limits after relative moves and mirroring,
  beats at the tempo in force, sums of times, the action budget, min < max, names defined
  elsewhere in the file (tests/schema/agreement.py lists these cases).

Usage: gen_schema.py [OUTPUT]   (default: schemas/seqc.schema.json beside this script's repo)
"""
import json
import os
import sys

PROFILES = {
    # name: (first id, last id, min, max, home, what)
    "xarm": (1, 6, 0, 1000, 500, "xArm bus servos 1-6 (claw, wrist_roll, wrist_pitch, elbow, "
             "shoulder, base), 0-1000 over 0-240deg, home 500"),
    "bus": (1, 32, 0, 1000, 500, "LewanSoul/Hiwonder bus servos 1-32 (s1..s32), 0-1000 over "
            "0-240deg, home 500"),
    "lsc-16": (0, 15, 500, 2500, 1500, "LSC-16 PWM channels 0-15 (ch0..ch15), 500-2500 us over "
               "0-180deg, home 1500"),
    "lsc-32": (0, 31, 500, 2500, 1500, "LSC-32 PWM channels 0-31 (ch0..ch31), 500-2500 us over "
               "0-180deg, home 1500"),
    "lsc-6": (1, 6, 500, 2500, 1500, "LSC-6 / LeArm PWM channels 1-6 (ch1..ch6), 500-2500 us "
              "over 0-180deg, home 1500; a group holds 255 actions"),
    "learm": (1, 6, 500, 2500, 1500, "the LeArm on its LSC-6 board: servos 1-6 (claw, wrist_roll, "
              "wrist_pitch, elbow, shoulder, base) with the arm's geometry built in, 500-2500 us "
              "over 0-180deg, home 1500; a group holds 255 actions"),
    "raspblock": (1, 4, 500, 2500, 1500, "the Yahboom Raspblock car board: rocker (drive), "
                  "gimbal (pan, tilt) and servos 1-4, streamed live"),
}
SERVO_PROFILES = [p for p in PROFILES if p != "raspblock"]
NAME = r"^[A-Za-z_][A-Za-z0-9_]*$"
NUM = r"[0-9]+(\.[0-9]+)?"


def doc(title, text, **more):
    """title, description and markdownDescription (the same text; backticks render)."""
    out = {"title": title, "description": text.replace("`", ""), "markdownDescription": text}
    out.update(more)
    return out


def string(title, text, pattern, message):
    """A string with a pattern, and the message editors show when it does not match."""
    return doc(title, text, type="string", pattern=pattern, patternErrorMessage=message)


def ref(name):
    return {"$ref": "#/definitions/" + name}


# Times. A servo controller's action lasts at least 20 ms; seqc rounds a step's time to whole
# milliseconds first, so 19.5ms is the smallest time it accepts.
MS_20 = r"0*(?:[2-9][0-9]|[1-9][0-9]{2,})(?:\.[0-9]+)?ms|0*19\.[5-9][0-9]*ms"
S_20 = r"0*[1-9][0-9]*(?:\.[0-9]+)?s|0+\.(?:[1-9][0-9]*|0[2-9][0-9]*|019[5-9][0-9]*)s"
BEATS = r"0*(?:[1-9][0-9]*(?:\.[0-9]+)?|0\.[0-9]*[1-9][0-9]*)(?:b|bars?)"
# An exact fraction, whole over whole with the unit after it (1/3b): a numerator up to
# 1,000,000 and a denominator from 1 to 1,000. The schema lets a step's fraction of a second
# through without the 20 ms floor (seqc checks it).
FRACTION = r"0*(?:[0-9]{1,6}|1000000)/0*(?:[1-9][0-9]{0,2}|1000)"
TIME_HELP = ("a time with its unit: `500ms`, `1.5s`, `2b` (beats; needs `tempo`) or `2bar` "
             "(bars; needs `meter`), or an exact fraction of one: `1/3b`, `1/6bar`, `1/3s`. A bare "
             "number is an error")
# A tempo's note: a fraction of a whole note (3/8) or its name, optionally dotted.
TEMPO_NOTE = (r"(?:0*(?:[1-9]|[12][0-9]|3[0-2])/0*(?:1|2|4|8|16|32)|"
              r"(?:dotted +)?(?:whole|half|quarter|eighth|sixteenth))")
TEMPO_NUMBER = r"0*(?:[1-9][0-9]{0,2}(?:\.[0-9]+)?|1000(?:\.0+)?)(?:bpm)?"

definitions = {
    "profile": doc("Robot profile", "A built-in profile: " + "; ".join(
        f"`{k}`: {v[5]}" for k, v in PROFILES.items()) + ".", enum=list(PROFILES)),
    "servoName": doc("Servo name", "Letters, digits and `_`, not starting with a digit.",
                     type="string", pattern=NAME,
                     patternErrorMessage="a servo name is letters, digits and _, not starting "
                                         "with a digit"),
    "servoTime": string("Time", TIME_HELP + "; at least `20ms` (one controller action).",
                        f"^(?:{MS_20}|{S_20}|{BEATS}|{FRACTION}(?:s|b|bars?))$",
                        "a time of at least 20ms with its unit: 500ms, 1.5s, 2b or 1bar (a bare "
                        "number is an error)"),
    "time": string("Time", TIME_HELP + ".", f"^(?:{NUM}|{FRACTION})(ms|s|b|bars?)$",
                   "a time with its unit: 500ms, 1.5s, 2b or 1bar (a bare number is an error)"),
    "carTime": string("Time", "`500ms`, `1.5s`, `2b` (beats at `tempo`) or `2bar` (bars; needs "
                      "`meter`), or an exact fraction of one (`1/3b`).",
                      f"^(?:{NUM}|{FRACTION})(ms|s|b|bars?)$",
                      "a time with its unit: 500ms, 1.5s, 2b or 1bar (a bare number is an error)"),
    "at": string("Start at", "Start this step exactly this long after the start of the list "
                 "that holds it (`at: 4bar`), or at a bar of the sequence counted from 1 "
                 "(`at: bar 9`, `at: bar 9 beat 2.5`); the gap before it is a hold.",
                 rf"^(?:(?:{NUM}|{FRACTION})(ms|s|b|bars?)|bar +[1-9][0-9]*(?: +beat +{NUM})?)$",
                 "a time with its unit (500ms, 1.5s, 2b or 1bar) or a position (bar 9, "
                 "bar 9 beat 3)"),
    "position": doc("Position", "Device units (`500`), degrees (`90deg`), relative to where the "
                    "servo is (`+50`, `-10deg`), or `home`.", type=["integer", "string"],
                    pattern=r"^(?:[+-]?[0-9]+(?:\.[0-9]+)?deg|[+-]?[0-9]+|home)$",
                    patternErrorMessage="a position: 500 (device units), 90deg, +50, -10deg or "
                                        "home"),
    "speed": string("Maximum speed", "Device units per second (`400/s`) or degrees per second "
                    "(`90deg/s`); faster moves are warnings.", rf"^{NUM}(deg)?/s$",
                    "a speed: 400/s (device units) or 90deg/s"),
    "accel": string("Maximum acceleration", "Device units (`4000/s2`) or degrees (`900deg/s2`) "
                    "per second squared (`/s^2` also works); checked along curved moves.",
                    rf"^{NUM}(deg)?/s(2|\^2)$", "an acceleration: 4000/s2 or 900deg/s2"),
    "tolerance": doc("Tolerance", "How far the controller's motion may stray from the intended "
                     "curve at any millisecond: device units (`1`, `0.5`) or degrees (`0.5deg`). "
                     "Default 1.", type=["number", "string"], exclusiveMinimum=0,
                     pattern=r"^(?:[0-9]*[1-9][0-9]*(?:\.[0-9]+)?|[0-9]+\.[0-9]*[1-9][0-9]*)(deg)?$",
                     patternErrorMessage="a positive distance: 1 (device units) or 0.5deg"),
    "tempo": doc("Tempo", "Beats of the meter per minute, 1-1000 (`tempo: 120`, `tempo: 120bpm`; "
                 "in 6/8 a beat is an eighth), for times written in beats; or a named note per "
                 "minute: `tempo: 3/8 = 60`, `tempo: dotted quarter = 60` (whole, half, quarter, "
                 "eighth, sixteenth, optionally dotted).", type=["number", "string"], minimum=1,
                 maximum=1000,
                 pattern=rf"^(?:{TEMPO_NOTE} *= *)?{TEMPO_NUMBER}$",
                 patternErrorMessage="beats per minute between 1 and 1000 (120 or 120bpm), or a "
                                     "note per minute (3/8 = 60, dotted quarter = 60)"),
    "meter": doc("Meter", "Beats per bar over the beat's note value (`3/4`, `6/8`): enables the "
                 "unit `bar`; as a step it changes the meter from there (on a bar line), each "
                 "note keeping its length.",
                 type="string", pattern=r"^0*[1-9][0-9]*/(1|2|4|8|16|32|64)$",
                 patternErrorMessage="beats per bar over a note value: 3/4, 4/4 or 6/8"),
    "ease": doc("Easing", "The shape of the move: `linear`; `in`, `out`, `in-out` (quadratic; "
                "also `ease-in`, `ease-out`, `ease-in-out`); `quad`, `cubic`, `quart`, `quint`, "
                "`sine`, `expo`, `circ`, `back`, `elastic` or `bounce` with `-in`, `-out` or "
                "`-in-out`; or `cubic-bezier(x1, y1, x2, y2)` with x1, x2 in [0, 1].",
                type="string",
                pattern=r"^(?:linear|in|out|in-out|ease-in|ease-out|ease-in-out|"
                        r"(?:quad|cubic|quart|quint|sine|expo|circ|back|elastic|bounce)-"
                        r"(?:in|out|in-out)|cubic-bezier\(\s*(?:0|1|0?\.[0-9]+|0\.[0-9]*|1\.0*)\s*,"
                        r"\s*-?[0-9.]+\s*,\s*(?:0|1|0?\.[0-9]+|0\.[0-9]*|1\.0*)\s*,\s*-?[0-9.]+\s*\))$",
                patternErrorMessage="an easing: linear, in, out, in-out, sine-in-out, "
                                    "back-out, ... or cubic-bezier(x1, y1, x2, y2)"),
}
definitions["positions"] = doc(
    "Positions", "`servo: position` for the servos to move; the others keep theirs.",
    type="object", propertyNames=ref("servoName"), additionalProperties=ref("position"))
definitions["poseOrPositions"] = doc(
    "Pose or positions", "A pose name (`ready`, `home`) or `{servo: position, ...}`.",
    type=["string", "object"], minLength=1, propertyNames=ref("servoName"),
    additionalProperties=ref("position"))


def servo_definition(profile):
    first, last, lo, hi, home, _ = PROFILES[profile]
    unit = "us" if lo == 500 else "device units"
    rng = lambda what: doc(what, f"{what} position on {profile}: {lo}-{hi} {unit}.",  # noqa: E731
                           type="integer", minimum=lo, maximum=hi)
    idd = doc("Servo id", f"The servo's id on {profile}: {first}-{last}.", type="integer",
              minimum=first, maximum=last)
    return doc("Servo definition",
               "`name: id`, or `name: {id, min, max, home, max_speed, max_accel}` (a profile "
               "servo may be refined without an id).",
               type=["integer", "object"], minimum=first, maximum=last,
               additionalProperties=False,
               properties={"id": idd, "min": rng("Lowest"), "max": rng("Highest"),
                           "home": doc("Home", f"Where `home` goes and what mirroring reflects "
                                       f"around; {lo}-{hi}.", type="integer", minimum=lo,
                                       maximum=hi),
                           "max_speed": ref("speed"), "max_accel": ref("accel")})


for p in PROFILES:
    definitions["servo_" + p] = servo_definition(p)

robot_object = doc(
    "Robot definition", "A profile refined for this robot: named servos with their own limits, "
    "and a mirror table for `mirror` steps.", type="object", required=["profile"],
    additionalProperties=False,
    properties={
        "profile": ref("profile"),
        "servos": doc("Servos", "Name servos and refine their limits: `name: id` or "
                      "`name: {id, min, max, home, max_speed, max_accel}`.",
                      type=["object", "null"], propertyNames=ref("servoName")),
        "mirror": doc("Mirror table", "Left/right pairs (`left_arm: right_arm`); a servo paired "
                      "with itself is reflected in place.", type="object",
                      propertyNames=ref("servoName"), additionalProperties=ref("servoName")),
        "arm": doc("Arm geometry", "Link lengths in mm and the servo of each joint, over the "
                   "profile's built-in geometry (the xArm has one), for `seqc preview` and "
                   "`seqc simulate`'s tip columns.", type="object", additionalProperties=False,
                   properties=dict(
                       {k: doc(k, f"`{k}` in mm: `97` or `97mm`.", type=["number", "string"],
                               exclusiveMinimum=0, pattern=r"^[0-9]+(\.[0-9]+)?(mm)?$",
                               patternErrorMessage="a length in mm: 97 or 97mm")
                        for k in ["base_height", "upper_arm", "forearm", "hand"]},
                       joints=doc("Joints", "Per joint its servo, the position where its angle "
                                  "is 0 and the direction it turns.", type="object",
                                  additionalProperties=False,
                                  properties={j: doc(
                                      f"{j} joint", f"The {j} joint: `{{servo, zero, sign}}`.",
                                      type="object", additionalProperties=False,
                                      properties={
                                          "servo": ref("servoName"),
                                          "zero": doc("Zero", "The position at which the "
                                                      "joint's angle is 0 (default: home).",
                                                      type="integer", minimum=0),
                                          "sign": doc("Sign", "1: a larger position turns the "
                                                      "joint the positive way; -1: the other.",
                                                      enum=[1, -1])})
                                      for j in ["base", "shoulder", "elbow", "wrist"]}),
                       claw=ref("servoName"))),
        "controller": doc("Controller model", "How the board moves a servo between whole-unit "
                          "targets, which fitting keeps every tolerance under: `straight-line` "
                          "(the exact line, every built-in profile's), `rounds` or `truncates` "
                          "(that line rounded or truncated to whole units at every instant).",
                          type="string", enum=["straight-line", "rounds", "truncates"]),
    },
    allOf=[{"if": {"properties": {"profile": {"const": p}}},
            "then": {"properties": {"servos": {"additionalProperties": ref("servo_" + p)}}}}
           for p in PROFILES])
robot_object["defaultSnippets"] = [{
    "label": "robot definition", "description": "a profile with named servos and a mirror table",
    "body": {"profile": "${1|lsc-16,lsc-32,lsc-6,learm,xarm|}",
             "servos": {"${2:left_arm}": {"id": 0, "min": 600, "max": 2400},
                        "${3:right_arm}": {"id": 1, "min": 600, "max": 2400}},
             "mirror": {"${2:left_arm}": "${3:right_arm}"}}}]
definitions["robotObject"] = robot_object

# Steps of a servo controller file: every key, and per verb the keys it allows.
SERVO_VERBS = {
    "move": ["move", "time", "ease", "steps", "tolerance", "elbow", "path", "at"],
    "wait": ["wait", "at"],
    "through": ["through", "tolerance", "at"],
    "together": ["together", "at"],
    "repeat": ["repeat", "do", "at"],
    "section": ["section", "with", "at"],
    "include": ["include", "at"],
    "mirror": ["mirror", "at"],
    "tempo": ["tempo"],
    "meter": ["meter"],
    "tolerance": ["tolerance"],
}
STEP_KEYS = {
    "move": doc("Move", "Move to a pose or to positions over `time` (straight, or along `ease`): "
                "`move: ready` or `move: {base: 60deg, claw: +50}`.",
                **{k: v for k, v in definitions["poseOrPositions"].items()
                   if k not in ("title", "description", "markdownDescription")},
                properties={
                    "tip": doc("Tip", "Where the claw's tip goes, `[x, y, z]` in millimetres "
                               "(`[150mm, 0mm, 80mm]`); with a sign on any coordinate, from "
                               "where the tip is (`[+20mm, 0mm, 0mm]`); named, always absolute "
                               "(`{x: 150mm, y: -80mm, z: 40mm}`). Needs the arm's geometry.",
                               type=["array", "object"], minItems=3, maxItems=3,
                               items={"type": "string", "pattern": r"^[+-]?[0-9.]+mm$",
                                      "patternErrorMessage": "a length in millimetres: 150mm, "
                                                             "+20mm"},
                               required=["x", "y", "z"], additionalProperties=False,
                               properties={c: doc(c, f"The tip's {c} in millimetres; a sign "
                                                  "is only its sign.", type="string",
                                                  pattern=r"^[+-]?[0-9.]+mm$",
                                                  patternErrorMessage="a length in millimetres: "
                                                                      "150mm, -80mm")
                                           for c in ("x", "y", "z")}),
                    "pitch": doc("Pitch", "The hand's angle with `tip`: 0deg up, 90deg level, "
                                 "180deg down (default: as it is).", type="string",
                                 pattern=r"^[+-]?[0-9.]+deg$",
                                 patternErrorMessage="an angle in degrees: 135deg"),
                    "elbow": doc("Elbow", "The `elbow` servo's position, or with `tip`: `up` "
                                 "(the default) or `down`, which of the two ways the arm "
                                 "reaches the point (also a key of the step).",
                                 anyOf=[ref("position"), {"type": "string",
                                                          "enum": ["up", "down"]}])}),
    "elbow": doc("Elbow", "With a `tip` move: `up` (the default) or `down`, which of the two "
                 "ways the arm reaches the point.", type="string", enum=["up", "down"]),
    "path": doc("Path", "With a `tip` move: `line` takes the tip in a straight line from where "
                "it is, within `tolerance` (in mm, default 1mm) at every millisecond.",
                type="string", enum=["line"]),
    "time": ref("servoTime"),
    "ease": ref("ease"),
    "steps": doc("Steps", "Cut the move into this many equal actions instead of fitting it "
                 "(each at least 20 ms).", type="integer", minimum=1, maximum=1020),
    "tolerance": doc("Tolerance", "The servos' tolerance (device units or degrees), or with "
                     "`path: line` the claw tip's, in millimetres (`0.5mm`).",
                     anyOf=[ref("tolerance"),
                            doc("Tip tolerance", "With `path: line`: how far the claw's tip may "
                                "stray from the line, in millimetres (`0.5mm`).", type="string",
                                pattern=r"^[0-9]*\.?[0-9]+mm$",
                                patternErrorMessage="a distance in millimetres: 1mm")]),
    "at": ref("at"),
    "wait": doc("Wait", "Hold every servo where it is for this long (in a `together` track: "
                "that track's servos).", **{"$ref": "#/definitions/servoTime"}),
    "through": doc("Through", "A smooth curve through waypoints, each reached `time` after the "
                   "previous one.", type="array", minItems=1, items=doc(
                       "Waypoint", "`pose` (a pose name or positions) reached `time` after the "
                       "previous waypoint.", type="object", required=["pose", "time"],
                       additionalProperties=False,
                       properties={"pose": ref("poseOrPositions"), "time": ref("time")})),
    "together": doc("Together", "Named tracks of steps that run side by side from the same "
                    "instant; a servo moves in one track only.", type="object", minProperties=1,
                    additionalProperties=ref("servoSteps")),
    "repeat": doc("Repeat", "Do the steps in `do` this many times (1-65535).",
                  type=["integer", "string"], minimum=1, maximum=65535,
                  pattern=r"^0*(?:[1-9][0-9]{0,3}|[1-5][0-9]{4}|6[0-4][0-9]{3}|65[0-4][0-9]{2}|"
                          r"655[0-2][0-9]|6553[0-5])$",
                  patternErrorMessage="a whole number of times, 1-65535"),
    "do": doc("Do", "The steps to repeat.", **{"$ref": "#/definitions/servoSteps"}),
    "section": doc("Section", "Perform a section of this file (or of a file that includes it) "
                   "here.", type="string", minLength=1),
    "with": doc("With", "Values for the section's parameters (`with: {amount: 80}`); the others "
                "keep their defaults.", type="object", propertyNames=ref("servoName"),
                additionalProperties=doc("Parameter value", "What `$name` stands for in the "
                                         "section's steps.", type=["string", "number"])),
    "include": doc("Include", "Perform another file's `sequence` here (a path relative to this "
                   "file).", type="string", minLength=1),
    "mirror": doc("Mirror", "Perform these steps with left and right swapped (the robot's mirror "
                  "table).", **{"$ref": "#/definitions/servoSteps"}),
    "tempo": ref("tempo"),
    "meter": ref("meter"),
}


def step_schema(keys, verbs, title, extra_rules=()):
    rules = []
    for verb, allowed in verbs.items():
        then = {"properties": {k: True for k in allowed}, "additionalProperties": False}
        if verb == "move":
            then["required"] = ["time"]
        if verb == "repeat":
            then["required"] = ["do"]
        # `tolerance` is a verb alone and a modifier of move and through: the verb's rule
        # applies only when no verb that takes it as a modifier is there.
        hosts = [v for v, keys in verbs.items() if verb in keys and keys != allowed]
        when = {"required": [verb]}
        if hosts:
            when["not"] = {"anyOf": [{"required": [h]} for h in hosts]}
        rules.append({"if": when, "then": then})
    rules.extend(extra_rules)
    return doc(title, "One thing the robot does: " + ", ".join(f"`{v}`" for v in verbs) + ".",
               type="object", properties=keys, additionalProperties=False,
               anyOf=[{"required": [v]} for v in verbs], allOf=rules,
               defaultSnippets=[
                   {"label": "move", "description": "move to a pose or positions",
                    "body": {"move": "${1:home}", "time": "${2:500ms}"}},
                   {"label": "repeat", "description": "repeat some steps",
                    "body": {"repeat": "${1:2}", "do": [{"move": "${2:home}",
                                                          "time": "${3:500ms}"}]}}])


definitions["servoStep"] = step_schema(STEP_KEYS, SERVO_VERBS, "Step")
definitions["servoSteps"] = doc("Steps", "A list of steps, each starting with `- `.",
                                type=["array", "null"], items=ref("servoStep"))
# A section's steps may say `$name` wherever a value, a servo name or a pose name goes: what
# that becomes is known only where the section is performed, so those steps are left to seqc.
section_with_params = doc(
    "Section with parameters", "`params` (names and default values) and the `steps`, which say "
    "`$name` where a parameter's value goes.", type="object", required=["steps"],
    additionalProperties=False,
    properties={
        "params": doc("Parameters", "Each parameter's name and default value "
                      "(`params: {amount: 40, joint: wrist_pitch}`).", type=["object", "null"],
                      propertyNames=ref("servoName"),
                      additionalProperties=doc("Default", "The value `$name` stands for unless "
                                               "the performance gives one.",
                                               type=["string", "number"])),
        "steps": doc("Steps", "The section's steps; `$name` (or `${name}`) stands for a "
                     "parameter's value, and an expression of parameters (`-$x`, `$x * 2`, "
                     "`$beat / 3`) for what it comes to.", type=["array", "null"],
                     items=doc("Step", "A step, checked by seqc where the section is performed.",
                               type="object")),
    })
definitions["section"] = doc(
    "Section", "A list of steps, or `{params, steps}` for a section with parameters.",
    type=["array", "null", "object"],
    allOf=[{"if": {"type": "array"}, "then": ref("servoSteps")},
           {"if": {"type": "object"}, "then": section_with_params}])
definitions["carSection"] = doc(
    "Section", "A list of steps, or `{params, steps}` for a section with parameters.",
    type=["array", "null", "object"],
    allOf=[{"if": {"type": "array"}, "then": ref("carSteps")},
           {"if": {"type": "object"}, "then": section_with_params}])

CAR_OUTPUTS = ["pan", "tilt", "servo1", "servo2", "servo3", "servo4"]
car_positions = doc("Pose or positions", "A pose name (`home`: the gimbal to 1500/1500) or "
                    "`{pan, tilt, servo1..servo4: position}`.", type=["string", "object"],
                    minLength=1, propertyNames={"enum": CAR_OUTPUTS},
                    additionalProperties=ref("position"))
CAR_KEYS = {
    "drive": doc("Drive", "Drive at these speeds for `time` (missing ones are 0); the car stops "
                 "when the step ends unless the next step drives.", type="object",
                 additionalProperties=False,
                 properties={"x": doc("x", "Sideways speed, right positive, -25..25.",
                                      type="integer", minimum=-25, maximum=25),
                             "y": doc("y", "Forward speed, -25..25.", type="integer",
                                      minimum=-25, maximum=25),
                             "z": doc("z", "Rotation, clockwise positive, -200..200.",
                                      type="integer", minimum=-200, maximum=200)}),
    "move": doc("Move", "Move the gimbal or servos over `time`, as small steps one `resolution` "
                "apart.", **{k: v for k, v in car_positions.items()
                            if k not in ("title", "description", "markdownDescription")}),
    "time": ref("carTime"),
    "ease": ref("ease"),
    "steps": doc("Steps", "Send the move as this many steps (1-100000).", type="integer",
                 minimum=1, maximum=100000),
    "wait": doc("Wait", "Send nothing for this long (a drive before it has stopped).",
                **{"$ref": "#/definitions/carTime"}),
    "repeat": STEP_KEYS["repeat"],
    "do": doc("Do", "The steps to repeat.", **{"$ref": "#/definitions/carSteps"}),
    "include": STEP_KEYS["include"],
    "at": ref("at"),
    "section": STEP_KEYS["section"],
    "with": STEP_KEYS["with"],
    "together": doc("Together", "Named tracks of steps that run side by side from the same "
                    "instant; the drive, the gimbal (pan and tilt) and each servo belong to one "
                    "track only.", type="object", minProperties=1,
                    additionalProperties=ref("carSteps")),
    "tempo": ref("tempo"),
    "meter": ref("meter"),
}
# drive and move first: their rules are given `time` below by position.
CAR_VERBS = {"drive": ["drive", "move", "time", "ease", "steps", "at"],
             "move": ["drive", "move", "time", "ease", "steps", "at"],
             "wait": ["wait", "at"], "repeat": ["repeat", "do", "at"],
             "include": ["include", "at"], "section": ["section", "with", "at"],
             "together": ["together", "at"], "tempo": ["tempo"], "meter": ["meter"]}
car_step = step_schema(CAR_KEYS, CAR_VERBS, "Step")
car_step["allOf"][0]["then"]["required"] = ["time"]
car_step["allOf"][1]["then"]["required"] = ["time"]
car_step["defaultSnippets"] = [
    {"label": "drive", "description": "drive for a while",
     "body": {"drive": {"y": "${1:15}"}, "time": "${2:1s}"}},
    {"label": "repeat", "description": "repeat some steps",
     "body": {"repeat": "${1:2}", "do": [{"drive": {"z": "${2:120}"}, "time": "${3:1b}"}]}}]
definitions["carStep"] = car_step
definitions["carSteps"] = doc("Steps", "A list of steps, each starting with `- `.",
                              type=["array", "null"], items=ref("carStep"))

PID = ["speed_kp", "speed_ki", "position_kp", "position_ki", "position_kd", "yaw_kp", "yaw_ki",
       "yaw_kd"]
pid = doc("PID", "Raspblock only: PID settings sent once before the first step; all nine keys "
          "are required.", type="object", additionalProperties=False,
          required=["mode"] + PID,
          properties={"mode": doc("Mode", "`speed` or `position` control.",
                                  enum=["speed", "position"]),
                      **{k: doc(k, f"{k}: 0-255.", type="integer", minimum=0, maximum=255)
                         for k in PID}})

TOP = {
    "robot": doc("Robot", "The robot this file is for: a built-in profile (`xarm`, `bus`, "
                 "`lsc-16`, `lsc-32`, `lsc-6`, `learm`, `raspblock`) or `{profile, servos, mirror}`.",
                 type=["string", "object"],
                 allOf=[{"if": {"type": "string"}, "then": ref("profile")},
                        {"if": {"type": "object"}, "then": ref("robotObject")}],
                 defaultSnippets=robot_object["defaultSnippets"]),
    "name": doc("Name", "Free text: what this choreography is.",
                type=["string", "number", "boolean", "null"]),
    "description": doc("Description", "Free text.", type=["string", "number", "boolean", "null"]),
    "music": doc("Music", "The song the dance is set to; it owns the tempo map (no top-level "
                 "`tempo` or `meter` beside it, no `tempo` or `meter` steps). The sequence "
                 "starts on its downbeat.", type="object", additionalProperties=False,
                 required=["file", "tempo", "meter"],
                 properties={
                     "file": doc("Song file", "The audio, relative to this file: WAV, FLAC, Ogg "
                                 "Vorbis, Opus or MP3.", type="string", minLength=1),
                     "downbeat": string("Downbeat", "Where bar 1 beat 1 falls in the audio "
                                        "(`0.750s`, `750ms`); default `0s`.",
                                        rf"^{NUM}(ms|s)$", "a time in the audio: 0.750s or 750ms"),
                     "tempo": ref("tempo"),
                     "meter": ref("meter"),
                     "changes": doc("Changes", "Where the song's tempo or meter changes, by bar "
                                    "(`{bar: 33, tempo: 132}`); bars increase.", type="array",
                                    items=doc("Change", "A change on a bar line.", type="object",
                                              additionalProperties=False, required=["bar"],
                                              minProperties=2,
                                              properties={
                                                  "bar": doc("Bar", "The bar it falls on (after "
                                                             "bar 1).", type="integer",
                                                             minimum=2),
                                                  "tempo": ref("tempo"),
                                                  "meter": ref("meter")})),
                 }),
    "tempo": ref("tempo"),
    "meter": ref("meter"),
    "tolerance": ref("tolerance"),
    "resolution": doc("Resolution", "Servo controllers: the older uniform expansion (an eased "
                      "move without `steps` becomes `time / resolution` equal actions; at least "
                      "`20ms`). Raspblock: one streamed step every `resolution` (default `20ms`).",
                      type="string"),
    "groups": doc("Groups", "Servo controllers: names for sets of servos, `name: [servo, ...]`; "
                  "a move, pose or waypoint naming a group gives each of its servos the value.",
                  type="object", propertyNames=ref("servoName"),
                  additionalProperties=doc("Group", "The servos it moves, each once.", type="array",
                                           minItems=1, uniqueItems=True,
                                           items=ref("servoName"))),
    "poses": doc("Poses", "Named positions for some servos, `name: {servo: position, ...}`; "
                 "`home` is built in.", type=["object", "null"],
                 additionalProperties=doc("Pose", "`servo: position, ...`", type=["object", "null"],
                                          additionalProperties=ref("position"))),
    "sections": doc("Sections", "Named step lists, performed with `- section: name`; a section "
                    "with parameters is `{params, steps}`.", type="object"),
    "sequence": doc("Sequence", "The steps the robot performs, in order.",
                    type=["array", "null"]),
    "pid": pid,
}

is_car = {"properties": {"robot": {"anyOf": [
    {"const": "raspblock"},
    {"type": "object", "required": ["profile"],
     "properties": {"profile": {"const": "raspblock"}}}]}}}
servo_file = {
    "properties": {
        "pid": False,
        "sequence": {"type": "array", "minItems": 1, "items": ref("servoStep")},
        "resolution": ref("servoTime"),
        "poses": {"additionalProperties": {"propertyNames": ref("servoName")}},
        "sections": {"additionalProperties": ref("section")},
    }}
car_file = {
    "properties": {
        "tolerance": False,
        "groups": False,
        "sequence": ref("carSteps"),
        "sections": {"additionalProperties": ref("carSection")},
        "resolution": ref("carTime"),
        "poses": {"additionalProperties": {"propertyNames": {"enum": CAR_OUTPUTS}}},
    }}

choreography = {
    "type": "object",
    "required": ["robot", "sequence"],
    "properties": TOP,
    "additionalProperties": False,
    "if": is_car, "then": car_file, "else": servo_file,
    # The song owns the tempo map: no second one beside it.
    "dependencies": {"music": {"not": {"anyOf": [{"required": ["tempo"]},
                                                 {"required": ["meter"]}]}}},
}
definitions["choreography"] = choreography

performer = doc("Performer", "A choreography file (relative to the show file) and the port it "
                "plays on.", type="object", required=["file"], additionalProperties=False,
                properties={
                    "file": doc("File", "The performer's choreography (`arm.yaml`).",
                                type="string", minLength=1),
                    "port": doc("Port", "Where it plays: `/dev/ttyUSB0`, `hid`, "
                                "`/dev/ttyAMA0@115200`, `emu:xarm`, `emu:raspblock`.",
                                type="string", minLength=1),
                    "group": doc("Group", "The action group a servo controller stores it in "
                                 "(0-254, default 0).", type="integer", minimum=0, maximum=254),
                })
show = doc("Show", "Several performers started at one instant on one clock (`seqc show`).",
           type="object", required=["show", "performers"], additionalProperties=False,
           properties={
               "show": doc("Show name", "The show's name.", type=["string", "number"]),
               "description": TOP["description"],
               "performers": doc("Performers", "`name: {file, port, group}` for each performer.",
                                 type="object", minProperties=1,
                                 propertyNames=ref("servoName"),
                                 additionalProperties=performer),
           },
           defaultSnippets=[{"label": "show", "description": "an arm and a car on one clock",
                             "body": {"show": "${1:duet}", "performers": {
                                 "arm": {"file": "${2:arm.yaml}", "port": "${3:/dev/ttyUSB0}"},
                                 "car": {"file": "${4:car.yaml}",
                                         "port": "${5:/dev/ttyAMA0@115200}"}}}}])
definitions["show"] = show

schema = {
    "$schema": "http://json-schema.org/draft-07/schema#",
    "$id": "https://seqc.invalid/schemas/seqc.schema.json",
    **doc("seqc choreography", "A robot's motion over time, compiled by seqc (docs/language.md), "
          "or a show of several (`show:`). `seqc check` checks everything here and more: limits "
          "after relative moves, beats at the tempo in force, the action budget."),
    "type": "object",
    "if": {"required": ["show"]},
    "then": ref("show"),
    "else": ref("choreography"),
    "definitions": definitions,
}


def main():
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "schemas/seqc.schema.json")
    text = json.dumps(schema, indent=2, ensure_ascii=False) + "\n"
    if out == "-":
        sys.stdout.write(text)
    else:
        with open(out, "w") as f:
            f.write(text)


if __name__ == "__main__":
    main()
