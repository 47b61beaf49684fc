// Pulling and turning a body with the mouse, as in MuJoCo's simulate: a double-click
// selects the body under the pointer (at the point clicked), Ctrl+left drag pulls that
// point across the view's image plane, Ctrl+right drag turns the body about the view's
// axes; the engine applies the springs in every step (Simulation.perturb*, see
// include/simlab/perturb.h) and the view draws a line from the point to where it is
// pulled. The drag arithmetic is plain functions of numbers, so node tests them.

// Radians of turn per pixel dragged.
const kTurnPerPixel = 0.01;

// `point` (world) in the frame of a body at `pos` with rotation `mat` (row-major 3x3):
// mat^T (point - pos).
export function toBodyFrame(point, pos, mat) {
  const d = [point[0] - pos[0], point[1] - pos[1], point[2] - pos[2]];
  return [0, 1, 2].map((k) => mat[k] * d[0] + mat[3 + k] * d[1] + mat[6 + k] * d[2]);
}

// Where a pulled point goes when the mouse moves (dx, dy) pixels: across the image plane
// through the point, one pixel being as long there as on the screen. camera: {position,
// forward, right, up} (unit vectors), fovy (degrees), height (pixels).
export function draggedPoint(point, dx, dy, camera) {
  const rel = [0, 1, 2].map((k) => point[k] - camera.position[k]);
  const depth = rel[0] * camera.forward[0] + rel[1] * camera.forward[1] + rel[2] * camera.forward[2];
  const perPixel = 2 * Math.max(depth, 1e-6) * Math.tan(camera.fovy * Math.PI / 360) / camera.height;
  return [0, 1, 2].map((k) => point[k] + perPixel * (dx * camera.right[k] - dy * camera.up[k]));
}

// q1 q2 (w, x, y, z).
function mulQuat(a, b) {
  return [a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
    a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
    a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
    a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]];
}

function axisAngle(axis, angle) {
  const s = Math.sin(angle / 2);
  return [Math.cos(angle / 2), axis[0] * s, axis[1] * s, axis[2] * s];
}

// The orientation a turned body goes to when the mouse moves (dx, dy) pixels: about the
// view's up axis for dx and its right axis for dy, in the world frame.
export function draggedQuat(quat, dx, dy, camera) {
  const turn = mulQuat(axisAngle(camera.up, dx * kTurnPerPixel), axisAngle(camera.right, dy * kTurnPerPixel));
  const q = mulQuat(turn, quat);
  const n = Math.hypot(...q);
  return q.map((v) => v / n);
}

// The mouse side of a lab's perturbation: selection, drags, and what the view draws.
export class Perturber {
  // sim: the Simulation; bodyOfGeom: model.geom_bodyid; views: get(name) of Data views
  // (xpos, xmat); camera(): the view's camera numbers (see draggedPoint).
  constructor(sim, bodyOfGeom, views, camera) {
    this.sim = sim;
    this.bodyOfGeom = bodyOfGeom;
    this.views = views;
    this.camera = camera;
    this.body = -1;
    this.mode = null;  // 'translate' or 'rotate' while dragging
  }

  // Selects the body of geom `g` at world point `point` (nothing, or a geom of the world:
  // none); returns the body selected, or -1.
  select(g, point) {
    const body = g >= 0 ? this.bodyOfGeom[g] : -1;
    if (body <= 0) {
      this.sim.perturbSelect(-1, 0, 0, 0);
      this.body = -1;
      return -1;
    }
    const xpos = this.views.get('xpos'), xmat = this.views.get('xmat');
    const local = toBodyFrame(point, xpos.subarray(3 * body, 3 * body + 3), xmat.subarray(9 * body, 9 * body + 9));
    this.sim.perturbSelect(body, local[0], local[1], local[2]);
    this.body = body;
    return body;
  }

  // A Ctrl+drag starts: 'translate' or 'rotate'; false when no body is selected.
  start(mode) {
    if (this.body <= 0) return false;
    this.mode = mode;
    this.sim.perturbStart(mode === 'rotate' ? 2 : 1);
    const state = this.sim.perturbState();
    this.refselpos = Array.from(state.refselpos);
    this.refquat = Array.from(state.refquat);
    return true;
  }

  move(dx, dy) {
    if (!this.mode) return;
    const camera = this.camera();
    if (this.mode === 'translate') {
      this.refselpos = draggedPoint(this.refselpos, dx, dy, camera);
      this.sim.perturbMoveTo(...this.refselpos);
    } else {
      this.refquat = draggedQuat(this.refquat, dx, dy, camera);
      this.sim.perturbTurnTo(...this.refquat);
    }
  }

  end() {
    this.mode = null;
    this.sim.perturbStop();
  }

  // The line the view draws while pulling: {from: the point now, to: where it is pulled},
  // or null.
  line() {
    if (this.mode !== 'translate') return null;
    const state = this.sim.perturbState();
    return { from: state.selpos, to: state.refselpos };
  }
}
