#!/usr/bin/env python3
"""FreeCAD's Adaptive clearing (libarea's Adaptive2d) of the pockets in pockets.json, written
as G-code the way FreeCAD's Path workbench writes it (PathScripts/PathAdaptive.py,
GenerateGCode, FreeCAD 0.20: helix ramp of straight segments, no helix arcs, no cone; one pass
from the top to the bottom), one program per pocket and step-over.

Usage: adaptive_gcode.py POCKETS_JSON OUT_DIR STEPOVER_PERCENT...
Writes OUT_DIR/adaptive_<pocket>_so<percent>.nc and prints one line per program.

The settings are FreeCAD's defaults for the Adaptive operation (clearing, inside, tolerance
0.1 mm, lift distance 0, finishing profile on, helix angle 5 deg, keep-tool-down ratio 3,
no helix diameter limit), the tool and the feeds are dieplan's (pockets.json): the cutting
feed F = fz * z * S for the horizontal and the vertical feed (the helix ramps run at the
vertical feed, as dieplan's run at the grooving feed).
"""

import json
import math
import os
import sys

# Debian's freecad puts its Python modules here (freecad-python3 for 0.20, older layouts in lib).
for lib in ("/usr/lib/freecad-python3/lib", "/usr/lib/freecad/lib"):
    if os.path.isdir(lib) and lib not in sys.path:
        sys.path.insert(0, lib)

import area  # noqa: E402  (libarea, from Debian's freecad)

# FreeCAD 0.20's defaults for the Adaptive operation (PathAdaptive.py, opSetDefaultValues).
TOLERANCE_MM = 0.1
LIFT_DISTANCE_MM = 0.0
FINISHING_PROFILE = True
HELIX_ANGLE_DEG = 5.0
KEEP_TOOL_DOWN_RATIO = 3.0
HELIX_DIAMETER_LIMIT_MM = 0.0
# Largest angle of one straight segment when an arc of the contour is discretised, deg.
ARC_STEP_DEG = 1.0
# The stock around the pocket (its bounding box grown by this), mm: Adaptive clears inside the
# pocket, the stock only tells it what is material.
STOCK_MARGIN_MM = 10.0


def discretise(outer):
    """The closed contour [[x, y, bulge], ...] as a list of points, arcs in ARC_STEP_DEG steps."""
    points = []
    n = len(outer)
    for i in range(n):
        x0, y0, bulge = outer[i]
        x1, y1, _ = outer[(i + 1) % n]
        points.append((x0, y0))
        if abs(bulge) < 1e-12:
            continue
        theta = 4.0 * math.atan(bulge)  # included angle, positive counter-clockwise
        chord = math.hypot(x1 - x0, y1 - y0)
        radius = chord / (2.0 * math.sin(abs(theta) / 2.0))
        # Centre: on the chord's perpendicular bisector, on the left for a positive bulge.
        mx, my = (x0 + x1) / 2.0, (y0 + y1) / 2.0
        ux, uy = (x1 - x0) / chord, (y1 - y0) / chord
        offset = radius * math.cos(abs(theta) / 2.0) * (1.0 if abs(theta) < math.pi else -1.0)
        side = 1.0 if theta > 0 else -1.0
        cx, cy = mx - side * uy * offset, my + side * ux * offset
        a0 = math.atan2(y0 - cy, x0 - cx)
        steps = max(1, int(math.ceil(abs(math.degrees(theta)) / ARC_STEP_DEG)))
        for k in range(1, steps):
            a = a0 + theta * k / steps
            points.append((cx + radius * math.cos(a), cy + radius * math.sin(a)))
    return points


def adaptive(pocket, tool_diameter_mm, stepover_percent):
    contour = discretise(pocket["outer"])
    xs = [p[0] for p in contour]
    ys = [p[1] for p in contour]
    m = STOCK_MARGIN_MM
    stock = [
        (min(xs) - m, min(ys) - m),
        (max(xs) + m, min(ys) - m),
        (max(xs) + m, max(ys) + m),
        (min(xs) - m, max(ys) + m),
        (min(xs) - m, min(ys) - m),
    ]
    a2d = area.Adaptive2d()
    a2d.stepOverFactor = 0.01 * stepover_percent
    a2d.toolDiameter = tool_diameter_mm
    a2d.helixRampDiameter = HELIX_DIAMETER_LIMIT_MM
    a2d.keepToolDownDistRatio = KEEP_TOOL_DOWN_RATIO
    a2d.stockToLeave = 0.0
    a2d.tolerance = TOLERANCE_MM
    a2d.forceInsideOut = False
    a2d.finishingProfile = FINISHING_PROFILE
    a2d.opType = area.AdaptiveOperationType.ClearingInside
    closed = contour + [contour[0]]
    return a2d.Execute([stock], [closed], lambda paths: False)


