// make_ray_golden.mjs — rays cast by MuJoCo itself (the oracle, MuJoCo 3.5.1) against
// the flexes of tests/conformance/flex/models/ray_flex.xml after 150 steps: for each flex,
// rays from points around its box aimed near its centre, under each combination of the
// vertex, edge, face and skin flags and two layers; the golden of the flex ray test.
//
//   SIMLAB_ORACLE=/path/to/oracle node tests/conformance/flex/make_ray_golden.mjs
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

import { loadOracleModel } from '../../../tools/oracle_model.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const modelPath = path.join(here, 'models', 'ray_flex.xml');
const { mj, model } = await loadOracleModel(modelPath);
const data = new mj.MjData(model);
for (let i = 0; i < 150; i++) mj.mj_step(model, data);
mj.mj_forward(model, data);  // (positions of the state reached, as the test recomputes them)

// The box of flex f's vertices.
function flexBox(f) {
  const xpos = data.flexvert_xpos, adr = model.flex_vertadr[f], n = model.flex_vertnum[f];
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let v = adr; v < adr + n; v++) {
    for (let k = 0; k < 3; k++) {
      lo[k] = Math.min(lo[k], xpos[3 * v + k]);
      hi[k] = Math.max(hi[k], xpos[3 * v + k]);
    }
  }
  return { lo, hi };
}

// Flags: vert, edge, face, skin.
const FLAGS = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1], [1, 1, 1, 0], [1, 0, 1, 1]];
const rays = [];
const vertid = new mj.IntBuffer(1);
const normal = new mj.DoubleBuffer(3);
for (let f = 0; f < model.nflex; f++) {
  const { lo, hi } = flexBox(f);
  const centre = [0, 1, 2].map((k) => 0.5 * (lo[k] + hi[k]));
  const reach = 2 * Math.max(...[0, 1, 2].map((k) => hi[k] - lo[k])) + 0.5;
  // Origins on a ring of directions around the box, aimed at points spread over it.
  for (let i = 0; i < 24; i++) {
    const theta = (Math.PI * (i % 6)) / 5, phi = (2 * Math.PI * i) / 24;
    const dir = [Math.sin(theta) * Math.cos(phi), Math.sin(theta) * Math.sin(phi), Math.cos(theta)];
    const target = [0, 1, 2].map((k) => centre[k] + 0.3 * (hi[k] - lo[k]) * Math.sin(1.7 * i + k));
    const pnt = [0, 1, 2].map((k) => target[k] + reach * dir[k]);
    const vec = [0, 1, 2].map((k) => -dir[k] * (1 + 0.25 * (i % 3)));
    for (const [vert, edge, face, skin] of FLAGS) {
      for (const layer of [0, 1]) {
        vertid.GetView()[0] = -1;
        const x = mj.mj_rayFlex(model, data, layer, vert, edge, face, skin, f, pnt, vec, vertid, normal);
        rays.push({ flex: f, layer, flags: [vert, edge, face, skin], pnt, vec, x,
                    vertid: x >= 0 ? vertid.GetView()[0] : -1, normal: Array.from(normal.GetView()) });
      }
    }
  }
}
const out = path.join(here, 'ray_flex.json');
fs.writeFileSync(out, JSON.stringify({ qpos: Array.from(data.qpos), rays }) + '\n');
const hits = rays.filter((r) => r.x >= 0).length;
console.log(`${out}: ${rays.length} rays, ${hits} hits`);
