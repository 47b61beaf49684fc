// The sparse layouts: the constraint Jacobian in compressed rows (efc_J_rownnz/rowadr/
// colind, as MuJoCo's from 60 dofs or with jacobian="sparse") and the rows of
// actuator_moment and ten_J that keep the dofs where they may be nonzero. The same model
// with a dense and a sparse Jacobian has the same rows with the same numbers; a row holds
// the dofs of its bodies' chains; and rows that move with the configuration leave
// nothing stale behind.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "simlab/simlab.h"

namespace simlab {
namespace {

// Two hinge chains (one on a free base) over a plane, coupled by a connect and a weld,
// with limits, friction loss, a fixed and a spatial tendon, and actuators on joints,
// tendons and a site.
std::string Scene(const std::string& jacobian) {
  return R"(<mujoco><option jacobian=")" + jacobian + R"("/>
    <default><joint damping=".1"/><geom size=".05"/></default>
    <worldbody><geom type="plane" size="5 5 .1"/>
      <body name="a" pos="0 0 .06"><freejoint/><geom type="box" size=".1 .1 .05"/>
        <site name="sa" pos=".1 0 0"/>
        <body name="a1" pos=".2 0 0"><joint name="ja1" axis="0 1 0" range="-.5 .5"/>
          <geom type="capsule" fromto="0 0 0 .2 0 0"/>
          <body name="a2" pos=".2 0 0"><joint name="ja2" axis="0 1 0" frictionloss=".1"/>
            <geom type="capsule" fromto="0 0 0 .2 0 -.1"/><site name="sa2" pos=".2 0 0"/>
          </body>
        </body>
      </body>
      <body name="b" pos="0 .5 .049"><joint name="jb0" type="slide" axis="1 0 0"/>
        <geom type="sphere"/>
        <body name="b1" pos=".2 0 0"><joint name="jb1" axis="0 0 1" range="-1 1"/>
          <geom type="capsule" fromto="0 0 0 .2 0 0"/>
          <body name="b2" pos=".2 0 0"><joint name="jb2" axis="0 0 1"/>
            <geom type="capsule" fromto="0 0 0 .2 0 0"/><site name="sb2" pos=".2 0 0"/>
          </body>
        </body>
      </body>
    </worldbody>
    <equality><connect body1="a2" body2="b2" anchor=".2 0 0"/>
      <weld body1="b" solref=".05 1"/></equality>
    <tendon><fixed name="fixed" limited="true" range="-.2 .2">
        <joint joint="ja1" coef="1"/><joint joint="jb2" coef="-.5"/></fixed>
      <spatial name="spatial" stiffness="10" damping=".5">
        <site site="sa"/><site site="sa2"/><site site="sb2"/></spatial></tendon>
    <actuator><motor joint="ja2" gear="2"/><position tendon="fixed" kp="5"/>
      <motor tendon="spatial"/><motor site="sa2" gear="0 0 1 0 0 0"/>
      <adhesion name="stick" body="a" ctrlrange="0 1" gain="1"/></actuator>
  </mujoco>)";
}

// Row r of efc_J as nv numbers.
std::vector<double> DenseRow(const Model& m, const Data& d, int r) {
  std::vector<double> row(m.nv, 0.0);
  for (int k = d.efc_J_rowadr[r]; k < d.efc_J_rowadr[r] + d.efc_J_rownnz[r]; k++) {
    row[d.efc_J_colind[k]] = d.efc_J[k];
  }
  return row;
}

// The dofs that move body b (its joints and its ancestors'), ascending.
std::vector<int> ChainDofs(const Model& m, int b) {
  std::vector<int> dofs;
  for (; b > 0; b = m.body_parentid[b]) {
    for (int k = 0; k < m.body_dofnum[b]; k++) dofs.push_back(m.body_dofadr[b] + k);
  }
  std::sort(dofs.begin(), dofs.end());
  return dofs;
}

// A state with contacts, active limits and moving joints: a few steps from qpos0 with
// the controls on.
Data SettledData(const Model& m) {
  Data d = MakeData(m);
  for (int i = 0; i < m.nu; i++) d.ctrl[i] = 0.5;
  for (int s = 0; s < 100; s++) Step(m, d);
  return d;
}

// The settled state of the dense model, copied into a Data of the sparse one; both then
// through Forward, with the solvers run to `iterations` and `tolerance` when given.
std::pair<Data, Data> SameState(Model& dense_model, Model& sparse_model, int iterations = 0,
                                double tolerance = 0) {
  Data dense = SettledData(dense_model);
  Data sparse = MakeData(sparse_model);
  sparse.qpos = dense.qpos;
  sparse.qvel = dense.qvel;
  sparse.ctrl = dense.ctrl;
  sparse.qacc_warmstart = dense.qacc_warmstart;
  for (Model* m : {&dense_model, &sparse_model}) {
    if (iterations > 0) m->opt.iterations = iterations;
    if (tolerance > 0) m->opt.tolerance = tolerance;
  }
  Forward(dense_model, dense);
  Forward(sparse_model, sparse);
  return {std::move(dense), std::move(sparse)};
}

TEST(SparseRows, DenseAndSparseJacobiansHoldTheSameRows) {
  Model dense_model = LoadXmlString(Scene("dense"));
  Model sparse_model = LoadXmlString(Scene("sparse"));
  auto [dense, sparse] = SameState(dense_model, sparse_model);

  const int nv = dense_model.nv;
  ASSERT_GT(dense.ncon, 0);
  ASSERT_EQ(dense.nefc, sparse.nefc);
  EXPECT_EQ(dense.nJ, dense.nefc * nv);
  EXPECT_LT(sparse.nJ, sparse.nefc * nv);
  int contact_rows = 0;
  for (int r = 0; r < dense.nefc; r++) {
    ASSERT_EQ(dense.efc_type[r], sparse.efc_type[r]) << "row " << r;
    ASSERT_EQ(dense.efc_id[r], sparse.efc_id[r]) << "row " << r;
    EXPECT_EQ(dense.efc_J_rownnz[r], nv);
    // The same numbers, computed the same way, whatever the layout.
    EXPECT_EQ(DenseRow(dense_model, dense, r), DenseRow(sparse_model, sparse, r)) << "row " << r;
    // Sparse rows list ascending dofs.
    const int* cols = &sparse.efc_J_colind[sparse.efc_J_rowadr[r]];
    EXPECT_TRUE(std::is_sorted(cols, cols + sparse.efc_J_rownnz[r]));
    EXPECT_NEAR(dense.efc_vel[r], sparse.efc_vel[r], 1e-12 * (1 + std::abs(dense.efc_vel[r])));

    // A contact row holds exactly the dofs of both bodies' chains.
    if (sparse.efc_type[r] >= kCnstrContactFrictionless) {
      contact_rows++;
      const Contact& c = sparse.contact[sparse.efc_id[r]];
      std::vector<int> want = ChainDofs(sparse_model, sparse_model.geom_bodyid[c.geom[0]]);
      std::vector<int> more = ChainDofs(sparse_model, sparse_model.geom_bodyid[c.geom[1]]);
      want.insert(want.end(), more.begin(), more.end());
      std::sort(want.begin(), want.end());
      want.erase(std::unique(want.begin(), want.end()), want.end());
      EXPECT_EQ(std::vector<int>(cols, cols + sparse.efc_J_rownnz[r]), want) << "row " << r;
    }
  }
  EXPECT_GT(contact_rows, 0);
  for (int v = 0; v < nv; v++) {
    EXPECT_NEAR(dense.qacc[v], sparse.qacc[v], 1e-8 * (1 + std::abs(dense.qacc[v]))) << v;
  }
}

// `xml` with a 60-dof chain added to its world (a free capsule and 54 hinged ones lying on
// the plane): an island large enough for the sparse Newton factor.
std::string WithLongChain(std::string xml) {
  std::string chain = R"(<body pos="0 -1 .039"><freejoint/>
      <geom type="capsule" fromto="0 0 0 .1 0 0" size=".04"/>)";
  for (int i = 0; i < 54; i++) {
    chain += R"(<body pos=".1 0 0"><joint axis=")" + std::string(i % 2 ? "0 0 1" : "0 1 0") +
             R"(" damping=".01"/><geom type="capsule" fromto="0 0 0 .1 0 0" size=".04"/>)";
  }
  for (int i = 0; i <= 54; i++) chain += "</body>";
  xml.replace(xml.find("</worldbody>"), 0, chain);
  return xml;
}

