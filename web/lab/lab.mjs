// The live lab of a lesson's lab block: mountLab(element, spec, {baseUrl}) loads the
// engine (web/dist, WebAssembly) and models/<model>.xml with every file it refers to
// (attached models, includes, meshes, textures...), resets to the block's keyframe and
// shows the 3D view, sliders, readouts, plots and note, simulating in real time. See
// web/README.md, "The lab".
import { arrayReader, arraysOf, evaluateExpr, parseExpr, parseTarget } from './expr.mjs';
import { gatherModelFiles } from './model_files.mjs';
import { LivePlot } from './plot.mjs';
import { LabScene } from './scene.mjs';
import { parseLabSpec } from './spec.mjs';

// Pacing: each frame steps in chunks until simulation time has caught up with the wall
// clock or kBudgetShare of the mean frame interval (10 ms at 60 Hz; at most kMaxBudgetMs
// when drawing itself is slow) is spent; time still owed then is dropped, so a slow
// machine shows a real-time factor below 1 rather than freezing. Wall-clock gaps longer
// than kMaxGap (a hidden tab) are skipped. A chunk is about kChunkMs of stepping, from the
// measured cost of a step.
const kBudgetShare = 0.6;
const kMaxBudgetMs = 50;
const kChunkMs = 1;
const kMaxGap = 0.25;

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

// models/<name>.xml and every file it refers to (see model_files.mjs): XML as text, other
// files as bytes, keyed by their path relative to the model's folder.
async function fetchModel(baseUrl, name) {
  const folder = new URL('models/', baseUrl);
  const filename = `${name}.xml`;
  const xml = await (await fetchOk(new URL(filename, folder))).text();
  const readText = async (path) => (await fetchOk(new URL(path, folder))).text();
  const readBytes = async (path) => new Uint8Array(await (await fetchOk(new URL(path, folder))).arrayBuffer());
  const files = await gatherModelFiles(filename, xml, readText, readBytes);
  return { filename, xml, files };
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
const kSceneArrays = ['geom_xpos', 'geom_xmat', 'xanchor', 'xaxis', 'qfrc_actuator'];

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
    const [simlab, files] = await Promise.all([loadEngine(distUrl), fetchModel(baseUrl, labSpec.model)]);
    const sim = new simlab.Simulation(files.filename, files.xml, files.files);
    status.remove();
    const contactLayout = { stride: simlab.contactStride, pos: simlab.contactPos, frame: simlab.contactFrame,
                            force: simlab.contactForce };
    const lab = new Lab(root, labSpec, sim, contactLayout);
    element.simlabLab = lab;
    return lab;
  } catch (error) {
    status.className = 'simlab-lab-error';
    status.textContent = `lab "${labSpec.title ?? labSpec.model}": ${error.message ?? error}`;
    throw error;
  }
}

// One mounted lab: the simulation, its widgets and the animation loop.
class Lab {
  constructor(root, spec, sim, contactLayout) {
    this.root = root;
    this.spec = spec;
    this.sim = sim;
    this.timestep = sim.option().timestep;
    this.toggles = { contacts: false, forces: false, joints: false };
    this.playing = spec.autoplay !== false;
    this.modelArrays = new Map();
    this.dataViews = new DataViews(sim);
    this.read = arrayReader((source, name) => this.array(source, name));
    // Frame rate and real-time factor over the last half second; engineFactor is simulated
    // time per second spent stepping (how much faster than real time it could run).
    // dropped: wall-clock seconds the simulation gave up catching (budget spent, or gaps
    // over kMaxGap), in total since the lab was mounted.
    // totalSteps, totalFrames: counted since mounting (steps per frame = their ratio).
    this.stats = { fps: 0, realTimeFactor: 0, engineFactor: 0, frames: 0, busy: 0,
                   windowStart: performance.now(), simStart: 0, dropped: 0, totalSteps: 0, totalFrames: 0 };
    // Pacing (see kBudgetShare): the mean frame interval and cost of a step, in ms.
    this.frameInterval = 1000 / 60;
    this.msPerStep = 0.05;
    // Reused every frame: the scene's state, the plots' sample rows.
    this.state = { model: null, contacts: null, contactLayout, geom_xpos: null, geom_xmat: null,
                   xanchor: null, xaxis: null, qfrc_actuator: null };

    this.view = root.appendChild(make('div', 'simlab-lab-view'));
    this.scene = new LabScene(this.view, Number(spec.height) > 0 ? Number(spec.height) : 300, spec.camera);
    this.buildToolbar();
    this.controls = (spec.controls ?? []).map((c) => this.buildControl(c));
    this.readouts = this.buildReadouts(spec.readouts ?? []);
    this.plots = (spec.plots ?? []).map((p) => this.buildPlot(p));
    if (spec.note) root.appendChild(make('p', 'simlab-lab-note', spec.note));
    this.sceneModel = this.modelObject();
    this.resolveArrays();
    this.scene.build(this.sceneModel, sim.statistic().extent || 1);
    new ResizeObserver(() => this.resize()).observe(root);
    // Off screen (scrolled away), the lab keeps simulating but does not pose or render its
    // view; back on screen, drawScene catches up.
    this.onScreen = true;
    new IntersectionObserver(([entry]) => { this.onScreen = entry.isIntersecting; }).observe(this.view);

    this.reset();
    this.frame = this.frame.bind(this);
    this.lastFrame = null;
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
      'hfield_nrow', 'hfield_ncol', 'hfield_adr', 'hfield_data', 'jnt_type', 'jnt_dofadr'];
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
    this.errorText = bar.appendChild(make('span', 'simlab-lab-error'));
    this.warningText = bar.appendChild(make('span', 'simlab-lab-warning'));
    this.statsText = bar.appendChild(make('span', 'simlab-lab-stats'));
    this.updatePlayButton();
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

