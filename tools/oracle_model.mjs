// Load a model into MuJoCo itself (the oracle), for the dump tools.
//
// MuJoCo comes from the oracle's node_modules: $SIMLAB_ORACLE, else ../shared/oracle
// beside the repository. Every file below the model's folder is copied into MuJoCo's
// virtual file system, so <include>, <attach> and mesh files resolve as on disk.
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

// Copy a folder into MuJoCo's virtual file system.
function copyTree(mj, hostDir, vfsDir) {
  for (const entry of fs.readdirSync(hostDir, { withFileTypes: true })) {
    const host = path.join(hostDir, entry.name);
    const vfs = `${vfsDir}/${entry.name}`;
    if (entry.isDirectory()) {
      try { mj.FS.mkdir(vfs); } catch { /* exists */ }
      copyTree(mj, host, vfs);
    } else if (entry.isFile()) {
      mj.FS.writeFile(vfs, fs.readFileSync(host));
    }
  }
}

// { mj, model } for the MJCF file at modelPath.
export async function loadOracleModel(modelPath) {
  const here = path.dirname(fileURLToPath(import.meta.url));
  const oracle = process.env.SIMLAB_ORACLE || path.join(here, '..', '..', 'shared', 'oracle');
  const entry = path.join(oracle, 'node_modules', 'mujoco', 'mujoco.js');
  const { default: loadMujoco } = await import(pathToFileURL(entry).href);
  const mj = await loadMujoco();
  try { mj.FS.mkdir('/model'); } catch { /* exists */ }
  copyTree(mj, path.dirname(path.resolve(modelPath)), '/model');
  const model = mj.MjModel.mj_loadXML(`/model/${path.basename(modelPath)}`);
  return { mj, model };
}
