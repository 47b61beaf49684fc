// Dump selected compiled mjModel fields from MuJoCo itself (the oracle) as JSON, the
// goldens of the compiler conformance test (tests/compiler_conformance_test.cc).
//
//   node tools/dump_model.mjs [--native BIN] MODEL.xml [OUT.json]
//
// Regenerate all compiler goldens (from the repository root):
//   for f in tests/compiler_models/*.xml; do
//     node tools/dump_model.mjs $f tests/compiler_goldens/$(basename $f .xml).json; done
//   node tools/dump_model.mjs ../shared/corpus/mujoco/model/humanoid/humanoid.xml \
//     tests/compiler_goldens/humanoid.json   (likewise slider_crank)
//
// MuJoCo comes from the oracle's node_modules: $SIMLAB_ORACLE, else ../shared/oracle
// beside the repository.
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';

import { loadOracleModel } from './oracle_model.mjs';

// Fields compared by the test; sizes first.
const SIZES = ['nq', 'nv', 'nu', 'na', 'nbody', 'njnt', 'ngeom', 'nsite', 'ntendon', 'nwrap',
  'nkey', 'nM', 'nmocap', 'neq', 'nmesh', 'nmeshvert', 'nmeshface', 'nmeshgraph', 'nmeshnormal', 'ncam',
  'nhfield', 'nhfielddata', 'nbvh', 'nD', 'nlight', 'ntex', 'ntexdata', 'nmat', 'nmeshtexcoord',
  'npair', 'nexclude', 'ntree', 'nB', 'nmeshpoly', 'nmeshpolyvert', 'nmeshpolymap', 'nskin',
  'nskinvert', 'nskintexvert', 'nskinface', 'nskinbone', 'nskinbonevert',
  'nflex', 'nflexnode', 'nflexvert', 'nflexedge', 'nflexelem', 'nflexelemdata', 'nflexelemedge',
  'nflexshelldata', 'nflexevpair', 'nflextexcoord', 'nJfe', 'nJfv'];
