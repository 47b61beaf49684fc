// Sleeping trees (MuJoCo 3.5's sleep, engine_sleep.c): with the sleep flag enabled, a
// kinematic tree whose dofs stay below opt.sleep_tolerance for kMinAwake steps, together
// with every tree its constraints join it to (its island), is put to sleep: its qvel and
// qacc are zeroed and the pipeline skips it until something wakes it (a force applied to
// it, a contact, tendon limit or equality with an awake tree, or a change of its state).
// Flexes sleep as MuJoCo 3.12 lets them: a flex held by an edge equality (whose trees may
// sleep, compiler/trees.cc) sleeps with its trees; asleep, it collides only with awake
// moving bodies and flexes (not itself), its equality makes no rows, and a contact or its
// equality with an awake tree wakes it.
//
// Data::tree_asleep is the state: < 0 awake (counting up from -(1 + kMinAwake) to -1 while
// the tree is slow), >= 0 asleep, the next tree of the island's cycle of sleeping trees.
// The other sleep arrays are derived from it by UpdateSleep.
#ifndef SIMLAB_ENGINE_SLEEP_H_
#define SIMLAB_ENGINE_SLEEP_H_

#include <array>
#include <cstddef>

#include "engine/stack.h"
#include "simlab/data.h"
#include "simlab/model.h"

namespace simlab {

// A body's (or any element's) sleep state (MuJoCo's mjtSleepState).
enum SleepState : int { kAsleep = 0, kAwake = 1, kStatic = 2 };

// tree_asleep of a tree that is fully awake.
inline constexpr int kTreeAwake = -(1 + kMinAwake);

// True when sleeping is enabled and some tree is asleep: the stages then leave the
// sleeping trees' outputs as they were (or zero, where MuJoCo zeroes them).
inline bool AnyAsleep(const Model& m, const Data& d) {
  return (m.opt.enableflags & kEnableSleep) && d.ntree_awake < m.ntree;
}

// The sleeping dofs' entries of up to five nv-arrays, kept while a stage recomputes every
// dof and put back by Restore: a sleeping tree's forces stay as they were when it fell
// asleep (MuJoCo computes only the awake dofs). Does nothing while every tree is awake.
class SleepingDofValues {
 public:
  using Arrays = std::array<double*, 5>;  // (unused slots null)
  SleepingDofValues(const Model& m, Data& d, StackFrame& frame, Arrays arrays);
  void Restore();

 private:
  const Model& m_;
  Data& d_;
  Arrays arrays_;
  Arrays kept_{};
  bool active_ = false;
};

// tree_awake, body_awake, the awake index lists and their counts, from tree_asleep.
// With `static_awake`, bodies of no tree count as awake instead of static (for reset).
void UpdateSleep(const Model& m, Data& d, bool static_awake = false);

// Wakes trees the user changed: asleep trees given a force or a velocity, or whose pose
// Kinematics found moved (it sets their tree_awake), or every tree when sleep is
// disabled. Returns how many woke (then UpdateSleep).
int WakeChanged(const Model& m, Data& d);
// Wakes asleep trees in contact with awake ones (after the collision stage); a flex's
// side of a contact is the body of its vertex, its element's first vertex or its first
// node.
int WakeOnContact(const Model& m, Data& d);
// Wakes asleep trees joined to awake ones by an active tendon limit (after the tendons).
int WakeOnTendonLimit(const Model& m, Data& d);
// Wakes asleep trees joined to awake ones (or to another island) by an active equality;
// a flex's equality wakes its sleeping trees once one of them is awake.
int WakeOnEquality(const Model& m, Data& d);

// Counts the awake trees' slow steps and puts whole islands (and unconstrained trees)
// to sleep; returns how many trees fell asleep (their qvel and qacc are zeroed).
int PutToSleep(const Model& m, Data& d);

// The initial sleep state at reset: trees with sleep="init" asleep, as islands of the
// constraints at the reset pose. Throws std::runtime_error when not all of them can sleep.
void ResetSleep(const Model& m, Data& d);

// Sleep state of an element (MuJoCo's mj_sleepState); `type` is an ObjType.
SleepState ElementSleepState(const Model& m, const Data& d, int type, int id);

}  // namespace simlab

#endif  // SIMLAB_ENGINE_SLEEP_H_