  buildReadouts(specs) {
    const box = this.root.appendChild(make('div', 'simlab-lab-readouts'));
    return specs.map((spec) => {
      const row = box.appendChild(make('div', 'simlab-lab-readout'));
      row.appendChild(make('span', 'label', spec.label ?? spec.expr));
      const value = row.appendChild(make('span', 'value'));
      const readout = { spec, row, value, tree: null, error: '', current: NaN };
      try {
        readout.tree = parseExpr(spec.expr);
      } catch (error) {
        readout.error = error.message;
      }
      return readout;
    });
  }

  buildPlot(spec) {
    const box = this.root.appendChild(make('div', 'simlab-lab-plot'));
    const traces = (spec.traces ?? []).map((trace) => {
      try {
        return parseExpr(trace.expr);
      } catch {
        return null;
      }
    });
    return { traces, values: traces.map(() => NaN),
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
    for (const { traces, values, plot } of this.plots) {
      for (let i = 0; i < traces.length; i++) values[i] = traces[i] ? this.evaluate(traces[i]) : NaN;
      plot.push(time, values);
      plot.draw();
    }
    this.sceneStale = true;
    if (this.onScreen) this.drawScene();
  }

  // The 3D view: posed anew from the state when a draw left it stale, then rendered.
  drawScene() {
    if (this.sceneStale) this.scene.update(this.sceneState(), this.toggles);
    this.sceneStale = false;
    this.scene.render();
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
    return state;
  }

  // Steps until simulation time has caught up with the wall clock or the frame's budget
  // is spent; drops what is still owed then. Chunks of about kChunkMs keep the checks of
  // the clock cheap.
  advance(gap) {
    this.debt += gap;
    const start = performance.now();
    const budget = Math.min(kMaxBudgetMs, kBudgetShare * this.frameInterval);
    let owed = Math.floor(this.debt / this.timestep + 1e-9);
    let spent = 0;
    while (owed > 0 && spent < budget) {
      const chunk = Math.min(owed, Math.max(1, Math.floor(kChunkMs / this.msPerStep)));
      this.sim.step(chunk);
      this.stats.totalSteps += chunk;
      const now = performance.now();
      this.msPerStep = 0.8 * this.msPerStep + 0.2 * Math.max(1e-4, (now - start - spent) / chunk);
      spent = now - start;
      this.debt -= chunk * this.timestep;
      owed -= chunk;
    }
    if (owed > 0) {
      this.stats.dropped += this.debt;
      this.debt = 0;
    }
    this.stats.busy += spent;
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
    const wall = this.lastFrame === null ? 0 : (now - this.lastFrame) / 1000;
    const gap = Math.min(kMaxGap, wall);
    if (this.playing) this.stats.dropped += wall - gap;
    if (gap > 0) this.frameInterval = 0.9 * this.frameInterval + 0.1 * 1000 * gap;
    this.lastFrame = now;
    const timeBefore = this.sim.time;
    if (this.playing) this.advance(gap);
    // Paused, a slider still acts at once: forward recomputes forces from the new ctrl
    // (as MuJoCo's simulate does while paused).
    else if (this.changed) this.sim.forward();
    // Readouts and plots only when time moved or something asked for it; the 3D view
    // whenever it is on screen (the camera may have moved).
    if (this.changed || this.sim.time !== timeBefore) this.draw();
    else if (this.onScreen) this.drawScene();
    this.showWarnings();
    this.countFrame(now);
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
    s.realTimeFactor = this.playing ? simulated / elapsed : 0;
    s.engineFactor = s.busy > 0 ? simulated / (s.busy / 1000) : 0;
    s.frames = 0;
    s.busy = 0;
    s.windowStart = now;
    s.simStart = this.sim.time;
    this.statsText.textContent = `${s.fps.toFixed(0)} fps, real-time factor ${s.realTimeFactor.toFixed(2)}` +
      (s.engineFactor ? ` (engine ${s.engineFactor.toFixed(0)}x)` : '');
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

  play() {
    this.playing = true;
    this.debt = 0;
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
    if (this.spec.key !== undefined && this.spec.key !== null) this.sim.resetKeyframe(this.spec.key);
    else this.sim.reset();
    for (const control of this.controls) {
      control.slider.value = control.spec.value ?? control.spec.min;
      this.applyControl(control);
    }
    this.sim.forward();
    for (const { plot } of this.plots) plot.clear();
    this.debt = 0;
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
    return { wall: this.lastFrame, time: this.sim.time, frames: this.stats.totalFrames, steps: this.stats.totalSteps };
  }

  readoutValues() {
    return this.readouts.map((r) => ({ label: r.spec.label, value: r.current, text: r.value.textContent, error: r.error }));
  }

  dispose() {
    this.disposed = true;
    this.scene.dispose();
    this.sim.delete();
  }
}
