// The live lab of a lesson's lab block: mountLab(element, spec, {baseUrl}) loads the
// engine (web/dist, WebAssembly) and models/<model>.xml with every file it refers to
// (attached models, includes, meshes, textures...), resets to the block's keyframe and
// shows the 3D view, sliders, readouts, plots and note, simulating in real time.
// mountModelViewer(element, folder, filename) does the same for any model, with panels
// generated from it (simlab view). See web/README.md, "The lab".
import { arrayReader, arraysOf, evaluateExpr, parseExpr, parseTarget } from './expr.mjs';
import { HistoryScrubber } from './history.mjs';
import { actuatorPoint, kLabelKinds, labelTexts } from './labels.mjs';
import { buildLintPanel, lintBody } from './lint_panel.mjs';
import { gatherModelFiles } from './model_files.mjs';
import { modelInfo, specFromModel } from './panels.mjs';
import { Perturber } from './perturb.mjs';
import { LivePlot, csvText } from './plot.mjs';
import { Pacer, kSpeeds, nextSpeed } from './pacer.mjs';
import { LabScene } from './scene.mjs';
import { parseLabSpec } from './spec.mjs';

let enginePromise = null;

// The WebAssembly module, loaded once per page.
function loadEngine(distUrl) {
  if (!enginePromise) {
    enginePromise = import(new URL('simlab.mjs', distUrl).href).then((m) => m.default());
  }
  return enginePromise;
}

async function fetchOk(url) {
  const response = await fetch(url);
  if (!response.ok) throw new Error(`${url}: HTTP ${response.status}`);
  return response;
}

// A model on the server: file `filename` of the folder at URL `folder`, each file of the
// folder read by its relative path.
export function urlSource(folder, filename) {
  const read = async (path) => fetchOk(new URL(path, folder));
  return {
    filename,
    readText: async (path) => (await read(path)).text(),
    readBytes: async (path) => new Uint8Array(await (await read(path)).arrayBuffer()),
  };
}

// A model source's file and every file it refers to (see model_files.mjs): XML as text,
// other files as bytes, keyed by their path relative to the model's folder.
async function fetchModel(source) {
  const xml = await source.readText(source.filename);
  const files = await gatherModelFiles(source.filename, xml, source.readText, source.readBytes);
  return { filename: source.filename, xml, files };
}

// Data arrays as views into wasm memory, looked up by id (no name string crosses into
// wasm). The rule: a view is valid until wasm memory grows, which only a call that
// allocates can do (step, contactData, any call passing a string, a model load); so
// each part of a draw makes those calls first and takes its views after them. A view of
// an array that never moves is kept from frame to frame and taken again only once its
// buffer is detached (memory grew); efc_* arrays change size with every step, so theirs
// are taken again every frame.
class DataViews {
  constructor(sim) {
    this.sim = sim;
    this.entries = new Map();  // name -> {id, view, perFrame}
    this.frame = 0;
  }

  // Called once per draw (efc_* views are taken again after it).
  nextFrame() { this.frame++; }

  // The view of Data array `name`, or null if there is none.
  get(name) {
    let entry = this.entries.get(name);
    if (!entry) {
      entry = { id: this.sim.dataId(name), view: null, frame: -1, perFrame: name.startsWith('efc_') };
      this.entries.set(name, entry);
    }
    if (entry.id < 0) return null;
    const stale = !entry.view || entry.view.buffer.byteLength === 0 ||
      (entry.perFrame && entry.frame !== this.frame);
    if (stale) {
      entry.view = this.sim.dataViewAt(entry.id);
      entry.frame = this.frame;
    }
    return entry.view;
  }
}

// The Data arrays the 3D view reads every frame.
const kSceneArrays = ['geom_xpos', 'geom_xmat', 'xanchor', 'xaxis', 'qfrc_actuator', 'xpos', 'xmat',
  'light_xpos', 'light_xdir', 'cam_xpos', 'cam_xmat', 'subtree_com', 'flexvert_xpos'];
// Bodies the camera chooser offers to track, at most.
const kMaxTracked = 40;

// A speed as shown: "1x", "1/8x".
function speedText(speed) {
  return speed >= 1 ? `${speed}x` : `1/${Math.round(1 / speed)}x`;
}

// A DOM element with a class and optional text.
function make(tag, className, text) {
  const node = document.createElement(tag);
  if (className) node.className = className;
  if (text !== undefined) node.textContent = text;
  return node;
}

