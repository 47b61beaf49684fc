// Dump the contacts MuJoCo itself (the oracle) finds after mj_forward, as JSON: the
// goldens of the per-pair collision test (tests/collision_pair_test.cc).
//
//   node tools/dump_contacts.mjs MODEL.xml [--key K] [OUT.json]
//
// Regenerate all pair goldens: tests/collision_pairs/make_goldens.sh
//
// MuJoCo comes from the oracle's node_modules: $SIMLAB_ORACLE, else ../shared/oracle
// beside the repository.
import fs from 'node:fs';

import { loadOracleModel } from './oracle_model.mjs';

// Per-contact fields written to the golden (arrays become plain lists).
const CONTACT_FIELDS = ['dist', 'pos', 'frame', 'includemargin', 'dim', 'geom', 'friction',
  'solref', 'solreffriction', 'solimp', 'exclude', 'efc_address', 'mu'];

// MODEL.xml, an optional --key K, an optional output file.
function parseArgs(argv) {
  const opts = { model: null, key: -1, out: null };
  for (let i = 0; i < argv.length; i++) {
    if (argv[i] === '--key') opts.key = parseInt(argv[++i], 10);
    else if (!opts.model) opts.model = argv[i];
    else if (!opts.out) opts.out = argv[i];
    else throw new Error(`unexpected argument ${argv[i]}`);
  }
  if (!opts.model) throw new Error('usage: node dump_contacts.mjs MODEL.xml [--key K] [OUT.json]');
  return opts;
}

// One contact as a plain object.
function contactJson(c) {
  const out = {};
  for (const f of CONTACT_FIELDS) {
    const v = c[f];
    out[f] = typeof v === 'object' ? Array.from(v, Number) : Number(v);
  }
  return out;
}

const opts = parseArgs(process.argv.slice(2));
const { mj, model } = await loadOracleModel(opts.model);
const data = new mj.MjData(model);
if (opts.key >= 0) mj.mj_resetDataKeyframe(model, data, opts.key);
mj.mj_forward(model, data);

const out = { engine: `mujoco ${mj.mj_versionString()}`, key: opts.key, ncon: data.ncon,
  contact: [] };
for (let i = 0; i < data.ncon; i++) {
  const c = data.contact.get(i);
  out.contact.push(contactJson(c));
  c.delete();
}
// One contact a line, so goldens read and diff well.
const lines = out.contact.map((c) => '  ' + JSON.stringify(c));
const head = JSON.stringify({ engine: out.engine, key: out.key, ncon: out.ncon });
const text = `${head.slice(0, -1)},\n "contact": [\n${lines.join(',\n')}\n]}`;
if (opts.out) fs.writeFileSync(opts.out, text + '\n'); else process.stdout.write(text + '\n');
data.delete();
model.delete();
