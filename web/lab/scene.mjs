// The lab's 3D view: every geom of a model drawn with three.js from geom_xpos/geom_xmat
// (and its skins, skins.mjs, and flexes, flexes.mjs),
// a camera placed as MuJoCo's free camera (azimuth, elevation, distance, lookat) with
// mouse orbit, pan and zoom, and overlays for contacts, forces and joint axes.
import * as THREE from '../node_modules/three/build/three.module.js';

import { SceneLabels } from './labels.mjs';
import { Lights, Materials } from './materials.mjs';
import { Flexes } from './flexes.mjs';
import { Skins } from './skins.mjs';

// Colours as MuJoCo draws them: numbers go to the screen as they are (no sRGB decoding of
// inputs, no encoding of the output), as in MuJoCo's OpenGL renderer.
THREE.ColorManagement.enabled = false;

// mjtGeom numbers.
const kPlane = 0, kHfield = 1, kSphere = 2, kCapsule = 3, kEllipsoid = 4, kCylinder = 5,
  kBox = 6, kMesh = 7, kSdf = 8;
// mjtJoint numbers of the joints that have one axis.
const kSlide = 2, kHinge = 3;
// Metres of arrow per newton (or newton metre); arrows are capped at kMaxArrow.
const kForceScale = 0.02, kMaxArrow = 0.3, kAxisLength = 0.08;
// MuJoCo hides geom groups 3 and up by default.
const kVisibleGroups = 3;

// Three.js primitives are built along y; MuJoCo's capsules and cylinders run along z.
function alongZ(geometry) {
  return geometry.rotateX(Math.PI / 2);
}

// A grid of the height field's elevations in its own frame (rows along y, columns along x).
function heightFieldGeometry(model, id) {
  const [rx, ry, elevation] = model.hfield_size.slice(4 * id, 4 * id + 3);
  const nrow = model.hfield_nrow[id], ncol = model.hfield_ncol[id], adr = model.hfield_adr[id];
  const positions = new Float32Array(3 * nrow * ncol);
  for (let r = 0; r < nrow; r++) {
    for (let c = 0; c < ncol; c++) {
      const k = r * ncol + c;
      positions.set([rx * (2 * c / (ncol - 1) - 1), ry * (2 * r / (nrow - 1) - 1),
        elevation * model.hfield_data[adr + k]], 3 * k);
    }
  }
  const indices = [];
  for (let r = 0; r + 1 < nrow; r++) {
    for (let c = 0; c + 1 < ncol; c++) {
      const k = r * ncol + c;
      indices.push(k, k + 1, k + ncol + 1, k, k + ncol + 1, k + ncol);
    }
  }
  return indexedGeometry(positions, indices);
}

// A triangle mesh of mesh `id` in the geom's frame (the compiler already centred it).
// With texture coordinates, every face corner gets its own vertex (a vertex can have
// different coordinates in different faces).
function meshGeometry(model, id) {
  const vadr = model.mesh_vertadr[id], vnum = model.mesh_vertnum[id];
  const fadr = model.mesh_faceadr[id], fnum = model.mesh_facenum[id];
  const tadr = model.mesh_texcoordadr?.[id] ?? -1;
  if (tadr < 0) {
    const positions = Float32Array.from(model.mesh_vert.subarray(3 * vadr, 3 * (vadr + vnum)));
    return indexedGeometry(positions, Array.from(model.mesh_face.subarray(3 * fadr, 3 * (fadr + fnum))));
  }
  const positions = new Float32Array(9 * fnum), uvs = new Float32Array(6 * fnum);
  for (let c = 0; c < 3 * fnum; c++) {
    const v = vadr + model.mesh_face[3 * fadr + c], t = tadr + model.mesh_facetexcoord[3 * fadr + c];
    positions.set(model.mesh_vert.subarray(3 * v, 3 * v + 3), 3 * c);
    uvs.set(model.mesh_texcoord.subarray(2 * t, 2 * t + 2), 2 * c);
  }
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  geometry.setAttribute('uv', new THREE.BufferAttribute(uvs, 2));
  geometry.computeVertexNormals();
  return geometry;
}

