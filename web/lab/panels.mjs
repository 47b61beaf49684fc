// The viewer's panels, generated from a model (apart from the DOM, so node can test
// them): a slider per control entry, readouts of the joints, actuator forces and sensors,
// the keyframes to reset to, as the lab spec a lesson block would write by hand.

// mjtJoint numbers of the joints whose position is one number.
const kSlide = 2, kHinge = 3;
// Readouts shown at most per group (a large model's panels stay usable).
const kMaxReadouts = 60;

// What the panels need of a model, read once from a Simulation (web/simlab_wasm.cc):
// sizes, element names and the arrays that place and bound each entry.
export function modelInfo(sim) {
  const sizes = sim.sizes();
  const names = (kind, count) => Array.from({ length: count }, (_, i) => sim.idToName(kind, i));
  const info = {
    sizes,
    statistic: sim.statistic(),
    visual: sim.visual(),
    names: { actuator: names('actuator', sizes.nactuator), jnt: names('jnt', sizes.njnt),
             sensor: names('sensor', sizes.nsensor), key: names('key', sizes.nkey) },
  };
  for (const name of ['actuator_ctrladr', 'actuator_ctrlnum', 'actuator_outadr', 'actuator_outnum',
    'actuator_ctrlrange', 'actuator_ctrllimited', 'jnt_type', 'jnt_qposadr', 'sensor_adr', 'sensor_dim']) {
    info[name] = sim.model(name);
  }
  return info;
}

// "name", or "kind i" for an unnamed element; with "[j]" for entry j of several.
function entryLabel(name, kind, id, j, count) {
  const base = name || `${kind} ${id}`;
  return count > 1 ? `${base}[${j}]` : base;
}

// One slider per control entry: MuJoCo's ctrlrange when limited, else -1..1 (as
// simulate); starting at 0, or the range's nearest end.
function controlSliders(info) {
  const sliders = [];
  for (let a = 0; a < info.sizes.nactuator; a++) {
    const adr = info.actuator_ctrladr[a], num = info.actuator_ctrlnum[a];
    for (let j = 0; j < num; j++) {
      const k = adr + j;
      const limited = info.actuator_ctrllimited[k] === 1;
      const [min, max] = limited ? [info.actuator_ctrlrange[2 * k], info.actuator_ctrlrange[2 * k + 1]] : [-1, 1];
      sliders.push({ label: entryLabel(info.names.actuator[a], 'actuator', a, j, num), set: `data.ctrl[${k}]`,
                     min, max, value: Math.min(max, Math.max(min, 0)) });
    }
  }
  return sliders;
}

// Readouts of one group, at most kMaxReadouts.
function group(name, entries) {
  return entries.slice(0, kMaxReadouts).map((entry) => ({ group: name, ...entry }));
}

function jointReadouts(info) {
  const entries = [];
  for (let j = 0; j < info.sizes.njnt; j++) {
    if (info.jnt_type[j] !== kSlide && info.jnt_type[j] !== kHinge) continue;
    entries.push({ label: entryLabel(info.names.jnt[j], 'joint', j, 0, 1), expr: `data.qpos[${info.jnt_qposadr[j]}]` });
  }
  return group('joint positions', entries);
}

// One readout per entry of a Data array that each element owns a slice of (adr[i],
// num[i] entries), labelled by the element's name.
function sliceReadouts(count, names, kind, adr, num, field) {
  const entries = [];
  for (let i = 0; i < count; i++) {
    for (let j = 0; j < num[i]; j++) {
      entries.push({ label: entryLabel(names[i], kind, i, j, num[i]), expr: `data.${field}[${adr[i] + j}]` });
    }
  }
  return entries;
}

function forceReadouts(info) {
  return group('actuator forces', sliceReadouts(info.sizes.nactuator, info.names.actuator, 'actuator',
                                                info.actuator_outadr, info.actuator_outnum, 'actuator_force'));
}

function sensorReadouts(info) {
  return group('sensors', sliceReadouts(info.sizes.nsensor, info.names.sensor, 'sensor',
                                        info.sensor_adr, info.sensor_dim, 'sensordata'));
}

// MuJoCo's default free camera (mjv_defaultFreeCamera): looking at the model's centre
// from 1.5 extents away, at <visual><global azimuth elevation> (90 and -45 by default; a
// lab spec's elevation is the angle above the horizon, the opposite sign).
function freeCamera(statistic, visual) {
  const extent = statistic?.extent > 0 ? statistic.extent : 1;
  return { target: Array.from(statistic?.center ?? [0, 0, 0]), distance: 1.5 * extent,
           azimuth: visual?.azimuth ?? 90, elevation: -(visual?.elevation ?? -45) };
}

// The lab spec of a model's viewer (see web/README.md, "The lab", for the fields).
export function specFromModel(info, title = '') {
  return {
    title,
    height: 420,
    camera: freeCamera(info.statistic, info.visual),
    autoplay: true,
    toggles: ['contacts', 'forces', 'joints'],
    controls: controlSliders(info),
    readouts: [...jointReadouts(info), ...forceReadouts(info), ...sensorReadouts(info)],
    keys: info.names.key,
    pickPlots: true,
  };
}
