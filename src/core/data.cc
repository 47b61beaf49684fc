// Data storage generated from the field table: allocation and field views.
#include <vector>

#include "core/field_view.h"
#include "simlab/data.h"
#include "simlab/simlab.h"

namespace simlab {

Data MakeData(const Model& m) {
  // Sizes named in the table resolve to the model's sizes.
#define SIMLAB_X(size) [[maybe_unused]] const int size = m.size;
  SIMLAB_MODEL_SIZES(SIMLAB_X)
#undef SIMLAB_X
  Data d;
#define SIMLAB_X(type, name, rows, cols) d.name.assign(static_cast<size_t>(rows) * (cols), type{});
  SIMLAB_DATA_FIELDS(SIMLAB_X)
#undef SIMLAB_X
  ResetData(m, d);
  return d;
}

std::vector<FieldView> DataFields(const Model& m, Data& d) {
#define SIMLAB_X(size) [[maybe_unused]] const int size = m.size;
  SIMLAB_MODEL_SIZES(SIMLAB_X)
#undef SIMLAB_X
  std::vector<FieldView> fields;
#define SIMLAB_X(type, name, rows, cols) fields.push_back(MakeFieldView(#name, #rows, #cols, d.name, rows, cols));
  SIMLAB_DATA_FIELDS(SIMLAB_X)
#undef SIMLAB_X
  return fields;
}

}  // namespace simlab