const ARRAYS = [
  'qpos0', 'qpos_spring',
  'body_parentid', 'body_rootid', 'body_weldid', 'body_mocapid', 'body_jntnum', 'body_jntadr',
  'body_dofnum', 'body_dofadr', 'body_treeid', 'body_geomnum', 'body_geomadr',
  'body_sameframe', 'body_pos', 'body_quat', 'body_ipos', 'body_iquat', 'body_mass',
  'body_subtreemass', 'body_inertia', 'body_gravcomp', 'body_simple', 'body_invweight0',
  'body_margin', 'body_bvhadr', 'body_bvhnum', 'bvh_depth', 'bvh_child', 'bvh_nodeid', 'bvh_aabb',
  'jnt_type', 'jnt_qposadr', 'jnt_dofadr', 'jnt_bodyid', 'jnt_group', 'jnt_limited',
  'jnt_actfrclimited', 'jnt_actgravcomp', 'jnt_solref', 'jnt_solimp', 'jnt_pos', 'jnt_axis',
  'jnt_stiffness', 'jnt_range', 'jnt_actfrcrange', 'jnt_margin',
  'dof_bodyid', 'dof_jntid', 'dof_parentid', 'dof_treeid', 'dof_Madr', 'dof_solref',
  'dof_solimp', 'dof_frictionloss', 'dof_armature', 'dof_damping', 'dof_invweight0',
  'dof_length', 'tree_bodyadr', 'tree_bodynum', 'tree_dofadr', 'tree_dofnum', 'tree_sleep_policy',
  'M_rownnz', 'M_rowadr', 'M_colind', 'D_rownnz', 'D_rowadr', 'D_diag', 'D_colind',
  'B_rownnz', 'B_rowadr', 'B_colind',
  'geom_type', 'geom_contype', 'geom_conaffinity', 'geom_condim', 'geom_bodyid', 'geom_group',
  'geom_priority', 'geom_sameframe', 'geom_solmix', 'geom_solref', 'geom_solimp', 'geom_size',
  'geom_rbound', 'geom_aabb', 'geom_pos', 'geom_quat', 'geom_friction', 'geom_margin', 'geom_gap',
  'geom_rgba', 'geom_fluid', 'geom_dataid',
  'mesh_vertadr', 'mesh_vertnum', 'mesh_faceadr', 'mesh_facenum', 'mesh_graphadr', 'mesh_scale',
  'mesh_pos', 'mesh_quat', 'mesh_vert', 'mesh_face', 'mesh_graph',
  'mesh_normaladr', 'mesh_normalnum', 'mesh_normal', 'mesh_texcoordadr', 'mesh_texcoordnum',
  'mesh_texcoord', 'mesh_facetexcoord',
  'mesh_polynum', 'mesh_polyadr', 'mesh_polynormal', 'mesh_polyvertadr', 'mesh_polyvertnum',
  'mesh_polyvert', 'mesh_polymapadr', 'mesh_polymapnum', 'mesh_polymap',
  'hfield_size', 'hfield_nrow', 'hfield_ncol', 'hfield_adr', 'hfield_data',
  'skin_matid', 'skin_group', 'skin_rgba', 'skin_inflate', 'skin_vertadr', 'skin_vertnum',
  'skin_texcoordadr', 'skin_faceadr', 'skin_facenum', 'skin_boneadr', 'skin_bonenum', 'skin_vert',
  'skin_texcoord', 'skin_face', 'skin_bonevertadr', 'skin_bonevertnum', 'skin_bonebindpos',
  'skin_bonebindquat', 'skin_bonebodyid', 'skin_bonevertid', 'skin_bonevertweight',
  'site_type', 'site_bodyid', 'site_group', 'site_sameframe', 'site_size', 'site_pos',
  'site_quat', 'site_rgba', 'geom_matid', 'site_matid',
  'light_mode', 'light_bodyid', 'light_targetbodyid', 'light_type', 'light_texid',
  'light_castshadow', 'light_bulbradius', 'light_intensity', 'light_range', 'light_active',
  'light_pos', 'light_dir', 'light_poscom0', 'light_pos0', 'light_dir0', 'light_attenuation',
  'light_cutoff', 'light_exponent', 'light_ambient', 'light_diffuse', 'light_specular',
  'tex_type', 'tex_colorspace', 'tex_height', 'tex_width', 'tex_nchannel', 'tex_adr',
  'tex_data', 'mat_texid', 'mat_texuniform', 'mat_texrepeat', 'mat_emission', 'mat_specular',
  'mat_shininess', 'mat_reflectance', 'mat_metallic', 'mat_roughness', 'mat_rgba',
  'cam_mode', 'cam_bodyid', 'cam_targetbodyid', 'cam_pos', 'cam_quat', 'cam_poscom0',
  'cam_pos0', 'cam_mat0', 'cam_projection', 'cam_fovy', 'cam_ipd', 'cam_resolution',
  'cam_output', 'cam_sensorsize', 'cam_intrinsic',
  'tendon_adr', 'tendon_num', 'tendon_limited', 'tendon_actfrclimited', 'tendon_solref_lim',
  'tendon_solimp_lim', 'tendon_solref_fri', 'tendon_solimp_fri', 'tendon_range',
  'tendon_actfrcrange', 'tendon_margin', 'tendon_stiffness', 'tendon_damping',
  'tendon_armature', 'tendon_frictionloss', 'tendon_lengthspring', 'tendon_length0',
  'tendon_invweight0', 'tendon_treenum', 'tendon_treeid',
  'wrap_type', 'wrap_objid', 'wrap_prm',
  'actuator_trntype', 'actuator_dyntype', 'actuator_gaintype', 'actuator_biastype',
  'actuator_trnid', 'actuator_actadr', 'actuator_actnum', 'actuator_group',
  'actuator_ctrllimited', 'actuator_forcelimited', 'actuator_actlimited', 'actuator_actearly',
  'actuator_dynprm', 'actuator_gainprm', 'actuator_biasprm', 'actuator_ctrlrange',
  'actuator_forcerange', 'actuator_actrange', 'actuator_gear', 'actuator_cranklength',
  'actuator_acc0', 'actuator_length0', 'actuator_lengthrange',
  'key_time', 'key_qpos', 'key_qvel', 'key_act', 'key_mpos', 'key_mquat', 'key_ctrl',
  'eq_type', 'eq_obj1id', 'eq_obj2id', 'eq_objtype', 'eq_active0', 'eq_solref', 'eq_solimp',
  'eq_data',
  'pair_dim', 'pair_geom1', 'pair_geom2', 'pair_signature', 'pair_solref', 'pair_solimp',
  'pair_margin', 'pair_gap', 'pair_friction', 'exclude_signature',
  'flex_contype', 'flex_conaffinity', 'flex_condim', 'flex_priority', 'flex_solmix',
  'flex_solref', 'flex_solimp', 'flex_friction', 'flex_margin', 'flex_gap', 'flex_internal',
  'flex_selfcollide', 'flex_activelayers', 'flex_passive', 'flex_dim', 'flex_matid',
  'flex_group', 'flex_interp', 'flex_nodeadr', 'flex_nodenum', 'flex_vertadr', 'flex_vertnum',
  'flex_edgeadr', 'flex_edgenum', 'flex_elemadr', 'flex_elemnum', 'flex_elemdataadr',
  'flex_elemedgeadr', 'flex_shellnum', 'flex_shelldataadr', 'flex_evpairadr', 'flex_evpairnum',
  'flex_texcoordadr', 'flex_nodebodyid', 'flex_vertbodyid', 'flex_vertedgeadr',
  'flex_vertedgenum', 'flex_vertedge', 'flex_edge', 'flex_edgeflap', 'flex_elem',
  'flex_elemtexcoord', 'flex_elemedge', 'flex_elemlayer', 'flex_shell', 'flex_evpair',
  'flex_vert', 'flex_vert0', 'flex_vertmetric', 'flex_node', 'flex_node0', 'flexedge_length0',
  'flexedge_invweight0', 'flex_radius', 'flex_size', 'flex_stiffness', 'flex_bending',
  'flex_damping', 'flex_edgestiffness', 'flex_edgedamping', 'flex_edgeequality', 'flex_rigid',
  'flexedge_rigid', 'flex_centered', 'flex_flatskin', 'flexedge_J_rownnz', 'flexedge_J_rowadr',
  'flexedge_J_colind', 'flexvert_J_rownnz', 'flexvert_J_rowadr', 'flexvert_J_colind',
  'flex_rgba', 'flex_texcoord',
];
const OPTIONS = ['timestep', 'impratio', 'tolerance', 'ls_tolerance', 'gravity', 'wind',
  'magnetic', 'density', 'viscosity', 'o_margin', 'o_solref', 'o_solimp', 'o_friction',
  'integrator', 'cone',
  'jacobian', 'solver', 'iterations', 'ls_iterations', 'noslip_iterations', 'disableflags',
  'enableflags', 'disableactuator'];