const kStyle = `
.simlab-lab { font: 14px system-ui, sans-serif; border: 1px solid #c8ccd4; border-radius: 6px;
  padding: 8px; background: #fff; max-width: 900px; }
.simlab-lab h3 { margin: 0 0 6px; font-size: 15px; }
.simlab-lab-view { width: 100%; position: relative; }
.simlab-lab-canvas { display: block; width: 100%; border-radius: 4px; cursor: grab; }
.simlab-lab-toolbar { display: flex; gap: 10px; align-items: center; flex-wrap: wrap; margin: 6px 0; }
.simlab-lab-stats { margin-left: auto; font-variant-numeric: tabular-nums; color: #555; }
.simlab-lab-warning { color: #a15c00; }
.simlab-lab-control { display: grid; grid-template-columns: 16em 1fr 7em; gap: 8px; align-items: center; }
.simlab-lab-readouts { display: grid; grid-template-columns: repeat(auto-fill, minmax(13em, 1fr));
  gap: 2px 16px; margin: 6px 0; font-variant-numeric: tabular-nums; }
.simlab-lab-readout .value { font-weight: 600; margin-left: 0.4em; }
.simlab-lab-error { color: #b00020; }
.simlab-lab-note { color: #444; font-size: 13px; margin: 6px 0 0; }
.simlab-lab-group { margin: 8px 0 2px; font-size: 13px; color: #333; }
.simlab-lab-info { position: absolute; left: 8px; top: 8px; margin: 0; padding: 4px 6px;
  font: 11px ui-monospace, monospace; color: #fff; background: rgba(20, 30, 45, 0.6);
  border-radius: 4px; pointer-events: none; }
.simlab-lab-history { display: inline-flex; align-items: center; gap: 4px; }
.simlab-lab-history input { width: 9em; }
.simlab-lab-history-text { font-variant-numeric: tabular-nums; min-width: 5.5em; color: #555; }
.simlab-lab-inset { position: absolute; box-sizing: border-box; border: 2px solid rgba(255, 255, 255, 0.9);
  box-shadow: 0 0 0 1px rgba(20, 30, 45, 0.5); border-radius: 3px; pointer-events: none;
  font: 11px system-ui, sans-serif; color: #fff; }
.simlab-lab-inset span { background: rgba(20, 30, 45, 0.6); padding: 1px 5px; border-radius: 0 0 3px 0; }
.simlab-lab-labels { position: absolute; left: 0; top: 0; pointer-events: none; }
.simlab-lab-label { position: absolute; left: 0; top: 0; font: 11px system-ui, sans-serif; color: #fff;
  white-space: nowrap; text-shadow: 0 0 2px #000, 0 0 2px #000; }
.simlab-lab-lint { margin: 6px 0; font-size: 13px; }
.simlab-lab-lint summary { cursor: pointer; color: #333; }
.simlab-lab-lint-finding { margin: 4px 0 4px 1em; padding: 3px 6px; border-left: 3px solid #c8ccd4; cursor: pointer; }
.simlab-lab-lint-warning { border-left-color: #d08a00; }
.simlab-lab-lint-finding .head { font-weight: 600; }
.simlab-lab-lint-finding .numbers { font-variant-numeric: tabular-nums; }
.simlab-lab-lint-finding .advice { color: #444; }
.simlab-lab-lint-picked { background: #fff4d6; }
.simlab-lab-pickable { cursor: pointer; border-radius: 3px; padding: 0 3px; }
.simlab-lab-pickable:hover { background: #eef2f8; }
.simlab-lab-picked { background: #dde8f7; }
`;

function addStyle() {
  if (document.getElementById('simlab-lab-style')) return;
  const style = make('style');
  style.id = 'simlab-lab-style';
  style.textContent = kStyle;
  document.head.appendChild(style);
  const css = make('link');
  css.rel = 'stylesheet';
  css.href = new URL('../node_modules/uplot/dist/uPlot.min.css', import.meta.url).href;
  document.head.appendChild(css);
}

// Mounts the lab of `spec` (an object, or a block's JSON text with typographic quotes)
// into `element`; resolves to its controller (also element.simlabLab). A model that
// fails to load shows its error in the element and rejects.
export async function mountLab(element, spec, options = {}) {
  const labSpec = typeof spec === 'string' ? parseLabSpec(spec) : spec;
  const baseUrl = options.baseUrl ? new URL(options.baseUrl, document.baseURI)
    : new URL('../../', import.meta.url);
  const distUrl = new URL(options.distUrl ?? '../dist/', import.meta.url);
  addStyle();
  element.textContent = '';
  const root = make('div', 'simlab-lab' + (labSpec.dock ? ' simlab-lab--dock' : ''));
  element.appendChild(root);
  if (labSpec.title) root.appendChild(make('h3', '', labSpec.title));
  const status = root.appendChild(make('div', 'simlab-lab-status', `loading ${labSpec.model}...`));
  try {
    const { simlab, sim } = await openModel(distUrl, urlSource(new URL('models/', baseUrl), `${labSpec.model}.xml`));
    status.remove();
    const lab = new Lab(root, labSpec, sim, contactLayoutOf(simlab));
    element.simlabLab = lab;
    return lab;
  } catch (error) {
    status.className = 'simlab-lab-error';
    status.textContent = `lab "${labSpec.title ?? labSpec.model}": ${error.message ?? error}`;
    throw error;
  }
}

// The engine and a Simulation of a model source's model, with its files.
async function openModel(distUrl, source) {
  const [simlab, files] = await Promise.all([loadEngine(distUrl), fetchModel(source)]);
  return { simlab, sim: new simlab.Simulation(files.filename, files.xml, files.files) };
}

// Where contactData()'s rows keep what the view draws.
function contactLayoutOf(simlab) {
  return { stride: simlab.contactStride, pos: simlab.contactPos, frame: simlab.contactFrame,
           force: simlab.contactForce };
}

// The viewer of any model: mounts a lab whose panels are generated from the model (see
// panels.mjs), with simulate's keys, into `element`; resolves to its controller (also
// element.simlabLab). `source`: the model (urlSource, or files the user picked).
export async function mountModelViewer(element, source, options = {}) {
  const filename = source.filename;
  const distUrl = new URL(options.distUrl ?? '../dist/', import.meta.url);
  addStyle();
  element.textContent = '';
  const root = make('div', 'simlab-lab simlab-lab--viewer');
  element.appendChild(root);
  const status = root.appendChild(make('div', 'simlab-lab-status', `loading ${filename}...`));
  try {
    const { simlab, sim } = await openModel(distUrl, source);
    status.remove();
    const lab = new Lab(root, specFromModel(modelInfo(sim), filename), sim, contactLayoutOf(simlab),
                        { keyboard: true, exports: true, perturb: true, info: true, inset: false });
    element.simlabLab = lab;
    return lab;
  } catch (error) {
    status.className = 'simlab-lab-error';
    status.textContent = `${filename}: ${error.message ?? error}`;
    throw error;
  }
}

