// Goldens for the MuJoCo-API scripts beside this file: each function below performs the
// same computation as the Python script of the same name, with MuJoCo 3.5.1 itself (the
// official WebAssembly build, npm package `mujoco` in ../shared/oracle), and writes
// goldens/NAME.json with exactly the keys the script prints. Run by hand from /work/main:
//
//   node python/tests/mujoco_api/make_goldens.mjs            # every golden
//   node python/tests/mujoco_api/make_goldens.mjs contacts   # only goldens/contacts.json
//
// The inline XML of a script is read from the script itself (its XML = """...""" or
// SENSOR_XML = """...""" literal), so the two cannot drift apart. MuJoCo's Python views
// (data.joint("x").qpos, model.body("x").mass...) are computed here from the flat arrays
// and the ids, so the goldens do not depend on a named-access implementation.
// Nested lists mirror numpy's shapes ((nbody, 3) is a list of nbody lists of 3), and a
// name MuJoCo's mj_id2name has no string for is null, as Python's None.
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const HERE = path.dirname(fileURLToPath(import.meta.url));
const MODELS = path.resolve(HERE, '../../../models');
const HUMANOID = path.resolve(HERE, '../../../../shared/corpus/mujoco/model/humanoid/humanoid.xml');
const ORACLE = path.resolve(HERE, '../../../../shared/oracle/node_modules/mujoco/mujoco.js');

const loadMujoco = (await import(pathToFileURL(ORACLE).href)).default;
const mj = await loadMujoco();

// ---------------------------------------------------------------------------------------
// Loading

let vfsCount = 0;

// Copy a host folder into MuJoCo's virtual file system, so <include>, <attach> and
// <model file=...> resolve as on disk (as ../shared/oracle/rollout.mjs does).
function copyTree(hostDir, vfsDir) {
  for (const entry of fs.readdirSync(hostDir, { withFileTypes: true })) {
    const host = path.join(hostDir, entry.name);
    const vfs = `${vfsDir}/${entry.name}`;
    if (entry.isDirectory()) {
      try { mj.FS.mkdir(vfs); } catch { /* exists */ }
      copyTree(host, vfs);
    } else if (entry.isFile()) {
      mj.FS.writeFile(vfs, fs.readFileSync(host));
    }
  }
}

// MjModel.from_xml_path: the model's folder goes to a fresh VFS folder first.
function fromXmlPath(file) {
  const dir = `/load${vfsCount++}`;
  mj.FS.mkdir(dir);
  copyTree(path.dirname(file), dir);
  return mj.MjModel.mj_loadXML(`${dir}/${path.basename(file)}`);
}

// MjModel.from_xml_string.
function fromXmlString(xml) {
  const file = `/string${vfsCount++}.xml`;
  mj.FS.writeFile(file, xml);
  return mj.MjModel.mj_loadXML(file);
}

// The triple-quoted XML literal assigned to `name` in a script of this folder.
function inlineXml(script, name = 'XML') {
  const text = fs.readFileSync(path.join(HERE, `${script}.py`), 'utf8');
  const match = text.match(new RegExp(`^${name} = """([\\s\\S]*?)"""`, 'm'));
  if (!match) throw new Error(`${script}.py has no ${name} = """...""" literal`);
  if (match[1].includes('\\')) throw new Error(`${script}.py: ${name} has a backslash`);
  return match[1];
}

// ---------------------------------------------------------------------------------------
// Arrays, names, enums

const list = (a) => Array.from(a);
const slice = (a, start, n) => Array.from(a.subarray(start, start + n));

// A flat row-major array as numpy's 2-D tolist(): `ncol` entries per row.
function rows(a, ncol) {
  const out = [];
  for (let i = 0; i < a.length; i += ncol) out.push(Array.from(a.subarray(i, i + ncol)));
  return out;
}

const OBJ = (kind) => mj.mjtObj[kind].value;
const id = (m, kind, name) => mj.mj_name2id(m, OBJ(kind), name);

// mj_id2name, where Python gives None for MuJoCo's NULL (an unnamed object or an id out
// of range). The JavaScript wrapper turns NULL into a string read from address 0, so the
// name is read from m.names here, and checked against the wrapper when there is one.
const NAME_ADR = {
  mjOBJ_BODY: 'name_bodyadr', mjOBJ_JOINT: 'name_jntadr', mjOBJ_GEOM: 'name_geomadr',
  mjOBJ_SITE: 'name_siteadr', mjOBJ_ACTUATOR: 'name_actuatoradr',
  mjOBJ_TENDON: 'name_tendonadr', mjOBJ_EQUALITY: 'name_eqadr', mjOBJ_KEY: 'name_keyadr',
  mjOBJ_SENSOR: 'name_sensoradr',
};
function nameOf(m, kind, i) {
  const adr = m[NAME_ADR[kind]];
  if (!(i >= 0 && i < adr.length)) return null;
  const names = m.names;
  let end = adr[i];
  while (names[end] !== 0) end++;
  if (end === adr[i]) return null;
  const name = Buffer.from(Uint8Array.from(names.subarray(adr[i], end), (x) => x & 255)).toString('utf8');
  if (mj.mj_id2name(m, OBJ(kind), i) !== name) throw new Error(`mj_id2name disagrees on ${name}`);
  return name;
}
// The `.name` of a named view: '' for an unnamed object.
const viewName = (m, kind, i) => nameOf(m, kind, i) ?? '';

