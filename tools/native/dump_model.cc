// Every compiled mjModel array, size, option and statistic of one model, as JSON, from a
// native MuJoCo build: the reference for models the WebAssembly oracle cannot compile
// (it crashes on <compiler fusestatic>). tools/dump_model.mjs --native runs it and keeps
// the fields of a compiler golden.
//
//   g++ -std=c++17 -O1 tools/native/dump_model.cc -I$MJ/src/include -L$MJ/build/lib \
//       -Wl,-rpath,$MJ/build/lib -lmujoco -o /tmp/dump_model_native
//   /tmp/dump_model_native MODEL.xml
//
// ($MJ: a tree built by ../shared/oracle/native/build.sh.)
#include <cstdio>
#include <type_traits>

#include <mujoco/mujoco.h>
#include <mujoco/mjxmacro.h>

namespace {

// A number as JSON: integers exactly, reals with round-trip precision.
template <typename T>
void PrintNumber(T v) {
  if constexpr (std::is_floating_point_v<T>) {
    std::printf("%.17g", static_cast<double>(v));
  } else {
    std::printf("%lld", static_cast<long long>(v));
  }
}

// "name":[values] of one array, with a separator before all but the first.
template <typename T>
void PrintArray(bool* first, const char* name, const T* values, long long count) {
  std::printf("%s\"%s\":[", *first ? "" : ",", name);
  for (long long i = 0; i < count; i++) {
    if (i) std::printf(",");
    PrintNumber(values[i]);
  }
  std::printf("]");
  *first = false;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s MODEL.xml\n", argv[0]);
    return 2;
  }
  char error[1000] = "";
  mjModel* m = mj_loadXML(argv[1], nullptr, error, sizeof(error));
  if (!m) {
    std::fprintf(stderr, "MuJoCo does not load %s: %s\n", argv[1], error);
    return 1;
  }
  std::printf("{\"engine\":\"mujoco %s native\",\"sizes\":{", mj_versionString());
  bool first = true;
#define X(name)                                                    \
  std::printf("%s\"%s\":%lld", first ? "" : ",", #name, (long long)m->name); \
  first = false;
  MJMODEL_SIZES
#undef X
  std::printf("},\"arrays\":{");
  first = true;
  MJMODEL_POINTERS_PREAMBLE(m)
#define X(type, name, rows, cols) \
  PrintArray(&first, #name, m->name, (long long)(m->rows) * (cols));
#define MJ_M(n) n
  MJMODEL_POINTERS
#undef X
  std::printf("},\"opt\":{");
  first = true;
#define X(type, name, count) PrintArray(&first, #name, &m->opt.name, count);
#define XVEC(type, name, count) PrintArray(&first, #name, m->opt.name, count);
  MJOPTION_FIELDS
#undef X
#undef XVEC
  std::printf("},\"stat\":{\"meaninertia\":");
  PrintNumber(m->stat.meaninertia);
  std::printf("}}\n");
  mj_deleteModel(m);
  return 0;
}
