#!/usr/bin/env python3
"""Writes the fidelity benchmark's glTF scenes (bench/scenes/*.gltf) from their published data.

The standard Cornell box: the geometry and camera of Cornell's published measurements (the
"Cornell Box Data" page: walls, the short and tall blocks, camera at z = -800 mm, 39.3 degree
field of view), in metres x 10 so its 0.55 m room spans 5.5 m as the engine's built-in box does.
Reflectances are the usual RGB reductions of the measured spectra (white 0.73, red 0.63/0.065/0.05,
green 0.14/0.45/0.09). Walls are 0.1 m slabs behind the published planes, so the outside of the box is
solid too. The box's coordinates (x toward the red wall, camera looking +z) are turned 180 degrees
about y into the engine's (red wall at -x, camera looking -z).

  cornell-sun.gltf    open front, the sun entering through it onto the floor (the ceiling is dark)
  cornell-point.gltf  the same box lit by a point light 0.5 m under the middle of the ceiling
  doorway.gltf        a closed 6 x 3 x 6 m room with a door; the sun lights the ground outside and a
                      patch of floor through the door (light leaking through walls shows up here)

Run from the repository root: scripts/make-fidelity-scenes.py (rewrites the three files).
"""
import base64
import json
import math
import os
import struct

WHITE = [0.73, 0.73, 0.73]
RED = [0.63, 0.065, 0.05]
GREEN = [0.14, 0.45, 0.09]


def cornell(p):
    """Cornell's (x, y, z) in mm to engine metres x 10 (180 degrees about y, centred on x and z)."""
    x, y, z = p
    return (-(x - 278.0) / 100.0, y / 100.0, -(z - 279.6) / 100.0)


