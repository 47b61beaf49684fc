"""Ray casting with mj_ray: geom groups, static geoms, excluded bodies, normals, misses.

MuJoCo 3.5's Python signature is
    mj_ray(m, d, pnt, vec, geomgroup, flg_static, bodyexclude, geomid, normal=None)
with geomgroup None or 6 uint8 flags, geomid an int32 array of shape (1,) (or None) and
normal a float64 array of shape (3,); it returns the distance along vec (in units of
|vec|), or -1 with geomid -1 when nothing is hit.

Prints one JSON object. goldens/ray_cast.json holds what MuJoCo 3.5.1 prints.
"""
import json

import numpy as np

import simlab as mujoco

# A floor, a fixed pillar (static, in group 2), a box on a hinge (group 0) and a sphere
# in group 1 hanging off the box's body.
XML = """
<mujoco model="rays">
  <worldbody>
    <geom name="floor" type="plane" size="2 2 0.1"/>
    <geom name="pillar" type="cylinder" size="0.05 0.3" pos="0.5 0 0.3" group="2"/>
    <body name="lid" pos="0 0 0.4">
      <joint name="tilt" type="hinge" axis="1 0 0"/>
      <geom name="lid" type="box" size="0.2 0.15 0.02"/>
      <geom name="bead" type="sphere" size="0.05" pos="0 0.3 0" group="1"/>
    </body>
  </worldbody>
</mujoco>
"""

model = mujoco.MjModel.from_xml_string(XML)
data = mujoco.MjData(model)
data.joint("tilt").qpos = 0.3
mujoco.mj_forward(model, data)
lid = model.body("lid").id

geomid = np.zeros(1, dtype=np.int32)
normal = np.zeros(3)


def cast(pnt, vec, geomgroup, flg_static, bodyexclude):
    """One ray with normal output: distance, the geom hit (by name) and its normal."""
    dist = mujoco.mj_ray(model, data, np.array(pnt, dtype=float), np.array(vec, dtype=float),
                         geomgroup, flg_static, bodyexclude, geomid, normal)
    name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, int(geomid[0]))
    return [dist, int(geomid[0]), name, normal.tolist()]


all_groups = None
groups_0_1 = np.array([1, 1, 0, 0, 0, 0], dtype=np.uint8)
group_0 = np.array([1, 0, 0, 0, 0, 0], dtype=np.uint8)
group_1 = np.array([0, 1, 0, 0, 0, 0], dtype=np.uint8)
out = {"rays": {
    # Straight down onto the tilted lid; then with the lid's body excluded: the floor.
    "down_lid": cast([0.05, 0.02, 1.0], [0, 0, -1], all_groups, 1, -1),
    "down_excluded": cast([0.05, 0.02, 1.0], [0, 0, -1], all_groups, 1, lid),
    # The same ray without static geoms (the floor is static): nothing is hit.
    "down_no_static": cast([0.05, 0.02, 1.0], [0, 0, -1], all_groups, 0, lid),
    # A vector of length 2: the distance is in units of |vec|.
    "down_long_vec": cast([0.05, 0.02, 1.0], [0, 0, -2], all_groups, 1, -1),
    # Sideways at the pillar (group 2) with and without its group enabled.
    "pillar_all": cast([1.0, 0.0, 0.2], [-1, 0, 0], all_groups, 1, -1),
    "pillar_masked": cast([1.0, 0.0, 0.2], [-1, 0, 0], groups_0_1, 1, -1),
    # At the bead from below, slanted: with group 1 only, then with group 0 only.
    "bead": cast([0.0, 0.5, 0.1], [0, -0.2, 0.4], group_1, 1, -1),
    "bead_masked": cast([0.0, 0.5, 0.1], [0, -0.2, 0.4], group_0, 1, -1),
    # Upward from above everything: a miss.
    "miss": cast([0.0, 0.0, 2.0], [0, 0, 1], all_groups, 1, -1),
}}

# The normal argument may be omitted.
dist = mujoco.mj_ray(model, data, np.array([0.05, 0.02, 1.0]), np.array([0.0, 0.0, -1.0]),
                     None, 1, -1, geomid)
out["no_normal"] = [dist, int(geomid[0])]

# The lid's geoms for reference.
out["lid_xpos"] = data.geom("lid").xpos.tolist()
out["lid_xmat"] = data.geom("lid").xmat.tolist()

print(json.dumps(out))
