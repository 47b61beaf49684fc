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

}  // namespace simlab

#endif  // SIMLAB_ENGINE_SENSOR_H_