class Builder:
    def __init__(self):
        self.materials = []
        self.meshes = []  # (name, material index, positions, normals, indices)

    def material(self, name, color):
        self.materials.append({"name": name, "pbrMetallicRoughness": {
            "baseColorFactor": color + [1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}})
        return len(self.materials) - 1

    def quads(self, name, material, quads):
        """Each quad: 4 corners counter-clockwise seen from the side its normal points to."""
        pos, nrm, idx = [], [], []
        for q in quads:
            a, b, c = [q[i] for i in range(3)]
            u = [b[i] - a[i] for i in range(3)]
            v = [c[i] - a[i] for i in range(3)]
            n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
            length = math.sqrt(sum(x * x for x in n))
            n = [x / length for x in n]
            base = len(pos)
            pos.extend(q)
            nrm.extend([n] * 4)
            idx.extend([base, base + 1, base + 2, base, base + 2, base + 3])
        self.meshes.append((name, material, pos, nrm, idx))

    def box(self, name, material, lo, hi):
        x0, y0, z0 = lo
        x1, y1, z1 = hi
        self.quads(name, material, [
            [(x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0)],  # -x
            [(x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1)],  # +x
            [(x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1)],  # -y
            [(x0, y1, z0), (x0, y1, z1), (x1, y1, z1), (x1, y1, z0)],  # +y
            [(x0, y0, z0), (x0, y1, z0), (x1, y1, z0), (x1, y0, z0)],  # -z
            [(x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)],  # +z
        ])

    def block(self, name, material, top):
        """A Cornell block from its 4 top corners (published order) down to the floor."""
        t = [cornell(p) for p in top]
        b = [(p[0], 0.0, p[2]) for p in t]
        quads = [self.upward(t)]
        for i in range(4):
            j = (i + 1) % 4
            quads.append(self.outward([b[i], b[j], t[j], t[i]], t))
        self.quads(name, material, quads)

    @staticmethod
    def normal(q):
        u = [q[1][i] - q[0][i] for i in range(3)]
        v = [q[2][i] - q[0][i] for i in range(3)]
        return [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]

    def upward(self, q):
        return q if self.normal(q)[1] > 0 else list(reversed(q))

    def outward(self, q, top):
        cx = sum(p[0] for p in top) / 4.0
        cz = sum(p[2] for p in top) / 4.0
        mx = sum(p[0] for p in q) / 4.0
        mz = sum(p[2] for p in q) / 4.0
        n = self.normal(q)
        return q if n[0] * (mx - cx) + n[2] * (mz - cz) > 0 else list(reversed(q))

    def write(self, path, scene_name, lights, camera):
        blob = bytearray()
        accessors, views, meshes, nodes = [], [], [], []

        def add_view(data, target):
            while len(blob) % 4:
                blob.append(0)
            views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data), "target": target})
            blob.extend(data)
            return len(views) - 1

        for name, material, pos, nrm, idx in self.meshes:
            p = add_view(b"".join(struct.pack("<3f", *v) for v in pos), 34962)
            n = add_view(b"".join(struct.pack("<3f", *v) for v in nrm), 34962)
            i = add_view(b"".join(struct.pack("<I", v) for v in idx), 34963)
            lo = [min(v[k] for v in pos) for k in range(3)]
            hi = [max(v[k] for v in pos) for k in range(3)]
            accessors.append({"bufferView": p, "componentType": 5126, "count": len(pos), "type": "VEC3",
                              "min": lo, "max": hi})
            accessors.append({"bufferView": n, "componentType": 5126, "count": len(nrm), "type": "VEC3"})
            accessors.append({"bufferView": i, "componentType": 5125, "count": len(idx), "type": "SCALAR"})
            a = len(accessors) - 3
            meshes.append({"name": name, "primitives": [
                {"attributes": {"POSITION": a, "NORMAL": a + 1}, "indices": a + 2, "material": material}]})
            nodes.append({"name": name, "mesh": len(meshes) - 1})

        light_defs = []
        for light in lights:
            node = {"name": light["name"], "extensions": {"KHR_lights_punctual": {"light": len(light_defs)}}}
            if "position" in light:
                node["translation"] = list(light["position"])
            if "direction" in light:
                node["rotation"] = look_rotation(light["direction"])
            nodes.append(node)
            d = {"name": light["name"], "type": light["type"], "color": light["color"],
                 "intensity": light["intensity"]}
            light_defs.append(d)

        nodes.append({"name": "camera", "camera": 0, "translation": list(camera["position"]),
                      "rotation": look_rotation(camera["forward"])})
        gltf = {
            "asset": {"version": "2.0", "generator": "LPV Engine scripts/make-fidelity-scenes.py"},
            "extensionsUsed": ["KHR_lights_punctual"],
            "extensions": {"KHR_lights_punctual": {"lights": light_defs}},
            "scene": 0,
            "scenes": [{"name": scene_name, "nodes": list(range(len(nodes)))}],
            "nodes": nodes,
            "meshes": meshes,
            "materials": self.materials,
            "cameras": [{"type": "perspective", "perspective": {
                "yfov": math.radians(camera["fov"]), "aspectRatio": 1.0, "znear": 0.1, "zfar": 100.0}}],
            "accessors": accessors,
            "bufferViews": views,
            "buffers": [{"byteLength": len(blob),
                         "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()}],
        }
        with open(path, "w") as f:
            json.dump(gltf, f, indent=1)
            f.write("\n")


def normalize(v):
    length = math.sqrt(sum(x * x for x in v))
    return [x / length for x in v]


def look_rotation(forward):
    """The quaternion (x, y, z, w) that turns a node's -z onto `forward` with +y kept up."""
    f = normalize(forward)
    up = [0.0, 1.0, 0.0] if abs(f[1]) < 0.99 else [0.0, 0.0, -1.0]
    r = normalize([f[1] * up[2] - f[2] * up[1], f[2] * up[0] - f[0] * up[2], f[0] * up[1] - f[1] * up[0]])
    u = [r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2], r[0] * f[1] - r[1] * f[0]]
    b = [-x for x in f]  # the node's +z
    m = [[r[0], u[0], b[0]], [r[1], u[1], b[1]], [r[2], u[2], b[2]]]
    t = m[0][0] + m[1][1] + m[2][2]
    if t > 0:
        s = math.sqrt(t + 1.0) * 2
        return [(m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s, 0.25 * s]
    if m[0][0] > m[1][1] and m[0][0] > m[2][2]:
        s = math.sqrt(1.0 + m[0][0] - m[1][1] - m[2][2]) * 2
        return [0.25 * s, (m[0][1] + m[1][0]) / s, (m[0][2] + m[2][0]) / s, (m[2][1] - m[1][2]) / s]
    if m[1][1] > m[2][2]:
        s = math.sqrt(1.0 + m[1][1] - m[0][0] - m[2][2]) * 2
        return [(m[0][1] + m[1][0]) / s, 0.25 * s, (m[1][2] + m[2][1]) / s, (m[0][2] - m[2][0]) / s]
    s = math.sqrt(1.0 + m[2][2] - m[0][0] - m[1][1]) * 2
    return [(m[0][2] + m[2][0]) / s, (m[1][2] + m[2][1]) / s, 0.25 * s, (m[1][0] - m[0][1]) / s]


def cornell_box():
    """The standard box without its light: walls as slabs outside the published planes."""
    b = Builder()
    white, red, green = b.material("white", WHITE), b.material("red", RED), b.material("green", GREEN)
    # The published room is 556 x 548.8 x 559.2 mm (its walls very nearly planes at these values).
    x0, x1 = cornell((556.0, 0, 0))[0], cornell((0.0, 0, 0))[0]
    z0, z1 = cornell((0, 0, 559.2))[2], cornell((0, 0, 0.0))[2]
    h, t = 5.488, 0.1
    b.box("floor", white, (x0 - t, -t, z0 - t), (x1 + t, 0.0, z1))
    b.box("ceiling", white, (x0 - t, h, z0 - t), (x1 + t, h + t, z1))
    b.box("back wall", white, (x0 - t, 0.0, z0 - t), (x1 + t, h, z0))
    b.box("red wall", red, (x0 - t, 0.0, z0), (x0, h, z1))
    b.box("green wall", green, (x1, 0.0, z0), (x1 + t, h, z1))
    b.block("short block", white, [(130.0, 165.0, 65.0), (82.0, 165.0, 225.0), (240.0, 165.0, 272.0),
                                    (290.0, 165.0, 114.0)])
    b.block("tall block", white, [(423.0, 330.0, 247.0), (265.0, 330.0, 296.0), (314.0, 330.0, 456.0),
                                   (472.0, 330.0, 406.0)])
    return b


CORNELL_CAMERA = {"position": cornell((278.0, 273.0, -800.0)), "forward": (0.0, 0.0, -1.0), "fov": 39.3}


def doorway():
    """A closed room, 6 x 3 x 6 m inside, walls 0.2 m; a door 1.2 x 2.2 m in its +z wall; the ground
    outside 30 x 30 m. The sun comes in low through the door."""
    b = Builder()
    white = b.material("plaster", [0.7, 0.7, 0.7])
    ground = b.material("ground", [0.45, 0.4, 0.3])
    wood = b.material("door frame", [0.5, 0.35, 0.2])
    half, h, t = 3.0, 3.0, 0.2
    b.box("ground", ground, (-15.0, -t, -15.0), (15.0, 0.0, 15.0))
    b.box("ceiling", white, (-half - t, h, -half - t), (half + t, h + t, half + t))
    b.box("back wall", white, (-half - t, 0.0, -half - t), (half + t, h, -half))
    b.box("left wall", white, (-half - t, 0.0, -half), (-half, h, half))
    b.box("right wall", white, (half, 0.0, -half), (half + t, h, half))
    door_lo, door_hi, door_h = -0.6, 0.6, 2.2
    b.box("front wall left", white, (-half - t, 0.0, half), (door_lo, h, half + t))
    b.box("front wall right", white, (door_hi, 0.0, half), (half + t, h, half + t))
    b.box("lintel", wood, (door_lo, door_h, half), (door_hi, h, half + t))
    return b


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    out = os.path.join(root, "bench", "scenes")
    os.makedirs(out, exist_ok=True)

    sun_color = [1.0, 1.0, 1.0]
    # Travelling into the box (-z) and down, onto the floor through the open front: the floor is
    # lit to about 4.5 m deep, the ceiling only by bounced light.
    sun = {"name": "sun", "type": "directional", "color": sun_color, "intensity": 20.0,
           "direction": normalize([0.25, -1.0, -0.8])}
    cornell_box().write(os.path.join(out, "cornell-sun.gltf"), "cornell-sun", [sun], CORNELL_CAMERA)

    point = {"name": "ceiling light", "type": "point", "color": [1.0, 1.0, 1.0], "intensity": 200.0,
             "position": (0.0, 4.988, 0.0)}
    cornell_box().write(os.path.join(out, "cornell-point.gltf"), "cornell-point", [point], CORNELL_CAMERA)

    low_sun = {"name": "sun", "type": "directional", "color": sun_color, "intensity": 20.0,
               "direction": normalize([-0.3, -0.55, -1.0])}
    inside = {"position": (2.2, 1.6, -2.2), "forward": normalize([-0.55, -0.25, 1.0]), "fov": 70.0}
    doorway().write(os.path.join(out, "doorway.gltf"), "doorway", [low_sun], inside)


if __name__ == "__main__":
    main()
