// Constraint islands: which dofs and rows form independent constraint problems.
#ifndef SIMLAB_ENGINE_ISLAND_H_
#define SIMLAB_ENGINE_ISLAND_H_

#include <vector>

#include "simlab/data.h"
#include "simlab/model.h"

namespace simlab {

struct Islands {
  int nisland = 0;
  std::vector<int> dof_island;  // island of each dof, -1 when no row reaches its tree
  std::vector<int> efc_island;  // island of each constraint row
};

// The islands of the current rows (island.cc).
void FindIslands(const Model& m, const Data& d, Islands* out);

}  // namespace simlab

#endif  // SIMLAB_ENGINE_ISLAND_H_