// One mounted lab: the simulation, its widgets and the animation loop.
class Lab {
  constructor(root, spec, sim, contactLayout, options = {}) {
    this.root = root;
    this.spec = spec;
    this.sim = sim;
    this.key = spec.key;
    this.options = options;
    this.timestep = sim.option().timestep;
    this.toggles = { contacts: false, forces: false, joints: false };
    this.playing = spec.autoplay !== false;
    this.modelArrays = new Map();
    this.dataViews = new DataViews(sim);
    this.read = arrayReader((source, name) => this.array(source, name));
    this.history = new HistoryScrubber(sim);
    this.labelItems = [];
    // Frame rate and real-time factor over the last half second; engineFactor is simulated
    // time per second spent stepping (how much faster than real time it could run).
    // totalFrames: counted since mounting.
    this.stats = { fps: 0, realTimeFactor: 0, engineFactor: 0, frames: 0,
                   windowStart: performance.now(), simStart: 0, totalFrames: 0 };
    // Pacing against the wall clock, at the chosen speed (see pacer.mjs; its `dropped` is
    // the wall time given up since mounting, `totalSteps` the steps taken).
    this.pacer = new Pacer({ timestep: this.timestep, step: (n) => this.sim.step(n) });
    // A hidden tab gets no frames: the time it was away is not caught up on return.
    this.onVisibility = () => { if (document.hidden) this.pacer.resync(); };
    document.addEventListener('visibilitychange', this.onVisibility);
    // Reused every frame: the scene's state, the plots' sample rows.
    this.state = { model: null, contacts: null, contactLayout, geom_xpos: null, geom_xmat: null,
                   xanchor: null, xaxis: null, qfrc_actuator: null };

    this.view = root.appendChild(make('div', 'simlab-lab-view'));
    this.scene = new LabScene(this.view, Number(spec.height) > 0 ? Number(spec.height) : 300, spec.camera);
    this.buildToolbar();
    this.buildLint();
    this.controls = (spec.controls ?? []).map((c) => this.buildControl(c));
    this.readouts = this.buildReadouts(spec.readouts ?? []);
    this.plots = (spec.plots ?? []).map((p) => this.buildPlot(p));
    if (spec.note) root.appendChild(make('p', 'simlab-lab-note', spec.note));
    this.sceneModel = this.modelObject();
    this.resolveArrays();
    this.scene.build(this.sceneModel, sim.statistic().extent || 1, sim.visual());
    if (options.perturb) this.attachPerturber();
    this.observers = [new ResizeObserver(() => this.resize())];
    this.observers[0].observe(root);
    // Off screen (scrolled away), the lab keeps simulating but does not pose or render its
    // view; back on screen, drawScene catches up.
    this.onScreen = true;
    this.observers.push(new IntersectionObserver(([entry]) => { this.onScreen = entry.isIntersecting; }));
    this.observers[1].observe(this.view);
    if (options.info) this.buildInfo();

    if (options.keyboard) this.listenToKeys();
    this.reset();
    this.frame = this.frame.bind(this);
    requestAnimationFrame(this.frame);
  }

  // A Model or Data array by name, or null if there is none (Model arrays are copied
  // once, unknown names remembered as null; Data arrays are views, see DataViews).
  array(source, name) {
    if (source === 'data') return this.dataViews.get(name);
    if (!this.modelArrays.has(name)) {
      const known = this.sim.modelNames().includes(name);
      this.modelArrays.set(name, known ? this.sim.model(name) : null);
    }
    return this.modelArrays.get(name);
  }

  // Looks up, once and before the first draw, every array the readouts, plots and scene
  // read, so that no name string crosses into wasm memory (and may grow it) mid-draw.
  resolveArrays() {
    const trees = [...this.readouts.map((r) => r.tree), ...this.plots.flatMap((p) => p.traces)];
    for (const tree of trees) for (const [source, name] of arraysOf(tree)) this.array(source, name);
    for (const name of kSceneArrays) this.dataViews.get(name);
  }

  // The Model arrays the 3D view needs, by name.
  modelObject() {
    const names = ['geom_type', 'geom_size', 'geom_rgba', 'geom_group', 'geom_dataid', 'mesh_vertadr',
      'mesh_vertnum', 'mesh_faceadr', 'mesh_facenum', 'mesh_vert', 'mesh_face', 'hfield_size',
      'hfield_nrow', 'hfield_ncol', 'hfield_adr', 'hfield_data', 'jnt_type', 'jnt_dofadr',
      'geom_matid', 'mat_rgba', 'mat_specular', 'mat_shininess', 'mat_emission', 'mat_texid',
      'mat_texrepeat', 'mat_texuniform', 'tex_type', 'tex_width', 'tex_height', 'tex_nchannel',
      'tex_adr', 'tex_data', 'light_type', 'light_active', 'light_castshadow', 'light_ambient',
      'light_diffuse', 'light_cutoff', 'light_exponent', 'mesh_texcoordadr', 'mesh_texcoord',
      'mesh_facetexcoord', 'skin_vertadr', 'skin_vertnum', 'skin_faceadr', 'skin_facenum',
      'skin_boneadr', 'skin_bonenum', 'skin_vert', 'skin_face', 'skin_bonebindpos', 'skin_bonebindquat',
      'skin_bonebodyid', 'skin_bonevertadr', 'skin_bonevertnum', 'skin_bonevertid',
      'skin_bonevertweight', 'skin_rgba', 'skin_inflate', 'skin_group', 'skin_matid',
      'flex_dim', 'flex_vertadr', 'flex_vertnum', 'flex_elemnum', 'flex_elemdataadr', 'flex_elem',
      'flex_shellnum', 'flex_shelldataadr', 'flex_shell', 'flex_rgba', 'flex_matid', 'flex_group',
      'flex_flatskin'];
    const model = {};
    for (const name of names) model[name] = this.array('model', name) ?? new Float64Array(0);
    return model;
  }

