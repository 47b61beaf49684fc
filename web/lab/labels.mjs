// Labels on the 3D view, as simulate's "label" option draws them: the name of every
// body, joint, geom, site, camera, light or actuator (its number when it has no name),
// written at where the object is now. Kept apart from the DOM's drawing so that node can
// test what is labelled where (labelKinds, labelTexts, labelPoint); SceneLabels places
// a pool of absolutely positioned elements over the canvas.

// The kinds that can be labelled: the Data array of each object's position (3 numbers
// per object) and the Model size that counts them. Bodies start at 1 (the world has no
// place to label); an actuator is labelled at its joint's anchor, or its site or body.
export const kLabelKinds = {
  body: { array: 'xpos', size: 'nbody', first: 1 },
  joint: { array: 'xanchor', size: 'njnt' },
  geom: { array: 'geom_xpos', size: 'ngeom' },
  site: { array: 'site_xpos', size: 'nsite' },
  camera: { array: 'cam_xpos', size: 'ncam' },
  light: { array: 'light_xpos', size: 'nlight' },
  actuator: { array: null, size: 'nu' },
};

// At most this many labels are drawn (a model of thousands of geoms stays responsive).
export const kMaxLabels = 400;

// mjtTrn numbers.
const kTrnJoint = 0, kTrnJointInParent = 1, kTrnSite = 4, kTrnBody = 5;

// The text of each object of `kind`: its name, or "<kind> <id>" without one.
// sizes: sim.sizes(); nameOf(kind, id): the object's name ('' when unnamed).
export function labelTexts(kind, sizes, nameOf) {
  const { size, first = 0 } = kLabelKinds[kind];
  const texts = [];
  for (let id = first; id < Math.min(sizes[size], first + kMaxLabels); id++) {
    texts.push({ id, text: nameOf(kind, id) || `${kind} ${id}` });
  }
  return texts;
}

// Where actuator `a` is labelled: [Data array, index] of its transmission's joint
// anchor, site or body position, or null (tendon transmissions have no single point).
export function actuatorPoint(model, a) {
  const type = model.actuator_trntype[a], target = model.actuator_trnid[2 * a];
  if (type === kTrnJoint || type === kTrnJointInParent) return ['xanchor', target];
  if (type === kTrnSite) return ['site_xpos', target];
  if (type === kTrnBody) return ['xpos', target];
  return null;
}

// Screen pixels (left, top) of a point at normalized device coordinates `ndc` ([x, y, z]
// as a camera projects it) on a view of width x height pixels, or null when the point is
// behind the camera or off the view.
export function labelPoint(ndc, width, height) {
  const [x, y, z] = ndc;
  if (!(z > -1 && z < 1) || Math.abs(x) > 1 || Math.abs(y) > 1) return null;
  return [(x + 1) / 2 * width, (1 - y) / 2 * height];
}

// The labels over a view: an element per label, made once and reused; hidden ones are
// not drawn.
export class SceneLabels {
  constructor(container) {
    this.layer = container.appendChild(document.createElement('div'));
    this.layer.className = 'simlab-lab-labels';
    this.elements = [];
  }

  // Shows `items` ({text, position: [x, y, z]} with position read now), each at
  // project(position) (normalized device coordinates), on a view of width x height pixels.
  draw(items, project, width, height) {
    while (this.elements.length < items.length) {
      const element = this.layer.appendChild(document.createElement('span'));
      element.className = 'simlab-lab-label';
      this.elements.push(element);
    }
    for (let i = 0; i < this.elements.length; i++) {
      const element = this.elements[i];
      const at = i < items.length ? labelPoint(project(items[i].position), width, height) : null;
      const display = at ? '' : 'none';
      if (element.style.display !== display) element.style.display = display;
      if (!at) continue;
      if (element.textContent !== items[i].text) element.textContent = items[i].text;
      element.style.transform = `translate(${at[0].toFixed(1)}px, ${at[1].toFixed(1)}px)`;
    }
  }

  clear() {
    this.draw([], null, 0, 0);
  }
}