// mjtXxx(value).name
function enumName(enumType, value) {
  for (const [key, member] of Object.entries(mj[enumType])) {
    if (member && typeof member === 'object' && member.value === value) return key;
  }
  throw new Error(`${enumType} has no member ${value}`);
}
const enumValue = (enumType, key) => mj[enumType][key].value;

// Whether a typed array MuJoCo's bindings expose holds real numbers or integers.
const KINDS = {
  Float64Array: 'real', Float32Array: 'real', Int32Array: 'integer', Uint8Array: 'integer',
};
const kindOf = (a) => KINDS[a.constructor.name];

// Lengths of a joint's qpos and qvel by mjtJoint (free, ball, slide, hinge).
const NQ = [7, 4, 1, 1];
const NV = [6, 3, 1, 1];

// The named Data views of MuJoCo's Python bindings, from flat arrays.
const jointQpos = (m, d, name) => {
  const j = id(m, 'mjOBJ_JOINT', name);
  return slice(d.qpos, m.jnt_qposadr[j], NQ[m.jnt_type[j]]);
};
const jointQvel = (m, d, name) => {
  const j = id(m, 'mjOBJ_JOINT', name);
  return slice(d.qvel, m.jnt_dofadr[j], NV[m.jnt_type[j]]);
};
const jointDof = (m, d, field, name) => {
  const j = id(m, 'mjOBJ_JOINT', name);
  return slice(d[field], m.jnt_dofadr[j], NV[m.jnt_type[j]]);
};
const setJointQpos = (m, d, name, values) => {
  const j = id(m, 'mjOBJ_JOINT', name);
  d.qpos.set(values, m.jnt_qposadr[j]);
};
const bodyField = (m, d, field, name, n) => slice(d[field], n * id(m, 'mjOBJ_BODY', name), n);
const siteField = (m, d, field, name, n) => slice(d[field], n * id(m, 'mjOBJ_SITE', name), n);
const geomField = (m, d, field, geom, n) => {
  const g = typeof geom === 'number' ? geom : id(m, 'mjOBJ_GEOM', geom);
  return slice(d[field], n * g, n);
};
const sensorData = (m, d, name) => {
  const s = id(m, 'mjOBJ_SENSOR', name);
  return slice(d.sensordata, m.sensor_adr[s], m.sensor_dim[s]);
};
const actuatorField = (m, d, field, name) => [d[field][id(m, 'mjOBJ_ACTUATOR', name)]];
const tendonField = (m, d, field, name) => [d[field][id(m, 'mjOBJ_TENDON', name)]];
const modelRow = (m, field, kind, name, n) => slice(m[field], n * id(m, kind, name), n);

const arraysEqual = (a, b) => a.length === b.length && a.every((x, i) => x === b[i]);
const maxAbsDiff = (a, b) => a.reduce((w, x, i) => Math.max(w, Math.abs(x - b[i])), 0);

// mj_contactForce for every active contact.
function contactForces(m, d) {
  const buf = new mj.DoubleBuffer(6);
  const out = [];
  for (let i = 0; i < d.ncon; i++) {
    mj.mj_contactForce(m, d, i, buf);
    out.push(list(buf.GetView()));
  }
  buf.delete();
  return out;
}

// The first ncon contacts as plain objects (data.contact is a copy in these bindings).
function contactList(d) {
  const vec = d.contact;
  const out = [];
  for (let i = 0; i < d.ncon; i++) {
    const c = vec.get(i);
    out.push({
      dist: c.dist, pos: list(c.pos), frame: list(c.frame), geom1: c.geom1, geom2: c.geom2,
      geom: list(c.geom), dim: c.dim, friction: list(c.friction), efc_address: c.efc_address,
    });
    c.delete();
  }
  vec.delete();
  return out;
}

// ---------------------------------------------------------------------------------------
// One function per script