// The dofs of the largest island.
int LargestIsland(const Model& m, const Data& d) {
  std::vector<int> size(std::max(d.nisland, 1), 0);
  for (int v = 0; v < m.nv; v++) {
    if (d.dof_island[v] >= 0) size[d.dof_island[v]]++;
  }
  return *std::max_element(size.begin(), size.end());
}

// The solvers on compressed rows (sparse products, the sparse Newton Hessian and its
// updates, PGS and noslip on the compressed efc_AR) find the accelerations the dense ones
// find, for both cones, with islands and on the whole model at once: a state with
// contacts, limits, equalities and friction loss; for Newton with a chain whose island
// has 60 dofs, so that the sparse factor runs.
TEST(SparseRows, SparseSolversFindTheDenseSolution) {
  for (const char* cone : {"pyramidal", "elliptic"}) {
    for (const char* solver : {"Newton", "CG", "PGS", "Newton noslip"}) {
      for (const char* island : {"enable", "disable"}) {
        // (the chain for Newton, whose factor it is for; the others on the small scene)
        bool chain = std::string(solver) == "Newton";
        auto variant = [&](const std::string& jacobian) {
          std::string xml = Scene(jacobian);
          std::string name = solver;
          bool noslip = name.find(" noslip") != std::string::npos;
          std::string option = std::string(R"(cone=")") + cone + R"(" solver=")" +
                               name.substr(0, name.find(' ')) +
                               R"(" )" +
                               (noslip ? R"(noslip_iterations="50" )" : "") +
                               R"(><flag island=")" + island + R"("/></option>)";
          xml.replace(xml.find("/>"), 2, " " + option);
          return LoadXmlString(chain ? WithLongChain(xml) : xml);
        };
        Model dense_model = variant("dense"), sparse_model = variant("sparse");
        auto [dense, sparse] = SameState(dense_model, sparse_model, 2000, 1e-15);
        ASSERT_GT(dense.ncon, 0);
        if (chain) {
          ASSERT_GE(std::string(island) == "enable" ? LargestIsland(sparse_model, sparse)
                                                    : sparse_model.nv,
                    60);
        }
        // (CG converges slowly along a direction of small curvature on this state: with
        // the elliptic cone both stop where the cost no longer falls, their costs equal to
        // 1e-16 relative, their accelerations 4e-6 apart)
        double tol = std::string(solver) == "CG" ? 1e-5 : 1e-7;
        for (int v = 0; v < dense_model.nv; v++) {
          EXPECT_NEAR(dense.qacc[v], sparse.qacc[v], tol * (1 + std::abs(dense.qacc[v])))
              << cone << " " << solver << " island " << island << " dof " << v;
        }
      }
    }
  }
}

