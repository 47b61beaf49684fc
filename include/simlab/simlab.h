// simlab: load an MJCF model, then simulate it exactly as MuJoCo does.
//
//   simlab::Model m = simlab::LoadXml("models/actuator_bench.xml");
//   simlab::Data d = simlab::MakeData(m);
//   simlab::Forward(m, d);          // all derived quantities for the current state
//   simlab::Step(m, d);             // advance by m.opt.timestep
//
// Loading throws simlab::Error (file, line, element, what is wrong). Simulating never
// throws: a diverging state, and an engine error inside Forward or a Step (an option set
// to a value that does not exist, say), are counted in d.warning, passed to
// d.warning_callback with their text, and the data is reset; the engine prints nothing.
#ifndef SIMLAB_SIMLAB_H_
#define SIMLAB_SIMLAB_H_

#include <map>
#include <span>
#include <stdexcept>
#include <string>

#include "simlab/data.h"
#include "simlab/model.h"

namespace simlab {

// A model that cannot be read or compiled. what() reads like
// "gantry.xml:42: <position name=\"grip\">: kp must be positive".
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Compile an MJCF file; included and attached files resolve relative to its folder.
Model LoadXml(const std::string& path);

// Compile MJCF text; `filename` names it in error messages and is the base folder
// for included files.
Model LoadXmlString(const std::string& xml, const std::string& filename = "<string>");

// Files given in memory: file name -> bytes (MjModel.from_xml_string's `assets`).
using Assets = std::map<std::string, std::string>;

// The same, reading included files, <model file="..."> and mesh files among `assets`
// before the disk, as MuJoCo's virtual file system: a file is matched by its base name,
// ignoring case, whatever the folders in the XML (meshdir too) or in the asset's name.
// Throws Error for two assets with the same base name (as "a.xml", "dir/A.xml").
Model LoadXmlString(const std::string& xml, const std::string& filename, const Assets& assets);

// Default state: qpos = qpos0, everything else zero, mocap poses from the model.
void ResetData(const Model& m, Data& d);

// Reset to keyframe `key` (as mj_resetDataKeyframe). Throws Error for a bad index.
void ResetDataKeyframe(const Model& m, Data& d, int key);

// The whole pipeline for the current state: positions, velocities, forces, qacc.
void Forward(const Model& m, Data& d);

// One step of the model's integrator (as mj_step).
void Step(const Model& m, Data& d);

// Step in two halves, so that inputs can depend on the positions and velocities:
// Step1 computes everything up to the velocity stage; set ctrl or qfrc_applied; Step2
// finishes the step (RK4 models integrate with Euler here, as in MuJoCo).
void Step1(const Model& m, Data& d);
void Step2(const Model& m, Data& d);

// Delays and sampling (nsample, delay, interp, interval of actuators and sensors).
// interp -1 uses the model's interpolation (0 hold, 1 linear, 2 cubic).
// Actuator `id`'s control as of `time` - its delay (as mj_readCtrl); ctrl itself if it
// has no history buffer. Throws Error for a bad id.
double ReadCtrl(const Model& m, const Data& d, int id, double time, int interp = -1);
// Sensor `id`'s value as of `time` - its delay into out (sensor_dim numbers, as
// mj_readSensor); its current sensordata if it has no history buffer.
void ReadSensor(const Model& m, const Data& d, int id, double time, double* out,
                int interp = -1);
// Overwrite an actuator's / sensor's history buffer with nsample strictly increasing
// times and nsample x dim values (either null keeps the buffer's own); a sensor's
// `phase` becomes its last interval tick (as mj_initCtrlHistory, mj_initSensorHistory).
void InitCtrlHistory(const Model& m, Data& d, int id, const double* times, const double* values);
void InitSensorHistory(const Model& m, Data& d, int id, const double* times,
                       const double* values, double phase);

// Id of a named object, or -1 (as mj_name2id).
int NameToId(const Model& m, ObjType type, const std::string& name);

// A sensor's id by name; throws Error if there is none (model.sensor("name").id).
int SensorId(const Model& m, const std::string& name);

// A sensor's output, sensor_dim numbers at sensor_adr in d.sensordata, by name
// (data.sensor("name").data); throws Error if there is none.
std::span<double> SensorData(const Model& m, Data& d, const std::string& name);

// MJCF names of enum values: a sensor type's element tag ("framepos"), an object type's
// keyword ("site"); "unknown" outside the enum.
const char* SensorTypeName(int type);
const char* ObjTypeName(int type);
// The object type an MJCF keyword ("joint"), or MuJoCo's field prefix or Python view name
// for it ("jnt", "cam", "eq", "keyframe"), names; kObjUnknown for none.
ObjType ObjTypeFromName(const std::string& name);

// What a warning means ("bad qacc (NaN or too large): simulation reset"), and the text
// passed to Data::warning_callback: that, its info and the time.
const char* WarningName(int warning);
std::string WarningText(int warning, int info, double time);

// The MuJoCo version whose semantics this engine follows.
const char* ReferenceVersion();

}  // namespace simlab

#endif  // SIMLAB_SIMLAB_H_