function load_sizes() {
  const SIZES = ['nq', 'nv', 'nu', 'na', 'nbody', 'njnt', 'ngeom', 'nsite', 'nsensor',
    'nsensordata', 'ntendon', 'neq', 'nkey', 'nM'];
  const sizes = (m) => {
    const out = {};
    for (const name of SIZES) out[name] = m[name];
    out.timestep = m.opt.timestep;
    out.gravity = list(m.opt.gravity);
    return out;
  };
  const out = {};
  out.from_string = sizes(fromXmlString(inlineXml('load_sizes')));
  for (const name of ['actuator_bench', 'gantry_gripper', 'double_pendulum']) {
    out[name] = sizes(fromXmlPath(path.join(MODELS, `${name}.xml`)));
  }
  const m = fromXmlPath(HUMANOID);
  out.humanoid = sizes(m);

  const d = new mj.MjData(m);
  out.humanoid_data = {
    time: d.time,
    qpos_is_qpos0: arraysEqual(list(d.qpos), list(m.qpos0)),
    qpos0: list(m.qpos0),
    key_qpos_1: rows(m.key_qpos, m.nq)[1],
    body_mass: list(m.body_mass),
  };

  // [array, columns] for each array the script reads the shape and kind of.
  const arrays = {
    qpos: [d.qpos, 0], ctrl: [d.ctrl, 0], xpos: [d.xpos, 3], xquat: [d.xquat, 4],
    xmat: [d.xmat, 9], qM: [d.qM, 0], sensordata: [d.sensordata, 0],
    actuator_gainprm: [m.actuator_gainprm, 10], body_mass: [m.body_mass, 0],
    geom_size: [m.geom_size, 3], geom_rgba: [m.geom_rgba, 4], geom_type: [m.geom_type, 0],
    jnt_limited: [m.jnt_limited, 0], key_qpos: [m.key_qpos, m.nq],
  };
  out.shapes = {};
  out.kinds = {};
  for (const [name, [a, ncol]] of Object.entries(arrays)) {
    out.shapes[name] = ncol ? [a.length / ncol, ncol] : [a.length];
    out.kinds[name] = kindOf(a);
  }
  return out;
}

function names_enums() {
  const gantry = fromXmlPath(path.join(MODELS, 'gantry_gripper.xml'));
  const bench = fromXmlPath(path.join(MODELS, 'actuator_bench.xml'));
  const out = {};

  const kinds = {
    body: ['mjOBJ_BODY', gantry.nbody], joint: ['mjOBJ_JOINT', gantry.njnt],
    geom: ['mjOBJ_GEOM', gantry.ngeom], actuator: ['mjOBJ_ACTUATOR', gantry.nu],
    tendon: ['mjOBJ_TENDON', gantry.ntendon], equality: ['mjOBJ_EQUALITY', gantry.neq],
    key: ['mjOBJ_KEY', gantry.nkey],
  };
  out.id2name = {};
  for (const [kind, [obj, n]] of Object.entries(kinds)) {
    out.id2name[kind] = [...Array(n).keys()].map((i) => nameOf(gantry, obj, i));
  }

  const lookups = [
    ['mjOBJ_BODY', 'cube'], ['mjOBJ_BODY', 'gripper/palm'], ['mjOBJ_BODY', 'world'],
    ['mjOBJ_JOINT', 'z'], ['mjOBJ_JOINT', 'gripper/finger_right'], ['mjOBJ_GEOM', 'cube'],
    ['mjOBJ_ACTUATOR', 'gripper/grip'], ['mjOBJ_TENDON', 'gripper/grip'],
    ['mjOBJ_EQUALITY', 'gripper/mirror'], ['mjOBJ_KEY', 'home'],
    ['mjOBJ_JOINT', 'no_such_joint'], ['mjOBJ_ACTUATOR', 'finger_left'],
  ];
  out.name2id = lookups.map(([obj, name]) => id(gantry, obj, name));

  out.actuator_names = [...Array(gantry.nu).keys()].map((i) => viewName(gantry, 'mjOBJ_ACTUATOR', i));
  const grip = id(gantry, 'mjOBJ_ACTUATOR', 'gripper/grip');
  out.grip = {
    id: grip, name: viewName(gantry, 'mjOBJ_ACTUATOR', grip),
    gainprm: slice(gantry.actuator_gainprm, 10 * grip, 10),
    biasprm: slice(gantry.actuator_biasprm, 10 * grip, 10),
    forcerange: slice(gantry.actuator_forcerange, 2 * grip, 2),
    trnid: slice(gantry.actuator_trnid, 2 * grip, 2),
    gear0: gantry.actuator_gear[6 * grip],
  };
  out.qposadr = {};
  for (const name of ['x', 'y', 'z', 'gripper/finger_left', 'gripper/finger_right', 'cube']) {
    out.qposadr[name] = modelRow(gantry, 'jnt_qposadr', 'mjOBJ_JOINT', name, 1);
  }
  out.cube_dofadr = gantry.jnt_dofadr[id(gantry, 'mjOBJ_JOINT', 'cube')];
  out.body_mass = {};
  for (const name of ['carriage', 'gripper/palm', 'gripper/left', 'cube']) {
    out.body_mass[name] = modelRow(gantry, 'body_mass', 'mjOBJ_BODY', name, 1);
  }
  out.body_by_index = [...Array(gantry.nbody).keys()].map((i) => viewName(gantry, 'mjOBJ_BODY', i));
  const home = id(gantry, 'mjOBJ_KEY', 'home');
  out.key_home = { id: home, qpos: slice(gantry.key_qpos, gantry.nq * home, gantry.nq) };

  out.geom_types = list(gantry.geom_type).map((t) => enumName('mjtGeom', t));
  out.joint_types = list(gantry.jnt_type).map((t) => enumName('mjtJoint', t));
  out.actuators = {};
  for (const [label, m] of [['bench', bench], ['gantry', gantry]]) {
    out.actuators[label] = {
      trn: list(m.actuator_trntype).map((t) => enumName('mjtTrn', t)),
      dyn: list(m.actuator_dyntype).map((t) => enumName('mjtDyn', t)),
      gain: list(m.actuator_gaintype).map((t) => enumName('mjtGain', t)),
      bias: list(m.actuator_biastype).map((t) => enumName('mjtBias', t)),
    };
  }
  const sensors = fromXmlString(inlineXml('names_enums', 'SENSOR_XML'));
  out.sensor_types = list(sensors.sensor_type).map((t) => enumName('mjtSensor', t));
  out.sensor_dim = list(sensors.sensor_dim);
  out.sensor_adr = list(sensors.sensor_adr);

  const BOX = enumValue('mjtGeom', 'mjGEOM_BOX');
  const SLIDE = enumValue('mjtJoint', 'mjJNT_SLIDE');
  out.box_geoms = [...Array(gantry.ngeom).keys()].filter((i) => gantry.geom_type[i] === BOX);
  out.slide_joints = [...Array(gantry.njnt).keys()].filter((i) => gantry.jnt_type[i] === SLIDE);
  out.enum_values = {};
  for (const [type, key] of [
    ['mjtObj', 'mjOBJ_BODY'], ['mjtObj', 'mjOBJ_ACTUATOR'], ['mjtGeom', 'mjGEOM_PLANE'],
    ['mjtGeom', 'mjGEOM_BOX'], ['mjtJoint', 'mjJNT_FREE'], ['mjtJoint', 'mjJNT_HINGE'],
    ['mjtTrn', 'mjTRN_TENDON'], ['mjtDyn', 'mjDYN_FILTER'], ['mjtGain', 'mjGAIN_FIXED'],
    ['mjtBias', 'mjBIAS_AFFINE'], ['mjtSensor', 'mjSENS_TOUCH'],
    ['mjtState', 'mjSTATE_FULLPHYSICS'], ['mjtWarning', 'mjWARN_BADQPOS'],
    ['mjtWarning', 'mjNWARNING'],
  ]) {
    out.enum_values[key] = enumValue(type, key);
  }
  return out;
}