  buildToolbar() {
    const bar = this.root.appendChild(make('div', 'simlab-lab-toolbar'));
    this.playButton = bar.appendChild(make('button', 'simlab-lab-play'));
    this.playButton.addEventListener('click', () => (this.playing ? this.pause() : this.play()));
    const reset = bar.appendChild(make('button', 'simlab-lab-reset', 'reset'));
    reset.addEventListener('click', () => this.guarded(() => this.reset()));
    const step = bar.appendChild(make('button', 'simlab-lab-step', 'step'));
    step.addEventListener('click', () => this.guarded(() => this.stepForward()));
    this.buildHistory(bar);
    this.speedSelect = bar.appendChild(this.buildSelect('simlab-lab-speed', 'speed',
      kSpeeds.map((speed) => [String(speed), `speed ${speedText(speed)}`]), (value) => this.setSpeed(Number(value))));
    if (this.spec.keys?.length) {
      // A keyframe to reset to (the spec's key first), or the model's default state.
      const choices = [['', 'default state'], ...this.spec.keys.map((name, k) => [String(k), `key ${name || k}`])];
      this.keySelect = bar.appendChild(this.buildSelect('simlab-lab-key', 'reset to', choices, (value) => {
        this.key = value === '' ? null : Number(value);
        this.guarded(() => this.reset());
      }));
      this.keySelect.value = this.key === null || this.key === undefined ? '' : String(this.key);
    }
    this.buildCameraSelect(bar);
    this.buildLabelSelect(bar);
    this.buildInsetToggle(bar);
    for (const name of this.spec.toggles ?? []) {
      if (!(name in this.toggles)) continue;
      const label = bar.appendChild(make('label', 'simlab-lab-toggle'));
      const box = label.appendChild(make('input'));
      box.type = 'checkbox';
      box.dataset.toggle = name;
      box.addEventListener('change', () => {
        this.toggles[name] = box.checked;
        this.guarded(() => this.draw());
      });
      label.append(` ${name}`);
    }
    if (this.options.exports) {
      const shot = bar.appendChild(make('button', 'simlab-lab-screenshot', 'screenshot'));
      shot.addEventListener('click', () => this.guarded(() => this.download('png')));
      const csv = bar.appendChild(make('button', 'simlab-lab-csv', 'CSV'));
      csv.title = 'the plotted series and the readouts, as CSV';
      csv.addEventListener('click', () => this.guarded(() => this.download('csv')));
    }
    this.errorText = bar.appendChild(make('span', 'simlab-lab-error'));
    this.warningText = bar.appendChild(make('span', 'simlab-lab-warning'));
    this.statsText = bar.appendChild(make('span', 'simlab-lab-stats'));
    this.updatePlayButton();
  }

  // The camera chooser: the free camera, a free camera tracking each moving body (at most
  // kMaxTracked of them), and each of the model's cameras. '[' and ']' cycle through them,
  // Escape goes back to the free camera (simulate's keys).
  buildCameraSelect(bar) {
    const sizes = this.sim.sizes();
    const parent = this.sim.model('body_parentid'), weld = this.sim.model('body_weldid');
    const fovy = this.sim.model('cam_fovy');
    const name = (kind, id, fallback) => this.sim.idToName(kind, id) || fallback;
    this.cameraChoices = [{ label: 'free camera', choice: { kind: 'free' } }];
    for (let b = 1, n = 0; b < sizes.nbody && n < kMaxTracked; b++) {
      // (bodies that move, and only the top of a chain that moves together)
      if (weld[b] === 0 || (parent[b] !== 0 && weld[parent[b]] === weld[b])) continue;
      this.cameraChoices.push({ label: `track ${name('body', b, `body ${b}`)}`, choice: { kind: 'track', body: b } });
      n++;
    }
    for (let c = 0; c < sizes.ncam; c++) {
      this.cameraChoices.push({ label: `camera ${name('camera', c, String(c))}`,
                                choice: { kind: 'fixed', camera: c, fovy: fovy[c] } });
    }
    if (this.cameraChoices.length === 1) return;
    this.cameraSelect = bar.appendChild(this.buildSelect('simlab-lab-camera', 'camera',
      this.cameraChoices.map(({ label }, k) => [String(k), label]), (value) => this.chooseCamera(Number(value))));
    this.scene.onLeaveFixed = () => this.chooseCamera(0);
  }

  // The history slider (simulate's): from the oldest state kept (left) to the newest
  // (right), with how far back the state shown is, in seconds. Moving it pauses and loads
  // that state; Left and Right arrows move one step (see stepBack, stepForward).
  buildHistory(bar) {
    const box = bar.appendChild(make('label', 'simlab-lab-history', 'history '));
    this.historySlider = box.appendChild(make('input'));
    Object.assign(this.historySlider, { type: 'range', min: 0, max: 0, step: 1, value: 0 });
    this.historySlider.setAttribute('aria-label', 'history');
    this.historyText = box.appendChild(make('span', 'simlab-lab-history-text'));
    this.historySlider.addEventListener('input', () => this.guarded(() => {
      this.scrubTo(Number(this.historySlider.max) - Number(this.historySlider.value));
    }));
  }

  // The slider and its text from the engine's history now (DOM writes only on change).
  showHistory() {
    const { slider, text } = this.history.sliderState(this.sim.time);
    if (this.historySlider.max !== slider.max) this.historySlider.max = slider.max;
    if (this.historySlider.value !== slider.value) this.historySlider.value = slider.value;
    if (this.historyText.textContent !== text) this.historyText.textContent = text;
  }

  // Pauses and shows the state `back` steps before the newest (clamped to what is kept).
  // Plots keep their samples until the simulation steps on from there.
  scrubTo(back) {
    this.pause();
    if (!this.history.scrubTo(back)) return;
    this.scrubbed = true;
    this.syncControls();
    this.draw();
  }

  // Left arrow: one state back in the history.
  stepBack() {
    this.scrubTo(this.history.back() + 1);
  }

  // Right arrow and the step button: one state forward in the history when scrubbed
  // back, else one step of the simulation.
  stepForward() {
    const back = this.history.back();
    if (back > 0) this.scrubTo(back - 1);
    else this.stepOnce();
  }