function indexedGeometry(positions, indices) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  geometry.setIndex(indices);
  geometry.computeVertexNormals();
  return geometry;
}

// The three.js geometry of geom `g` (an sdf geom is drawn as its mesh), or null for
// types the view does not draw.
function geomGeometry(model, g, extent) {
  const s = model.geom_size.subarray(3 * g, 3 * g + 3);
  switch (model.geom_type[g]) {
    case kPlane: {
      const [hx, hy] = planeHalfSize(model, g, extent);
      return new THREE.PlaneGeometry(2 * hx, 2 * hy);
    }
    case kHfield: return heightFieldGeometry(model, model.geom_dataid[g]);
    case kSphere: return new THREE.SphereGeometry(s[0], 24, 16);
    case kCapsule: return alongZ(new THREE.CapsuleGeometry(s[0], 2 * s[1], 8, 24));
    case kEllipsoid: return new THREE.SphereGeometry(1, 24, 16).scale(s[0], s[1], s[2]);
    case kCylinder: return alongZ(new THREE.CylinderGeometry(s[0], s[0], 2 * s[1], 24));
    case kBox: return new THREE.BoxGeometry(2 * s[0], 2 * s[1], 2 * s[2]);
    case kMesh: return meshGeometry(model, model.geom_dataid[g]);
    case kSdf: return model.geom_dataid[g] >= 0 ? meshGeometry(model, model.geom_dataid[g]) : null;
    default: return null;
  }
}

// The half sizes a plane is drawn with (a zero size is infinite: drawn large relative to
// the model).
function planeHalfSize(model, g, extent) {
  const s = model.geom_size.subarray(3 * g, 3 * g + 3);
  return [0, 1].map((k) => (s[k] > 0 ? s[k] : 4 * extent));
}

// Sets a three.js object's matrix from row `g` of geom_xpos (3 numbers) and geom_xmat
// (a row-major 3x3 rotation), read in place.
function setPose(object, xpos, xmat, g) {
  const p = 3 * g, r = 9 * g;
  object.matrix.set(xmat[r], xmat[r + 1], xmat[r + 2], xpos[p],
                    xmat[r + 3], xmat[r + 4], xmat[r + 5], xpos[p + 1],
                    xmat[r + 6], xmat[r + 7], xmat[r + 8], xpos[p + 2],
                    0, 0, 0, 1);
  object.matrixWorldNeedsUpdate = true;
}

// A pool of arrows of one colour, reused frame to frame; unused ones are hidden. Drawing
// allocates nothing once the pool is as large as the frame needs.
// Overlays (arrows, contact points, the perturbation's line) are drawn over the geoms,
// so that a force inside a body or a contact between two stays in sight.
function drawOnTop(object) {
  object.material.depthTest = false;
  object.material.depthWrite = false;
  object.renderOrder = 1;
}

class ArrowPool {
  constructor(scene, color) {
    this.scene = scene;
    this.color = color;
    this.arrows = [];
    this.used = 0;
    this.direction = new THREE.Vector3();
  }

  begin() { this.used = 0; }

  // An arrow from `origin` along `vector` (Vector3s, read only; length capped), skipped
  // when tiny.
  add(origin, vector) {
    const v = this.direction.copy(vector);
    const length = Math.min(v.length(), kMaxArrow);
    if (length < 1e-4) return;
    if (this.used === this.arrows.length) {
      const arrow = new THREE.ArrowHelper(new THREE.Vector3(0, 0, 1), new THREE.Vector3(), 1, this.color);
      drawOnTop(arrow.line);
      drawOnTop(arrow.cone);
      this.scene.add(arrow);
      this.arrows.push(arrow);
    }
    const arrow = this.arrows[this.used++];
    arrow.position.copy(origin);
    arrow.setDirection(v.normalize());
    arrow.setLength(length, Math.min(0.3 * length, 0.02), Math.min(0.15 * length, 0.01));
    arrow.visible = true;
  }

  end() {
    for (let i = this.used; i < this.arrows.length; i++) this.arrows[i].visible = false;
  }
}

