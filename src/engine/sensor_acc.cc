// Sensors that read quantities computed on demand (MuJoCo engine_sensor.c): the
// acceleration-stage accelerometer, force, torque, framelinacc and frameangacc (from
// cacc and cfrc_int), the velocity-stage subtreelinvel and subtreeangmom, and the
// position-stage energies. Each asks for its quantity only when this step has not computed it yet,
// so RnePostConstraint runs at most once per step and only in models with such sensors.
#include "engine/engine.h"
#include "engine/sensor.h"
#include "math/math.h"

namespace simlab {

namespace {

void EnsureRnePost(const Model& m, Data& d) {
  if (!d.flg_rnepost) RnePostConstraint(m, d);
}

}  // namespace

// The site's linear acceleration in its own frame, gravity included (a body at rest
// reads -gravity: the world's acceleration of +g in cacc).
void AccelerometerSensor(const Model& m, Data& d, int i, double* out) {
  EnsureRnePost(m, d);
  double acc[6];
  ObjectAcceleration(m, d, kObjSite, m.sensor_objid[i], acc, true);
  math::Copy3(out, acc + 3);
}

// force / torque: cfrc_int of the site's body (what its parent exerts on the subtree
// rooted there), moved to the site and expressed in the site's frame.
void ForceTorqueSensor(const Model& m, Data& d, int i, double* out) {
  EnsureRnePost(m, d);
  int site = m.sensor_objid[i];
  int body = m.site_bodyid[site];
  double wrench[6];
  math::TransformSpatial(wrench, &d.cfrc_int[6 * body], true, &d.site_xpos[3 * site],
                         &d.subtree_com[3 * m.body_rootid[body]], &d.site_xmat[9 * site]);
  math::Copy3(out, m.sensor_type[i] == kSensForce ? wrench + 3 : wrench);
}

// framelinacc / frameangacc: the object's acceleration at its position, world-oriented.
void FrameAccSensor(const Model& m, Data& d, int i, double* out) {
  EnsureRnePost(m, d);
  double acc[6];
  ObjectAcceleration(m, d, m.sensor_objtype[i], m.sensor_objid[i], acc, false);
  math::Copy3(out, m.sensor_type[i] == kSensFrameLinAcc ? acc + 3 : acc);
}

// subtreelinvel / subtreeangmom of the sensor's body.
void SubtreeMomentumSensor(const Model& m, Data& d, int i, double* out) {
  if (!d.flg_subtreevel) SubtreeVel(m, d);
  const std::vector<double>& field =
      m.sensor_type[i] == kSensSubtreeLinVel ? d.subtree_linvel : d.subtree_angmom;
  math::Copy3(out, &field[3 * m.sensor_objid[i]]);
}

// e_potential / e_kinetic, both at the position stage (M and qvel are known by then).
void EnergySensor(const Model& m, Data& d, int i, double* out) {
  if (m.sensor_type[i] == kSensEPotential) {
    if (!d.flg_energypos) EnergyPos(m, d);
    out[0] = d.energy[0];
  } else {
    if (!d.flg_energyvel) EnergyVel(m, d);
    out[0] = d.energy[1];
  }
}

}  // namespace simlab