  // Stepping on from a scrubbed state: the plots' samples after it are dropped (the
  // engine drops the newer states).
  leaveScrubbed() {
    if (!this.scrubbed) return;
    this.scrubbed = false;
    for (const { plot } of this.plots) plot.dropAfter(this.sim.time);
  }

  // The sliders show the values their targets hold now (a scrubbed state brings its ctrl).
  syncControls() {
    for (const control of this.controls) {
      if (!control.target) continue;
      control.slider.value = this.dataViews.get(control.target.name)[control.target.index];
      control.shown.textContent = `${Number(control.slider.value)} ${control.spec.unit ?? ''}`;
    }
  }

  // simulate's label option: the name of every object of one kind over the view.
  buildLabelSelect(bar) {
    const sizes = this.sim.sizes();
    const kinds = Object.keys(kLabelKinds).filter((kind) => {
      const { size, first = 0 } = kLabelKinds[kind];
      return sizes[size] > first;
    });
    const choices = [['', 'no labels'], ...kinds.map((kind) => [kind, `label ${kind}`])];
    this.labelSelect = bar.appendChild(this.buildSelect('simlab-lab-label-kind', 'labels', choices,
      (value) => this.guarded(() => this.chooseLabels(value))));
  }

  // Labels on every object of `kind` ('' for none): their texts and the Data array and
  // index of their positions are looked up now, the positions read every frame.
  chooseLabels(kind) {
    const model = { actuator_trntype: this.array('model', 'actuator_trntype'),
                    actuator_trnid: this.array('model', 'actuator_trnid') };
    const nameOf = (k, id) => this.sim.idToName(k, id);
    this.labelItems = [];
    for (const { id, text } of kind ? labelTexts(kind, this.sim.sizes(), nameOf) : []) {
      const [array, index] = kind === 'actuator' ? actuatorPoint(model, id) ?? [] : [kLabelKinds[kind].array, id];
      if (!array || !this.dataViews.get(array)) continue;
      this.labelItems.push({ text, array, index, position: [0, 0, 0] });
    }
    if (this.labelSelect) this.labelSelect.value = kind;
    this.sceneStale = true;
    this.draw();
  }

  // The labels at their objects' positions now (and the picked lint finding's mark).
  drawLabels() {
    const items = this.lintMark ? [...this.labelItems, this.lintMark] : this.labelItems;
    if (!items.length && !this.labelsShown) return;
    for (const item of items) {
      const view = this.dataViews.get(item.array);
      for (let k = 0; k < 3; k++) item.position[k] = view[3 * item.index + k];
    }
    this.scene.drawLabels(items);
    this.labelsShown = items.length > 0;
  }

  // simlab lint's findings for the model at the lab's keyframe, in a panel under the
  // toolbar; a picked finding's body glows in the view and carries the check's name.
  buildLint() {
    let findings;
    try {
      findings = this.sim.lint(this.key ?? -1);
    } catch (error) {
      findings = [];
    }
    this.lintFindings = findings;
    this.lintPanel = this.root.appendChild(buildLintPanel(findings, (finding, row) => this.guarded(() => {
      this.pickLint(finding, row);
    })));
  }

  pickLint(finding, row) {
    for (const other of this.lintPanel.querySelectorAll('.simlab-lab-lint-picked')) other.classList.remove('simlab-lab-lint-picked');
    row.classList.add('simlab-lab-lint-picked');
    const names = ['geom_bodyid', 'eq_type', 'eq_obj1id', 'jnt_bodyid', 'actuator_trntype', 'actuator_trnid', 'site_bodyid'];
    const model = Object.fromEntries(names.map((name) => [name, this.array('model', name)]));
    const body = lintBody(model, finding);
    this.scene.highlightBody(body, model.geom_bodyid);
    this.lintMark = body > 0 ? { text: `${finding.check}: ${finding.element}`, array: 'xpos', index: body, position: [0, 0, 0] } : null;
    this.sceneStale = true;
    this.drawScene();
  }

  // A close-up in the view's corner through the model's first camera (a lesson's model
  // places one where the action is: the gantry's follows the fingers and the cube), on
  // by default in a lesson's lab; a checkbox turns it off and on.
  buildInsetToggle(bar) {
    if (!this.sim.sizes().ncam) return;
    const label = bar.appendChild(make('label', 'simlab-lab-toggle'));
    this.insetBox = label.appendChild(make('input'));
    this.insetBox.type = 'checkbox';
    this.insetBox.className = 'simlab-lab-inset-toggle';
    this.insetBox.checked = this.options.inset ?? true;
    label.append(' inset');
    this.insetBox.addEventListener('change', () => this.guarded(() => this.showInset(this.insetBox.checked)));
    this.showInset(this.insetBox.checked);
  }

  showInset(on) {
    const name = this.sim.idToName('camera', 0);
    // (on the left, where a lesson's camera leaves floor; on the right beside the
    // viewer's info panel)
    const side = this.options.info ? 'right' : 'left';
    this.scene.setInset(on ? { camera: 0, fovy: this.sim.model('cam_fovy')[0], label: `camera ${name || 0}`, side } : null);
    this.sceneStale = true;
    if (this.state.geom_xpos) this.drawScene();
  }

  // Draws with camera choice k (an index into cameraChoices).
  chooseCamera(k) {
    const count = this.cameraChoices?.length ?? 1;
    const index = ((k % count) + count) % count;
    this.cameraIndex = index;
    this.scene.setCamera(this.cameraChoices?.[index]?.choice ?? { kind: 'free' });
    if (this.cameraSelect) this.cameraSelect.value = String(index);
    this.sceneStale = true;
    this.draw();
  }