// The camera's pose from MuJoCo's free-camera numbers: it looks along
// (cos el cos az, cos el sin az, sin el) at `target` from `distance` away, z up. Written
// into `out` (an array or Vector3-like with set) when given.
export function cameraPosition({ azimuth, elevation, distance, target }, out = null) {
  const az = azimuth * Math.PI / 180, el = elevation * Math.PI / 180;
  const x = target[0] - distance * Math.cos(el) * Math.cos(az);
  const y = target[1] - distance * Math.cos(el) * Math.sin(az);
  const z = target[2] - distance * Math.sin(el);
  if (out) return out.set(x, y, z);
  return [x, y, z];
}

// Poses a three.js camera as model camera c: at cam_xpos, turned by cam_xmat (MuJoCo's
// cameras look along their -z with y up, as three.js cameras do), with vertical field of
// view `fovy` degrees.
function placeModelCamera(camera, state, c, fovy) {
  const p = state.cam_xpos, r = state.cam_xmat;
  kPose.set(r[9 * c], r[9 * c + 1], r[9 * c + 2], p[3 * c],
            r[9 * c + 3], r[9 * c + 4], r[9 * c + 5], p[3 * c + 1],
            r[9 * c + 6], r[9 * c + 7], r[9 * c + 8], p[3 * c + 2], 0, 0, 0, 1);
  kPose.decompose(camera.position, camera.quaternion, camera.scale);
  if (camera.fov !== fovy) {
    camera.fov = fovy;
    camera.updateProjectionMatrix();
  }
}
const kPose = new THREE.Matrix4();

export class LabScene {
  constructor(container, height, cameraSpec) {
    this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    this.renderer.outputColorSpace = THREE.LinearSRGBColorSpace;
    this.renderer.shadowMap.enabled = true;
    this.renderer.shadowMap.type = THREE.PCFShadowMap;
    this.renderer.domElement.className = 'simlab-lab-canvas';
    container.appendChild(this.renderer.domElement);
    this.container = container;
    this.height = height;
    this.scene = new THREE.Scene();
    // (a model's skybox replaces the background; the lights come with the model, see build)
    this.scene.background = new THREE.Color(0.93, 0.95, 0.98);
    // MuJoCo's default vertical field of view is 45 degrees.
    this.camera = new THREE.PerspectiveCamera(45, 1, 0.005, 100);
    this.camera.up.set(0, 0, 1);
    // A lab block's elevation is the angle above the horizon the camera looks down from
    // (the lesson's 20 sees the scene from above); MuJoCo's free camera counts it the
    // other way (its elevation is where it looks: -45 in MuJoCo's viewer is from above).
    const spec = { ...cameraSpec };
    if (spec.elevation !== undefined) spec.elevation = -spec.elevation;
    this.view = { azimuth: 90, elevation: -45, distance: 2, target: [0, 0, 0], ...spec };
    this.view.target = [...this.view.target];
    this.contactPoints = [];
    // Scratch vectors the overlays reuse every frame.
    this.scratch = { origin: new THREE.Vector3(), vector: new THREE.Vector3(),
                     anchor: new THREE.Vector3(), axis: new THREE.Vector3() };
    this.arrows = {
      contact: new ArrowPool(this.scene, 0xd62728),
      actuator: new ArrowPool(this.scene, 0x2ca02c),
      axis: new ArrowPool(this.scene, 0x1f77b4),
    };
    // The perturbation's line (from the pulled point to where it is pulled) and the
    // handler of double-clicks and Ctrl+drags (see perturb.mjs), set by the lab.
    this.perturbLine = new THREE.Line(new THREE.BufferGeometry().setFromPoints([new THREE.Vector3(), new THREE.Vector3()]),
                                      new THREE.LineBasicMaterial({ color: 0xd62728 }));
    this.perturbLine.visible = false;
    drawOnTop(this.perturbLine);
    this.perturbLine.frustumCulled = false;
    this.scene.add(this.perturbLine);
    this.perturber = null;
    // The inset: a model camera's picture in the view's corner (setInset), framed and
    // captioned by an element over the canvas.
    this.inset = null;
    this.insetCamera = new THREE.PerspectiveCamera(45, 1, 0.005, 100);
    this.insetFrame = container.appendChild(document.createElement('div'));
    this.insetFrame.className = 'simlab-lab-inset';
    this.insetFrame.style.display = 'none';
    this.labels = new SceneLabels(container);
    this.projected = new THREE.Vector3();
    this.raycaster = new THREE.Raycaster();
    this.attachMouse(this.renderer.domElement);
    this.resize();
  }