function actuators() {
  const NAMES = ['motor', 'position', 'velocity', 'filter'];
  const JOINTS = ['motor_hinge', 'position_hinge', 'velocity_hinge', 'filter_hinge'];
  const m = fromXmlPath(path.join(MODELS, 'actuator_bench.xml'));
  const d = new mj.MjData(m);
  const act = (name) => id(m, 'mjOBJ_ACTUATOR', name);
  const snapshot = () => {
    const out = {
      time: d.time, qpos: list(d.qpos), qvel: list(d.qvel), act: list(d.act),
      ctrl: list(d.ctrl), actuator_force: list(d.actuator_force),
      actuator_length: list(d.actuator_length), actuator_velocity: list(d.actuator_velocity),
      qfrc_actuator: list(d.qfrc_actuator), force_by_name: {}, ctrl_by_name: {}, joints: {},
    };
    for (const n of NAMES) {
      out.force_by_name[n] = actuatorField(m, d, 'actuator_force', n);
      out.ctrl_by_name[n] = actuatorField(m, d, 'ctrl', n);
    }
    for (const j of JOINTS) out.joints[j] = [jointQpos(m, d, j), jointQvel(m, d, j)];
    return out;
  };
  const out = {};

  out.params = {};
  for (const name of NAMES) {
    const a = act(name);
    out.params[name] = {
      id: a, gainprm: slice(m.actuator_gainprm, 10 * a, 10),
      biasprm: slice(m.actuator_biasprm, 10 * a, 10),
      dynprm: slice(m.actuator_dynprm, 10 * a, 3), gear: slice(m.actuator_gear, 6 * a, 6),
      ctrlrange: slice(m.actuator_ctrlrange, 2 * a, 2),
      forcerange: slice(m.actuator_forcerange, 2 * a, 2),
    };
  }
  out.names_by_index = [...Array(m.nu).keys()].map((i) => viewName(m, 'mjOBJ_ACTUATOR', i));
  out.actuator_gainprm = rows(m.actuator_gainprm, 10).map((r) => r.slice(0, 3));

  d.ctrl[act('motor')] = 0.5;
  d.ctrl[act('position')] = 1.2;
  d.ctrl.set([2.0, 1.0], 2);
  for (let i = 0; i < 250; i++) mj.mj_step(m, d);
  out.after_250 = snapshot();

  d.ctrl[act('motor')] = 3.0;
  mj.mj_forward(m, d);
  out.clamped = {
    ctrl: actuatorField(m, d, 'ctrl', 'motor'),
    force: actuatorField(m, d, 'actuator_force', 'motor'),
    qfrc: jointDof(m, d, 'qfrc_actuator', 'motor_hinge'),
  };

  m.actuator_gainprm[0] = 5;
  mj.mj_forward(m, d);
  out.gain5 = {
    gainprm: slice(m.actuator_gainprm, 10 * act('motor'), 10),
    force: list(d.actuator_force), qacc: list(d.qacc),
  };

  for (let i = 0; i < 100; i++) {
    mj.mj_step1(m, d);
    d.ctrl[0] = -0.25 * d.qvel[0];
    d.ctrl[3] = 0.5;
    mj.mj_step2(m, d);
  }
  out.after_step12 = snapshot();

  mj.mj_resetData(m, d);
  out.reset = snapshot();
  d.ctrl.set([1.0, -1.0, 1.0, -1.0]);
  mj.mj_step(m, d);
  out.one_step = snapshot();
  return out;
}

