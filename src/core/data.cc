// Data storage generated from the field table: allocation and field views.
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "core/field_view.h"
#include "simlab/data.h"
#include "simlab/simlab.h"

namespace simlab {

namespace {

constexpr uint64_t kSaturated = std::numeric_limits<uint64_t>::max();

// a * b and a + b, saturating at kSaturated instead of wrapping.
uint64_t Mul(uint64_t a, uint64_t b) {
  uint64_t out = 0;
  return __builtin_mul_overflow(a, b, &out) ? kSaturated : out;
}
uint64_t Add(uint64_t a, uint64_t b) {
  uint64_t out = 0;
  return __builtin_add_overflow(a, b, &out) ? kSaturated : out;
}

// "16.0 GB", for the message.
std::string Gigabytes(uint64_t bytes) {
  if (bytes == kSaturated) return "more than 16 EB";
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f GB", static_cast<double>(bytes) / (1 << 30));
  return text;
}

}  // namespace

uint64_t StackDoubles(const Model& m) {
  // Vectors of the state's sizes for every stage...
  uint64_t states = static_cast<uint64_t>(m.nq) + m.nv + m.na + m.nbody + m.nu;
  uint64_t rest = Add(Mul(16, states), 64);
  if (m.opt.integrator != kIntegratorImplicit) return rest;
  // ...and for the implicit integrator the RNE derivative (engine/derivative.cc): 6 x nv
  // blocks for each body's velocity, acceleration and force and each dof's cdof_dot.
  uint64_t nv = m.nv, nbody = m.nbody, block = Mul(6, nv);
  uint64_t derivative = Mul(Add(Add(Mul(3, nbody), nv), 1), block);
  return Add(derivative, rest);
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
    total = Add(total, bytes);
    if (bytes > most) most = bytes, most_name = name;
  };
#define SIMLAB_X(type, name, rows, cols) count(#name, Mul(Mul(rows, cols), sizeof(type)));
  SIMLAB_DATA_FIELDS(SIMLAB_X)
#undef SIMLAB_X
  count("stack", Mul(StackDoubles(m), sizeof(double)));
  if (largest) *largest = most_name;
  if (largest_bytes) *largest_bytes = most;
  return total;
}

Data MakeData(const Model& m) {
  // The whole size first, within the budget of one Data (MuJoCo's "Invalid data: ...
  // too large" when its buffer cannot be sized).
  const char* largest = "";
  uint64_t largest_bytes = 0, total = DataBytes(m, &largest, &largest_bytes);
  if (total > kMaxDataBytes) {
    throw Error("Invalid data: " + std::string(largest) + " too large: the arrays of Data " +
                "need " + Gigabytes(total) + " (" + largest + " " + Gigabytes(largest_bytes) +
                "), over the " + Gigabytes(kMaxDataBytes) + " budget of one Data");
  }

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