  // The geom under the pointer and the world point hit ({g, point}), or null (also over
  // the inset).
  pick(clientX, clientY) {
    const box = this.renderer.domElement.getBoundingClientRect();
    if (this.inInset(clientX - box.left, clientY - box.top)) return null;
    const ndc = new THREE.Vector2(2 * (clientX - box.left) / box.width - 1, 1 - 2 * (clientY - box.top) / box.height);
    this.camera.updateMatrixWorld();
    this.raycaster.setFromCamera(ndc, this.camera);
    const meshes = this.geoms.map(({ mesh }) => mesh);
    for (const { mesh } of this.geoms) mesh.matrixWorld.copy(mesh.matrix);
    const hit = this.raycaster.intersectObjects(meshes, false)[0];
    if (!hit) return null;
    const entry = this.geoms.find(({ mesh }) => mesh === hit.object);
    return { g: entry.g, point: hit.point.toArray() };
  }

  // The camera as the perturbation's drags need it (see perturb.mjs, draggedPoint).
  cameraNumbers() {
    this.camera.updateMatrixWorld();
    const column = (k) => new THREE.Vector3().setFromMatrixColumn(this.camera.matrixWorld, k).toArray();
    const forward = column(2).map((v) => -v);
    return { position: this.camera.position.toArray(), forward, right: column(0), up: column(1),
             fovy: this.camera.fov, height: this.height };
  }

  // Geoms of `body` glow (the selected body), others not; body -1: none.
  highlightBody(body, bodyOfGeom) {
    for (const { g, mesh } of this.geoms) {
      const material = mesh.material;
      material.userData.emissive ??= material.emissive.clone();
      material.emissive.copy(bodyOfGeom[g] === body ? new THREE.Color(0x404000) : material.userData.emissive);
    }
  }

  // The perturbation's line, or none (null).
  setPerturbLine(line) {
    this.perturbLine.visible = !!line;
    if (!line) return;
    const position = this.perturbLine.geometry.attributes.position;
    position.setXYZ(0, line.from[0], line.from[1], line.from[2]);
    position.setXYZ(1, line.to[0], line.to[1], line.to[2]);
    position.needsUpdate = true;
  }

  resize() {
    const width = this.container.clientWidth || 640;
    this.renderer.setSize(width, this.height, false);
    this.renderer.domElement.style.height = `${this.height}px`;
    this.camera.aspect = width / this.height;
    this.camera.updateProjectionMatrix();
  }

  // One three.js mesh per visible geom of the model, in its material; the skybox, the
  // headlight and the model's lights (`visual`: sim.visual(), for the headlight).
  build(model, extent, visual = null) {
    this.geoms = [];
    this.materials = new Materials(model);
    for (let g = 0; g < model.geom_type.length; g++) {
      if (model.geom_group[g] >= kVisibleGroups) continue;
      const geometry = geomGeometry(model, g, extent);
      if (!geometry) continue;
      const plane = model.geom_type[g] === kPlane;
      const material = this.materials.geomMaterial(g, plane ? planeHalfSize(model, g, extent) : null,
                                                   !!geometry.attributes.uv);
      const mesh = new THREE.Mesh(geometry, material);
      mesh.matrixAutoUpdate = false;
      mesh.receiveShadow = true;
      mesh.castShadow = !plane && !material.transparent;
      this.scene.add(mesh);
      this.geoms.push({ g, mesh });
    }
    this.skins = new Skins(this.scene, model);
    this.flexes = new Flexes(this.scene, model);
    const sky = this.materials.skybox();
    if (sky) {
      this.scene.background = sky;
      // (MuJoCo's skybox has its up face at +z; three.js puts a cube texture's at +y)
      this.scene.backgroundRotation = new THREE.Euler(Math.PI / 2, 0, 0);
    }
    this.lights = new Lights(this.scene, this.camera, model, visual, extent);
    this.scene.add(this.insetCamera);
    // (the shaders compiled now, before the first frames, which would otherwise stall)
    this.renderer.compile(this.scene, this.camera);
  }

