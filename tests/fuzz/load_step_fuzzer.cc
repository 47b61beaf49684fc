// libFuzzer target: the bytes are MJCF text, loaded, stepped and reset.
//
//   tools/fuzz.sh 60      # build with clang (build-fuzz/), make the seed corpus, fuzz 60 s
//   build-fuzz/load_step_fuzzer CRASH_FILE      # replay one input
//
// The outcomes that are fine: the loader refuses the text with simlab::Error (so does
// MakeData, for a model whose arrays would be too large), or the model loads and then
// steps, resets and steps again. Anything else is a finding: another exception from the
// loader, any exception from the engine (Step never throws for a model that loaded; see
// simlab.h), a crash, a sanitizer report, a timeout or running out of memory. Findings
// abort with a line naming the phase and the exception, so libFuzzer saves the input.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cxxabi.h>
#include <exception>
#include <new>
#include <optional>
#include <string>
#include <typeinfo>

#include "simlab/simlab.h"

namespace {

// Inputs larger than this are not run (and not added to the corpus): an MJCF file of a
// few kilobytes already reaches every part of the loader, and the cost of one input
// must stay bounded. tools/fuzz.sh passes a smaller -max_len.
constexpr size_t kMaxInputBytes = 64 * 1024;

// Steps per phase: enough for contacts to appear, integrators to run several times and
// a diverging state to be detected and reset, few enough to keep each input fast.
constexpr int kStepsAfterLoad = 20;
constexpr int kStepsAfterReset = 10;

// The file name the text is loaded as. Its folder does not exist, so an <include>,
// <model file> or mesh file named by a relative path is refused instead of being read
// from wherever the fuzzer happens to run.
constexpr char kFileName[] = "/nonexistent-simlab-fuzz/input.xml";

// The readable name of an exception's type ("std::out_of_range").
std::string TypeName(const std::type_info& type) {
  int status = 0;
  char* name = abi::__cxa_demangle(type.name(), nullptr, nullptr, &status);
  std::string out = status == 0 && name ? name : type.name();
  std::free(name);
  return out;
}

// Reports an exception that is a finding and aborts (libFuzzer saves the input).
[[noreturn]] void Finding(const char* phase, const std::string& kind, const char* what) {
  std::fprintf(stderr, "\n==simlab-fuzz== FINDING: %s threw %s: %s\n", phase, kind.c_str(),
               what);
  std::fflush(stderr);
  std::abort();
}

// Runs `body`; an exception escaping it is a finding for `phase`, except a
// simlab::Error when `refusal_ok` (the loader's answer to a bad file): then returns false.
template <typename F>
bool Guarded(const char* phase, F&& body, bool refusal_ok = false) {
  try {
    body();
    return true;
  } catch (const simlab::Error& e) {
    if (refusal_ok) return false;
    Finding(phase, "simlab::Error", e.what());
  } catch (const std::exception& e) {
    Finding(phase, TypeName(typeid(e)), e.what());
  } catch (...) {
    Finding(phase, "an exception of unknown type", "");
  }
}

void StepN(const simlab::Model& m, simlab::Data& d, int n) {
  for (int i = 0; i < n; ++i) simlab::Step(m, d);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* bytes, size_t size) {
  // -1: libFuzzer neither runs nor keeps inputs over the limit.
  if (size > kMaxInputBytes) return -1;
  const std::string xml(reinterpret_cast<const char*>(bytes), size);

  // Load: simlab::Error is the loader's answer to a bad file, and fine; so is a refusal
  // of MakeData, for a model too large to simulate.
  std::optional<simlab::Model> model;
  auto load = [&] { model.emplace(simlab::LoadXmlString(xml, kFileName)); };
  if (!Guarded("LoadXmlString", load, true)) return 0;
  const simlab::Model& m = *model;
  std::optional<simlab::Data> data;
  if (!Guarded("MakeData", [&] { data.emplace(simlab::MakeData(m)); }, true)) return 0;
  simlab::Data& d = *data;

  // Simulate, reset to the default state, simulate again; then, when the model has
  // keyframes, reset to one of them (chosen by the input's size, so that every keyframe
  // gets its turn across inputs) and simulate again. None of this may throw.
  Guarded("Step after load", [&] { StepN(m, d, kStepsAfterLoad); });
  Guarded("ResetData", [&] { simlab::ResetData(m, d); });
  Guarded("Forward after ResetData", [&] { simlab::Forward(m, d); });
  Guarded("Step after ResetData", [&] { StepN(m, d, kStepsAfterReset); });
  if (m.nkey > 0) {
    const int key = static_cast<int>(size % static_cast<size_t>(m.nkey));
    Guarded("ResetDataKeyframe", [&] { simlab::ResetDataKeyframe(m, d, key); });
    Guarded("Step after ResetDataKeyframe", [&] { StepN(m, d, kStepsAfterReset); });
  }
  return 0;
}
