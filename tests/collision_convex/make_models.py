#!/usr/bin/env python3
"""Writes the convex-pair models of tests/collision_convex_test.cc: one fixed geom A in
the world, one free geom B, and keyframes placing B at random poses around A (deep,
shallow and no contact). Deterministic (seeded); rerun make_goldens.sh afterwards.

    python3 tests/collision_convex/make_models.py
"""
import math
import os
import random

HERE = os.path.dirname(os.path.abspath(__file__))

# geom type -> (size attribute, bounding radius)
SHAPES = {
    'sphere': ('0.1', 0.1),
    'capsule': ('0.08 0.15', 0.23),
    'ellipsoid': ('0.1 0.15 0.2', 0.2),
    'cylinder': ('0.1 0.15', math.hypot(0.1, 0.15)),
    'box': ('0.1 0.15 0.2', math.sqrt(0.01 + 0.0225 + 0.04)),
    'mesh': (None, 0.19),
}

# A small convex mesh (an irregular octahedron-like hull with 12 vertices).
MESH_VERTS = [
    (0.12, 0, 0), (-0.1, 0.02, 0), (0.01, 0.13, 0.01), (0, -0.11, 0.02), (0.02, 0, 0.15),
    (0, 0.01, -0.12), (0.07, 0.07, 0.07), (-0.06, -0.06, 0.08), (0.07, -0.05, -0.07),
    (-0.06, 0.08, -0.06), (0.05, 0.08, -0.08), (-0.08, -0.03, -0.07),
]
# A box-like mesh with few vertices (exhaustive support search).
SMALL_MESH_VERTS = [(x * 0.08, y * 0.1, z * 0.06) for x in (-1, 1) for y in (-1, 1)
                    for z in (-1, 1)]

PAIRS = [
    # (name, A, B, options)
    ('plane_ellipsoid', 'plane', 'ellipsoid', {}),
    ('sphere_ellipsoid', 'sphere', 'ellipsoid', {}),
    ('capsule_ellipsoid', 'capsule', 'ellipsoid', {}),
    ('capsule_cylinder', 'capsule', 'cylinder', {}),
    ('ellipsoid_ellipsoid', 'ellipsoid', 'ellipsoid', {}),
    ('ellipsoid_cylinder', 'ellipsoid', 'cylinder', {}),
    ('ellipsoid_box', 'ellipsoid', 'box', {}),
    ('cylinder_cylinder', 'cylinder', 'cylinder', {}),
    ('cylinder_box', 'cylinder', 'box', {}),
    ('sphere_ellipsoid_margin', 'sphere', 'ellipsoid', {'margin': 0.02}),
    ('capsule_cylinder_margin', 'capsule', 'cylinder', {'margin': 0.01}),
    ('ellipsoid_cylinder_margin', 'ellipsoid', 'cylinder', {'margin': 0.015}),
    ('cylinder_box_margin', 'cylinder', 'box', {'margin': 0.01}),
    ('plane_ellipsoid_margin', 'plane', 'ellipsoid', {'margin': 0.02}),
    ('cylinder_box_multiccd', 'cylinder', 'box', {'multiccd': True}),
    ('capsule_cylinder_multiccd', 'capsule', 'cylinder', {'multiccd': True}),
    ('cylinder_cylinder_multiccd', 'cylinder', 'cylinder', {'multiccd': True}),
]
MESH_PAIRS = [
    ('plane_mesh', 'plane', 'mesh', {}),
    ('plane_mesh_small', 'plane', 'mesh', {'small': True}),
    ('sphere_mesh', 'sphere', 'mesh', {}),
    ('capsule_mesh', 'capsule', 'mesh', {}),
    ('ellipsoid_mesh', 'ellipsoid', 'mesh', {}),
    ('cylinder_mesh', 'cylinder', 'mesh', {}),
    ('box_mesh', 'box', 'mesh', {}),
    ('mesh_mesh', 'mesh', 'mesh', {}),
    ('box_mesh_small', 'box', 'mesh', {'small': True}),
    ('mesh_mesh_margin', 'mesh', 'mesh', {'margin': 0.01}),
    ('cylinder_mesh_multiccd', 'cylinder', 'mesh', {'multiccd': True}),
]


def random_quat(rng):
  u1, u2, u3 = rng.random(), rng.random(), rng.random()
  a, b = math.sqrt(1 - u1), math.sqrt(u1)
  return (a * math.sin(2 * math.pi * u2), a * math.cos(2 * math.pi * u2),
          b * math.sin(2 * math.pi * u3), b * math.cos(2 * math.pi * u3))


