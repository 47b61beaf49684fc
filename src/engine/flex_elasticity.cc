// Elastic forces of flexes (see flex_elasticity.h), in MuJoCo's order of operations.
//
// Bending (triangle flexes): each inner edge's flap (v0 v1 the edge, v2 v3 the opposite
// vertices) pulls its four vertices by -B x - b16 n, with B the compiler's 4x4 operator
// over the vertex positions x and n the gradients of the flap's volume (the curved
// reference); its damping is -damping B qvel.
//
// Elements: each edge's squared elongation (plus Rayleigh damping, the change of its
// squared length over the last step times damping / timestep) drives the element's
// vertices through the compiler's edge metric: f = -sum metric[a][b] elong[a] grad[b],
// grad[b] the gradient of edge b's squared length over two.
//
// Interpolated flexes: the nodes in their corotated frame, displaced from their reference
// positions, feel K displacement (and damping K velocity), rotated back to the world.
#include "engine/flex_elasticity.h"

#include <cmath>

#include "engine/engine.h"
#include "engine/flex_cells.h"
#include "engine/sensor.h"
#include "engine/stack.h"
#include "math/dot.h"
#include "math/math.h"

namespace simlab {

namespace {

// Where the metric between edges a and b of a triangle ([0]) or a tetrahedron ([1]) is
// among its element's 21 flex_stiffness numbers: the upper triangle (a <= b), row by
// row, as the compiler stores it; [b][a] names the same number.
struct MetricIndex {
  int at[2][6][6] = {};
};
constexpr MetricIndex MakeMetricIndex() {
  MetricIndex index;
  for (int dim = 2; dim <= 3; dim++) {
    int nedge = kFlexElemEdgeCount[dim - 1], id = 0;
    for (int a = 0; a < nedge; a++) {
      for (int b = a; b < nedge; b++) {
        index.at[dim - 2][a][b] = id;
        index.at[dim - 2][b][a] = id++;
      }
    }
  }
  return index;
}
constexpr MetricIndex kMetricIndex = MakeMetricIndex();

// A body that is a simple point mass (slide joints along its frame's axes, MuJoCo's
// body_simple 2: three, or the two of a 2d flexcomp) takes a vertex force on its dofs
// directly, seen in its frame.
constexpr int kSimplePointMass = 2;

}  // namespace

// r = q v q*, also computed for a zero v (MuJoCo's inline variant, which keeps the signs
// of zero that math::RotVecQuat's shortcut would not).
void FlexRotateAlways(double* r, const double* v, const double* q) {
  if (q[0] == 1 && q[1] == 0 && q[2] == 0 && q[3] == 0) return math::Copy3(r, v);
  double t[3] = {q[0] * v[0] + q[2] * v[2] - q[3] * v[1],
                 q[0] * v[1] + q[3] * v[0] - q[1] * v[2],
                 q[0] * v[2] + q[1] * v[1] - q[2] * v[0]};
  r[0] = v[0] + 2 * (q[2] * t[2] - q[3] * t[1]);
  r[1] = v[1] + 2 * (q[3] * t[0] - q[1] * t[2]);
  r[2] = v[2] + 2 * (q[1] * t[1] - q[2] * t[0]);
}

// The deformation gradient (row-major 3x3) at p of the nodes' positions (MuJoCo's
// mju_defGradient).
void FlexDeformationGradient(double mat[9], const double p[3], const double* nodes, int order) {
  for (int k = 0; k < 9; k++) mat[k] = 0;
  int node = 0;
  for (int i = 0; i <= order; i++) {
    for (int j = 0; j <= order; j++) {
      for (int k = 0; k <= order; k++) {
        double g[3];
        FlexShapeGradient(g, p, i, j, k, order);
        for (int r = 0; r < 3; r++) {
          for (int c = 0; c < 3; c++) mat[3 * r + c] += nodes[3 * node + r] * g[c];
        }
        node++;
      }
    }
  }
}

// Refines quat toward the rotation nearest `mat` (Mueller et al., "A robust method to
// extract the rotational part of deformations"; MuJoCo's mju_mat2Rot): at most 500 steps,
// until the correcting rotation is below 1e-9 radians.
void FlexNearestRotation(double quat[4], const double mat[9]) {
  for (int iter = 0; iter < 500; iter++) {
    // The correcting rotation: sum of rot_col x mat_col over the sum of their dots.
    double rot[9];
    math::QuatToMat(rot, quat);
    double cross[3][3], dot[3];
    for (int c = 0; c < 3; c++) {
      double rot_col[3] = {rot[c], rot[3 + c], rot[6 + c]};
      double mat_col[3] = {mat[c], mat[3 + c], mat[6 + c]};
      math::Cross3(cross[c], rot_col, mat_col);
      dot[c] = math::Dot3(rot_col, mat_col);
    }
    double omega[3];
    for (int k = 0; k < 3; k++) omega[k] = cross[0][k] + cross[1][k] + cross[2][k];
    math::Scale3(omega, omega, 1.0 / (std::abs(dot[0] + dot[1] + dot[2]) + math::kTiny));
    double angle = math::Normalize3(omega);
    if (angle < 1e-9) break;

    // Apply it on the left.
    double step[4];
    math::AxisAngleToQuat(step, omega, angle);
    math::MulQuat(quat, step, quat);
    math::NormalizeQuat(quat);
  }
}

namespace {

// A flap's bending forces (world frame) into its vertices' slide dofs as MuJoCo 3.12 puts
// them: turned into each vertex body's frame, where its sliders are; a pinned vertex (not
// three dofs) takes none, its pin carries them.
void ApplyBendingInBodyFrames(const Model& m, Data& d, int f, const int v[4], bool spring,
                              bool damper, const double* spring_force, const double* damper_force) {
  const int* bodyid = &m.flex_vertbodyid[m.flex_vertadr[f]];
  for (int i = 0; i < 4; i++) {
    int body = bodyid[v[i]];
    if (m.body_dofnum[body] != 3) continue;
    double spring_local[3], damper_local[3];
    math::MulMatTVec3(spring_local, &d.xmat[9 * body], spring_force + 3 * i);
    math::MulMatTVec3(damper_local, &d.xmat[9 * body], damper_force + 3 * i);
    int dofadr = m.body_dofadr[body];
    for (int x = 0; x < 3; x++) {
      if (spring) d.qfrc_spring[dofadr + x] -= spring_local[x];
      if (damper) d.qfrc_damper[dofadr + x] -= damper_local[x] * m.flex_damping[f];
    }
  }
}

// Thin-plate bending of triangle flex f: each inner edge's flap.
void BendingForces(const Model& m, Data& d, int f, bool spring, bool damper) {
  const double* xpos = &d.flexvert_xpos[3 * m.flex_vertadr[f]];
  const int* bodyid = &m.flex_vertbodyid[m.flex_vertadr[f]];
  for (int edge = m.flex_edgeadr[f]; edge < m.flex_edgeadr[f] + m.flex_edgenum[f]; edge++) {
    int v[4] = {m.flex_edge[2 * edge], m.flex_edge[2 * edge + 1], m.flex_edgeflap[2 * edge],
                m.flex_edgeflap[2 * edge + 1]};
    if (v[3] == -1) continue;
    int adr = m.flex_bendingadr[f] + kFlexBendingSize * (edge - m.flex_edgeadr[f]);
    const double* b = &m.flex_bending[adr];

    // Forces of the curved reference: gradients of the flap's volume.
    double ed[3][3], frc[4][3];
    for (int k = 0; k < 3; k++) math::Sub3(ed[k], xpos + 3 * v[k + 1], xpos + 3 * v[0]);
    math::Cross3(frc[1], ed[1], ed[2]);
    math::Cross3(frc[2], ed[2], ed[0]);
    math::Cross3(frc[3], ed[0], ed[1]);
    for (int x = 0; x < 3; x++) frc[0][x] = -(frc[1][x] + frc[2][x] + frc[3][x]);

    // B x + b16 frc, and B qvel: MuJoCo 3.5.1 reads the vertices' dofs as world
    // translations; 3.12 (a model that follows it) takes a pinned vertex (a static body,
    // no dofs of its own) as still.
    bool newer = m.release == Release::k3_12;
    static const double kStill[3] = {0, 0, 0};
    const double* vel[4];
    for (int i = 0; i < 4; i++) {
      int body = bodyid[v[i]];
      bool pinned = newer && m.body_dofnum[body] != 3;
      vel[i] = pinned ? kStill : &d.qvel[m.body_dofadr[body]];
    }
    double spring_force[12] = {}, damper_force[12] = {};
    for (int i = 0; i < 4; i++) {
      for (int x = 0; x < 3; x++) {
        for (int j = 0; j < 4; j++) {
          if (spring) spring_force[3 * i + x] += b[4 * i + j] * xpos[3 * v[j] + x];
          if (damper) damper_force[3 * i + x] += b[4 * i + j] * vel[j][x];
        }
        if (spring) spring_force[3 * i + x] += b[16] * frc[i][x];
      }
    }
    if (newer) {
      ApplyBendingInBodyFrames(m, d, f, v, spring, damper, spring_force, damper_force);
      continue;
    }

    // Into the vertices' dofs.
    for (int i = 0; i < 4; i++) {
      int body = bodyid[v[i]];
      for (int x = 0; x < m.body_dofnum[body]; x++) {
        int dof = m.body_dofadr[body] + x;
        if (spring) d.qfrc_spring[dof] -= spring_force[3 * i + x];
        if (damper) d.qfrc_damper[dof] -= damper_force[3 * i + x] * m.flex_damping[f];
      }
    }
  }
}

// Linear elasticity of interpolated flex f in its corotated frame.
void InterpolatedForces(const Model& m, Data& d, int f, bool spring, bool damper) {
  int nnode = m.flex_nodenum[f], ndof = 3 * nnode;
  const int* bodyid = &m.flex_nodebodyid[m.flex_nodeadr[f]];
  const double* xpos0 = &m.flex_node0[3 * m.flex_nodeadr[f]];
  const double* k = &m.flex_stiffness[m.flex_stiffnessadr[f]];
  StackFrame frame(d);
  double* xpos = frame.Alloc(ndof);
  double* displacement = frame.Alloc(ndof);
  double* frc = frame.Alloc(ndof);
  // (velocities only reach the damping)
  double* vel = damper ? frame.Alloc(ndof) : nullptr;
  double* dmp = damper ? frame.Alloc(ndof) : nullptr;

  // Corotated state and displacement from the reference.
  double quat[4] = {1, 0, 0, 0};
  FlexInterpState(m, d, f, xpos, vel, quat);
  for (int i = 0; i < ndof; i++) displacement[i] = xpos[i] - xpos0[i];

  // Forces in the corotated frame (k holds minus the stiffness).
  if (spring) math::MulMatVec(frc, k, displacement, ndof, ndof);
  if (damper) math::MulMatVec(dmp, k, vel, ndof, ndof);

  // Back to the world, onto the node bodies' dofs (a node off its body's origin through
  // the body's Jacobian at the node's corotated position, as MuJoCo applies it).
  const double no_torque[3] = {0, 0, 0};
  math::NegQuat(quat, quat);
  for (int i = 0; i < nnode; i++) {
    double qfrc[3], qdmp[3] = {0, 0, 0};
    FlexRotateAlways(qfrc, frc + 3 * i, quat);
    if (damper) {
      FlexRotateAlways(qdmp, dmp + 3 * i, quat);
      math::Scale3(qdmp, qdmp, m.flex_damping[f]);
    }
    int body = bodyid[i], dofadr = m.body_dofadr[body];
    if (m.flex_centered[f]) {
      for (int x = 0; x < 3; x++) {
        if (spring) d.qfrc_spring[dofadr + x] += qfrc[x];
        if (damper) d.qfrc_damper[dofadr + x] += qdmp[x];
      }
    } else {
      if (spring) ApplyForceTorque(m, d, qfrc, no_torque, xpos + 3 * i, body, d.qfrc_spring.data());
      if (damper) ApplyForceTorque(m, d, qdmp, no_torque, xpos + 3 * i, body, d.qfrc_damper.data());
    }
  }
}

// Squared edge lengths' half gradients of one element: for edge e, grad[e][0] on its first
// vertex and grad[e][1] = -grad[e][0] on its second.
void SquaredLengthGradients(double grad[6][2][3], const double* xpos, const int* vert,
                            const int edges[6][2], int nedge) {
  for (int e = 0; e < nedge; e++) {
    const double* x0 = xpos + 3 * vert[edges[e][0]];
    const double* x1 = xpos + 3 * vert[edges[e][1]];
    math::Sub3(grad[e][0], x0, x1);
    math::Sub3(grad[e][1], x1, x0);
  }
}

// The elongation of each edge of flex f's square, with Rayleigh damping (Kharevych et al.,
// "Geometric, variational integrators for computer animation", section 5.2), by the
// flex's edge ids: computed once for all the elements that hold the edge.
void EdgeElongations(const Model& m, const Data& d, int f, double damping_rate,
                     double* elongation) {
  double timestep = m.opt.timestep;
  int edgeadr = m.flex_edgeadr[f];
  for (int e = 0; e < m.flex_edgenum[f]; e++) {
    int edge = edgeadr + e;
    double length = d.flexedge_length[edge], rest = m.flexedge_length0[edge];
    double previous = length - d.flexedge_velocity[edge] * timestep;
    elongation[e] = length * length - rest * rest +
                    (length * length - previous * previous) * damping_rate;
  }
}

// The local forces (3 per vertex) of one element of dimension dim (vertices vert, flex
// edge ids edge_ids): f = -sum over edges a, b of metric[a][b] elongation[a] grad[b], the
// metric's upper triangle being the element's 21 stiffness numbers.
void ElementForce(const double* metric21, const double* xpos, const int* vert,
                  const int* edge_ids, const double* elongation, int dim, double force[12]) {
  const int(*edges)[2] = kFlexElemEdges[dim - 1];
  const int(*index)[6] = kMetricIndex.at[dim - 2];
  int nedge = kFlexElemEdgeCount[dim - 1];
  double grad[6][2][3];
  SquaredLengthGradients(grad, xpos, vert, edges, nedge);

  // f -= elongation[a] metric[a][b] grad[b] on edge b's two vertices.
  for (int k = 0; k < 12; k++) force[k] = 0;
  for (int a = 0; a < nedge; a++) {
    double elong = elongation[edge_ids[a]];
    for (int b = 0; b < nedge; b++) {
      double metric = metric21[index[a][b]];
      for (int i = 0; i < 2; i++) {
        for (int x = 0; x < 3; x++) force[3 * edges[b][i] + x] -= elong * grad[b][i][x] * metric;
      }
    }
  }
}

// Element elasticity of flex f (triangles or tetrahedra), into qfrc_spring.
void ElementForces(const Model& m, Data& d, int f) {
  int dim = m.flex_dim[f], nedge = kFlexElemEdgeCount[dim - 1], nvert = m.flex_vertnum[f];
  const int* elem = &m.flex_elem[m.flex_elemdataadr[f]];
  const int* elemedge = &m.flex_elemedge[m.flex_elemedgeadr[f]];
  const double* xpos = &d.flexvert_xpos[3 * m.flex_vertadr[f]];
  const double* k = &m.flex_stiffness[m.flex_stiffnessadr[f]];
  double damping_rate = m.opt.timestep > 0 ? m.flex_damping[f] / m.opt.timestep : 0;
  StackFrame frame(d);
  double* qfrc = frame.Alloc(3 * nvert);
  double* elongation = frame.Alloc(m.flex_edgenum[f]);
  EdgeElongations(m, d, f, damping_rate, elongation);

  // Sum the elements' forces per vertex.
  for (int t = 0; t < m.flex_elemnum[f]; t++) {
    const int* vert = elem + (dim + 1) * t;
    double force[12];
    ElementForce(k + kFlexStiffnessSize * t, xpos, vert, elemedge + nedge * t, elongation, dim,
                 force);
    for (int i = 0; i <= dim; i++) {
      for (int x = 0; x < 3; x++) qfrc[3 * vert[i] + x] += force[3 * i + x];
    }
  }

  // Onto the dofs: in their frame for point masses, through the Jacobian for pinned vertices.
  const int* bodyid = &m.flex_vertbodyid[m.flex_vertadr[f]];
  const double no_torque[3] = {0, 0, 0};
  for (int v = 0; v < nvert; v++) {
    int body = bodyid[v];
    if (m.body_simple[body] != kSimplePointMass) {
      ApplyForceTorque(m, d, qfrc + 3 * v, no_torque, xpos + 3 * v, body, d.qfrc_spring.data());
    } else {
      double local[3];
      math::MulMatTVec3(local, &d.xmat[9 * body], qfrc + 3 * v);
      int adr = m.body_dofadr[body];
      for (int x = 0; x < m.body_dofnum[body]; x++) d.qfrc_spring[adr + x] += local[x];
    }
  }
}

}  // namespace

void FlexInterpState(const Model& m, const Data& d, int f, double* xpos, double* vel,
                     double quat[4]) {
  int nnode = m.flex_nodenum[f], nodeadr = m.flex_nodeadr[f];
  const int* bodyid = &m.flex_nodebodyid[nodeadr];

  // World positions and velocities of the nodes: body origins, or points of the bodies.
  for (int i = 0; i < nnode; i++) {
    FlexNodeXpos(m, d, f, nodeadr + i, xpos + 3 * i);
    if (!vel) continue;
    int body = bodyid[i];
    if (m.flex_centered[f]) {
      math::Copy3(vel + 3 * i, &d.qvel[m.body_dofadr[body]]);
    } else {
      double screw[6];
      ObjectVelocity(m, d, kObjBody, body, screw, false);
      math::Copy3(vel + 3 * i, screw + 3);
    }
  }

  // The rotation of the deformation gradient at the centre, inverted.
  const double centre[3] = {0.5, 0.5, 0.5};
  double mat[9];
  FlexDeformationGradient(mat, centre, xpos, m.flex_interp[f]);
  FlexNearestRotation(quat, mat);
  math::NegQuat(quat, quat);

  // Into the corotated frame, positions about the centre.
  for (int i = 0; i < nnode; i++) {
    math::RotVecQuat(xpos + 3 * i, xpos + 3 * i, quat);
    math::Add3(xpos + 3 * i, xpos + 3 * i, centre);
    if (vel) math::RotVecQuat(vel + 3 * i, vel + 3 * i, quat);
  }
}

void FlexElasticForces(const Model& m, Data& d, bool spring, bool damper) {
  for (int f = 0; f < m.nflex; f++) {
    int dim = m.flex_dim[f];
    if (dim == 1 || m.flex_rigid[f]) continue;

    // A flex made of cells (MuJoCo 3.12): its cells' or faces' elasticity, a shell's
    // bending.
    if (FlexHasCells(m, f)) {
      FlexCellElasticForces(m, d, f, spring, damper);
      continue;
    }

    // Bending first, then the elements (a flex without stiffness has none).
    if (dim == 2) BendingForces(m, d, f, spring, damper);
    if (m.flex_stiffness[m.flex_stiffnessadr[f]] == 0) continue;
    if (m.flex_interp[f]) {
      InterpolatedForces(m, d, f, spring, damper);
    } else {
      ElementForces(m, d, f);
    }
  }
}

}  // namespace simlab