function pendulum_views() {
  const m = fromXmlPath(path.join(MODELS, 'double_pendulum.xml'));
  const poses = (d) => ({
    time: d.time, qpos: list(d.qpos), qvel: list(d.qvel), qacc: list(d.qacc),
    upper_xpos: bodyField(m, d, 'xpos', 'upper', 3),
    lower_xpos: bodyField(m, d, 'xpos', 'lower', 3),
    lower_xquat: bodyField(m, d, 'xquat', 'lower', 4),
    lower_xmat: bodyField(m, d, 'xmat', 'lower', 9),
    lower_com: bodyField(m, d, 'xipos', 'lower', 3),
    tip: siteField(m, d, 'site_xpos', 'tip', 3),
    tip_xmat: siteField(m, d, 'site_xmat', 'tip', 9),
    geom_xpos: [0, 1].map((g) => geomField(m, d, 'geom_xpos', g, 3)),
    xpos: rows(d.xpos, 3), xquat: rows(d.xquat, 4),
  });
  const d = new mj.MjData(m);
  const out = {};
  out.masses = {};
  for (const name of ['upper', 'lower']) out.masses[name] = modelRow(m, 'body_mass', 'mjOBJ_BODY', name, 1);
  out.shoulder_qposadr = m.jnt_qposadr[id(m, 'mjOBJ_JOINT', 'shoulder')];
  out.elbow_dofadr = m.jnt_dofadr[id(m, 'mjOBJ_JOINT', 'elbow')];

  d.qpos[m.jnt_qposadr[id(m, 'mjOBJ_JOINT', 'shoulder')]] = 0.3;
  d.qvel[m.jnt_dofadr[id(m, 'mjOBJ_JOINT', 'elbow')]] = -1.0;
  mj.mj_forward(m, d);
  out.posed = poses(d);

  for (let i = 0; i < 300; i++) mj.mj_step(m, d);
  out.stepped = poses(d);

  const other = new mj.MjData(m);
  other.qpos.set([0.3, 0.0]);
  other.qvel.set([0.0, -1.0]);
  for (let i = 0; i < 300; i++) {
    mj.mj_step1(m, other);
    mj.mj_step2(m, other);
  }
  out.step12 = poses(other);
  out.step12_equal = arraysEqual(list(other.qpos), list(d.qpos));

  m.opt.timestep = 0.001;
  m.opt.gravity.set([2.0, 0.0, -9.81]);
  mj.mj_resetData(m, d);
  for (let i = 0; i < 500; i++) mj.mj_step(m, d);
  out.new_options = { timestep: m.opt.timestep, gravity: list(m.opt.gravity) };
  out.tilted = poses(d);

  m.opt.gravity.set([0.0, 0.0, -1.62]);
  d.qpos.set([1.0, -0.5]);
  d.qvel.fill(0);
  for (let i = 0; i < 200; i++) mj.mj_step(m, d);
  out.moon = poses(d);
  return out;
}

function contacts() {
  const SENSORS = ['touch', 'corner_pos', 'box_quat', 'acc', 'vel'];
  const m = fromXmlString(inlineXml('contacts'));
  const d = new mj.MjData(m);
  const contactsOf = () => {
    const cs = contactList(d);
    return {
      ncon: d.ncon, len: cs.length,
      dist: cs.map((c) => c.dist), pos: cs.map((c) => c.pos), frame: cs.map((c) => c.frame),
      geom1: cs.map((c) => c.geom1), geom2: cs.map((c) => c.geom2), geom: cs.map((c) => c.geom),
      dim: cs.map((c) => c.dim), friction: cs.map((c) => c.friction),
      efc_address: cs.map((c) => c.efc_address),
      shape_pos: [cs.length, 3], shape_frame: [cs.length, 9],
      each: cs.map((c) => [c.dist, c.pos, c.geom1, c.geom2]),
      names: cs.map((c) => c.geom.map((g) => nameOf(m, 'mjOBJ_GEOM', g))),
      force: contactForces(m, d),
    };
  };
  const state = () => {
    const sensors = {};
    for (const name of SENSORS) sensors[name] = sensorData(m, d, name);
    return {
      time: d.time, qpos: list(d.qpos), qvel: list(d.qvel),
      box_qpos: jointQpos(m, d, 'box'), ball_qvel: jointQvel(m, d, 'ball'),
      box_xpos: bodyField(m, d, 'xpos', 'box', 3), box_xquat: bodyField(m, d, 'xquat', 'box', 4),
      capsule_geom_xpos: geomField(m, d, 'geom_xpos', 'capsule', 3),
      corner_site: siteField(m, d, 'site_xpos', 'corner', 3),
      sensors, sensordata: list(d.sensordata), qfrc_constraint: list(d.qfrc_constraint),
      nefc: d.nefc,
    };
  };
  const out = {};
  mj.mj_forward(m, d);
  out.start = { ncon: d.ncon, len: d.ncon, dist: contactList(d).map((c) => c.dist) };
  for (let i = 0; i < 100; i++) mj.mj_step(m, d);
  out.landing = { contacts: contactsOf(), state: state() };
  for (let i = 0; i < 300; i++) mj.mj_step(m, d);
  out.settled = { contacts: contactsOf(), state: state() };
  return out;
}