  // Poses every geom from the state, then draws the toggled overlays. state.contacts
  // holds contactData()'s rows, or null; state.contactLayout says where what is in a row
  // ({stride, pos, frame, force}, the module's constants).
  update(state, toggles) {
    this.cameraState = state;
    for (const { g, mesh } of this.geoms) setPose(mesh, state.geom_xpos, state.geom_xmat, g);
    if (state.xpos) this.skins?.update(state.xpos, state.xquat);
    this.flexes?.update(state.flexvert_xpos);
    this.lights?.update(state);
    const ncon = state.contacts ? state.contacts.length / state.contactLayout.stride : 0;
    this.drawContacts(toggles.contacts ? state : null, ncon);
    this.drawForces(toggles.forces ? state : null, ncon);
    this.drawAxes(toggles.joints ? state : null);
  }

  // A dot at each contact point.
  drawContacts(state, ncon) {
    const shown = state ? ncon : 0;
    while (this.contactPoints.length < shown) {
      const dot = new THREE.Mesh(new THREE.SphereGeometry(0.004, 8, 6),
                                 new THREE.MeshBasicMaterial({ color: 0xff7f0e }));
      drawOnTop(dot);
      this.scene.add(dot);
      this.contactPoints.push(dot);
    }
    for (let i = 0; i < this.contactPoints.length; i++) {
      const dot = this.contactPoints[i];
      dot.visible = i < shown;
      if (!dot.visible) continue;
      const at = i * state.contactLayout.stride + state.contactLayout.pos;
      dot.position.set(state.contacts[at], state.contacts[at + 1], state.contacts[at + 2]);
    }
  }

  // Contact forces (world frame, from the contact frame's rows) and the actuators'
  // generalized forces on each slide and hinge joint, along its axis.
  drawForces(state, ncon) {
    const { contact, actuator } = this.arrows;
    const { origin, vector } = this.scratch;
    contact.begin();
    actuator.begin();
    if (state) {
      const rows = state.contacts, layout = state.contactLayout;
      for (let i = 0; i < ncon; i++) {
        const start = i * layout.stride;
        const pos = start + layout.pos, frame = start + layout.frame, force = start + layout.force;
        // world = frame^T force (the frame's rows are the contact axes).
        for (let k = 0; k < 3; k++) {
          let sum = 0;
          for (let row = 0; row < 3; row++) sum += rows[force + row] * rows[frame + 3 * row + k];
          vector.setComponent(k, sum * kForceScale);
        }
        contact.add(origin.set(rows[pos], rows[pos + 1], rows[pos + 2]), vector);
      }
      this.forEachAxis(state, (j, anchor, axis) => {
        const f = state.qfrc_actuator[state.model.jnt_dofadr[j]] * kForceScale;
        actuator.add(anchor, vector.copy(axis).multiplyScalar(f));
      });
    }
    contact.end();
    actuator.end();
  }

  drawAxes(state) {
    const { axis: pool } = this.arrows;
    const { vector } = this.scratch;
    pool.begin();
    if (state) this.forEachAxis(state, (j, anchor, axis) => pool.add(anchor, vector.copy(axis).multiplyScalar(kAxisLength)));
    pool.end();
  }

  // visit(j, anchor, axis) for each slide and hinge joint; anchor and axis are scratch
  // Vector3s, valid during the call only.
  forEachAxis(state, visit) {
    const type = state.model.jnt_type;
    const { anchor, axis } = this.scratch;
    for (let j = 0; j < type.length; j++) {
      if (type[j] !== kSlide && type[j] !== kHinge) continue;
      anchor.fromArray(state.xanchor, 3 * j);
      axis.fromArray(state.xaxis, 3 * j);
      visit(j, anchor, axis);
    }
  }

