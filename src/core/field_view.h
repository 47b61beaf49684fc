// Building FieldViews over the vectors of Model and Data.
#ifndef SIMLAB_CORE_FIELD_VIEW_H_
#define SIMLAB_CORE_FIELD_VIEW_H_

#include <type_traits>
#include <vector>

#include "simlab/model.h"

namespace simlab {

template <typename T>
FieldView MakeFieldView(const char* name, const char* rows_name, const char* cols_name,
                        std::vector<T>& v, int rows, int cols) {
  FieldView f;
  f.name = name;
  f.rows_name = rows_name;
  f.cols_name = cols_name;
  f.rows = rows;
  f.cols = cols;
  if constexpr (std::is_same_v<T, int>) {
    f.is_int = true;
    f.ints = v.data();
  } else {
    f.doubles = v.data();
  }
  return f;
}

}  // namespace simlab

#endif  // SIMLAB_CORE_FIELD_VIEW_H_
