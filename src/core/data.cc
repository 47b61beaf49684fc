// Data storage generated from the field table: allocation and field views.
#include <algorithm>
#include <string>
#include <vector>

#include "core/field_view.h"
#include "engine/engine.h"
#include "mjcf/limits.h"
#include "simlab/data.h"
#include "simlab/simlab.h"

namespace simlab {

using mjcf::AddBytes;
using mjcf::MulBytes;

uint64_t StackDoubles(const Model& m) {
  // Vectors of the state's sizes for every stage...
  uint64_t states = static_cast<uint64_t>(m.nq) + m.nv + m.na + m.nbody + m.nu;
  uint64_t rest = AddBytes(MulBytes(16, states), 64);
  // ...and a flex's elastic forces (engine/flex_elasticity.cc): 3 per vertex and 1 per
  // edge, or 15 per node, and 6 nv for forces applied at points.
  uint64_t flex = 0;
  for (int f = 0; f < m.nflex; f++) {
    uint64_t elements = AddBytes(MulBytes(3, m.flex_vertnum[f]), m.flex_edgenum[f]);
    flex = std::max({flex, elements, MulBytes(15, m.flex_nodenum[f])});
  }
  if (m.nflex) rest = AddBytes(rest, AddBytes(flex, MulBytes(6, m.nv)));
  if (m.opt.integrator != kIntegratorImplicit) return rest;
  // ...and for the implicit integrator the RNE derivative (engine/derivative.cc): 6-row
  // blocks over the body-dof pattern B for each body's velocity, acceleration and force,
  // over its body's row of B for each dof's cdof_dot, and one of 6 nv.
  uint64_t bodies = MulBytes(18, static_cast<uint64_t>(m.nB));
  uint64_t derivative = AddBytes(AddBytes(bodies, DofBlockOffsets(m, nullptr)), MulBytes(6, m.nv));
  return AddBytes(derivative, rest);
}

uint64_t DataBytes(const Model& m, const char** largest, uint64_t* largest_bytes) {
  // Sizes named in the table resolve to the model's sizes.
#define SIMLAB_X(size) [[maybe_unused]] const uint64_t size = static_cast<uint64_t>(m.size);
  SIMLAB_MODEL_SIZES(SIMLAB_X)
#undef SIMLAB_X
  // Every array of the table, then the stack.
  uint64_t total = 0, most = 0;
  const char* most_name = "";
  auto count = [&](const char* name, uint64_t bytes) {
    total = AddBytes(total, bytes);
    if (bytes > most) most = bytes, most_name = name;
  };
#define SIMLAB_X(type, name, rows, cols) count(#name, MulBytes(MulBytes(rows, cols), sizeof(type)));
  SIMLAB_DATA_FIELDS(SIMLAB_X)
#undef SIMLAB_X
  count("stack", MulBytes(StackDoubles(m), sizeof(double)));
  if (largest) *largest = most_name;
  if (largest_bytes) *largest_bytes = most;
  return total;
}

std::string DataOverBudget(const Model& m) {
  const char* largest = "";
  uint64_t largest_bytes = 0, total = DataBytes(m, &largest, &largest_bytes);
  if (total <= kMaxDataBytes) return "";
  return std::string(largest) + " too large: the model's Data would need " +
         mjcf::ByteSize(total) + " (" + largest + " " + mjcf::ByteSize(largest_bytes) +
         "), over the " + mjcf::ByteSize(kMaxDataBytes) + " budget of one Data";
}

Data MakeData(const Model& m) {
  // The whole size first (MuJoCo's "Invalid data: ... too large" when its buffer cannot
  // be sized).
  std::string over = DataOverBudget(m);
  if (!over.empty()) throw Error("Invalid data: " + over);

  // Sizes named in the table resolve to the model's sizes.
#define SIMLAB_X(size) [[maybe_unused]] const int size = m.size;
  SIMLAB_MODEL_SIZES(SIMLAB_X)
#undef SIMLAB_X
  Data d;
#define SIMLAB_X(type, name, rows, cols) d.name.assign(static_cast<size_t>(rows) * (cols), type{});
  SIMLAB_DATA_FIELDS(SIMLAB_X)
#undef SIMLAB_X
  d.moment_rownnz.assign(static_cast<size_t>(m.nout), 0);
  d.moment_colind.assign(static_cast<size_t>(m.nout) * m.nv, 0);
  d.ten_J_rownnz.assign(static_cast<size_t>(m.ntendon), 0);
  d.ten_J_colind.assign(static_cast<size_t>(m.ntendon) * m.nv, 0);
  InitPlugins(m, d);
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
