// Constraint islands: which dofs and rows form independent constraint problems.
#ifndef SIMLAB_ENGINE_ISLAND_H_
#define SIMLAB_ENGINE_ISLAND_H_

#include "simlab/data.h"
#include "simlab/model.h"

namespace simlab {

// The islands of the current rows: d.nisland, d.dof_island (-1 for dofs no row reaches)
// and d.efc_island (island.cc).
void FindIslands(const Model& m, Data& d);

}  // namespace simlab

#endif  // SIMLAB_ENGINE_ISLAND_H_