  // Which camera draws: {kind: 'free'}, {kind: 'track', body} (the free camera's target
  // follows the body's subtree centre of mass, as MuJoCo's tracking camera) or
  // {kind: 'fixed', camera} (model camera `camera`, posed by the engine).
  setCamera(choice) {
    this.cameraChoice = choice;
    if (choice.kind !== 'fixed') this.camera.fov = this.freeFovy ?? 45;
    this.camera.updateProjectionMatrix();
  }

  // Places the camera: a model camera at cam_xpos/cam_xmat with its fovy (looking along
  // its -z, y up, as three.js cameras), else the free camera around its target.
  placeCamera() {
    const choice = this.cameraChoice ?? { kind: 'free' };
    const state = this.cameraState;
    if (choice.kind === 'fixed' && state?.cam_xpos) {
      placeModelCamera(this.camera, state, choice.camera, choice.fovy);
      return;
    }
    if (choice.kind === 'track' && state?.subtree_com) {
      for (let k = 0; k < 3; k++) this.view.target[k] = state.subtree_com[3 * choice.body + k];
    }
    const target = this.view.target;
    cameraPosition(this.view, this.camera.position);
    this.camera.lookAt(target[0], target[1], target[2]);
  }

  render() {
    this.placeCamera();
    this.renderer.render(this.scene, this.camera);
    this.renderInset();
  }

  // A model camera's picture in a bottom corner of the view ({camera, fovy, label, side:
  // 'left' or 'right'}), or none (null).
  setInset(inset) {
    this.inset = inset;
    this.insetFrame.style.display = inset ? '' : 'none';
    this.insetFrame.textContent = '';
    if (inset) this.insetFrame.appendChild(document.createElement('span')).textContent = inset.label;
  }

  // The inset's rectangle in CSS pixels from the view's top left ({left, top, width,
  // height}): in its bottom corner, nearly the view's height, at most 40% of its width.
  insetRect() {
    const margin = 8;
    const width = this.container.clientWidth || 640;
    const height = Math.max(60, Math.round(0.9 * this.height) - margin);
    const w = Math.round(Math.min(1.25 * height, 0.4 * width));
    const left = this.inset?.side === 'left' ? margin : width - w - margin;
    return { left, top: this.height - height - margin, width: w, height };
  }

  inInset(x, y) {
    if (!this.inset) return false;
    const r = this.insetRect();
    return x >= r.left && x <= r.left + r.width && y >= r.top && y <= r.top + r.height;
  }

  // Draws the inset over the corner of the picture (scissored; the shadow maps of the
  // main picture are reused).
  renderInset() {
    if (!this.inset || !this.cameraState?.cam_xpos) return;
    const r = this.insetRect();
    const bottom = this.height - r.top - r.height;
    placeModelCamera(this.insetCamera, this.cameraState, this.inset.camera, this.inset.fovy);
    if (this.insetCamera.aspect !== r.width / r.height) {
      this.insetCamera.aspect = r.width / r.height;
      this.insetCamera.updateProjectionMatrix();
    }
    Object.assign(this.insetFrame.style, { left: `${r.left}px`, top: `${r.top}px`,
                                           width: `${r.width}px`, height: `${r.height}px` });
    const renderer = this.renderer;
    // (the headlight lights the picture of the camera that draws, as in MuJoCo)
    this.lights?.attachHeadlight(this.insetCamera);
    renderer.shadowMap.autoUpdate = false;
    renderer.setScissorTest(true);
    renderer.setScissor(r.left, bottom, r.width, r.height);
    renderer.setViewport(r.left, bottom, r.width, r.height);
    renderer.render(this.scene, this.insetCamera);
    renderer.setScissorTest(false);
    renderer.setViewport(0, 0, this.container.clientWidth || 640, this.height);
    renderer.shadowMap.autoUpdate = true;
    this.lights?.attachHeadlight(this.camera);
  }