function jacobians() {
  const m = fromXmlString(inlineXml('jacobians'));
  const d = new mj.MjData(m);
  const nv = m.nv;
  const out = { nv, nM: m.nM };

  setJointQpos(m, d, 'yaw', [0.4]);
  setJointQpos(m, d, 'lift', [0.05]);
  setJointQpos(m, d, 'pitch', [-0.6]);
  setJointQpos(m, d, 'wrist', [0.5, 0.5, -0.5, 0.5]);
  d.qvel.set([0.3, -0.1, 0.2, 1.0, -0.5, 0.25]);
  mj.mj_forward(m, d);

  const wrist = id(m, 'mjOBJ_BODY', 'wrist');
  const tool = id(m, 'mjOBJ_SITE', 'tool');
  const hand = id(m, 'mjOBJ_GEOM', 'hand');
  out.ids = [wrist, tool, hand];
  out.masses = {};
  for (const name of ['base', 'upper', 'wrist']) out.masses[name] = modelRow(m, 'body_mass', 'mjOBJ_BODY', name, 1);

  const jacp = new mj.DoubleBuffer(3 * nv);
  const jacr = new mj.DoubleBuffer(3 * nv);
  const both = () => [rows(jacp.GetView(), nv), rows(jacr.GetView(), nv)];

  mj.mj_jacSite(m, d, jacp, jacr, tool);
  out.jacSite = both();
  const qvel = list(d.qvel);
  out.tool_velocity = out.jacSite[0].map((row) => row.reduce((s, x, j) => s + x * qvel[j], 0));

  mj.mj_jacBody(m, d, jacp, jacr, wrist);
  out.jacBody = both();

  const jacpCom = new mj.DoubleBuffer(3 * nv);
  mj.mj_jacBodyCom(m, d, jacpCom, null, id(m, 'mjOBJ_BODY', 'upper'));
  out.jacBodyCom = rows(jacpCom.GetView(), nv);

  mj.mj_jacGeom(m, d, jacp, jacr, hand);
  out.jacGeom = both();

  const wristPos = bodyField(m, d, 'xpos', 'wrist', 3);
  const point = [wristPos[0] + 0.02, wristPos[1] + 0.05, wristPos[2] + -0.03];
  mj.mj_jac(m, d, jacp, jacr, point, wrist);
  out.jac_point = point;
  out.jac = both();

  const M = new mj.DoubleBuffer(nv * nv);
  mj.mj_fullM(m, M, d.qM);
  out.qM = list(d.qM);
  out.fullM = rows(M.GetView(), nv);
  const vec = [1.0, -2.0, 0.5, 0.25, 3.0, -1.5];
  const res = new mj.DoubleBuffer(nv);
  mj.mj_mulM(m, d, res, vec);
  out.mulM = list(res.GetView());
  const Mvec = out.fullM.map((row) => row.reduce((s, x, j) => s + x * vec[j], 0));
  out.mulM_vs_fullM = maxAbsDiff(Mvec, out.mulM);

  for (let i = 0; i < 200; i++) mj.mj_step(m, d);
  mj.mj_jacSite(m, d, jacp, jacr, tool);
  out.stepped = {
    qpos: list(d.qpos), jacSite: both(), tool: siteField(m, d, 'site_xpos', 'tool', 3),
  };
  mj.mj_fullM(m, M, d.qM);
  out.stepped.fullM = rows(M.GetView(), nv);
  for (const b of [jacp, jacr, jacpCom, M, res]) b.delete();
  return out;
}