// --native BIN: the fields from a native MuJoCo build instead (tools/native/dump_model.cc
// compiled as BIN), for models the WebAssembly oracle cannot compile (fusestatic).
const args = process.argv.slice(2);
let nativeBin = null;
const at = args.indexOf('--native');
if (at >= 0) nativeBin = args.splice(at, 2)[1];
const [modelPath, outPath] = args;
if (!modelPath) throw new Error('usage: node dump_model.mjs [--native BIN] MODEL.xml [OUT.json]');
const { mj, model } = nativeBin ? nativeModel(nativeBin, modelPath) : await loadOracleModel(modelPath);

// The native dump shaped as the oracle's model: sizes and arrays by name, opt, stat.
function nativeModel(bin, path) {
  const text = execFileSync(bin, [path], { maxBuffer: 1 << 30 }).toString();
  const dump = JSON.parse(text);
  const opt = {};
  for (const [k, v] of Object.entries(dump.opt)) opt[k] = v.length === 1 ? v[0] : v;
  const fields = { ...dump.sizes, ...dump.arrays, opt, stat: dump.stat };
  return { mj: { mj_versionString: () => dump.engine.replace(/^mujoco /, '') }, model: fields };
}

// Sizes, arrays (typed arrays become plain lists), options.
const out = { engine: `mujoco ${mj.mj_versionString()}`, sizes: {}, arrays: {}, opt: {} };
for (const s of SIZES) out.sizes[s] = model[s];
for (const a of ARRAYS) {
  const v = model[a];
  if (v === undefined) continue;
  out.arrays[a] = Array.from(v, Number);
}
for (const o of OPTIONS) {
  const v = model.opt[o];
  if (v === undefined) continue;
  out.opt[o] = typeof v === 'object' ? Array.from(v, Number) : Number(v);
}
out.stat = { meaninertia: Number(model.stat.meaninertia) };
const text = JSON.stringify(out);
if (outPath) fs.writeFileSync(outPath, text + '\n'); else process.stdout.write(text + '\n');
