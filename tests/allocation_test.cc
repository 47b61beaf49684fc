// A steady simulation takes nothing from the heap: once the arrays a step uses have
// grown to what the model needs (the contacts of a resting pose, the constraint rows,
// the solver's scratch), stepping allocates nothing. The count comes from the global
// operator new, replaced in this test program, and counts only inside CountAllocations.
#include <gtest/gtest.h>

#include <cstdlib>
#include <new>
#include <string>

#include "simlab/simlab.h"

namespace {

bool g_counting = false;
long g_allocations = 0;

}  // namespace

void* operator new(std::size_t size) {
  if (g_counting) g_allocations++;
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  if (g_counting) g_allocations++;
  return std::malloc(size ? size : 1);
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }

namespace simlab {
namespace {

// Heap allocations made by `steps` steps of a model after `warmup` steps.
long AllocationsPerRun(const std::string& relative, int warmup, int steps) {
  Model m = LoadXml(std::string(SIMLAB_SOURCE_DIR) + "/" + relative);
  Data d = MakeData(m);
  for (int i = 0; i < warmup; i++) Step(m, d);
  g_allocations = 0;
  g_counting = true;
  for (int i = 0; i < steps; i++) Step(m, d);
  g_counting = false;
  return g_allocations;
}

TEST(Allocation, SteadySteppingAllocatesNothing) {
  // With contacts and constraint rows (the gantry holding the cube, the humanoid
  // lying on the floor) and without (the actuator bench).
  EXPECT_EQ(AllocationsPerRun("tests/models/bench_gantry_holding.xml", 200, 300), 0);
  EXPECT_EQ(AllocationsPerRun("tests/conformance/contact/models/humanoid.xml", 3000, 300), 0);
  EXPECT_EQ(AllocationsPerRun("models/actuator_bench.xml", 100, 300), 0);
  // A soft box resting on the floor: flex kinematics, edge equality rows, flex contacts.
  EXPECT_EQ(AllocationsPerRun("../shared/corpus/mujoco/model/flex/softbox.xml", 400, 100), 0);
}

// Interpolated flexes made of cells (MuJoCo 3.12): strain equality rows (a cube of cells,
// a shell with bending), a volume and a shell side by side.
TEST(Allocation, FlexCellsAndStrainStepWithoutAllocating) {
  EXPECT_EQ(AllocationsPerRun("../shared/corpus/mujoco/model/flex/strain.xml", 300, 100), 0);
  EXPECT_EQ(AllocationsPerRun("../shared/corpus/mujoco/model/flex/bunny_shell.xml", 50, 50), 0);
  EXPECT_EQ(AllocationsPerRun("../shared/corpus/mujoco/model/flex/hollow_vs_solid.xml", 300, 100), 0);
}

}  // namespace
}  // namespace simlab