function ray_cast() {
  const m = fromXmlString(inlineXml('ray_cast'));
  const d = new mj.MjData(m);
  setJointQpos(m, d, 'tilt', [0.3]);
  mj.mj_forward(m, d);
  const lid = id(m, 'mjOBJ_BODY', 'lid');

  // One geomid and one normal buffer for every ray, as the script reuses its arrays.
  const geomid = new mj.IntBuffer(1);
  const normal = new mj.DoubleBuffer(3);
  const cast = (pnt, vec, geomgroup, flgStatic, bodyexclude) => {
    const dist = mj.mj_ray(m, d, pnt, vec, geomgroup, flgStatic, bodyexclude, geomid, normal);
    const g = geomid.GetView()[0];
    return [dist, g, nameOf(m, 'mjOBJ_GEOM', g), list(normal.GetView())];
  };
  const allGroups = null;
  const groups01 = [1, 1, 0, 0, 0, 0];
  const group0 = [1, 0, 0, 0, 0, 0];
  const group1 = [0, 1, 0, 0, 0, 0];
  const out = {
    rays: {
      down_lid: cast([0.05, 0.02, 1.0], [0, 0, -1], allGroups, 1, -1),
      down_excluded: cast([0.05, 0.02, 1.0], [0, 0, -1], allGroups, 1, lid),
      down_no_static: cast([0.05, 0.02, 1.0], [0, 0, -1], allGroups, 0, lid),
      down_long_vec: cast([0.05, 0.02, 1.0], [0, 0, -2], allGroups, 1, -1),
      pillar_all: cast([1.0, 0.0, 0.2], [-1, 0, 0], allGroups, 1, -1),
      pillar_masked: cast([1.0, 0.0, 0.2], [-1, 0, 0], groups01, 1, -1),
      bead: cast([0.0, 0.5, 0.1], [0, -0.2, 0.4], group1, 1, -1),
      bead_masked: cast([0.0, 0.5, 0.1], [0, -0.2, 0.4], group0, 1, -1),
      miss: cast([0.0, 0.0, 2.0], [0, 0, 1], allGroups, 1, -1),
    },
  };
  const dist = mj.mj_ray(m, d, [0.05, 0.02, 1.0], [0.0, 0.0, -1.0], null, 1, -1, geomid, null);
  out.no_normal = [dist, geomid.GetView()[0]];
  out.lid_xpos = geomField(m, d, 'geom_xpos', 'lid', 3);
  out.lid_xmat = geomField(m, d, 'geom_xmat', 'lid', 9);
  geomid.delete();
  normal.delete();
  return out;
}

function gripper() {
  const ACTUATORS = ['x', 'y', 'z', 'gripper/grip'];
  const m = fromXmlPath(path.join(MODELS, 'gantry_gripper.xml'));
  const d = new mj.MjData(m);
  const report = () => {
    const cs = contactList(d);
    const ctrl = {};
    const force = {};
    for (const name of ACTUATORS) {
      ctrl[name] = actuatorField(m, d, 'ctrl', name);
      force[name] = actuatorField(m, d, 'actuator_force', name);
    }
    return {
      time: d.time, qpos: list(d.qpos), qvel: list(d.qvel), ctrl, force,
      fingers: [jointQpos(m, d, 'gripper/finger_left'), jointQpos(m, d, 'gripper/finger_right')],
      grip_length: tendonField(m, d, 'ten_length', 'gripper/grip'),
      grip_velocity: tendonField(m, d, 'ten_velocity', 'gripper/grip'),
      ten_length: list(d.ten_length),
      cube_qpos: jointQpos(m, d, 'cube'),
      cube_xpos: bodyField(m, d, 'xpos', 'cube', 3),
      palm_xpos: bodyField(m, d, 'xpos', 'gripper/palm', 3),
      finger_geom_xpos: geomField(m, d, 'geom_xpos', 'gripper/finger_left', 3),
      ncon: d.ncon,
      contact_geom: cs.map((c) => c.geom),
      contact_dist: cs.map((c) => c.dist),
      contact_frame: cs.map((c) => c.frame),
      contact_force: contactForces(m, d),
    };
  };
  const z = id(m, 'mjOBJ_ACTUATOR', 'z');
  const grip = id(m, 'mjOBJ_ACTUATOR', 'gripper/grip');
  const out = {};
  mj.mj_resetDataKeyframe(m, d, id(m, 'mjOBJ_KEY', 'home'));
  out.home = report();
  d.ctrl[z] = -0.33;
  for (let i = 0; i < 400; i++) mj.mj_step(m, d);
  out.lowered = report();
  d.ctrl[grip] = 0.0;
  for (let i = 0; i < 300; i++) mj.mj_step(m, d);
  out.closed = report();
  for (let k = 1; k <= 10; k++) {
    d.ctrl[z] = -0.33 + 0.01 * k;
    for (let i = 0; i < 25; i++) mj.mj_step(m, d);
  }
  out.lifted = report();
  mj.mj_resetDataKeyframe(m, d, 1);
  out.key1 = { qpos: list(d.qpos), ctrl: list(d.ctrl), time: d.time };
  return out;
}