  // Labels (see labels.mjs) at the items' positions as the camera placed by the last
  // render sees them, or none (an empty list).
  drawLabels(items) {
    const v = this.projected, ndc = [0, 0, 0];
    const project = (p) => {
      v.set(p[0], p[1], p[2]).project(this.camera);
      ndc[0] = v.x; ndc[1] = v.y; ndc[2] = v.z;
      return ndc;
    };
    this.labels.draw(items, project, this.container.clientWidth || 640, this.height);
  }

  // Left drag orbits (azimuth, elevation), right or shift drag pans the target, the
  // wheel zooms (distance); with a perturber, a double-click selects and Ctrl+drag pulls
  // or turns.
  // The wheel zooms only once the view was clicked (it has focus) or with Ctrl held, so
  // that scrolling the lesson past the lab scrolls the page. Touch drags orbit too.
  attachMouse(canvas) {
    let last = null;
    canvas.tabIndex = 0;
    canvas.style.touchAction = 'none';
    canvas.addEventListener('contextmenu', (e) => e.preventDefault());
    canvas.addEventListener('pointerdown', (e) => {
      canvas.focus({ preventScroll: true });
      // Ctrl+drag pulls (left) or turns (right) the selected body, if there is one.
      const mode = e.button === 2 ? 'rotate' : 'translate';
      const perturb = e.ctrlKey && !!this.perturber?.start(mode);
      last = { x: e.clientX, y: e.clientY, pan: e.button === 2 || e.shiftKey, perturb };
      canvas.setPointerCapture(e.pointerId);
    });
    canvas.addEventListener('dblclick', (e) => this.perturber?.select(this.pick(e.clientX, e.clientY)));
    const release = () => {
      if (last?.perturb) this.perturber.end();
      last = null;
    };
    canvas.addEventListener('pointerup', release);
    canvas.addEventListener('pointercancel', release);
    canvas.addEventListener('pointermove', (e) => {
      if (!last) return;
      const dx = e.clientX - last.x, dy = e.clientY - last.y;
      last.x = e.clientX;
      last.y = e.clientY;
      if (last.perturb) this.perturber.move(dx, dy);
      else if (last.pan) this.pan(dx, dy);
      else this.orbit(dx, dy);
    });
    canvas.addEventListener('wheel', (e) => {
      if (document.activeElement !== canvas && !e.ctrlKey) return;
      e.preventDefault();
      this.view.distance = Math.min(50, Math.max(0.05, this.view.distance * Math.exp(0.001 * e.deltaY)));
    }, { passive: false });
  }

  // (orbiting or panning from a model camera goes back to the free camera, as in simulate)
  leaveFixedCamera() {
    if (this.cameraChoice?.kind === 'fixed') this.onLeaveFixed?.();
  }

  orbit(dx, dy) {
    this.leaveFixedCamera();
    this.view.azimuth -= 0.4 * dx;
    this.view.elevation = Math.max(-89, Math.min(89, this.view.elevation + 0.4 * dy));
  }

  // Moves the target in the camera's image plane, by the pixels dragged at its distance.
  pan(dx, dy) {
    this.leaveFixedCamera();
    if (this.cameraChoice?.kind === 'track') return;  // (the tracked body holds the target)
    const perPixel = 2 * this.view.distance * Math.tan(Math.PI / 8) / this.height;
    const right = new THREE.Vector3().setFromMatrixColumn(this.camera.matrixWorld, 0);
    const up = new THREE.Vector3().setFromMatrixColumn(this.camera.matrixWorld, 1);
    for (let k = 0; k < 3; k++) {
      this.view.target[k] += perPixel * (-dx * right.getComponent(k) + dy * up.getComponent(k));
    }
  }

  // Frees the GPU side of every object drawn (geometries and materials), then the renderer.
  dispose() {
    this.scene.traverse((object) => {
      object.geometry?.dispose();
      const materials = Array.isArray(object.material) ? object.material : [object.material];
      for (const material of materials) material?.dispose();
    });
    this.materials?.dispose();
    this.renderer.dispose();
    this.renderer.domElement.remove();
    this.insetFrame.remove();
    this.labels.layer.remove();
  }
}