// After the configuration moves, actuator_moment, ten_J and the velocities derived from
// them are those of a fresh Data in the new configuration: no stale entries.
TEST(SparseRows, MomentAndTendonRowsFollowTheConfiguration) {
  Model m = LoadXmlString(Scene("sparse"));
  Data moved = SettledData(m);
  Data fresh = MakeData(m);
  fresh.qpos = moved.qpos;
  fresh.qvel = moved.qvel;
  Forward(m, moved);
  Forward(m, fresh);
  EXPECT_EQ(moved.actuator_moment, fresh.actuator_moment);
  EXPECT_EQ(moved.ten_J, fresh.ten_J);
  EXPECT_EQ(moved.actuator_velocity, fresh.actuator_velocity);
  EXPECT_EQ(moved.ten_velocity, fresh.ten_velocity);

  // The velocities are the rows times qvel over all dofs.
  for (int i = 0; i < m.nu; i++) {
    double s = 0;
    for (int v = 0; v < m.nv; v++) s += moved.actuator_moment[i * m.nv + v] * moved.qvel[v];
    EXPECT_NEAR(moved.actuator_velocity[i], s, 1e-12) << "actuator " << i;
  }
  for (int t = 0; t < m.ntendon; t++) {
    double s = 0;
    for (int v = 0; v < m.nv; v++) s += moved.ten_J[t * m.nv + v] * moved.qvel[v];
    EXPECT_NEAR(moved.ten_velocity[t], s, 1e-12) << "tendon " << t;
  }
}

// An adhesion actuator's row follows the contacts of its body: lifted off the plane, the
// body touches nothing and the row is all zero (nothing left from the touching pose).
TEST(SparseRows, AdhesionRowEmptiesWhenTheContactsGo) {
  Model m = LoadXmlString(Scene("sparse"));
  Data d = SettledData(m);
  int stick = m.NameToId(kObjActuator, "stick");
  ASSERT_GE(stick, 0);
  const double* row = &d.actuator_moment[static_cast<size_t>(stick) * m.nv];
  ASSERT_TRUE(std::any_of(row, row + m.nv, [](double x) { return x != 0; }));
  d.qpos[2] = 2;  // body a's free joint: lifted
  Forward(m, d);
  row = &d.actuator_moment[static_cast<size_t>(stick) * m.nv];
  EXPECT_TRUE(std::all_of(row, row + m.nv, [](double x) { return x == 0; }));
}

}  // namespace
}  // namespace simlab