function humanoid_state() {
  const m = fromXmlPath(HUMANOID);
  const d = new mj.MjData(m);
  const step = (data, n) => { for (let i = 0; i < n; i++) mj.mj_step(m, data); };
  const summary = (data) => ({
    time: data.time, qpos: list(data.qpos), qvel: list(data.qvel), ncon: data.ncon,
    contact_geom: contactList(data).map((c) => c.geom),
    torso_xpos: bodyField(m, data, 'xpos', 'torso', 3),
    root_qpos: jointQpos(m, data, 'root'),
    knee_left: jointQpos(m, data, 'knee_left'),
    hamstring_right: tendonField(m, data, 'ten_length', 'hamstring_right'),
    actuator_force: list(data.actuator_force),
  });
  const out = {};

  mj.mj_resetDataKeyframe(m, d, id(m, 'mjOBJ_KEY', 'stand_on_left_leg'));
  d.ctrl.set([...Array(m.nu).keys()].map((i) => 0.1 * ((i % 5) - 2)));
  step(d, 100);
  out.t100 = summary(d);

  // copy.copy, copy.deepcopy and mj_copyData all copy the whole MjData.
  const copies = [new mj.MjData(m, d), new mj.MjData(m, d), new mj.MjData(m, d)];
  const sig = enumValue('mjtState', 'mjSTATE_FULLPHYSICS');
  const size = mj.mj_stateSize(m, sig);
  const stateBuf = new mj.DoubleBuffer(size);
  mj.mj_getState(m, d, stateBuf, sig);
  const state = list(stateBuf.GetView());
  stateBuf.delete();
  out.state_size = size;
  out.state = state;

  step(d, 150);
  for (const other of copies) step(other, 150);
  out.t250 = summary(d);
  out.copies_equal = copies.map((other) => arraysEqual(list(other.qpos), list(d.qpos))
    && arraysEqual(list(other.qvel), list(d.qvel)) && other.time === d.time);

  const shallow = copies[0];
  shallow.ctrl.fill(0);
  step(shallow, 50);
  out.shallow_t300 = summary(shallow);
  out.original_untouched = arraysEqual(out.t250.qpos, list(d.qpos));

  mj.mj_setState(m, d, state, sig);
  out.rewound = { time: d.time, qpos: list(d.qpos) };
  step(d, 150);
  out.replayed = summary(d);

  mj.mj_resetData(m, d);
  out.reset = { time: d.time, qpos: list(d.qpos), ctrl: list(d.ctrl) };
  mj.mj_resetDataKeyframe(m, d, 0);
  mj.mj_forward(m, d);
  out.squat = summary(d);
  for (const other of copies) other.delete();
  return out;
}

function reset_warnings() {
  const m = fromXmlString(inlineXml('reset_warnings'));
  const d = new mj.MjData(m);
  // (The warning vector and its elements are views into d: not deleted here.)
  const warning = (i) => {
    const w = d.warning.get(i);
    return { number: w.number, lastinfo: w.lastinfo };
  };
  const nwarning = d.warning.size();
  const state = () => ({
    time: d.time, qpos: list(d.qpos), qvel: list(d.qvel), act: list(d.act), ctrl: list(d.ctrl),
    warnings: [...Array(nwarning).keys()].map((i) => warning(i).number),
  });
  const out = { nkey: m.nkey, na: m.na, nwarning };

  mj.mj_resetDataKeyframe(m, d, id(m, 'mjOBJ_KEY', 'raised'));
  out.raised = state();
  for (let i = 0; i < 200; i++) mj.mj_step(m, d);
  out.raised_200 = state();
  out.raised_200.actuator_force = list(d.actuator_force);

  mj.mj_resetDataKeyframe(m, d, 1);
  out.still = state();

  d.time = 10.0;
  for (let i = 0; i < 3; i++) mj.mj_step(m, d);
  out.time_after_3 = d.time;

  const BADQPOS = enumValue('mjtWarning', 'mjWARN_BADQPOS');
  const BADQVEL = enumValue('mjtWarning', 'mjWARN_BADQVEL');
  mj.mj_resetDataKeyframe(m, d, 0);
  d.qpos[1] = NaN;
  mj.mj_step(m, d);
  out.bad_qpos = state();
  out.bad_qpos.number = warning(BADQPOS).number;
  out.bad_qpos.lastinfo = warning(BADQPOS).lastinfo;

  mj.mj_resetDataKeyframe(m, d, 0);
  d.qvel[0] = Infinity;
  for (let i = 0; i < 2; i++) mj.mj_step(m, d);
  out.bad_qvel = state();
  out.bad_qvel.number = warning(BADQVEL).number;
  out.bad_qvel.lastinfo = warning(BADQVEL).lastinfo;

  mj.mj_resetData(m, d);
  out.reset = state();
  return out;
}

// ---------------------------------------------------------------------------------------
// Writing

const SCRIPTS = {
  load_sizes, names_enums, actuators, pendulum_views, contacts, jacobians, ray_cast,
  gripper, humanoid_state, reset_warnings,
};

// JSON has no NaN or infinity (JSON.stringify would write null): refuse them.
function checkFinite(value, where) {
  if (typeof value === 'number' && !Number.isFinite(value)) {
    throw new Error(`${where}: ${value} is not finite`);
  }
  if (Array.isArray(value)) value.forEach((v, i) => checkFinite(v, `${where}[${i}]`));
  else if (value && typeof value === 'object') {
    for (const [k, v] of Object.entries(value)) checkFinite(v, `${where}.${k}`);
  }
}

const wanted = process.argv.slice(2);
for (const name of wanted) {
  if (!SCRIPTS[name]) throw new Error(`unknown script ${name}; known: ${Object.keys(SCRIPTS).join(' ')}`);
}
fs.mkdirSync(path.join(HERE, 'goldens'), { recursive: true });
for (const [name, make] of Object.entries(SCRIPTS)) {
  if (wanted.length && !wanted.includes(name)) continue;
  const golden = make();
  checkFinite(golden, name);
  const file = path.join(HERE, 'goldens', `${name}.json`);
  fs.writeFileSync(file, `${JSON.stringify(golden)}\n`);
  console.log(`wrote ${path.relative(process.cwd(), file)} (MuJoCo ${mj.mj_versionString()})`);
}
