// Sensors (MuJoCo's engine_sensor.c): each stage of the pipeline ends by writing the
// sensors that need it into d.sensordata. sensor.cc runs the stages and the simple
// types; each family of sensors with more to compute lives in its own file and is
// called from the dispatch with the signature
//
//   void XxxSensor(const Model& m, Data& d, int i, double* out)
//
// writing sensor i's m.sensor_dim[i] numbers to `out`.
#ifndef SIMLAB_ENGINE_SENSOR_H_
#define SIMLAB_ENGINE_SENSOR_H_

#include "simlab/data.h"
#include "simlab/model.h"

namespace simlab {

// The sensors of each stage, after that stage of Forward (mj_sensorPos/Vel/Acc).
void SensorPos(const Model& m, Data& d);
void SensorVel(const Model& m, Data& d);
void SensorAcc(const Model& m, Data& d);

// One sensor's value at its stage, with its cutoff applied (mj_computeSensor).
void ComputeSensor(const Model& m, Data& d, int i, double* out);
// The same, or for a delayed sensor or an interval sensor between ticks its history
// buffer's value (history.cc, MuJoCo compute_or_read_sensor).
void ComputeOrReadSensor(const Model& m, Data& d, int i, double* out);

// The position and orientation of an object with a spatial frame (body inertial frame,
// body frame, geom, site, camera), and its body.
struct ObjectFrame {
  const double* pos = nullptr;
  const double* mat = nullptr;
  int body = 0;
};
ObjectFrame GetObjectFrame(const Model& m, const Data& d, int objtype, int objid);
// Its orientation as a quaternion.
void ObjectQuat(const Model& m, const Data& d, int objtype, int objid, double quat[4]);
// Its 6D velocity / acceleration (angular, linear) at its position, in the world's
// orientation or (local) its own (mj_objectVelocity, mj_objectAcceleration).
void ObjectVelocity(const Model& m, const Data& d, int objtype, int objid, double res[6],
                    bool local);
void ObjectAcceleration(const Model& m, const Data& d, int objtype, int objid, double res[6],
                        bool local);

// Geometric sensors (sensor_geometry.cc): camprojection; insidesite; distance, normal
// and fromto between two geoms or the geoms of two bodies.
void CamProjectionSensor(const Model& m, Data& d, int i, double* out);
void InsideSiteSensor(const Model& m, Data& d, int i, double* out);
void GeomDistanceSensor(const Model& m, Data& d, int i, double* out);
// Whether a world point lies strictly inside a shape (site or geom type and size) at
// pos/mat (MuJoCo's mju_insideGeom); used by insidesite and the contact sensor's site.
bool InsideShape(const double* pos, const double* mat, const double* size, int type,
                 const double* point);
// The smallest signed distance between two geoms, up to distmax, and the segment from
// geom1's nearest point to geom2's (zeros beyond distmax), by the narrow phase with
// distmax as margin (MuJoCo's mj_geomDistance). `con` holds kMaxContactPair contacts
// of scratch.
double GeomDistance(const Model& m, const Data& d, int geom1, int geom2, double distmax,
                    double fromto[6], Contact* con);

// Rangefinders (sensor_ray.cc): rays from a site along its z axis, or one per pixel of
// a camera, with the fields of the sensor's data mask.
void RangefinderSensor(const Model& m, Data& d, int i, double* out);

// Contact sensors (sensor_contact.cc): touch (normal forces whose ray meets a site's
// volume) and contact (matching contacts' fields per slot, sorted or netted).
void TouchSensor(const Model& m, Data& d, int i, double* out);
void ContactSensor(const Model& m, Data& d, int i, double* out);
// Tactile sensor (sensor_tactile.cc): a mesh's vertices as taxels on a geom; pressure and
// slip speeds of each taxel inside a primitive geom touching the geom's weld body.
void TactileSensor(const Model& m, Data& d, int i, double* out);

// Sensors of quantities computed on demand (sensor_acc.cc): accelerometer, force and
// torque, framelinacc/frameangacc (RnePostConstraint), subtreelinvel/subtreeangmom
// (SubtreeVel), e_potential/e_kinetic (EnergyPos/EnergyVel).
void AccelerometerSensor(const Model& m, Data& d, int i, double* out);
void ForceTorqueSensor(const Model& m, Data& d, int i, double* out);
void FrameAccSensor(const Model& m, Data& d, int i, double* out);
void SubtreeMomentumSensor(const Model& m, Data& d, int i, double* out);
void EnergySensor(const Model& m, Data& d, int i, double* out);

}  // namespace simlab

#endif  // SIMLAB_ENGINE_SENSOR_H_
