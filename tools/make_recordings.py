#!/usr/bin/env python3
"""Writes the play scene scenes/toy_table_4d.json and the scripted recordings of recordings/scripted/.

A scripted recording is a hand (or a phone) moved along key frames, sampled at 90 Hz like a headset, in
the recording format of docs/recording-format.md. Key frames are (time s, world point x y z, controller
turn as (axis, degrees), squeeze, 4D mode). The tool converts world points to tracking space with the
scene's `interaction.origin`, so the scripts read in world coordinates. Run from the repository root:
    python3 tools/make_recordings.py
then tools/update_replay_hashes.sh, and commit all of it.
"""
import json
import math

RATE = 90.0  # Hz, a Quest's rate
G4 = [0, -9.81, 0, 0]
TOY_ORIGIN = [0.0, 1.6, 0.0, 0.0]  # the tracking origin: the head's start, 1.6 m above the floor


def toy_table():
    top = 0.8
    h = 0.08
    cell = 0.12  # 24-cell circumradius; its octahedral facet rests on the table at y = r / sqrt(2)
    return {
        "description": (
            "A 4D toy table for play with hands and a phone: a table top 0.8 m high (a static hypercuboid) "
            "on a floor, with tesseracts (16 cm), a 24-cell and a duocylinder standing on it, all in "
            "the w = 0 slice, and an orange tesseract where the shipped Quest 2 log squeezes. The tracking origin is the head's starting point, 1.6 m above the floor, as "
            "in the Quest 2 logs (poses relative to the starting pose)."),
        "dim": 4,
        "gravity": G4,
        "timestep": 1.0 / 120.0,
        "interaction": {"origin": TOY_ORIGIN, "scale": 1.0, "grab_radius": 0.05, "gravity_tilt": 15.0},
        "bodies": [
            {"name": "floor", "static": True, "shape": {"type": "halfspace", "normal": [0, 1, 0, 0], "offset": 0},
             "friction": 0.6, "kinetic_friction": 0.5},
            {"name": "table", "static": True, "shape": {"type": "box", "half_extents": [0.8, top / 2, 0.5, 0.5]},
             "position": [0, top / 2, 0, 0], "friction": 0.5, "kinetic_friction": 0.4, "color": [0.55, 0.4, 0.3]},
            {"name": "red", "shape": {"type": "box", "half_extents": [h] * 4}, "position": [-0.4, top + h, 0, 0],
             "density": 500.0, "color": [0.85, 0.25, 0.2]},
            {"name": "blue", "shape": {"type": "box", "half_extents": [h] * 4}, "position": [-0.05, top + h, 0, 0],
             "density": 500.0, "color": [0.25, 0.4, 0.85]},
            {"name": "cell24", "shape": {"type": "regular_polytope", "polytope": "24-cell", "circumradius": cell},
             "position": [0.3, top + cell / math.sqrt(2) + 0.002, 0, 0], "density": 500.0,
             "color": [0.3, 0.75, 0.35]},
            # Where the Quest 2 log's right hand squeezes (tracking (0.627, -0.759, 0.309) at t = 34.7 s).
            {"name": "orange", "shape": {"type": "box", "half_extents": [h] * 4}, "position": [0.62, top + h, 0.3, 0],
             "density": 500.0, "color": [0.95, 0.55, 0.15]},
            {"name": "duocylinder", "shape": {"type": "duocylinder", "radii": [0.07, 0.07]},
             "position": [0.1, top + 0.07 + 0.002, -0.3, 0], "density": 500.0, "angular_drag": 1.0,
             "color": [0.9, 0.75, 0.2]},
        ],
    }


def quat(axis, degrees):
    """Unit quaternion [w, x, y, z] turning by `degrees` about unit axis 'x', 'y' or 'z' (right-handed)."""
    a = math.radians(degrees) / 2
    v = {"x": (1, 0, 0), "y": (0, 1, 0), "z": (0, 0, 1)}[axis]
    return [math.cos(a), v[0] * math.sin(a), v[1] * math.sin(a), v[2] * math.sin(a)]


