// Fixed tendons: a linear combination of joint positions, L = sum coef_i q_i.
#include <string>

#include "compiler/compiler.h"
#include "mjcf/error.h"

namespace simlab::compiler {

using mjcf::kAuto;
using mjcf::kTrue;
using mjcf::ThrowAt;

namespace {

bool Limited(const mjcf::CompilerSpec& c, const mjcf::Source& src, int limited,
             const std::array<double, 2>& range, const char* attr) {
  bool hasrange = !(range[0] == 0 && range[1] == 0);
  if (limited == kAuto && !c.autolimits && hasrange) {
    ThrowAt(src, std::string("has ") + attr + "range but not " + attr +
                     "limited; set autolimits=\"true\" in <compiler> or set " + attr + "limited");
  }
  return limited == kTrue || (limited == kAuto && range[0] < range[1]);
}

// Checks and copies one tendon's scalar fields.
void TendonFields(const mjcf::CompilerSpec& c, const mjcf::TendonSpec& t, int i, Model* m) {
  m->tendon_limited[i] = Limited(c, t.src, t.limited, t.range, "");
  if (m->tendon_limited[i] && t.range[0] >= t.range[1]) ThrowAt(t.src, "invalid tendon range");
  m->tendon_actfrclimited[i] = Limited(c, t.src, t.actfrclimited, t.actfrcrange, "actuatorfrc");
  if (m->tendon_actfrclimited[i] &&
      (t.actfrcrange[0] >= t.actfrcrange[1] || t.actfrcrange[0] > 0 || t.actfrcrange[1] < 0)) {
    ThrowAt(t.src, "invalid actuatorfrcrange");
  }
  if (t.springlength[0] > t.springlength[1]) ThrowAt(t.src, "invalid springlength");
  for (int k = 0; k < 2; k++) {
    m->tendon_range[2 * i + k] = t.range[k];
    m->tendon_actfrcrange[2 * i + k] = t.actfrcrange[k];
    m->tendon_lengthspring[2 * i + k] = t.springlength[k];
  }
  for (int k = 0; k < kNRef; k++) {
    m->tendon_solref_lim[kNRef * i + k] = t.solref_limit[k];
    m->tendon_solref_fri[kNRef * i + k] = t.solref_friction[k];
  }
  for (int k = 0; k < kNImp; k++) {
    m->tendon_solimp_lim[kNImp * i + k] = t.solimp_limit[k];
    m->tendon_solimp_fri[kNImp * i + k] = t.solimp_friction[k];
  }
  m->tendon_margin[i] = t.margin;
  m->tendon_stiffness[i] = t.stiffness;
  m->tendon_damping[i] = t.damping;
  m->tendon_armature[i] = t.armature;
  m->tendon_frictionloss[i] = t.frictionloss;
  m->tendon_names[i] = t.src.name;
}

}  // namespace

void CompileTendons(const mjcf::ModelSpec& spec, const CompileState& state, Model* m) {
  std::vector<std::string> joint_names;
  for (const JointState& j : state.joints) joint_names.push_back(j.spec->src.name);
  int adr = 0;
  for (int i = 0; i < m->ntendon; i++) {
    const mjcf::TendonSpec& t = spec.tendons[i];
    if (t.wraps.empty()) ThrowAt(t.src, "a tendon path cannot be empty");
    if (!t.src.name.empty() && FindName(m->tendon_names, t.src.name) >= 0) {
      ThrowAt(t.src, "repeated tendon name '" + t.src.name + "'");
    }
    TendonFields(spec.compiler, t, i, m);

    // Path: one joint wrap per coefficient.
    m->tendon_adr[i] = adr;
    m->tendon_num[i] = static_cast<int>(t.wraps.size());
    for (const mjcf::WrapSpec& w : t.wraps) {
      int jid = FindName(joint_names, w.joint);
      if (jid < 0) ThrowAt(w.src, "unknown joint '" + w.joint + "'");
      m->wrap_type[adr] = 1;  // mjWRAP_JOINT
      m->wrap_objid[adr] = jid;
      m->wrap_prm[adr] = w.coef;
      adr++;
    }
  }
}

}  // namespace simlab::compiler
