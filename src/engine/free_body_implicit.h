// Standalone free bodies under implicitfast, as MuJoCo 3.12 steps them (only for models
// that follow 3.12, Model::release): a body with one free joint and nothing else in its
// tree is taken out of the symmetric step matrix (its rows are M's) and solved on its own,
// with the 6 x 6 block of M - h qDeriv plus the derivative of its gyroscopic (bias) force,
// which the symmetric matrix has to leave out. (MuJoCo's mj_isFreeBody, mjd_freeMhat and
// the free-body loop of mj_implicitSkip.)
#ifndef SIMLAB_ENGINE_FREE_BODY_IMPLICIT_H_
#define SIMLAB_ENGINE_FREE_BODY_IMPLICIT_H_

#include "simlab/data.h"
#include "simlab/model.h"

namespace simlab {

// Is `body` alone in its tree with one free joint (mj_isFreeBody)?
bool IsStandaloneFreeBody(const Model& m, int body);

// Does the model's step solve its standalone free bodies on their own (implicitfast in a
// model that follows 3.12)? Their rows of the symmetric step matrix are then M's.
bool SolvesFreeBodiesApart(const Model& m);

// Overwrites the accelerations of each awake standalone free body with the solution of
// its own block A qacc = qfrc, A = M - h qDeriv - h d(bias)/d(qvel) (by LU with partial
// pivoting; a singular block keeps the symmetric solve's answer).
void SolveFreeBodies(const Model& m, const Data& d, const double* qfrc, double* qacc);

}  // namespace simlab

#endif  // SIMLAB_ENGINE_FREE_BODY_IMPLICIT_H_