  // simulate's info panel over the view: time, real-time factor, step time, contacts,
  // constraint rows, solver iterations, warnings, and the energy when the model enables it.
  buildInfo() {
    this.infoText = this.view.appendChild(make('pre', 'simlab-lab-info'));
    this.energyEnabled = (this.sim.option().enableflags & 2) !== 0;  // mjENBL_ENERGY
  }

  showInfo() {
    if (!this.infoText) return;
    const c = this.sim.counts();
    const lines = [
      `time        ${this.sim.time.toFixed(3)} s`,
      `real time   ${this.stats.realTimeFactor.toFixed(2)}x${this.pacer.speed === 1 ? '' : ` (speed ${speedText(this.pacer.speed)})`}`,
      `step        ${(1000 * this.pacer.msPerStep).toFixed(0)} us`,
      `contacts    ${c.ncon}`,
      `constraints ${c.nefc}`,
      `solver      ${c.solver_niter} iterations`,
      `warnings    ${this.sim.warningTotal()}`,
    ];
    if (this.energyEnabled) lines.push(`energy      ${(c.energy[0] + c.energy[1]).toFixed(3)} J`);
    const text = lines.join('\n');
    if (this.infoText.textContent !== text) this.infoText.textContent = text;
  }

  // Double-click selects a body, Ctrl+drag pulls or turns it (see perturb.mjs); the
  // selected body glows.
  attachPerturber() {
    const bodyOfGeom = this.array('model', 'geom_bodyid');
    this.perturber = new Perturber(this.sim, bodyOfGeom, this.dataViews, () => this.scene.cameraNumbers());
    this.scene.perturber = {
      select: (hit) => this.guarded(() => {
        const body = this.perturber.select(hit ? hit.g : -1, hit ? hit.point : [0, 0, 0]);
        this.scene.highlightBody(body, bodyOfGeom);
        this.scene.render();
      }),
      start: (mode) => this.perturber.start(mode),
      move: (dx, dy) => this.guarded(() => this.perturber.move(dx, dy)),
      end: () => this.guarded(() => this.perturber.end()),
    };
  }

  // A drop-down of [value, text] choices calling onChange(value).
  buildSelect(className, label, choices, onChange) {
    const select = make('select', className);
    select.setAttribute('aria-label', label);
    for (const [value, text] of choices) {
      const option = select.appendChild(make('option', '', text));
      option.value = value;
    }
    select.addEventListener('change', () => onChange(select.value));
    return select;
  }

  // simulate's keys, on the whole page (for a page with one lab): Space plays or pauses,
  // Right arrow takes one step (or one state forward in the history when scrubbed back),
  // Left arrow goes one state back in the history, Backspace resets, '-' and '=' slow down and speed up, '['
  // and ']' change the camera and Escape goes back to the free one.
  // Keys typed into a form field, or pressed on a focused button, are theirs.
  listenToKeys() {
    this.onKey = (event) => {
      const tag = event.target?.tagName;
      if (['INPUT', 'SELECT', 'TEXTAREA', 'BUTTON'].includes(tag) || event.ctrlKey || event.metaKey || event.altKey) return;
      const actions = {
        ' ': () => (this.playing ? this.pause() : this.play()),
        ArrowRight: () => this.stepForward(),
        ArrowLeft: () => this.stepBack(),
        Backspace: () => this.reset(),
        '-': () => this.changeSpeed(-1),
        '=': () => this.changeSpeed(1),
        '+': () => this.changeSpeed(1),
        ']': () => this.chooseCamera((this.cameraIndex ?? 0) + 1),
        '[': () => this.chooseCamera((this.cameraIndex ?? 0) - 1),
        Escape: () => this.chooseCamera(0),
      };
      const action = actions[event.key];
      if (!action) return;
      event.preventDefault();
      this.guarded(action);
    };
    document.addEventListener('keydown', this.onKey);
  }

  // A slider writing its target (data.NAME[i]) on input; a bad target disables it and
  // says why.
  buildControl(spec) {
    const row = this.root.appendChild(make('div', 'simlab-lab-control'));
    row.appendChild(make('label', '', spec.label ?? spec.set));
    const slider = row.appendChild(make('input'));
    slider.type = 'range';
    Object.assign(slider, { min: spec.min, max: spec.max, step: spec.step ?? 'any' });
    slider.setAttribute('aria-label', spec.label ?? spec.set);
    const shown = row.appendChild(make('span', 'simlab-lab-value'));
    const control = { spec, slider, shown, target: null };
    try {
      control.target = parseTarget(spec.set);
      this.read('data', control.target.name, control.target.index);  // checks name and index
    } catch (error) {
      control.target = null;
      slider.disabled = true;
      shown.className = 'simlab-lab-error';
      shown.textContent = error.message;
    }
    slider.addEventListener('input', () => this.applyControl(control));
    return control;
  }

  // Writes the slider's value through the target's view (no name string into wasm).
  applyControl(control) {
    if (!control.target) return;
    const value = Number(control.slider.value);
    this.dataViews.get(control.target.name)[control.target.index] = value;
    this.changed = true;
    control.shown.textContent = `${value} ${control.spec.unit ?? ''}`;
  }

  // Readouts, under a heading per group when they have one; with spec.pickPlots a click
  // on a readout adds it to the plot of picked readouts (another click takes it out).
  buildReadouts(specs) {
    let box = null, group;
    return specs.map((spec) => {
      if (!box || spec.group !== group) {
        group = spec.group;
        if (group) this.root.appendChild(make('h4', 'simlab-lab-group', group));
        box = this.root.appendChild(make('div', 'simlab-lab-readouts'));
      }
      const row = box.appendChild(make('div', 'simlab-lab-readout'));
      row.appendChild(make('span', 'label', spec.label ?? spec.expr));
      const value = row.appendChild(make('span', 'value'));
      const readout = { spec, row, value, tree: null, error: '', current: NaN };
      try {
        readout.tree = parseExpr(spec.expr);
      } catch (error) {
        readout.error = error.message;
      }
      if (this.spec.pickPlots) {
        row.classList.add('simlab-lab-pickable');
        row.title = 'click to plot';
        row.addEventListener('click', () => this.guarded(() => this.togglePicked(readout)));
      }
      return readout;
    });
  }

