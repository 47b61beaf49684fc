// Skins in the lab's view: each skin's triangle mesh, its vertices carried by their bones
// every frame as MuJoCo's mjv_updateActiveSkin carries them (a bone moves its vertices by
// the body's motion since the bind pose, weighted; normals are area-weighted face
// normals; `inflate` pushes each vertex out along its normal).
import * as THREE from '../node_modules/three/build/three.module.js';

// MuJoCo hides skin groups 3 and up by default, as geom groups.
const kVisibleGroups = 3;

// The rotation of q (w x y z) as a row-major 3x3 matrix, into out.
function quatToMat(q, out) {
  const [w, x, y, z] = q;
  out[0] = w * w + x * x - y * y - z * z; out[1] = 2 * (x * y - w * z); out[2] = 2 * (x * z + w * y);
  out[3] = 2 * (x * y + w * z); out[4] = w * w - x * x + y * y - z * z; out[5] = 2 * (y * z - w * x);
  out[6] = 2 * (x * z - w * y); out[7] = 2 * (y * z + w * x); out[8] = w * w - x * x - y * y + z * z;
  return out;
}

// a * conj(b), quaternions w x y z.
function mulConj(a, b) {
  const [aw, ax, ay, az] = a, bw = b[0], bx = -b[1], by = -b[2], bz = -b[3];
  return [aw * bw - ax * bx - ay * by - az * bz, aw * bx + ax * bw + ay * bz - az * by,
          aw * by - ax * bz + ay * bw + az * bx, aw * bz + ax * by - ay * bx + az * bw];
}

export class Skins {
  // One three.js mesh per visible skin, coloured by its material or rgba.
  constructor(scene, model) {
    this.model = model;
    this.meshes = [];
    const count = model.skin_vertnum?.length ?? 0;
    for (let s = 0; s < count; s++) {
      if (model.skin_group[s] >= kVisibleGroups) continue;
      const vertnum = model.skin_vertnum[s], faceadr = model.skin_faceadr[s];
      const geometry = new THREE.BufferGeometry();
      geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(3 * vertnum), 3));
      geometry.setAttribute('normal', new THREE.BufferAttribute(new Float32Array(3 * vertnum), 3));
      geometry.setIndex(Array.from(model.skin_face.subarray(3 * faceadr, 3 * (faceadr + model.skin_facenum[s]))));
      const mat = model.skin_matid[s];
      const rgba = mat >= 0 ? model.mat_rgba.subarray(4 * mat, 4 * mat + 4) : model.skin_rgba.subarray(4 * s, 4 * s + 4);
      const material = new THREE.MeshPhongMaterial({
        color: new THREE.Color(rgba[0], rgba[1], rgba[2]), opacity: rgba[3], transparent: rgba[3] < 1,
        side: THREE.DoubleSide, shininess: 30,
      });
      const mesh = new THREE.Mesh(geometry, material);
      mesh.frustumCulled = false;
      mesh.castShadow = rgba[3] >= 1;
      mesh.receiveShadow = true;
      scene.add(mesh);
      this.meshes.push({ s, mesh });
    }
    this.rotate = new Float64Array(9);
  }

  // Poses every skin from the bodies' xpos and xquat.
  update(xpos, xquat) {
    for (const { s, mesh } of this.meshes) {
      const position = mesh.geometry.attributes.position, normal = mesh.geometry.attributes.normal;
      this.carry(s, xpos, xquat, position.array);
      this.normals(s, position.array, normal.array);
      this.inflate(s, position.array, normal.array);
      position.needsUpdate = true;
      normal.needsUpdate = true;
    }
  }

  // Each vertex: the sum over its bones of weight x (R v + t), R = body rotation times
  // the inverse bind rotation, t = body position - R bindpos.
  carry(s, xpos, xquat, out) {
    const m = this.model, R = this.rotate, vertadr = m.skin_vertadr[s], vert = m.skin_vert;
    out.fill(0);
    for (let j = m.skin_boneadr[s]; j < m.skin_boneadr[s] + m.skin_bonenum[s]; j++) {
      const body = m.skin_bonebodyid[j];
      quatToMat(mulConj(xquat.subarray(4 * body, 4 * body + 4), m.skin_bonebindquat.subarray(4 * j, 4 * j + 4)), R);
      const b0 = m.skin_bonebindpos[3 * j], b1 = m.skin_bonebindpos[3 * j + 1], b2 = m.skin_bonebindpos[3 * j + 2];
      const t0 = xpos[3 * body] - (R[0] * b0 + R[1] * b1 + R[2] * b2);
      const t1 = xpos[3 * body + 1] - (R[3] * b0 + R[4] * b1 + R[5] * b2);
      const t2 = xpos[3 * body + 2] - (R[6] * b0 + R[7] * b1 + R[8] * b2);
      const end = m.skin_bonevertadr[j] + m.skin_bonevertnum[j];
      for (let k = m.skin_bonevertadr[j]; k < end; k++) {
        const v = m.skin_bonevertid[k], w = m.skin_bonevertweight[k], p = 3 * (vertadr + v);
        const x = vert[p], y = vert[p + 1], z = vert[p + 2];
        out[3 * v] += w * (R[0] * x + R[1] * y + R[2] * z + t0);
        out[3 * v + 1] += w * (R[3] * x + R[4] * y + R[5] * z + t1);
        out[3 * v + 2] += w * (R[6] * x + R[7] * y + R[8] * z + t2);
      }
    }
  }

  // Vertex normals: the sum of the (area-weighted) normals of the faces around it.
  normals(s, pos, out) {
    const m = this.model, face = m.skin_face;
    out.fill(0);
    for (let f = m.skin_faceadr[s]; f < m.skin_faceadr[s] + m.skin_facenum[s]; f++) {
      const a = 3 * face[3 * f], b = 3 * face[3 * f + 1], c = 3 * face[3 * f + 2];
      const e10 = pos[b] - pos[a], e11 = pos[b + 1] - pos[a + 1], e12 = pos[b + 2] - pos[a + 2];
      const e20 = pos[c] - pos[a], e21 = pos[c + 1] - pos[a + 1], e22 = pos[c + 2] - pos[a + 2];
      const n0 = e11 * e22 - e12 * e21, n1 = e12 * e20 - e10 * e22, n2 = e10 * e21 - e11 * e20;
      out[a] += n0; out[a + 1] += n1; out[a + 2] += n2;
      out[b] += n0; out[b + 1] += n1; out[b + 2] += n2;
      out[c] += n0; out[c + 1] += n1; out[c + 2] += n2;
    }
    for (let v = 0; v < out.length; v += 3) {
      const len = Math.max(1e-15, Math.hypot(out[v], out[v + 1], out[v + 2]));
      out[v] /= len;
      out[v + 1] /= len;
      out[v + 2] /= len;
    }
  }

  // `inflate`: every vertex moved that far along its normal.
  inflate(s, pos, normal) {
    const amount = this.model.skin_inflate[s];
    if (!amount) return;
    for (let k = 0; k < pos.length; k++) pos[k] += amount * normal[k];
  }
}