class Gcode:
    def __init__(self):
        self.lines = []

    def add(self, word, **axes):
        parts = [word]
        for k in ("X", "Y", "Z", "I", "J", "F"):
            if k in axes:
                parts.append("%s%.4f" % (k, axes[k]))
        self.lines.append(" ".join(parts))


def program(results, pocket, horiz_feed, vert_feed, spindle_rpm, clearance_z, safe_z):
    """FreeCAD's GenerateGCode for one pass from z_top to z_bottom (UseHelixArcs off)."""
    g = Gcode()
    g.lines += ["(adaptive clearing: libarea Adaptive2d, FreeCAD 0.20 G-code)", "G21 G17 G90 G94", "G0 Z%.4f" % clearance_z]
    g.lines.append("S%d M3" % round(spindle_rpm))
    top, bottom = pocket["z_top"], pocket["z_bottom"]
    helix_radius = 0.0
    for region in results:
        (hx, hy), (sx, sy) = region.HelixCenterPoint, region.StartPoint
        helix_radius = max(helix_radius, math.hypot(sx - hx, sy - hy))
    depth_per_circle = 2.0 * math.pi * helix_radius * math.tan(math.radians(HELIX_ANGLE_DEG))
    lz = top
    for region in results:
        (hx, hy), (sx, sy) = region.HelixCenterPoint, region.StartPoint
        start_angle = math.atan2(sy - hy, sx - hx)
        r_helix = math.hypot(sx - hx, sy - hy)
        pass_depth = top - bottom
        if r_helix > 0.01:
            r = r_helix - 0.01
            maxfi = pass_depth / depth_per_circle * 2.0 * math.pi
            fi = 0.0
            offset = -maxfi + start_angle - math.pi / 16.0
            g.add("G0", Z=clearance_z)
            g.add("G0", X=hx + r * math.cos(offset), Y=hy + r * math.sin(offset), Z=clearance_z)
            g.add("G0", X=hx + r * math.cos(offset), Y=hy + r * math.sin(offset), Z=safe_z)
            g.add("G1", X=hx + r * math.cos(offset), Y=hy + r * math.sin(offset), Z=top, F=vert_feed)
            while fi < maxfi:
                z = top - fi / maxfi * (top - bottom)
                g.add("G1", X=hx + r * math.cos(fi + offset), Y=hy + r * math.sin(fi + offset), Z=z, F=vert_feed)
                fi += math.pi / 16.0
            maxfi += 2.0 * math.pi
            while fi < maxfi:
                g.add("G1", X=hx + r * math.cos(fi + offset), Y=hy + r * math.sin(fi + offset), Z=bottom, F=horiz_feed)
                fi += math.pi / 16.0
        else:
            g.add("G0", Z=clearance_z)
            g.add("G0", X=sx, Y=sy, Z=clearance_z)
            g.add("G1", X=sx, Y=sy, Z=bottom, F=vert_feed)
        lz = bottom
        for motion, points in region.AdaptivePaths:
            for x, y in points:
                if motion == area.AdaptiveMotionType.Cutting:
                    z = bottom
                    if z != lz:
                        g.add("G1", Z=z, F=vert_feed)
                    g.add("G1", X=x, Y=y, F=horiz_feed)
                elif motion == area.AdaptiveMotionType.LinkClear:
                    z = bottom + LIFT_DISTANCE_MM
                    if z != lz:
                        g.add("G0", Z=z)
                    g.add("G0", X=x, Y=y)
                elif motion == area.AdaptiveMotionType.LinkNotClear:
                    z = clearance_z
                    if z != lz:
                        g.add("G0", Z=z)
                    g.add("G0", X=x, Y=y)
                else:
                    continue
                lz = z
        if lz != clearance_z:
            g.add("G0", Z=clearance_z)
            lz = clearance_z
    g.lines += ["M5", "M30"]
    return "\n".join(g.lines) + "\n"


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    spec = json.load(open(sys.argv[1]))
    out_dir = sys.argv[2]
    os.makedirs(out_dir, exist_ok=True)
    c = spec["conditions"]
    feed = c["fz_mm"] * spec["tool"]["flutes"] * c["spindle_rpm"]
    clearance = spec["safe_z_mm"]
    for pocket in spec["pockets"]:
        for arg in sys.argv[3:]:
            stepover = float(arg)
            results = adaptive(pocket, spec["tool"]["diameter_mm"], stepover)
            # FreeCAD's safe height is above the start depth, below the clearance height.
            text = program(results, pocket, feed, feed, c["spindle_rpm"], clearance, pocket["z_top"] + 0.5 * clearance)
            name = os.path.join(out_dir, "adaptive_%s_so%g.nc" % (pocket["name"], stepover))
            with open(name, "w") as f:
                f.write(text)
            print("%s: %d regions, %d lines" % (name, len(results), text.count("\n")))


if __name__ == "__main__":
    main()
