// The tool of the 3-D view in its shape: which end mill the job's result names for a
// path (shape, diameter, corner radius), and its mesh, a lathe of its profile (a flat
// bottom of radius R − r, a quarter torus of radius r, then the cylinder) standing on its
// tip at the origin, z up.
import * as THREE from 'three';

/** The tool's colour. */
const TOOL_COLOR = 0xd4a017;
/** The tool's length, in diameters. */
const TOOL_LENGTH_DIAMETERS = 3;
/** Segments round the tool's axis. */
const AROUND_SEGMENTS = 32;
/** Segments of the quarter torus of its corner (the ball's quarter sphere). */
const CORNER_SEGMENTS = 12;
/** The path a plan's ball-end baseline is drawn as. */
const BASELINE_PATH = 'baseline';
/** The path a plan's stair-step roughing is drawn as. */
const STAIR_STEP_PATH = 'stair_step';
/** A corner radius within this of 0 or of R is that end, mm. */
const RADIUS_EPS_MM = 1e-9;

/**
 * The end mill the job's result names for `path`: `{ shape, diameter_mm, corner_radius_mm }`
 * (`shape` square, radius or ball); a plan's baseline path its ball; its stair-step path
 * the step's ball or radius end mill; a plan's program the
 * chosen candidate's end mill; null when the result names no tool.
 */
export function toolOf(job, path) {
  const r = job.result || {};
  if (path === BASELINE_PATH && r.baseline?.diameter_mm) {
    return { shape: 'ball', diameter_mm: r.baseline.diameter_mm, corner_radius_mm: r.baseline.diameter_mm / 2 };
  }
  if (path === STAIR_STEP_PATH && r.stair_step?.diameter_mm) {
    const s = r.stair_step;
    return { shape: s.tool_type ?? null, diameter_mm: s.diameter_mm, corner_radius_mm: s.corner_radius_mm ?? 0 };
  }
  if (r.tool?.diameter_mm) {
    return { shape: r.tool.tool_type ?? null, diameter_mm: r.tool.diameter_mm, corner_radius_mm: r.tool.corner_radius_mm ?? 0 };
  }
  const chosen = (r.candidates || []).find((c) => c.tool_id === r.chosen_tool_id);
  if (!chosen?.diameter_mm) return null;
  return { shape: chosen.tool_type ?? null, diameter_mm: chosen.diameter_mm, corner_radius_mm: chosen.corner_radius_mm ?? 0 };
}

/** The corner radius the tool is drawn with: R for a ball, 0 for a square end mill or none named, else its own within 0–R. */
function cornerRadius(tool) {
  const radius = tool.diameter_mm / 2;
  if (tool.shape === 'ball') return radius;
  if (tool.shape !== 'radius') return 0;
  return Math.min(radius, Math.max(0, tool.corner_radius_mm || 0));
}

/**
 * The tool's profile from its tip up, as (radius, height) points, mm: the flat bottom to
 * R − r, the quarter circle of radius r to (R, r), the flank up to its length, the top.
 * Sharp corners are given twice, so that the lathe shades each side flat.
 */
export function toolProfile(tool) {
  const radius = tool.diameter_mm / 2;
  const r = cornerRadius(tool);
  const length = tool.diameter_mm * TOOL_LENGTH_DIAMETERS;
  const points = [[0, 0]];
  if (radius - r > RADIUS_EPS_MM) points.push([radius - r, 0]);
  if (r > RADIUS_EPS_MM) {
    for (let k = 1; k <= CORNER_SEGMENTS; k++) {
      const angle = -Math.PI / 2 + (k * Math.PI) / 2 / CORNER_SEGMENTS;
      points.push([radius - r + r * Math.cos(angle), r + r * Math.sin(angle)]);
    }
  } else {
    // The square corner, a second time.
    points.push([radius, 0]);
  }
  points.push([radius, length], [radius, length], [0, length]);
  return points;
}

/** The tool's mesh standing on its tip at the origin, z up; named `tool`, its shape in `userData`. */
export function toolMesh(tool) {
  const profile = toolProfile(tool).map(([x, y]) => new THREE.Vector2(x, y));
  const geometry = new THREE.LatheGeometry(profile, AROUND_SEGMENTS);
  // The lathe turns round y; the tool stands along z.
  geometry.rotateX(Math.PI / 2);
  const material = new THREE.MeshStandardMaterial({ color: TOOL_COLOR, metalness: 0.6, roughness: 0.35, transparent: true, opacity: 0.85 });
  const mesh = new THREE.Mesh(geometry, material);
  mesh.name = 'tool';
  mesh.userData.shape = tool.shape ?? 'unnamed';
  return mesh;
}

/** The largest radius of the mesh `tool` up to `height` mm above its tip: how round its tip is. */
export function radiusAt(tool, height) {
  const positions = tool.geometry.getAttribute('position');
  let widest = 0;
  for (let k = 0; k < positions.count; k++) {
    if (positions.getZ(k) > height + RADIUS_EPS_MM) continue;
    widest = Math.max(widest, Math.hypot(positions.getX(k), positions.getY(k)));
  }
  return widest;
}
