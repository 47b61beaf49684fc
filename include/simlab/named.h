// Named access: one object's rows of the Model and Data arrays, by its name or id.
//
// MuJoCo's Python bindings give `model.actuator("grip").gainprm` and
// `data.joint("finger").qpos`; these are the same views in C++, generated from the field
// tables (model.h, data.h) rather than written out per field:
//
//   simlab::Named grip = simlab::ModelObject(m, simlab::kObjActuator, "gripper/grip");
//   double kp = grip["gainprm"][0];
//   simlab::Named finger = simlab::DataObject(m, d, simlab::kObjJoint, "gripper/finger_left");
//   double q = finger["qpos"][0];
//
// A field belongs to a kind's view when its rows count that kind's objects (actuator_*
// arrays have nactuator rows); its attribute name is the field name without the kind's prefix
// ("actuator_gainprm" -> "gainprm", "geom_xpos" -> "xpos", "ten_length" -> "length").
// Joints also see the qpos-sized and dof-sized arrays, sliced at jnt_qposadr/jnt_dofadr;
// actuators their controls (nu-sized: ctrl, ctrlrange) at actuator_ctrladr and their
// force outputs (nout-sized: force, length, gear) at actuator_outadr;
// sensors see their sensor_dim numbers of sensordata as "data"; height fields their
// elevation grid. Views point into the arrays: writes go through.
#ifndef SIMLAB_NAMED_H_
#define SIMLAB_NAMED_H_

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "simlab/data.h"
#include "simlab/model.h"
#include "simlab/simlab.h"

namespace simlab {

// No object of that kind has the name (Python: KeyError).
class UnknownName : public Error {
 public:
  using Error::Error;
};

// An object index or attribute outside what exists (Python: IndexError/AttributeError).
class BadIndex : public Error {
 public:
  using Error::Error;
};

// One attribute of a named object: its slice of one Model or Data array.
struct Slice {
  std::string attr;           // the attribute ("gainprm")
  const char* field = "";     // the array it slices ("actuator_gainprm")
  bool is_int = false;
  double* doubles = nullptr;  // first element (double arrays)
  int* ints = nullptr;        // first element (int arrays)
  int ndim = 1;               // 1: shape[0] numbers; 2: shape[0] x shape[1]
  int shape[2] = {0, 0};

  size_t size() const { return static_cast<size_t>(shape[0]) * (ndim == 2 ? shape[1] : 1); }
  // The numbers of a double slice; throws BadIndex for an int slice.
  std::span<double> Doubles() const;
  // The numbers of an int slice; throws BadIndex for a double slice.
  std::span<int> Ints() const;
  // Element k of a double slice (flat, row-major); throws BadIndex when out of range.
  double& operator[](size_t k) const;
};

// A named object's view: its id, name and attributes.
class Named {
 public:
  Named(ObjType kind, int id, std::string name, std::vector<Slice> slices)
      : kind_(kind), id_(id), name_(std::move(name)), slices_(std::move(slices)) {}

  ObjType kind() const { return kind_; }
  int id() const { return id_; }
  const std::string& name() const { return name_; }
  // Every attribute, in the order of the field table.
  const std::vector<Slice>& attributes() const { return slices_; }
  // The attribute `attr`, or null.
  const Slice* Find(std::string_view attr) const;
  // The attribute `attr`; throws BadIndex naming the attributes there are.
  const Slice& operator[](std::string_view attr) const;

 private:
  ObjType kind_;
  int id_;
  std::string name_;
  std::vector<Slice> slices_;
};

// The kinds with views into Model (actuator, body, camera, equality, exclude, geom,
// hfield, joint, mesh, pair, sensor, site, tendon, key) and into Data (actuator, body,
// camera, geom, joint, sensor, site, tendon), as MuJoCo's bindings have them.
std::span<const ObjType> ModelViewKinds();
std::span<const ObjType> DataViewKinds();

// MuJoCo's Python name of a kind's view ("actuator", "body", "cam", "eq", "jnt", "key"...)
// and its alternative name ("camera", "equality", "joint", "keyframe"; "ten" in Data), or "".
const char* ViewName(ObjType kind);
const char* ViewAltName(ObjType kind, bool data);

// Object `id` (or the object named `name`) of `kind` as a Model view. Throws UnknownName
// for a name that no object has, BadIndex for an id out of range or a kind without view.
Named ModelObject(Model& m, ObjType kind, int id);
Named ModelObject(Model& m, ObjType kind, const std::string& name);
// The same for Data (the model gives the slicing).
Named DataObject(const Model& m, Data& d, ObjType kind, int id);
Named DataObject(const Model& m, Data& d, ObjType kind, const std::string& name);

// The id of the object of `kind` named `name`; throws UnknownName (listing the names
// there are) when none has it.
int IdOf(const Model& m, ObjType kind, const std::string& name);

}  // namespace simlab

#endif  // SIMLAB_NAMED_H_