  // Adds a readout to the plot of picked readouts, or takes it out; the plot is made
  // anew with its traces (and goes away with the last one).
  togglePicked(readout) {
    this.picked ??= [];
    const at = this.picked.indexOf(readout);
    if (at >= 0) this.picked.splice(at, 1);
    else this.picked.push(readout);
    readout.row.classList.toggle('simlab-lab-picked', at < 0);
    const old = this.plots.findIndex((p) => p.picked);
    if (old >= 0) {
      this.plots[old].box.remove();
      this.plots.splice(old, 1);
    }
    if (!this.picked.length) return;
    const traces = this.picked.map((r) => ({ label: r.spec.label ?? r.spec.expr }));
    const box = make('div', 'simlab-lab-plot');
    this.view.after(box);
    this.plots.push({ picked: true, box, traces: this.picked.map((r) => r.tree), values: traces.map(() => NaN),
                      plot: new LivePlot(box, { traces, window: 10 }, this.width()) });
  }

  // The plotted series (time and one column per trace, for every plot), then the readouts
  // now (label, value), as CSV text.
  exportCsv() {
    const lines = [];
    for (const { plot } of this.plots) lines.push(...plot.csvLines(), '');
    lines.push('"readout","value"');
    for (const r of this.readouts) lines.push(`${csvText(r.spec.label ?? r.spec.expr)},${r.current}`);
    return lines.join('\n') + '\n';
  }

  // Saves the view as a PNG, or exportCsv() as CSV, through the browser's download.
  download(kind) {
    const stem = (this.spec.title || 'simlab').replace(/\.xml$/i, '').replace(/[^\w.-]+/g, '_');
    const link = make('a');
    link.download = `${stem}_t${this.sim.time.toFixed(3)}.${kind}`;
    if (kind === 'png') {
      this.scene.render();  // (the canvas holds its picture only until the frame ends)
      link.href = this.scene.renderer.domElement.toDataURL('image/png');
    } else {
      link.href = URL.createObjectURL(new Blob([this.exportCsv()], { type: 'text/csv' }));
      setTimeout(() => URL.revokeObjectURL(link.href), 10000);
    }
    link.click();
  }

  buildPlot(spec) {
    const box = this.root.appendChild(make('div', 'simlab-lab-plot'));
    box.dataset.spec = '1';
    const traces = (spec.traces ?? []).map((trace) => {
      try {
        return parseExpr(trace.expr);
      } catch {
        return null;
      }
    });
    return { traces, values: traces.map(() => NaN), box,
             plot: new LivePlot(box, { ...spec, traces: spec.traces ?? [] }, this.width()) };
  }

  width() {
    return Math.max(200, (this.root.clientWidth || 640) - 16);
  }

  resize() {
    this.scene.resize();
    for (const { plot } of this.plots) plot.setWidth(this.width());
  }

  // The value of a parsed expression now, or NaN (the error is kept in this.lastError).
  evaluate(tree) {
    try {
      this.lastError = '';
      return evaluateExpr(tree, this.read);
    } catch (error) {
      this.lastError = error.message;
      return NaN;
    }
  }

  // Readouts, plot samples and the 3D view from the current state. Each part takes its
  // views after its own calls that may grow wasm memory (see DataViews): the readouts and
  // plots first, then the scene (contactData(), then the poses).
  draw() {
    this.changed = false;
    this.dataViews.nextFrame();
    for (const r of this.readouts) {
      const value = r.tree ? this.evaluate(r.tree) : NaN;
      const error = r.tree ? this.lastError : r.error;
      r.current = value;
      r.error = error;
      const className = error ? 'value simlab-lab-error' : 'value';
      const text = error ? error : value.toFixed(r.spec.digits ?? 3);
      // The DOM only when what it shows changes.
      if (r.value.className !== className) r.value.className = className;
      if (r.value.textContent !== text) r.value.textContent = text;
    }
    const time = this.sim.time;
    // (a scrubbed state is shown, not plotted: the plots keep the newer samples)
    for (const { traces, values, plot } of this.scrubbed ? [] : this.plots) {
      for (let i = 0; i < traces.length; i++) values[i] = traces[i] ? this.evaluate(traces[i]) : NaN;
      plot.push(time, values);
      plot.draw();
    }
    this.sceneStale = true;
    if (this.onScreen) this.drawScene();
    if (this.historySlider) this.showHistory();
  }

  // The 3D view: posed anew from the state when a draw left it stale, then rendered.
  drawScene() {
    if (this.sceneStale) this.scene.update(this.sceneState(), this.toggles);
    this.sceneStale = false;
    if (this.perturber) this.scene.setPerturbLine(this.perturber.line());
    this.scene.render();
    this.drawLabels();
  }

  // What the view draws (one object, refilled every frame): contacts as ncon rows of
  // contactLayout.stride numbers (see web/README.md), then views of the poses and forces.
  sceneState() {
    const state = this.state;
    const wantsContacts = this.toggles.contacts || this.toggles.forces;
    state.contacts = wantsContacts ? this.sim.contactData() : null;
    state.model = this.sceneModel;
    state.geom_xpos = this.dataViews.get('geom_xpos');
    state.geom_xmat = this.dataViews.get('geom_xmat');
    state.xanchor = this.dataViews.get('xanchor');
    state.xaxis = this.dataViews.get('xaxis');
    state.qfrc_actuator = this.dataViews.get('qfrc_actuator');
    state.light_xpos = this.dataViews.get('light_xpos');
    state.light_xdir = this.dataViews.get('light_xdir');
    state.cam_xpos = this.dataViews.get('cam_xpos');
    state.cam_xmat = this.dataViews.get('cam_xmat');
    state.subtree_com = this.dataViews.get('subtree_com');
    if (this.sceneModel.skin_vertnum.length) {
      state.xpos = this.dataViews.get('xpos');
      state.xquat = this.dataViews.get('xquat');
    }
    if (this.sceneModel.flex_dim.length) state.flexvert_xpos = this.dataViews.get('flexvert_xpos');
    return state;
  }

