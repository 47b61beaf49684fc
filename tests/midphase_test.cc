// The midphase (the bodies' bounding volume trees) only prunes geom pairs that cannot
// touch: along a rollout of bodies with several geoms each, every state's contacts are
// the ones that the all-pairs loop (midphase disabled) finds, geom pair by geom pair.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <tuple>
#include <vector>

#include "simlab/simlab.h"

namespace simlab {
namespace {

using ContactKey = std::tuple<int, int, double, double, double, double>;

// The contacts after Forward, as (geom1, geom2, dist, pos) in a fixed order.
std::vector<ContactKey> SortedContacts(const Model& m, Data d) {
  Forward(m, d);
  std::vector<ContactKey> keys;
  for (int i = 0; i < d.ncon; i++) {
    const Contact& c = d.contact[i];
    keys.emplace_back(c.geom[0], c.geom[1], c.dist, c.pos[0], c.pos[1], c.pos[2]);
  }
  std::sort(keys.begin(), keys.end());
  return keys;
}

TEST(Midphase, FindsWhatAllPairsFind) {
  Model m = LoadXml(std::string(SIMLAB_SOURCE_DIR) +
                    "/tests/collision_pairs/models/midphase_mixed.xml");
  Model all_pairs = m;
  all_pairs.opt.disableflags |= kDisableMidphase;
  ASSERT_GT(m.nbvh, 0);
  Data d = MakeData(m);
  int steps_with_contacts = 0;
  for (int step = 0; step < 400; step++) {
    std::vector<ContactKey> tree = SortedContacts(m, d);
    std::vector<ContactKey> loop = SortedContacts(all_pairs, d);
    ASSERT_EQ(tree, loop) << "step " << step;
    steps_with_contacts += !tree.empty();
    Step(m, d);
  }
  EXPECT_GT(steps_with_contacts, 300);
}

}  // namespace
}  // namespace simlab