def random_dir(rng):
  while True:
    v = [rng.uniform(-1, 1) for _ in range(3)]
    n = math.sqrt(sum(x * x for x in v))
    if 0.1 < n <= 1:
      return [x / n for x in v]


def fmt(values):
  return ' '.join(f'{v:.6g}' for v in values)


def geom_xml(kind, opts, extra):
  margin = opts.get('margin')
  m = f' margin="{margin}"' if margin else ''
  if kind == 'plane':
    return f'<geom type="plane" size="0 0 1"{m}{extra}/>'
  if kind == 'mesh':
    mesh = 'small' if opts.get('small') else 'hull'
    return f'<geom type="mesh" mesh="{mesh}"{m}{extra}/>'
  return f'<geom type="{kind}" size="{SHAPES[kind][0]}"{m}{extra}/>'


def poses(rng, a, b, count):
  out = []
  for i in range(count):
    quat = random_quat(rng)
    if a == 'plane':
      # B's centre above or slightly below the plane
      height = SHAPES[b][1] * rng.uniform(-0.2, 1.1)
      pos = [rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3), height]
    else:
      reach = SHAPES[a][1] + SHAPES[b][1]
      scale = rng.uniform(0.15, 1.05) if i < count - 2 else rng.uniform(1.0, 1.4)
      pos = [x * reach * scale for x in random_dir(rng)]
    out.append((pos, quat))
  return out


def header(name, a, b, opts):
  lines = [f'<mujoco model="{name}">']
  if opts.get('multiccd'):
    lines.append('  <option><flag multiccd="enable"/></option>')
  if 'mesh' in (a, b):
    lines.append('  <asset>')
    lines.append(f'    <mesh name="hull" vertex="{fmt(sum(MESH_VERTS, ()))}"/>')
    lines.append(f'    <mesh name="small" vertex="{fmt(sum(SMALL_MESH_VERTS, ()))}"/>')
    lines.append('  </asset>')
  return lines


def model(name, a, b, opts, keyed):
  lines = header(name, a, b, opts)
  lines.append('  <worldbody>')
  a_orient = '' if a == 'plane' else ' euler="20 -35 50"'
  lines.append('    ' + geom_xml(a, opts, a_orient))
  lines.append('    <body name="b">')
  lines.append('      <freejoint/>')
  lines.append('      ' + geom_xml(b, opts, ''))
  lines.append('    </body>')
  lines.append('  </worldbody>')
  lines.append('  <keyframe>')
  lines.extend(f'    <key qpos="{fmt(pos + list(quat))}"/>' for pos, quat in keyed)
  lines.append('  </keyframe>')
  lines.append('</mujoco>')
  return '\n'.join(lines) + '\n'


# The same poses as one scene for tests/collision_pairs (the whole driver): case i puts
# geom A at x = 3 i (planes: one plane for all) and geom B at its keyed pose from there.
def scene(name, a, b, opts, keyed):
  lines = [f'<!-- {a} : {b}, the random poses of tests/collision_convex/models/{name}.xml -->']
  lines += header(name + '_gjk', a, b, opts)
  lines.append('  <worldbody>')
  if a == 'plane':
    lines.append('    ' + geom_xml(a, opts, ''))
  for i, (pos, quat) in enumerate(keyed):
    x = 3 * i
    if a != 'plane':
      lines.append(f'    <body name="c{i}_a" pos="{x} 0 0" euler="20 -35 50"><freejoint/>'
                   + geom_xml(a, opts, '') + '</body>')
    where = fmt([pos[0] + x, pos[1], pos[2]])
    lines.append(f'    <body name="c{i}_b" pos="{where}" quat="{fmt(quat)}"><freejoint/>'
                 + geom_xml(b, opts, '') + '</body>')
  lines.append('  </worldbody>')
  lines.append('</mujoco>')
  return '\n'.join(lines) + '\n'


def main():
  rng = random.Random(20260905)
  pairs_dir = os.path.join(HERE, '..', 'collision_pairs', 'models')
  for name, a, b, opts in PAIRS + MESH_PAIRS:
    keyed = poses(rng, a, b, 16)
    with open(os.path.join(HERE, 'models', name + '.xml'), 'w') as f:
      f.write(model(name, a, b, opts, keyed))
    with open(os.path.join(pairs_dir, name + '_gjk.xml'), 'w') as f:
      f.write(scene(name, a, b, opts, keyed))


if __name__ == '__main__':
  main()
