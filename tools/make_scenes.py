#!/usr/bin/env python3
"""Writes the contact scenes of scenes/ (the paper's figures 1-4 and the box pyramids) as JSON.

The layouts are the same as the C++ builders in scenes/builders/ (pyramid: row pitch 2.25 half extents
horizontally, 2 vertically). Run from the repository root: python3 tools/make_scenes.py; then run
tools/update_scene_hashes.sh and commit both.
"""
import json
import math

G4 = [0, -9.81, 0, 0]


def ground(dim, friction=0.6):
    n = [0] * dim
    n[1] = 1
    return {"name": "ground", "static": True, "shape": {"type": "halfspace", "normal": n, "offset": 0},
            "friction": friction, "kinetic_friction": friction}


def box(name, half, pos, **extra):
    b = {"name": name, "shape": {"type": "box", "half_extents": half}, "position": pos}
    b.update(extra)
    return b


def rotor_plane(dim, i, j, angle):
    """Rotor exp(-angle/2 e_ij) (turns e_i towards e_j by angle), components scalar first then e01, e02, ..."""
    k = dim * (dim - 1) // 2
    planes = [(a, b) for a in range(dim) for b in range(a + 1, dim)]
    # Even subalgebra size 2^(dim-1): scalar, bivectors, 4-vectors, ...
    r = [0.0] * (2 ** (dim - 1))
    r[0] = math.cos(angle / 2)
    r[1 + planes.index((i, j))] = -math.sin(angle / 2)
    assert len(planes) == k
    return r


def write(name, scene):
    with open("scenes/" + name, "w") as f:
        json.dump(scene, f, indent=1)
        f.write("\n")


def fig1():
    # Three tesseracts stacked, each slightly offset in x and w and turned a little in the ground plane.
    bodies = [ground(4)]
    for k in range(3):
        bodies.append(box("tesseract%d" % k, [0.5] * 4, [0.06 * k, 0.5 + 1.0 * k, 0, -0.05 * k],
                          rotor=rotor_plane(4, 0, 2, 0.15 * k)))
    write("fig1_stack_4d.json", {
        "description": "Paper figure 1: a stack of three 4D hypercubes (1 m tesseracts) on the ground, each "
                       "offset a little in x and w and turned in the xz plane. It stands.",
        "dim": 4, "gravity": G4, "timestep": 1 / 120, "bodies": bodies})


def fig2():
    # A layer of 4-balls on a 3 x 3 x 3 grid over x, z, w; a duocylinder rolls onto them.
    bodies = [ground(4)]
    r = 0.3
    for i in range(3):
        for k in range(3):
            for m in range(3):
                bodies.append({"name": "ball_%d%d%d" % (i, k, m), "shape": {"type": "ball", "radius": r},
                               "position": [0.7 * (i - 1), r, 0.7 * (k - 1), 0.7 * (m - 1)],
                               "friction": 0.4, "kinetic_friction": 0.3})
    bodies.append({"name": "duocylinder", "shape": {"type": "duocylinder", "radii": [0.5, 0.5]},
                   "position": [-2.0, 0.5 + 2 * r + 0.3, 0, 0], "velocity": [2.0, 0, 0, 0],
                   "angular_velocity": [-4.0, 0, 0, 0, 0, 0], "friction": 0.6, "kinetic_friction": 0.5})
    write("fig2_duocylinder_4d.json", {
        "description": "Paper figure 2: a duocylinder (radii 0.5, 0.5) rolls onto a layer of 27 4-balls laid out "
                       "over x, z and w; balls offset in w look like they float in the w = 0 slice.",
        "dim": 4, "gravity": G4, "timestep": 1 / 120,
        # A person standing 1.4 m back from the middle of the layer (wedge xr, the input layer).
        "interaction": {"origin": [0, 1.6, 1.4, 0]},
        "bodies": bodies})


def fig3():
    # Twelve hypercubic dominoes along x; the last four step away in w, by 0.15 m each.
    bodies = [ground(4, 0.5)]
    half = [0.1, 0.6, 0.3, 0.3]
    for k in range(12):
        w = 0.15 * max(0, k - 7)
        d = box("domino%d" % k, half, [0.7 * k, 0.6, 0, w], friction=0.5, kinetic_friction=0.4)
        if k == 0:
            # The first leans 20 degrees towards +x on its bottom edge at x = +0.1 and falls from there.
            a = math.radians(20)
            d["rotor"] = rotor_plane(4, 0, 1, -a)  # turns e1 (up) towards +x by a
            d["position"] = [0.1 - 0.1 * math.cos(a) + 0.6 * math.sin(a), 0.1 * math.sin(a) + 0.6 * math.cos(a), 0, 0]
        bodies.append(d)
    write("fig3_dominoes_4d.json", {
        "description": "Paper figure 3: twelve hypercubic dominoes (0.2 x 1.2 x 0.6 x 0.6 m) 0.7 m apart along x. "
                       "The first leans over by 20 degrees; the last four are offset in w by 0.15, 0.3, 0.45 and 0.6 m, "
                       "out of the w = 0 view, and still fall.",
        "dim": 4, "gravity": G4, "timestep": 1 / 120, "bodies": bodies})


def fig4():
    write("fig4_spinning_4d.json", {
        "description": "Paper figure 4: the hypercuboid (1.1, 0.3, 2.5, 0.7) m spinning about its intermediate "
                       "plane (e23) with a small perturbation, thrown up from the ground it lands on: it tumbles "
                       "in the air (the 4D Dzhanibekov effect) and then settles.",
        "dim": 4, "gravity": G4, "timestep": 1 / 120,
        "bodies": [ground(4), box("hypercuboid", [0.55, 0.15, 1.25, 0.35], [0, 2.0, 0, 0],
                                  velocity=[0, 4.0, 0, 0], angular_velocity=[0.02, 0.02, 0.01, 4.0, 0.01, 0.01])]})


def pyramid(dim, rows, name):
    bodies = [ground(dim)]
    half = 0.5
    for row in range(rows):
        count = rows - row
        for i in range(count):
            p = [0.0] * dim
            p[0] = (i - 0.5 * (count - 1)) * 2.25 * half
            p[1] = half + 2 * half * row
            bodies.append(box("box_%d_%d" % (row, i), [half] * dim, p, friction=0.6, kinetic_friction=0.6,
                              density=1000))
    write(name, {
        "description": "A %d-row pyramid of %d boxes (1 m, 1000 kg/m^%d) in the xy plane, as in Box2D's pyramid "
                       "benchmark; it must rest without collapsing." % (rows, rows * (rows + 1) // 2, dim),
        "dim": dim, "gravity": [0, -9.81] + [0] * (dim - 2), "timestep": 1 / 60,
        "contact": {"contact_iterations": 8, "position_iterations": 3}, "bodies": bodies})


if __name__ == "__main__":
    fig1()
    fig2()
    fig3()
    fig4()
    pyramid(2, 20, "pyramid_2d.json")
    pyramid(3, 20, "pyramid_3d.json")
