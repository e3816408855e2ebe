// The 3-D scene of a job with three.js: the stock's height map as a shaded mesh, the
// tool path as coloured lines (rapids dashed), the tool where the time slider puts it.
// Coordinates are the job's, in mm, z up.
import * as THREE from 'three';
import { OrbitControls } from '/vendor/three/OrbitControls.js';
import { toolMesh, radiusAt } from './tool3d.js';

/** The stock's colour: steel. */
const STEEL = 0xaab4be;
/** The dashes of rapids, as a fraction of the scene's size. */
const DASH_FRACTION = 0.01;
/** Opacity of rapids, so that they read as thinner than the cut. */
const RAPID_OPACITY = 0.55;
/** Background of the view. */
const BACKGROUND = 0xf7f8fa;

/** Decodes the height map's tops (base64 of little-endian f32). */
export function decodeTops(stock) {
  const bytes = Uint8Array.from(atob(stock.tops), (c) => c.charCodeAt(0));
  const view = new DataView(bytes.buffer);
  const tops = new Float32Array(bytes.length / 4);
  for (let k = 0; k < tops.length; k++) tops[k] = view.getFloat32(4 * k, true);
  return tops;
}

/**
 * The stock as a mesh over the height map's cell centres; the quads whose four corners
 * hold no material (at the layer's bottom: cut through) are left out.
 */
function stockMesh(stock) {
  const tops = decodeTops(stock);
  const { x0_mm: x0, y0_mm: y0, cell_mm: cell, columns: nx, rows: ny } = stock.grid;
  const bottom = stock.z_bottom_mm;
  const positions = new Float32Array(nx * ny * 3);
  for (let j = 0; j < ny; j++) {
    for (let i = 0; i < nx; i++) {
      const k = j * nx + i;
      positions.set([x0 + (i + 0.5) * cell, y0 + (j + 0.5) * cell, tops[k]], 3 * k);
    }
  }
  const empty = (k) => tops[k] <= bottom;
  const index = [];
  for (let j = 0; j + 1 < ny; j++) {
    for (let i = 0; i + 1 < nx; i++) {
      const a = j * nx + i; const b = a + 1; const c = a + nx; const d = c + 1;
      if (empty(a) && empty(b) && empty(c) && empty(d)) continue;
      index.push(a, b, d, a, d, c);
    }
  }
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  geometry.setIndex(index);
  geometry.computeVertexNormals();
  const material = new THREE.MeshStandardMaterial({ color: STEEL, metalness: 0.25, roughness: 0.6, side: THREE.DoubleSide });
  const mesh = new THREE.Mesh(geometry, material);
  mesh.name = 'stock';
  return mesh;
}

/** The layer's outline at its bottom: where the stock ends. */
function layerOutline(stock) {
  const { x0_mm: x0, y0_mm: y0, cell_mm: cell, columns: nx, rows: ny } = stock.grid;
  const box = new THREE.Box3(new THREE.Vector3(x0, y0, stock.z_bottom_mm), new THREE.Vector3(x0 + nx * cell, y0 + ny * cell, stock.z_top_mm));
  const helper = new THREE.Box3Helper(box, 0x9e9e9e);
  helper.name = 'layer';
  return helper;
}

/**
 * Segments of the path between vertices `order` (indices into the trace's vertices, in
 * path order) that join neighbours of one run: per segment the position in `order` of its
 * end vertex (its start is the trace's vertex before it). Feed and rapid apart. Vertices
 * left out between two break the path there (no chord across a gap).
 */
function segments(trace, order) {
  const { run } = trace.v;
  const feed = new Uint32Array(order.length); const rapid = new Uint32Array(order.length);
  let feeds = 0; let rapids = 0;
  for (let n = 1; n < order.length; n++) {
    const b = order[n];
    if (order[n - 1] !== b - 1 || run[b - 1] !== run[b]) continue;
    if (run[b] < 0) rapid[rapids++] = n;
    else feed[feeds++] = n;
  }
  return { feed: feed.subarray(0, feeds), rapid: rapid.subarray(0, rapids) };
}

/** The line segments `list` (see `segments`) of the path through `order`, as a geometry. */
function lineGeometry(trace, order, list) {
  const { x, y, z } = trace.v;
  const positions = new Float32Array(list.length * 6);
  for (let s = 0; s < list.length; s++) {
    const b = order[list[s]];
    const at = 6 * s;
    positions[at] = x[b - 1]; positions[at + 1] = y[b - 1]; positions[at + 2] = z[b - 1] ?? 0;
    positions[at + 3] = x[b]; positions[at + 4] = y[b]; positions[at + 5] = z[b] ?? 0;
  }
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  return geometry;
}

/**
 * The scene of a job in `container`; `stock` may be null (the path alone); `tool` the end
 * mill drawn (see tool3d.js).
 */