def qmul(p, q):
    w1, x1, y1, z1 = p
    w2, x2, y2, z2 = q
    return [w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
            w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2]


def header(source):
    return {"format": "wedge-recording", "version": 1, "source": source,
            "units": {"time": "s", "position": "m", "acceleration": "g", "rotation_rate": "rad/s"},
            "conventions": {
                "tracking": "OpenXR: x right, y up, z toward the user; right-handed",
                "orientation": "unit quaternion [w, x, y, z], controller to tracking",
                "device": "x right, y up, z out of the screen",
                "acceleration": "gravity included, pointing the way it pulls (CoreMotion)",
                "buttons": "A, B on the right controller; X, Y on the left"}}


def hand_script(keys, origin, hand="right", duration=None):
    """Samples piecewise-linear key frames: (t, [x, y, z] world, [(axis, deg), ...] turns applied in order
    in the controller's axes, squeeze, mode4d). Turns interpolate per key (linear in angle)."""
    lines = []
    end = duration if duration is not None else keys[-1][0]
    n = int(round(end * RATE))
    for i in range(n + 1):
        t = i / RATE
        k = 0
        while k + 1 < len(keys) and keys[k + 1][0] <= t:
            k += 1
        a = keys[k]
        b = keys[min(k + 1, len(keys) - 1)]
        u = 0.0 if b[0] == a[0] else min(max((t - a[0]) / (b[0] - a[0]), 0.0), 1.0)
        p = [a[1][j] + u * (b[1][j] - a[1][j]) - origin[j] for j in range(3)]
        # The controller's turn: the sum of all turns so far (each key lists the total, one entry per axis).
        q = [1.0, 0.0, 0.0, 0.0]
        for (axis, deg_a), (_, deg_b) in zip(a[2], b[2]):
            q = qmul(q, quat(axis, deg_a + u * (deg_b - deg_a)))
        lines.append({"t": round(t, 9), "type": "hand", "hand": hand, "position": [round(c, 9) for c in p],
                      "orientation": [round(c, 12) for c in q], "squeeze": a[3], "trigger": 0.0, "buttons": [],
                      "mode4d": a[4]})
    return lines


def write(path, source, lines):
    with open(path, "w") as f:
        f.write(json.dumps(header(source), separators=(",", ":")) + "\n")
        for line in sorted(lines, key=lambda l: l["t"]):
            f.write(json.dumps(line, separators=(",", ":")) + "\n")


def toy_table_grab():
    """Grab the red tesseract, lift it, turn it 90 deg in the slice (about z), then 60 deg into w (A held:
    x toward w), sweep it through the blue one, and throw it off the table's end."""
    y = 0.88  # the tesseracts' centres
    turns0 = [("z", 0), ("x", 0)]
    turns_z = [("z", 90), ("x", 0)]
    turns_zx = [("z", 90), ("x", 60)]
    keys = [
        (0.0, [-0.4, 1.10, 0], turns0, 0.0, False),
        (0.5, [-0.4, 1.10, 0], turns0, 0.0, False),
        (1.0, [-0.4, y, 0], turns0, 0.0, False),      # down onto the red tesseract's centre
        (1.2, [-0.4, y, 0], turns0, 1.0, False),      # squeeze: grab
        (1.8, [-0.4, 1.20, 0], turns0, 1.0, False),   # lift 32 cm
        (2.8, [-0.4, 1.20, 0], turns_z, 1.0, False),  # turn 90 deg about the controller's z
        (3.0, [-0.4, 1.20, 0], turns_z, 1.0, True),   # hold A (4D mode)
        (4.0, [-0.4, 1.20, 0], turns_zx, 1.0, True),  # turn 60 deg about x: x toward w
        (4.2, [-0.4, 1.20, 0], turns_zx, 1.0, False),
        (4.2, [-0.4, 1.20, 0], turns_zx, 1.0, False),
        (4.8, [-0.3, 0.92, 0], turns_zx, 1.0, False),  # down beside the blue one
        (5.3, [0.45, 0.92, 0], turns_zx, 1.0, False),  # sweep through it at 1.5 m/s
        (5.7, [0.75, 1.30, 0], turns_zx, 1.0, False),  # up and toward the end of the table
        (5.75, [0.85, 1.35, 0], turns_zx, 0.0, False),  # open the hand: thrown
        (7.5, [0.85, 1.35, 0], turns_zx, 0.0, False),
    ]
    return hand_script(keys, TOY_ORIGIN)