  // The animation loop: while playing, steps to keep simulation time with the wall clock
  // (see advance), then draws and updates the frame rate and real-time factor.
  frame(now) {
    if (this.disposed) return;
    try {
      this.frameBody(now);
    } catch (error) {
      this.fail(error);
    }
    requestAnimationFrame(this.frame);
  }

  // An engine error (or any other) pauses the lab and shows the message in its toolbar;
  // reset clears it.
  fail(error) {
    this.pause();
    this.errorText.textContent = `stopped: ${error.message ?? error}`;
  }

  frameBody(now) {
    const timeBefore = this.sim.time;
    this.pacer.frame(now, this.playing);
    // Paused, a slider still acts at once: forward recomputes forces from the new ctrl
    // (as MuJoCo's simulate does while paused).
    if (!this.playing && this.changed) this.sim.forward();
    // Readouts and plots only when time moved or something asked for it; the 3D view
    // whenever it is on screen (the camera may have moved).
    if (this.changed || this.sim.time !== timeBefore) this.draw();
    else if (this.onScreen) this.drawScene();
    this.showWarnings();
    this.countFrame(now);
    this.showInfo();
  }

  // The engine's warnings since the last reset (a state that diverged and was reset, an
  // engine error...), in the toolbar; looked up only when their count changes.
  showWarnings() {
    const total = this.sim.warningTotal();
    if (total === this.warningTotal) return;
    this.warningTotal = total;
    const text = this.sim.warnings()
      .map((w) => `${w.message ? `engine error: ${w.message}` : w.name} (${w.number}x)`)
      .join('; ');
    this.warningText.textContent = text ? `warning: ${text}` : '';
  }

  countFrame(now) {
    const s = this.stats;
    s.frames++;
    s.totalFrames++;
    const elapsed = (now - s.windowStart) / 1000;
    if (elapsed < 0.5) return;
    s.fps = s.frames / elapsed;
    const simulated = Math.max(0, this.sim.time - s.simStart);
    const busy = this.pacer.takeBusy();
    s.realTimeFactor = this.playing ? simulated / elapsed : 0;
    s.engineFactor = busy > 0 ? simulated / (busy / 1000) : 0;
    s.frames = 0;
    s.windowStart = now;
    s.simStart = this.sim.time;
    const speed = this.pacer.speed === 1 ? '' : `, speed ${speedText(this.pacer.speed)}`;
    this.statsText.textContent = `${s.fps.toFixed(0)} fps, real-time factor ${s.realTimeFactor.toFixed(2)}` +
      (s.engineFactor ? ` (engine ${s.engineFactor.toFixed(0)}x)` : '') + speed;
  }

  // Runs `action`; an error stops the lab with its message instead of escaping.
  guarded(action) {
    try {
      action();
    } catch (error) {
      this.fail(error);
    }
  }

  updatePlayButton() {
    this.playButton.textContent = this.playing ? 'pause' : 'play';
  }

  // Paused, one step forward.
  stepOnce() {
    this.pause();
    this.leaveScrubbed();
    this.step(1);
  }

  // Simulated seconds per wall second (1, 1/2 ... 1/64).
  setSpeed(speed) {
    this.pacer.speed = kSpeeds.includes(speed) ? speed : 1;
    this.pacer.clearDebt();
    this.speedSelect.value = String(this.pacer.speed);
  }

  changeSpeed(direction) {
    this.setSpeed(nextSpeed(this.pacer.speed, direction));
  }

  play() {
    this.leaveScrubbed();
    this.playing = true;
    this.pacer.clearDebt();
    this.updatePlayButton();
  }

  pause() {
    this.playing = false;
    this.updatePlayButton();
  }

  // The keyframe (or the default state), the sliders back at their initial values,
  // written into ctrl, and empty plots.
  reset() {
    this.errorText.textContent = '';
    if (this.key !== undefined && this.key !== null) this.sim.resetKeyframe(this.key);
    else this.sim.reset();
    for (const control of this.controls) {
      control.slider.value = control.spec.value ?? control.spec.min;
      this.applyControl(control);
    }
    this.sim.forward();
    for (const { plot } of this.plots) plot.clear();
    this.scrubbed = false;
    this.pacer.clearDebt();
    this.stats.simStart = this.sim.time;
    this.draw();
  }

  // For tests and lesson scripts: the slider of control k moved to `value` (as input
  // from the user would), n steps without pacing, the readouts' values.
  setControl(k, value) {
    const control = this.controls[k];
    control.slider.value = value;
    control.slider.dispatchEvent(new Event('input'));
  }

  step(n = 1) {
    this.sim.step(n);
    this.draw();
  }

  // The animation clock: the last frame's wall time (ms), the simulation time then, and the
  // frames drawn and steps taken by the animation loop so far.
  clock() {
    return { wall: this.pacer.lastFrame, time: this.sim.time, frames: this.stats.totalFrames,
             steps: this.pacer.totalSteps };
  }

  readoutValues() {
    return this.readouts.map((r) => ({ label: r.spec.label, value: r.current, text: r.value.textContent, error: r.error }));
  }

  dispose() {
    this.disposed = true;
    for (const observer of this.observers) observer.disconnect();
    for (const { plot } of this.plots) plot.dispose();
    if (this.onKey) document.removeEventListener('keydown', this.onKey);
    document.removeEventListener('visibilitychange', this.onVisibility);
    this.scene.dispose();
    this.sim.delete();
  }
}
