// The collision stage (MuJoCo mj_collision): candidate body pairs from the broad phase,
// merged in signature order with the explicit <pair>s, filtered as MuJoCo filters them,
// then one narrow-phase call per geom pair (collision_table.cc) whose contacts get
// their parameters here.
//
// The contact order is MuJoCo's: body pairs by signature (body1 << 16) + body2, explicit
// pairs of a signature before that body pair's own geom pairs, geom pairs in geom order.
// Candidates come from MuJoCo's sweep and prune along the principal axis of the geoms,
// with its single-precision ends, so that even touching boxes pair up as in MuJoCo.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "engine/collision.h"
#include "engine/collision_driver.h"
#include "engine/constraint.h"
#include "engine/engine.h"
#include "engine/sleep.h"
#include "engine/stack.h"
#include "engine/timer.h"
#include "math/math.h"

namespace simlab {

namespace {

bool Enabled(const Model& m, int bit) { return (m.opt.enableflags & bit) != 0; }
bool Disabled(const Model& m, int bit) { return (m.opt.disableflags & bit) != 0; }

}  // namespace

// ------------------------------------------------------------ contact parameters
// (shared with the flex collider: collision_driver.h)

// Margin, reference, impedance and friction, or the global overrides (mj_assign*).
double AssignMargin(const Model& m, double margin) {
  return Enabled(m, kEnableOverride) ? m.opt.o_margin : margin;
}

// True when neither geom's contype meets the other's conaffinity.
bool BitmaskRejects(int contype1, int conaffinity1, int contype2, int conaffinity2) {
  return !(contype1 & conaffinity2) && !(contype2 & conaffinity1);
}

namespace {

// Condim, gap, solref, solimp and 5-d friction of two sides without an explicit pair:
// the higher priority side's, else condim and friction by max, solref/solimp mixed by
// solmix (solref by min when either is in direct form).
double SolMix(double mix1, double mix2) {
  if (mix1 >= kMinVal && mix2 >= kMinVal) return mix1 / (mix1 + mix2);
  if (mix1 < kMinVal && mix2 < kMinVal) return 0.5;
  return mix1 < kMinVal ? 0.0 : 1.0;
}

// One side's contact properties: a geom's, or a flex's.
struct Surface {
  int priority, condim;
  double gap, solmix;
  const double* solref;
  const double* solimp;
  const double* friction;
};

Surface SurfaceOf(const Model& m, int g, int f) {
  if (f >= 0) {
    return {m.flex_priority[f], m.flex_condim[f], m.flex_gap[f], m.flex_solmix[f],
            &m.flex_solref[kNRef * f], &m.flex_solimp[kNImp * f], &m.flex_friction[3 * f]};
  }
  return {m.geom_priority[g], m.geom_condim[g], m.geom_gap[g], m.geom_solmix[g],
          &m.geom_solref[kNRef * g], &m.geom_solimp[kNImp * g], &m.geom_friction[3 * g]};
}

}  // namespace

ContactParams MixedParams(const Model& m, int g1, int g2, int f1, int f2) {
  ContactParams p;
  Surface s1 = SurfaceOf(m, g1, f1), s2 = SurfaceOf(m, g2, f2);
  p.gap = s1.gap + s2.gap;
  double fri[3];
  if (s1.priority != s2.priority) {
    // The higher priority side decides everything.
    const Surface& s = s1.priority > s2.priority ? s1 : s2;
    p.condim = s.condim;
    std::copy_n(s.solref, kNRef, p.solref);
    std::copy_n(s.solimp, kNImp, p.solimp);
    std::copy_n(s.friction, 3, fri);
  } else {
    // Same priority: max condim and friction, mixed solver parameters.
    p.condim = std::max(s1.condim, s2.condim);
    double mix = SolMix(s1.solmix, s2.solmix);
    bool standard = s1.solref[0] > 0 && s2.solref[0] > 0;
    for (int i = 0; i < kNRef; i++) {
      p.solref[i] = standard ? mix * s1.solref[i] + (1 - mix) * s2.solref[i]
                             : std::min(s1.solref[i], s2.solref[i]);
    }
    for (int i = 0; i < kNImp; i++) p.solimp[i] = mix * s1.solimp[i] + (1 - mix) * s2.solimp[i];
    for (int i = 0; i < 3; i++) fri[i] = std::max(s1.friction[i], s2.friction[i]);
  }
  // Tangential friction twice, torsional once, rolling twice.
  p.friction[0] = p.friction[1] = fri[0];
  p.friction[2] = fri[1];
  p.friction[3] = p.friction[4] = fri[2];
  return p;
}

namespace {

ContactParams GeomPairParams(const Model& m, int g1, int g2) {
  return MixedParams(m, g1, g2, -1, -1);
}

// The explicit pair's own parameters.
ContactParams PairParams(const Model& m, int ipair) {
  ContactParams p;
  p.condim = m.pair_dim[ipair];
  p.gap = m.pair_gap[ipair];
  std::copy_n(&m.pair_solref[kNRef * ipair], kNRef, p.solref);
  std::copy_n(&m.pair_solreffriction[kNRef * ipair], kNRef, p.solreffriction);
  std::copy_n(&m.pair_solimp[kNImp * ipair], kNImp, p.solimp);
  std::copy_n(&m.pair_friction[5 * ipair], 5, p.friction);
  return p;
}

}  // namespace

// Parameters of one new contact (mj_setContact), with the global overrides.
void SetContact(const Model& m, const ContactParams& p, double includemargin, int g1, int g2,
                Contact* c) {
  bool override = Enabled(m, kEnableOverride);
  c->geom[0] = c->geom1 = g1;
  c->geom[1] = c->geom2 = g2;
  c->flex[0] = c->flex[1] = c->elem[0] = c->elem[1] = c->vert[0] = c->vert[1] = -1;
  c->dim = p.condim;
  c->includemargin = includemargin;
  for (int i = 0; i < kNRef; i++) {
    c->solref[i] = override ? m.opt.o_solref[i] : p.solref[i];
    c->solreffriction[i] = override ? m.opt.o_solref[i] : p.solreffriction[i];
  }
  for (int i = 0; i < kNImp; i++) c->solimp[i] = override ? m.opt.o_solimp[i] : p.solimp[i];
  for (int i = 0; i < 5; i++) {
    c->friction[i] = std::max(kMinMu, override ? m.opt.o_friction[i] : p.friction[i]);
  }
  c->exclude = c->dist >= includemargin;
  CompleteContactFrame(c->frame);
  c->efc_address = -1;
  c->mu = 0;
  std::fill(c->H, c->H + 36, 0.0);
}

Contact* ContactRoom(Data& d, int n) {
  if (d.contact.size() < static_cast<size_t>(d.ncon + n)) {
    d.contact.resize(static_cast<size_t>(d.ncon + n) * 2);
  }
  return &d.contact[d.ncon];
}

namespace {

// ------------------------------------------------------------ geom filters

// Distance of geom g's centre above plane geom p.
double PlaneGeomDist(const Data& d, int p, int g) {
  const double* mat = &d.geom_xmat[9 * p];
  double normal[3] = {mat[2], mat[5], mat[8]};
  double dif[3];
  math::Sub3(dif, &d.geom_xpos[3 * g], &d.geom_xpos[3 * p]);
  return math::Dot3(dif, normal);
}

// True when the bounding spheres (or a plane and a sphere) are farther than margin.
bool SpheresApart(const Model& m, const Data& d, int g1, int g2, double margin) {
  double r1 = m.geom_rbound[g1], r2 = m.geom_rbound[g2];
  if (r1 > 0 && r2 > 0) {
    double dif[3];
    math::Sub3(dif, &d.geom_xpos[3 * g1], &d.geom_xpos[3 * g2]);
    double bound = r1 + r2 + margin;
    return dif[0] * dif[0] + dif[1] * dif[1] + dif[2] * dif[2] > bound * bound;
  }
  if (m.geom_type[g1] == kGeomPlane && r2 > 0 && PlaneGeomDist(d, g1, g2) > margin + r2) {
    return true;
  }
  return m.geom_type[g2] == kGeomPlane && r1 > 0 && PlaneGeomDist(d, g2, g1) > margin + r1;
}

// Is either box infinite in every direction (then the boxes are never apart)? Records
// which are infinite in some direction (planes: the other box's faces are not tested).
bool AnyBoxEverywhere(const double* const aabb[2], bool infinite[2]) {
  for (int i = 0; i < 2; i++) {
    const double* half = aabb[i] + 3;
    if (half[0] >= kMaxVal && half[1] >= kMaxVal && half[2] >= kMaxVal) return true;
    infinite[i] = half[0] >= kMaxVal || half[1] >= kMaxVal || half[2] >= kMaxVal;
  }
  return false;
}

// Are the boxes apart along one face normal, given how each box's axes project on it
// (along[i]) and where each box's centre projects (proj[i])?
bool ApartAlong(const double* const aabb[2], const double along[2][3], const double proj[2],
                double margin) {
  double radius[2];
  for (int i = 0; i < 2; i++) {
    radius[i] = std::abs(aabb[i][3] * along[i][0]) + std::abs(aabb[i][4] * along[i][1]) +
                std::abs(aabb[i][5] * along[i][2]);
  }
  return radius[0] + radius[1] + margin < std::abs(proj[1] - proj[0]);
}

// True when two oriented boxes (aabb: centre and half sizes in a frame at pos with
// axes mat) are farther than margin apart along one of their six face normals (MuJoCo's
// mj_collideOBB without its shared products, with its arithmetic: a box infinite in every
// direction is never apart, and the faces of a box are not tested against one infinite in
// some direction). The centres' projections come from the centres (geoms); tree walks
// take them from the frames' shared products (TreeFrames).
bool OrientedBoxesApart(const double* aabb1, const double* pos1, const double* mat1,
                        const double* aabb2, const double* pos2, const double* mat2,
                        double margin) {
  const double* aabb[2] = {aabb1, aabb2};
  const double* mat[2] = {mat1, mat2};
  const double* pos[2] = {pos1, pos2};
  bool infinite[2];
  if (AnyBoxEverywhere(aabb, infinite)) return false;
  // Box centres in the world, and each box's axes (columns of its frame).
  double centre[2][3], axis[2][3][3];
  for (int i = 0; i < 2; i++) {
    math::MulMatVec3(centre[i], mat[i], aabb[i]);
    for (int k = 0; k < 3; k++) centre[i][k] += pos[i][k];
    for (int j = 0; j < 3; j++) {
      for (int k = 0; k < 3; k++) axis[i][j][k] = mat[i][3 * k + j];
    }
  }
  // Along each face normal of box j: the centres' projections and the half widths.
  for (int j = 0; j < 2; j++) {
    if (infinite[1 - j]) continue;
    for (int k = 0; k < 3; k++) {
      const double* normal = axis[j][k];
      double along[2][3], proj[2];
      for (int i = 0; i < 2; i++) {
        for (int l = 0; l < 3; l++) along[i][l] = math::Dot3(axis[i][l], normal);
        proj[i] = math::Dot3(centre[i], normal);
      }
      if (ApartAlong(aabb, along, proj, margin)) return true;
    }
  }
  return false;
}

// The same for two geoms' boxes (geom_aabb in each geom's frame).
bool BoxesApart(const Model& m, const Data& d, int g1, int g2, double margin) {
  return OrientedBoxesApart(&m.geom_aabb[6 * g1], &d.geom_xpos[3 * g1], &d.geom_xmat[9 * g1],
                            &m.geom_aabb[6 * g2], &d.geom_xpos[3 * g2], &d.geom_xmat[9 * g2],
                            margin);
}

// Is the point outside box (pos, mat, size) inflated by `ratio` (1), inside the box
// deflated by it (-1), or in between (0)?  (mju_outsideBox)
int OutsideBox(const double* point, const double* pos, const double* mat, const double* size,
               double ratio) {
  double dif[3], local[3];
  math::Sub3(dif, point, pos);
  math::MulMatTVec3(local, mat, dif);
  for (int k = 0; k < 3; k++) {
    if (local[k] > size[k] * ratio || local[k] < -size[k] * ratio) return 1;
  }
  for (int k = 0; k < 3; k++) {
    if (local[k] > size[k] / ratio || local[k] < -size[k] / ratio) return 0;
  }
  return -1;
}

// Box-box contacts outside one box and not inside the other, and repeated positions,
// are dropped (MuJoCo's clean-up after mjc_BoxBox). Returns the new count.
int CleanBoxBox(const Model& m, const Data& d, Contact* con, int num, int g1, int g2,
                double margin) {
  constexpr double kRemoveRatio = 1.01;
  bool bad[kMaxContactPair] = {};
  double size1[3], size2[3];
  for (int k = 0; k < 3; k++) {
    size1[k] = m.geom_size[3 * g1 + k] + margin;
    size2[k] = m.geom_size[3 * g2 + k] + margin;
  }
  for (int i = 0; i < num; i++) {
    int out1 = OutsideBox(con[i].pos, &d.geom_xpos[3 * g1], &d.geom_xmat[9 * g1], size1,
                          kRemoveRatio);
    int out2 = OutsideBox(con[i].pos, &d.geom_xpos[3 * g2], &d.geom_xmat[9 * g2], size2,
                          kRemoveRatio);
    bad[i] = (out1 == 1 && out2 != -1) || (out2 == 1 && out1 != -1);
  }
  // A contact repeated later is dropped in favour of the later one.
  for (int i = 0; i < num - 1; i++) {
    if (bad[i]) continue;
    for (int j = i + 1; j < num; j++) {
      if (bad[j]) continue;
      if (con[i].pos[0] == con[j].pos[0] && con[i].pos[1] == con[j].pos[1] &&
          con[i].pos[2] == con[j].pos[2]) {
        bad[i] = 1;
        break;
      }
    }
  }
  int kept = 0;
  for (int j = 0; j < num; j++) {
    if (bad[j]) continue;
    if (kept < j) con[kept] = con[j];
    kept++;
  }
  return kept;
}

// ------------------------------------------------------------ one geom pair

// Collides geoms g1 and g2, or explicit pair `ipair` (g1 = g2 = -1), and appends the
// contacts to d.contact (mj_collideGeoms).
void CollideGeoms(const Model& m, Data& d, int g1, int g2, int ipair) {
  if (ipair >= 0) {
    g1 = m.pair_geom1[ipair];
    g2 = m.pair_geom2[ipair];
    // (with sleep enabled, a pair of which neither body is awake is skipped)
    if ((m.opt.enableflags & kEnableSleep) && d.body_awake[m.geom_bodyid[g1]] != kAwake &&
        d.body_awake[m.geom_bodyid[g2]] != kAwake) {
      return;
    }
  }
  if (m.geom_type[g1] > m.geom_type[g2]) std::swap(g1, g2);
  CollideFn collide = CollisionFunction(m.geom_type[g1], m.geom_type[g2]);
  if (!collide) return;
  if (ipair < 0 && BitmaskRejects(m.geom_contype[g1], m.geom_conaffinity[g1],
                                  m.geom_contype[g2], m.geom_conaffinity[g2])) {
    return;
  }
  double margin = AssignMargin(m, ipair < 0 ? m.geom_margin[g1] + m.geom_margin[g2]
                                            : m.pair_margin[ipair]);
  if (SpheresApart(m, d, g1, g2, margin)) return;

  // Narrow phase into the free end of the contact array.
  Contact* con = ContactRoom(d, kMaxContactPair);
  int num = collide(m, d, con, g1, g2, margin);
  if (num <= 0) return;
  if (m.geom_type[g1] == kGeomBox && m.geom_type[g2] == kGeomBox) {
    num = CleanBoxBox(m, d, con, num, g1, g2, margin);
  }
  // Parameters: the pair's own, or combined from the two geoms; a tangent only where the
  // collider chose one (SetContact completes the frame from it, or from none).
  ContactParams p = ipair < 0 ? GeomPairParams(m, g1, g2) : PairParams(m, ipair);
  bool tangent = ChoosesTangent(collide);
  for (int i = 0; i < num; i++) {
    if (!tangent) math::Zero3(con[i].frame + 3);
    SetContact(m, p, margin - p.gap, g1, g2, con + i);
  }
  d.ncon += num;
}

// Collides geoms g1, g2 unless an explicit pair of this body pair (pairs [start, end))
// already covers them (mj_collideGeomPair).
void CollideUnlessPaired(const Model& m, Data& d, int g1, int g2, int start, int end) {
  for (int k = start; k < end; k++) {
    if ((m.pair_geom1[k] == g1 && m.pair_geom2[k] == g2) ||
        (m.pair_geom1[k] == g2 && m.pair_geom2[k] == g1)) {
      return;
    }
  }
  CollideGeoms(m, d, g1, g2, -1);
}

// ------------------------------------------------------------ broad phase

// Can body b collide with anything? (bodyflex ids: b >= nbody is flex b - nbody)
bool CanCollide(const Model& m, int b) {
  if (b >= m.nbody) return m.flex_contype[b - m.nbody] || m.flex_conaffinity[b - m.nbody];
  return m.body_contype[b] || m.body_conaffinity[b];
}

// The contype and conaffinity of a body (its geoms' together) or of a flex.
int ContypeOf(const Model& m, int b) {
  return b < m.nbody ? m.body_contype[b] : m.flex_contype[b - m.nbody];
}
int ConaffinityOf(const Model& m, int b) {
  return b < m.nbody ? m.body_conaffinity[b] : m.flex_conaffinity[b - m.nbody];
}

bool HasPlane(const Model& m, int b) {
  for (int g = m.body_geomadr[b]; g < m.body_geomadr[b] + m.body_geomnum[b]; g++) {
    if (m.geom_type[g] == kGeomPlane) return true;
  }
  return false;
}

// True when MuJoCo never collides these bodies: welded together, or (unless the
// filterparent flag is disabled) one welded to the other's parent (filterBodyPair); or,
// while trees sleep (body_awake given, else null), both asleep, or one asleep and the
// other welded to the world. `always1` marks the world side of the always-colliding
// pairs (which counts as asleep).
bool BodyPairFiltered(const Model& m, const int* body_awake, int b1, int b2, bool always1) {
  int weld1 = always1 ? 0 : m.body_weldid[b1];
  int weld2 = m.body_weldid[b2];
  int parent1 = always1 ? 0 : m.body_weldid[m.body_parentid[weld1]];
  int parent2 = m.body_weldid[m.body_parentid[weld2]];
  if (weld1 == weld2) return true;
  if (body_awake) {
    bool asleep1 = always1 || body_awake[b1] == kAsleep, asleep2 = body_awake[b2] == kAsleep;
    if ((asleep1 && asleep2) || (asleep1 && weld2 == 0) || (asleep2 && weld1 == 0)) return true;
  }
  if (always1 && weld2 == 0) return true;
  bool filterparent = !Disabled(m, kDisableFilterparent);
  return filterparent && weld1 != 0 && weld2 != 0 && (weld1 == parent2 || weld2 == parent1);
}

// Does body-or-flex b (b >= nbody: flex b - nbody) move and is it awake? A flex is as its
// trees (ElementSleepState), a body must be awake and on a tree.
bool MovesAwake(const Model& m, const Data& d, int b) {
  if (b >= m.nbody) return ElementSleepState(m, d, kObjFlex, b - m.nbody) == kAwake;
  return d.body_awake[b] == kAwake && m.body_treeid[b] >= 0;
}

// The principal frame (rows) of the moving points, geoms' centres and flex vertices not
// on the world: sweep-and-prune runs along its first axis, where the bodies spread most.
// False, with no frame, when there are no moving points.
bool PrincipalFrame(const Model& m, const Data& d, double frame[9]) {
  double cen[3] = {0, 0, 0}, cov[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  int count = 0;
  for (int g = 0; g < m.ngeom; g++) {
    if (!m.geom_bodyid[g]) continue;
    math::Add3(cen, cen, &d.geom_xpos[3 * g]);
    count++;
  }
  for (int v = 0; v < m.nflexvert; v++) {
    if (!m.flex_vertbodyid[v]) continue;
    math::Add3(cen, cen, &d.flexvert_xpos[3 * v]);
    count++;
  }
  if (count == 0) return false;
  math::Scale3(cen, cen, 1.0 / count);
  auto accumulate = [&](const double* point) {
    double dif[3];
    math::Sub3(dif, point, cen);
    for (int r = 0; r < 3; r++) {
      for (int c = 0; c < 3; c++) cov[3 * r + c] += dif[r] * dif[c];
    }
  };
  for (int g = 0; g < m.ngeom; g++) {
    if (m.geom_bodyid[g]) accumulate(&d.geom_xpos[3 * g]);
  }
  for (int v = 0; v < m.nflexvert; v++) {
    if (m.flex_vertbodyid[v]) accumulate(&d.flexvert_xpos[3 * v]);
  }
  for (double& x : cov) x *= 1.0 / count;
  double eigval[3], quat[4];
  math::Eig3(eigval, quat, cov, [](double* q) { math::NormalizeQuat(q); });
  math::QuatToMat(frame, quat);
  return true;
}

// A body's box in `frame`: its geoms' bounding spheres grown by their margins.
void BodyBox(const Model& m, const Data& d, int b, const double* frame, double* lo,
             double* hi) {
  for (int i = 0; i < m.body_geomnum[b]; i++) {
    int g = m.body_geomadr[b] + i;
    double margin = Enabled(m, kEnableOverride) ? 0.5 * m.opt.o_margin : m.geom_margin[g];
    for (int k = 0; k < 3; k++) {
      double c = math::Dot3(&d.geom_xpos[3 * g], frame + 3 * k);
      double r = m.geom_rbound[g] + margin;
      lo[k] = i == 0 ? c - r : std::min(lo[k], c - r);
      hi[k] = i == 0 ? c + r : std::max(hi[k], c + r);
    }
  }
}

// Sweep and prune (MuJoCo mj_SAP) over the collidable bodies' boxes (lo, hi per body, in
// `boxes` at 6 per body): interval ends on the first axis in single precision, sorted
// stably (ties keep min-then-max in body order); each opening interval meets the open
// ones whose boxes also overlap on the other two axes. Calls add(b1, b2) per candidate.
template <typename Add>
void SweepAndPrune(BroadPhaseScratch& s, const double* boxes, Add add) {
  // Interval i is body s.bodies[i] (ascending), so ties 2 i and 2 i + 1 keep the order
  // the ends would be added in: by body, its lower end first. (The collidable bodies are
  // the model's: last step's ends are the same intervals.)
  SortEnds(s.ends, 2 * s.bodies.size(), [&](uint32_t tie) {
    int b = s.bodies[tie >> 1];
    return SweepKey(boxes[6 * b + ((tie & 1) ? 3 : 0)], static_cast<int>(tie));
  });
  s.open.clear();
  for (uint64_t end : s.ends) {
    int id = s.bodies[(end & 0xFFFFFFFFu) >> 1];
    if (end & 1) {
      s.open.erase(std::find(s.open.begin(), s.open.end(), id));
      continue;
    }
    const double* x2 = boxes + 6 * id;
    for (int b1 : s.open) {
      const double* x1 = boxes + 6 * b1;
      // (one branch for the four tests: which of them fails is not predictable)
      bool apart = (x1[1] > x2[4]) | (x2[1] > x1[4]) | (x1[2] > x2[5]) | (x2[2] > x1[5]);
      if (!apart) add(b1, id);
    }
    s.open.push_back(id);
  }
}

// Body pairs worth testing, as sorted unique signatures (b1 << 16) + b2, b1 < b2, in
// d.broadphase.pairs: MuJoCo's mj_broadphase.
void BroadPhase(const Model& m, Data& d) {
  const int* sleeping = AnyAsleep(m, d) ? d.body_awake.data() : nullptr;
  std::vector<int>& pairs = d.broadphase.pairs;
  pairs.clear();
  auto add = [&](int b1, int b2) {
    if (BitmaskRejects(ContypeOf(m, b1), ConaffinityOf(m, b1), ContypeOf(m, b2),
                       ConaffinityOf(m, b2))) {
      return;
    }
    pairs.push_back((std::min(b1, b2) << 16) + std::max(b1, b2));
  };
  // The world's geoms and static bodies with planes meet every moving body.
  for (int b1 = 0; b1 < m.nbody; b1++) {
    if (!CanCollide(m, b1)) continue;
    if (!((b1 == 0 && m.body_geomnum[b1] > 0) || (m.body_weldid[b1] == 0 && HasPlane(m, b1)))) {
      continue;
    }
    for (int b2 = 0; b2 < m.nbody; b2++) {
      if (CanCollide(m, b2) && !BodyPairFiltered(m, sleeping, b1, b2, true)) add(b1, b2);
    }
    // (not a sleeping flex)
    for (int f = 0; f < m.nflex; f++) {
      if (!sleeping || ElementSleepState(m, d, kObjFlex, f) != kAsleep) add(b1, m.nbody + f);
    }
  }
  // Other bodies and flexes meet when their boxes overlap in the principal frame of the
  // moving geoms and flex vertices (there is none when every one is the world's). Fewer
  // than two collidable ones meet nothing: the frame is not computed.
  int nbodyflex = m.nbody + m.nflex;
  std::vector<int>& bodies = d.broadphase.bodies;
  bodies.clear();
  for (int b = 1; b < nbodyflex; b++) {
    if (CanCollide(m, b)) bodies.push_back(b);
  }
  double frame[9];
  if (bodies.size() >= 2 && PrincipalFrame(m, d, frame)) {
    StackFrame scratch(d);
    double* boxes = scratch.Alloc(6 * static_cast<size_t>(nbodyflex));
    for (int b : bodies) {
      if (b < m.nbody) {
        BodyBox(m, d, b, frame, &boxes[6 * b], &boxes[6 * b + 3]);
      } else {
        FlexBox(m, d, b - m.nbody, frame, &boxes[6 * b], &boxes[6 * b + 3]);
      }
    }
    SweepAndPrune(d.broadphase, boxes, [&](int b1, int b2) {
      // (the weld filter is for body pairs only; while trees sleep, a pair with a flex
      // is kept when either side moves awake)
      bool two_bodies = b1 < m.nbody && b2 < m.nbody;
      if (two_bodies ? !BodyPairFiltered(m, sleeping, b1, b2, false)
                     : !sleeping || MovesAwake(m, d, b1) || MovesAwake(m, d, b2)) {
        add(b1, b2);
      }
    });
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
}

// ------------------------------------------------------------ one body pair

// The geom pairs of bodies b1 < b2 that no explicit pair in [start, end) covers.
// The leaf geom of node `node` of body b's tree, or -1 for an inner node.
int LeafGeom(const Model& m, int b, int node) {
  const int* child = &m.bvh_child[2 * (m.body_bvhadr[b] + node)];
  return child[0] < 0 && child[1] < 0 ? m.bvh_nodeid[m.body_bvhadr[b] + node] : -1;
}

// Do the boxes of node n1 of body b1's tree and node n2 of b2's overlap (within margin)?
// (frames: the two bodies' inertial frames)
bool NodesOverlap(const Model& m, TreeFrames& frames, int b1, int n1, int b2, int n2,
                  double margin) {
  return !frames.Apart(&m.bvh_aabb[6 * (m.body_bvhadr[b1] + n1)],
                       &m.bvh_aabb[6 * (m.body_bvhadr[b2] + n2)], margin);
}

// The surface area of node n of body b's box, over 8 (from its half sizes).
double NodeArea(const Model& m, int b, int n) {
  const double* half = &m.bvh_aabb[6 * (m.body_bvhadr[b] + n) + 3];
  return half[0] * half[1] + half[1] * half[2] + half[2] * half[0];
}

// The object side k of a contact is sorted by: its geom, else its flex element, else
// its flex vertex (MuJoCo's contactcompare).
int SortObject(const Contact& c, int k) {
  return c.geom[k] >= 0 ? c.geom[k] : (c.elem[k] >= 0 ? c.elem[k] : c.vert[k]);
}

}  // namespace

// Sorts the contacts [first, d.ncon) by the objects of their two sides (for geom-geom
// contacts: by (geom[0], geom[1])), keeping the order of equals: an index sort, then one
// permutation through the free end of d.contact (the contacts are large; this allocates
// only when that end is short).
void SortContacts(Data& d, int first) {
  int n = d.ncon - first;
  if (n < 2) return;
  Contact* con = d.contact.data() + first;
  SolverFrame ints(d.solver_scratch);
  int* order = ints.IntsToWrite(n);
  for (int i = 0; i < n; i++) order[i] = i;
  std::sort(order, order + n, [con](int a, int b) {
    int a0 = SortObject(con[a], 0), b0 = SortObject(con[b], 0);
    if (a0 != b0) return a0 < b0;
    int a1 = SortObject(con[a], 1), b1 = SortObject(con[b], 1);
    return a1 != b1 ? a1 < b1 : a < b;
  });
  bool sorted = true;
  for (int i = 0; i < n && sorted; i++) sorted = order[i] == i;
  if (sorted) return;
  // (ContactRoom may move the array: the contacts are found again after it)
  Contact* spare = ContactRoom(d, n);
  con = d.contact.data() + first;
  std::copy(con, con + n, spare);
  for (int i = 0; i < n; i++) con[i] = spare[order[i]];
}

namespace {

// Collides the geoms of two bodies by walking their trees together (MuJoCo's
// mj_collideTree for two bodies): a pair of nodes whose boxes are apart is dropped with
// everything below it; otherwise the larger (by surface) of two inner nodes, or the
// inner one of a leaf and an inner node, is opened. Leaf pairs go to the narrow phase.
// The body pair's contacts are then sorted by geom pair, as MuJoCo sorts them, so that
// the tree's shape never shows in the result.
void CollideTrees(const Model& m, Data& d, int b1, int b2, int start, int end) {
  int ncon_before = d.ncon;
  double margin = AssignMargin(m, m.body_margin[b1] + m.body_margin[b2]);
  SolverFrame ints(d.solver_scratch);
  int* stack = ints.IntsToWrite(2 * static_cast<size_t>(m.body_bvhnum[b1] + m.body_bvhnum[b2]));
  int nstack = 1;
  stack[0] = stack[1] = 0;
  TreeFrames frames(&d.xipos[3 * b1], &d.ximat[9 * b1], &d.xipos[3 * b2], &d.ximat[9 * b2]);
  while (nstack) {
    nstack--;
    int n1 = stack[2 * nstack], n2 = stack[2 * nstack + 1];
    int leaf1 = LeafGeom(m, b1, n1), leaf2 = LeafGeom(m, b2, n2);
    if (leaf1 >= 0 && leaf2 >= 0) {
      // (two leaves: their geoms' spheres and boxes first, as MuJoCo's midphase)
      double pair_margin = AssignMargin(m, m.geom_margin[leaf1] + m.geom_margin[leaf2]);
      if (!SpheresApart(m, d, leaf1, leaf2, pair_margin) && !BoxesApart(m, d, leaf1, leaf2, pair_margin)) {
        CollideUnlessPaired(m, d, leaf1, leaf2, start, end);
      }
      continue;
    }
    if (!NodesOverlap(m, frames, b1, n1, b2, n2, margin)) continue;
    // Open node 1 or node 2: push its children.
    bool open1 = leaf2 >= 0 || (leaf1 < 0 && NodeArea(m, b1, n1) > NodeArea(m, b2, n2));
    int opened = open1 ? m.body_bvhadr[b1] + n1 : m.body_bvhadr[b2] + n2;
    const int* child = &m.bvh_child[2 * opened];
    for (int i = 0; i < 2; i++) {
      if (child[i] < 0) continue;
      stack[2 * nstack] = open1 ? child[i] : n1;
      stack[2 * nstack + 1] = open1 ? n2 : child[i];
      nstack++;
    }
  }
  SortContacts(d, ncon_before);
}

// Collides the geoms of two bodies: through their trees when both have several geoms
// (unless the midphase is disabled), else every geom with every geom.
void CollideBodies(const Model& m, Data& d, int b1, int b2, int start, int end) {
  bool single = m.body_geomnum[b1] == 1 && m.body_geomnum[b2] == 1;
  bool trees = m.body_bvhadr[b1] >= 0 && m.body_bvhadr[b2] >= 0;
  if (!single && trees && !Disabled(m, kDisableMidphase)) {
    CollideTrees(m, d, b1, b2, start, end);
    return;
  }
  for (int g1 = m.body_geomadr[b1]; g1 < m.body_geomadr[b1] + m.body_geomnum[b1]; g1++) {
    for (int g2 = m.body_geomadr[b2]; g2 < m.body_geomadr[b2] + m.body_geomnum[b2]; g2++) {
      CollideUnlessPaired(m, d, g1, g2, start, end);
    }
  }
}

}  // namespace

void CompleteContactFrame(double* frame) {
  math::Normalize3(frame);
  double* y = frame + 3;
  if (math::Dot3(y, y) < 0.25) {
    math::Zero3(y);
    if (frame[1] < 0.5 && frame[1] > -0.5) {
      y[1] = 1;
    } else {
      y[2] = 1;
    }
  }
  double along = math::Dot3(frame, y);
  for (int k = 0; k < 3; k++) y[k] -= along * frame[k];
  math::Normalize3(y);
  math::Cross3(frame + 6, frame, y);
}

void Collision(const Model& m, Data& d) {
  d.ncon = 0;
  if (Disabled(m, kDisableConstraint) || Disabled(m, kDisableContact) ||
      m.nbody + m.nflex < 2) {
    return;
  }

  {
    StageTimer timer(d, kTimerColBroad);
    BroadPhase(m, d);
  }
  StageTimer timer(d, kTimerColNarrow);
  int pairadr = 0, exadr = 0;
  for (int signature : d.broadphase.pairs) {
    // Explicit pairs up to this signature come first.
    int start = pairadr;
    while (pairadr < m.npair && m.pair_signature[pairadr] <= signature) {
      CollideGeoms(m, d, -1, -1, pairadr++);
    }
    // Excluded body pairs.
    while (exadr < m.nexclude && m.exclude_signature[exadr] < signature) exadr++;
    if (exadr < m.nexclude && m.exclude_signature[exadr] == signature) continue;
    int b1 = signature >> 16, b2 = signature & 0xFFFF;
    if (b2 >= m.nbody) {
      CollideWithFlex(m, d, b1, b2);
    } else {
      CollideBodies(m, d, b1, b2, start, pairadr);
    }
  }
  // Explicit pairs past the last body pair.
  while (pairadr < m.npair) CollideGeoms(m, d, -1, -1, pairadr++);
  // Flexes with themselves (not while asleep).
  CollideFlexSelf(m, d);
}

// The end's value in single precision, its bits mapped to unsigned ones in the same
// order (a NaN as +inf, -0 as +0), above the tie order.
uint64_t SweepKey(double x, int tie) {
  float f = std::isnan(x) ? std::numeric_limits<float>::infinity() : static_cast<float>(x);
  if (f == 0) f = 0;
  uint32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
  bits = (bits & 0x80000000u) ? ~bits : (bits | 0x80000000u);
  return (static_cast<uint64_t>(bits) << 32) | static_cast<uint32_t>(tie);
}

// (the world's axes and origin give MuJoCo's numbers for a missing frame exactly)
constexpr double kIdentity[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
constexpr double kOrigin[3] = {0, 0, 0};

bool BoxesApartOriented(const double* aabb1, const double* pos1, const double* mat1,
                        const double* aabb2, const double* pos2, const double* mat2,
                        double margin) {
  return OrientedBoxesApart(aabb1, pos1 ? pos1 : kOrigin, mat1 ? mat1 : kIdentity, aabb2,
                            pos2 ? pos2 : kOrigin, mat2 ? mat2 : kIdentity, margin);
}

TreeFrames::TreeFrames(const double* pos1, const double* mat1, const double* pos2,
                       const double* mat2)
    : pos_{pos1 ? pos1 : kOrigin, pos2 ? pos2 : kOrigin},
      mat_{mat1 ? mat1 : kIdentity, mat2 ? mat2 : kIdentity} {}

void TreeFrames::Make() {
  double axis[2][3][3];
  for (int i = 0; i < 2; i++) {
    for (int j = 0; j < 3; j++) {
      for (int k = 0; k < 3; k++) axis[i][j][k] = mat_[i][3 * k + j];
    }
  }
  for (int i = 0; i < 2; i++) {
    for (int j = 0; j < 2; j++) {
      for (int k = 0; k < 3; k++) {
        for (int l = 0; l < 3; l++) product_[i][j][k][l] = math::Dot3(axis[i][l], axis[j][k]);
        offset_[i][j][k] = math::Dot3(pos_[i], axis[j][k]);
      }
    }
  }
  made_ = true;
}

bool TreeFrames::Apart(const double* aabb1, const double* aabb2, double margin) {
  const double* aabb[2] = {aabb1, aabb2};
  bool infinite[2];
  if (AnyBoxEverywhere(aabb, infinite)) return false;
  if (!made_) Make();
  for (int j = 0; j < 2; j++) {
    if (infinite[1 - j]) continue;
    for (int k = 0; k < 3; k++) {
      double along[2][3], proj[2];
      for (int i = 0; i < 2; i++) {
        const double* product = product_[i][j][k];
        const double* c = aabb[i];
        for (int l = 0; l < 3; l++) along[i][l] = product[l];
        proj[i] = c[0] * product[0] + c[1] * product[1] + c[2] * product[2] + offset_[i][j][k];
      }
      if (ApartAlong(aabb, along, proj, margin)) return true;
    }
  }
  return false;
}

}  // namespace simlab
