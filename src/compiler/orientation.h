// Orientation and frame helpers used while compiling: the MJCF orientation
// alternatives, frame composition, and principal axes of a 3x3 inertia.
#ifndef SIMLAB_COMPILER_ORIENTATION_H_
#define SIMLAB_COMPILER_ORIENTATION_H_

#include "mjcf/spec.h"

namespace simlab::compiler {

// Smallest squared norm accepted for a direction (MuJoCo's mjEPS).
inline constexpr double kEps = 1e-14;

// Normalizes v (length n) unless its squared norm is below kEps; returns the norm
// before, or 0 if too small. Leaves v untouched when it is already unit length.
double NormalizeVec(double* v, int n);

// Sets quat from the orientation alternative, if one was written (else leaves quat).
// Returns an error text, or nullptr. Angles are in degrees if `degree`.
const char* ResolveOrientation(double* quat, bool degree, const std::string& eulerseq,
                               const mjcf::Orientation& alt);

// The composed pose of a frame chain (outermost frame first), normalized; each frame's
// angles read under its own model's settings (`model`: this model's).
// Throws on a bad orientation in any frame.
void FramePose(const mjcf::FrameSpec& frame, const mjcf::CompilerSpec& model, double pos[3],
               double quat[4]);

// (pos, quat) <- (fpos, fquat) * (pos, quat)
void AccumulateChild(const double fpos[3], const double fquat[4], double pos[3], double quat[4]);

// Eigen-decomposition of a symmetric 3x3 matrix by Jacobi rotations kept as a
// quaternion, eigenvalues sorted in decreasing order (MuJoCo's convention, so the
// principal frames match). eigvec is the rotation matrix of quat.
void Eig3(double eigval[3], double quat[4], const double mat[9]);

// Principal inertia and frame of a full inertia (xx yy zz xy xz yz); error text if
// it is not positive definite.
const char* FullInertia(double quat[4], double inertia[3], const double full[6]);

// global[6] (xx yy zz xy xz yz) of a diagonal inertia in a frame rotated by quat.
void GlobalInertia(double global[6], const double local[3], const double quat[4]);
// The inertia (xx yy zz xy xz yz) of point mass `mass` at offset d (MuJoCo's mjuu_offcenter).
void OffCenter(double res[6], double mass, const double d[3]);

// The rotation taking the z axis to direction `vec` (zaxis, fromto), as MuJoCo's
// compiler computes it (a half turn about x for -z).
void ZAxisQuat(double quat[4], const double vec[3]);

}  // namespace simlab::compiler

#endif  // SIMLAB_COMPILER_ORIENTATION_H_