export function createScene(container, { stock, tool: toolSpec }) {
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
  container.append(renderer.domElement);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(BACKGROUND);
  scene.add(new THREE.HemisphereLight(0xffffff, 0x505a64, 1.6));
  const sun = new THREE.DirectionalLight(0xffffff, 1.8);
  sun.position.set(-0.6, -0.8, 1.5);
  scene.add(sun);
  const camera = new THREE.PerspectiveCamera(40, 1, 0.1, 1e6);
  camera.up.set(0, 0, 1);
  const controls = new OrbitControls(camera, renderer.domElement);
  controls.enableDamping = false;
  controls.screenSpacePanning = true;
  if (stock) {
    scene.add(stockMesh(stock));
    scene.add(layerOutline(stock));
  }
  let tool = toolMesh(toolSpec);
  tool.visible = false;
  scene.add(tool);
  const path = new THREE.Group();
  scene.add(path);
  let pathParts = null;
  // The camera is framed once, on the first path: later paths (another layer, quantity or
  // unit) keep the view the user chose.
  let framed = false;

  const render = () => renderer.render(scene, camera);
  controls.addEventListener('change', render);
  const resize = () => {
    const width = container.clientWidth || 600;
    const height = Math.round(Math.max(260, Math.min(window.innerHeight * 0.7, width * 0.62)));
    renderer.setSize(width, height);
    camera.aspect = width / height;
    camera.updateProjectionMatrix();
    render();
  };

  return {
    canvas: renderer.domElement,
    render,
    resize,
    /** Draws the path through `order` (vertex indices) with each vertex's colour. */
    setPath(trace, order, colorOf, rapidColor) {
      for (const child of [...path.children]) { child.geometry.dispose(); child.material.dispose(); path.remove(child); }
      const { feed, rapid } = segments(trace, order);
      const feedGeometry = lineGeometry(trace, order, feed);
      const colors = new Float32Array(feed.length * 6);
      // Colours come from a few bins: each parsed once.
      const parsed = new Map();
      const rgb = (css) => {
        if (!parsed.has(css)) { const c = new THREE.Color(css); parsed.set(css, [c.r, c.g, c.b, c.r, c.g, c.b]); }
        return parsed.get(css);
      };
      for (let s = 0; s < feed.length; s++) colors.set(rgb(colorOf(order[feed[s]])), 6 * s);
      feedGeometry.setAttribute('color', new THREE.BufferAttribute(colors, 3));
      path.add(new THREE.LineSegments(feedGeometry, new THREE.LineBasicMaterial({ vertexColors: true })));
      const rapidLines = new THREE.LineSegments(lineGeometry(trace, order, rapid), new THREE.LineDashedMaterial({
        color: rapidColor, transparent: true, opacity: RAPID_OPACITY, dashSize: 1, gapSize: 1 }));
      rapidLines.computeLineDistances();
      const extent = new THREE.Box3().setFromObject(path).getSize(new THREE.Vector3()).length();
      rapidLines.material.dashSize = rapidLines.material.gapSize = Math.max(extent, 1) * DASH_FRACTION;
      path.add(rapidLines);
      // How many segments of each kind end at or before the n-th vertex of `order`.
      const upTo = (list) => { const counts = new Uint32Array(order.length); let k = 0; for (let n = 0; n < order.length; n++) { while (k < list.length && list[k] <= n) k++; counts[n] = k; } return counts; };
      pathParts = { feed: path.children[0], rapid: rapidLines, feedUpTo: upTo(feed), rapidUpTo: upTo(rapid) };
      if (!framed) this.fit();
      framed = true;
    },
    /** Frames the stock and the path, seen from the front left above. */
    fit() {
      const box = new THREE.Box3();
      for (const child of scene.children) if (child.name === 'stock' || child === path) box.expandByObject(child);
      if (box.isEmpty()) return;
      const size = box.getSize(new THREE.Vector3());
      const centre = box.getCenter(new THREE.Vector3());
      const radius = Math.max(size.length() / 2, 1);
      const distance = radius / Math.sin(THREE.MathUtils.degToRad(camera.fov / 2));
      camera.position.copy(centre).add(new THREE.Vector3(-0.45, -0.75, 0.55).normalize().multiplyScalar(distance));
      camera.near = distance / 1000;
      camera.far = distance * 10;
      camera.updateProjectionMatrix();
      controls.target.copy(centre);
      controls.update();
      render();
    },
    /** Shows the path up to its `n`-th vertex (of the order drawn) and the tool there. */
    showUpTo(n, x, y, z) {
      if (!pathParts) return;
      pathParts.feed.geometry.setDrawRange(0, 2 * pathParts.feedUpTo[n]);
      pathParts.rapid.geometry.setDrawRange(0, 2 * pathParts.rapidUpTo[n]);
      tool.visible = x != null;
      if (x != null) tool.position.set(x, y, z ?? 0);
      render();
    },
    /** The tool's position, mm, or null when it is not shown. */
    toolPosition: () => (tool.visible ? [tool.position.x, tool.position.y, tool.position.z] : null),
    /** Draws the end mill `spec` (see tool3d.js) where the tool stands. */
    setTool(spec) {
      const next = toolMesh(spec);
      next.position.copy(tool.position);
      next.visible = tool.visible;
      scene.remove(tool);
      tool.geometry.dispose();
      tool.material.dispose();
      tool = next;
      scene.add(tool);
      render();
    },
    /** The largest radius of the tool's mesh up to `height` mm above its tip, mm. */
    toolRadiusAt: (height) => radiusAt(tool, height),
    dispose() {
      controls.dispose();
      scene.traverse((o) => { o.geometry?.dispose(); o.material?.dispose(); });
      renderer.dispose();
    },
  };
}

/** Whether this browser can draw WebGL. */
export function hasWebGL() {
  try {
    const canvas = document.createElement('canvas');
    return Boolean(canvas.getContext('webgl2') || canvas.getContext('webgl'));
  } catch {
    return false;
  }
}
