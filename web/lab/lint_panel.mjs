// The lab's lint panel: simlab lint's findings for the model (sim.lint(key), see
// include/simlab/lint.h), listed under a summary line; picking one marks its element in
// the 3D view (the body it acts on glows and is labelled with the check). lintBody is
// apart from the DOM so that node can test it.

import { actuatorPoint } from './labels.mjs';

// mjtEq: a joint equality.
const kEqJoint = 2;

// The body a finding's element sits on or acts on, or -1 (a keyframe, a tendon
// actuator, a default class...). model: the Model arrays named below, by name.
export function lintBody(model, finding) {
  const id = finding.id;
  if (id < 0) return -1;
  switch (finding.kind) {
    case 'geom': return model.geom_bodyid[id];
    case 'equality':
      return model.eq_type[id] === kEqJoint ? model.jnt_bodyid[model.eq_obj1id[id]] : -1;
    case 'actuator': {
      // (the body of the point the actuator is labelled at: its joint's, site's or own)
      const [array, index] = actuatorPoint(model, id) ?? [];
      const bodyOf = { xanchor: model.jnt_bodyid, site_xpos: model.site_bodyid };
      return array === undefined ? -1 : array === 'xpos' ? index : bodyOf[array][index];
    }
    default: return -1;
  }
}

// "2 warnings, 1 note", or "no findings".
export function lintSummary(findings) {
  const warnings = findings.filter((f) => f.severity === 'warning').length;
  const notes = findings.length - warnings;
  if (!findings.length) return 'no findings';
  const plural = (n, word) => `${n} ${word}${n === 1 ? '' : 's'}`;
  return `${plural(warnings, 'warning')}, ${plural(notes, 'note')}`;
}

// The panel: a <details> with the summary, and a row per finding (severity, element and
// line, the numbers, what it means, what to do); onPick(finding) when a row is clicked.
export function buildLintPanel(findings, onPick) {
  const panel = document.createElement('details');
  panel.className = 'simlab-lab-lint';
  const summary = panel.appendChild(document.createElement('summary'));
  summary.textContent = `lint: ${lintSummary(findings)}`;
  for (const finding of findings) {
    const row = panel.appendChild(document.createElement('div'));
    row.className = `simlab-lab-lint-finding simlab-lab-lint-${finding.severity}`;
    const head = row.appendChild(document.createElement('div'));
    head.className = 'head';
    head.textContent = `${finding.severity}: ${finding.element} [${finding.check}] ` +
      `(${finding.file}:${finding.line})`;
    for (const [className, text] of [['numbers', finding.numbers], ['meaning', finding.meaning],
                                     ['advice', `fix: ${finding.advice}`]]) {
      const line = row.appendChild(document.createElement('div'));
      line.className = className;
      line.textContent = text;
    }
    row.addEventListener('click', () => onPick(finding, row));
  }
  return panel;
}
