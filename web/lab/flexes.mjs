// Flexes in the lab's view, drawn from the engine's flexvert_xpos every frame: a cable
// (dim 1) as line segments between its vertices, a cloth (dim 2) as its triangles, a
// soft body (dim 3) as its shell (the faces no two tetrahedra share). Normals follow the
// deformed surface; flatskin flexes are shaded per face.
import * as THREE from '../node_modules/three/build/three.module.js';

// MuJoCo hides flex groups 3 and up by default, as geom groups.
const kVisibleGroups = 3;

// The triangles (or segments) to draw of flex f, as vertex ids within the flex.
function flexIndices(model, f) {
  const dim = model.flex_dim[f];
  if (dim === 1) {
    const adr = model.flex_elemdataadr[f], n = 2 * model.flex_elemnum[f];
    return Array.from(model.flex_elem.subarray(adr, adr + n));
  }
  if (dim === 2) {
    const adr = model.flex_elemdataadr[f], n = 3 * model.flex_elemnum[f];
    return Array.from(model.flex_elem.subarray(adr, adr + n));
  }
  const adr = model.flex_shelldataadr[f], n = 3 * model.flex_shellnum[f];
  return adr < 0 ? [] : Array.from(model.flex_shell.subarray(adr, adr + n));
}

// The flex's colour: its material's, else its rgba.
function flexColor(model, f) {
  const mat = model.flex_matid[f];
  return mat >= 0 ? model.mat_rgba.subarray(4 * mat, 4 * mat + 4) : model.flex_rgba.subarray(4 * f, 4 * f + 4);
}

export class Flexes {
  // One three.js object per visible flex.
  constructor(scene, model) {
    this.model = model;
    this.items = [];
    const count = model.flex_dim?.length ?? 0;
    for (let f = 0; f < count; f++) {
      if (model.flex_group[f] >= kVisibleGroups) continue;
      const index = flexIndices(model, f);
      if (!index.length) continue;
      const vertnum = model.flex_vertnum[f];
      const geometry = new THREE.BufferGeometry();
      geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(3 * vertnum), 3));
      geometry.setIndex(index);
      const rgba = flexColor(model, f);
      const color = new THREE.Color(rgba[0], rgba[1], rgba[2]);
      let object;
      if (model.flex_dim[f] === 1) {
        object = new THREE.LineSegments(geometry, new THREE.LineBasicMaterial({ color }));
      } else {
        const material = new THREE.MeshPhongMaterial({
          color, opacity: rgba[3], transparent: rgba[3] < 1, side: THREE.DoubleSide, shininess: 30,
          flatShading: !!model.flex_flatskin[f],
        });
        object = new THREE.Mesh(geometry, material);
        object.castShadow = rgba[3] >= 1;
        object.receiveShadow = true;
      }
      object.frustumCulled = false;
      scene.add(object);
      this.items.push({ f, object });
    }
  }

  // Moves every flex's vertices to flexvert_xpos (3 per vertex, all flexes in turn).
  update(flexvertXpos) {
    if (!flexvertXpos) return;
    for (const { f, object } of this.items) {
      const position = object.geometry.attributes.position;
      const adr = 3 * this.model.flex_vertadr[f];
      position.array.set(flexvertXpos.subarray(adr, adr + position.array.length));
      position.needsUpdate = true;
      if (this.model.flex_dim[f] > 1) object.geometry.computeVertexNormals();
    }
  }

  // Whether there is anything to draw (the lab reads flexvert_xpos only then).
  get any() {
    return this.items.length > 0;
  }
}
