// The warning channel (MuJoCo mj_warning and the bad-state checks of mj_step): warnings
// are counted in d.warning with their last info and passed to d.warning_callback; the
// engine prints nothing.
#include <cmath>
#include <string>
#include <vector>

#include "engine/engine.h"
#include "simlab/simlab.h"

namespace simlab {

namespace {

bool IsBad(double x) { return std::isnan(x) || x > kMaxVal || x < -kMaxVal; }

}  // namespace

void RaiseWarning(Data& d, Warning w, int info, const std::string& text) {
  d.warning[w].number++;
  d.warning[w].lastinfo = info;
  if (d.warning_callback) {
    d.warning_callback(d, w, info, text.empty() ? WarningText(w, info, d.time) : text);
  }
}

bool WarnAndResetIfBad(const Model& m, Data& d, const std::vector<double>& values, Warning w) {
  for (size_t i = 0; i < values.size(); i++) {
    if (!IsBad(values[i])) continue;
    RaiseWarning(d, w, static_cast<int>(i));
    // The reset clears the warnings: this one keeps its count.
    WarningStat kept = d.warning[w];
    if (!(m.opt.disableflags & kDisableAutoreset)) {
      ResetData(m, d);
      d.nreset++;
    }
    d.warning[w] = kept;
    return true;
  }
  return false;
}

}  // namespace simlab