def toy_table_tilt():
    """A phone held upright and still, turned 30 deg counterclockwise (about its z, out of the screen)
    over 1 s, held; from t = 4 s the tilt button is on (gravity turns toward w). Accelerometer only,
    100 Hz, as a still phone reads: gravity in the device frame, (-sin a, -cos a, 0) g."""
    lines = []
    for i in range(0, 701):
        t = i / 100.0
        a = math.radians(30.0 * min(max(t - 1.0, 0.0), 1.0))
        lines.append({"t": round(t, 9), "type": "motion",
                      "acceleration": [round(-math.sin(a), 12), round(-math.cos(a), 12), 0.0], "tilt": t >= 4.0})
    return lines


def dominoes_push():
    """Paper figure 3's dominoes (identity tracking: world = tracking): catch the leaning first domino
    near its top at once, lift it, turn it 40 deg about the vertical and back, then push it into the
    second domino and let go: the row falls."""
    p0 = [0.348, 0.974, 0]  # on domino0's axis, 0.4 m above its centre (it leans 20 deg toward +x)
    t0 = [("y", 0)]
    t1 = [("y", 40)]
    keys = [
        (0.0, p0, t0, 1.0, False),              # grab at once: it is falling
        (0.6, [0.25, 1.10, 0], t0, 1.0, False),  # lift it 10 cm or so
        (1.4, [0.25, 1.10, 0], t1, 1.0, False),  # turn about the vertical
        (2.2, [0.25, 1.10, 0], t0, 1.0, False),  # and back
        (2.9, [0.75, 1.00, 0], t0, 1.0, False),  # push into domino1
        (3.0, [0.78, 1.00, 0], t0, 0.0, False),  # let go
        (8.0, [0.78, 1.00, 0], t0, 0.0, False),
    ]
    return hand_script(keys, [0, 0, 0])


def chain_swing():
    """The 4D chain (scenes/chain_4d.json, identity tracking): take its free end at once, before it falls,
    and hold it up, the chain sagging between the beam and the hand; swing it out of the x-y plane (toward
    +z), down and round to the other side, fling it up and let go at 3 s: it swings free, whipping and
    knocking itself, for 7 s."""
    end = [1.84, 1.975, 0]  # link_11's centre, the chain's free end
    t0 = [("z", 0)]
    keys = [
        (0.0, end, t0, 1.0, False),               # grab at once: it is about to fall
        (0.8, [1.2, 1.5, 0], t0, 1.0, False),     # hold it up, the chain sagging
        (1.6, [0.7, 0.6, 0.8], t0, 1.0, False),   # swing it down and out toward +z
        (2.4, [-0.4, 0.8, 0.5], t0, 1.0, False),  # round under the beam to the other side
        (3.0, [-0.9, 1.4, -0.2], t0, 1.0, False),  # fling it up
        (3.05, [-0.92, 1.45, -0.2], t0, 0.0, False),  # let go
        (10.0, [-0.92, 1.45, -0.2], t0, 0.0, False),
    ]
    return hand_script(keys, [0, 0, 0])


def main():
    with open("scenes/toy_table_4d.json", "w") as f:
        json.dump(toy_table(), f, indent=2)
        f.write("\n")
    write("recordings/scripted/toy_table_grab.jsonl", "script", toy_table_grab())
    write("recordings/scripted/toy_table_tilt.jsonl", "script", toy_table_tilt())
    write("recordings/scripted/dominoes_push.jsonl", "script", dominoes_push())
    write("recordings/scripted/chain_swing.jsonl", "script", chain_swing())


if __name__ == "__main__":
    main()
