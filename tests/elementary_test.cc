// The elementary functions of math/elementary.h against values printed by the C library
// of MuJoCo's WebAssembly build (emscripten's musl, `%a` of sin, cos, atan, atan2, asin and
// acos at random arguments). Each row was picked where glibc rounds at least one of the six
// differently, so std::sin and company would fail here.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "math/elementary.h"

namespace simlab::math {
namespace {

// x, y, u, then sin x, cos x, atan x, atan2(y, x), asin u, acos u.
struct Sample {
  double x, y, u, sin, cos, atan, atan2, asin, acos;
};

constexpr Sample kSamples[] = {
    {-0x1.573232a1474dp-1, -0x1.4043be1762b5ap-1, 0x1.9024f7e10caa2p-1, -0x1.3e1130f7a3f85p-1, 0x1.91384161da9ccp-1, -0x1.2e584292d796bp-1, -0x1.3203e77dcd4f2p+1, 0x1.cb5305bf74d96p-1, 0x1.58ec64c910c9ap-1},
    {0x1.dc2aecd061d4p-1, -0x1.e468432b4de4p-3, 0x1.a114417b631dep-1, 0x1.9a6f1a8935d49p-1, 0x1.3215b87211aa6p-1, 0x1.7f90f01c6a766p-1, -0x1.fe0bd7e1111bbp-3, 0x1.e7736b1817fc7p-1, 0x1.3ccbff706da6ap-1},
    {0x1.d69400e0bc08cp+0, 0x1.331426cefbf71p+3, -0x1.b865972e08b5cp-1, 0x1.edcdddee51f43p-1, -0x1.0e90cf0e3d6efp-2, 0x1.1293716db207p+0, 0x1.61ac407dce1c2p+0, -0x1.091ab636af549p+0, 0x1.4d9d35bd7913p+1},
    {-0x1.c9b93813df3c5p+2, -0x1.bfe79bad34264p+0, -0x1.cda3905656544p-1, -0x1.86ebef9804e21p-1, 0x1.4aa46918ea8e6p-1, -0x1.6e8f550991674p+0, -0x1.7369d8e9ce44cp+1, -0x1.1fa087afd0668p+0, 0x1.58e01e7a099cp+1},
    {-0x1.375d4a9dd699p+7, 0x1.18beb4a27ef26p+9, -0x1.a9496c6b1a294p-1, 0x1.f85305daeab66p-1, 0x1.614afbc7c7a51p-3, -0x1.907ac0f5fda13p+0, 0x1.d75d5b316218cp+0, -0x1.f5e3ba848cd94p-1, 0x1.4688c943449f1p+1},
    {-0x1.3af37d5609694p-1, 0x1.49f4bf78d25d8p-1, 0x1.f2ab340bc09ccp-2, -0x1.2775fad539943p-1, 0x1.a2259f3c9c30cp-1, -0x1.1a5b29773931fp-1, 0x1.2a9d833c2ccb4p+1, 0x1.046b29ffcfaecp-1, 0x1.0fea20445afa2p+0},
    {-0x1.fe3cf0766d6f9p+8, 0x1.f645003ef8c74p+11, 0x1.c3f956fa56862p-1, -0x1.ed58b3573f20cp-1, 0x1.11e28d695d374p-2, -0x1.919f442777ae8p+0, 0x1.b2755f4c37954p+0, 0x1.14ead5acbe80bp+0, 0x1.f4d37e5e11434p-2},
    {0x1.03b406962feb9p-10, 0x1.a0953548d8d69p-13, -0x1.4f812b7ecb6dep-1, 0x1.03b403cd76d11p-10, 0x1.ffffef88a3d7cp-1, 0x1.03b40104bde8fp-10, 0x1.9544bd0f1f95p-3, -0x1.6dda54d0bbc29p-1, 0x1.24866fd650596p+1},
    {0x1.6ee23b6edd792p-4, -0x1.b7a72021a3aa7p-5, 0x1.35334e8dd5d3p-2, 0x1.6e64b15b2c71ep-4, 0x1.fdf28e4e6303cp-1, 0x1.6de841436cep-4, -0x1.146206d5c28a8p-1, 0x1.3a1a5bb93bbffp-2, 0x1.43991e55f3e19p+0},
    {-0x1.21db1e97e1fc9p-7, -0x1.c65909430695ap-8, -0x1.b9a0d8efd8548p-3, -0x1.21da26ddb7c5bp-7, 0x1.fffadf4056797p-1, -0x1.21d92f2902d8bp-7, -0x1.3d091c8f8aa34p+1, -0x1.bd1fe5fb90b19p-3, 0x1.c9c3b203b4e7cp+0},
    {0x1.2d636eaf3f581p-7, -0x1.e780025b5ec9p-10, 0x1.2e6123c1ba596p-1, 0x1.2d6258324cc62p-7, 0x1.fffa74b6ac1edp-1, 0x1.2d6141bbfc784p-7, -0x1.9893529aac6cp-3, 0x1.43791d909393ep-1, 0x1.e0c64cf7f20f2p-1},
    {-0x1.252c3dc47a79dp+9, 0x1.c51008314b4b8p+9, -0x1.4b7870972f4ccp-1, -0x1.cf895ec04997dp-1, -0x1.b2de87e5f20fdp-2, -0x1.91aff01c0f108p+0, 0x1.12936be66c84fp+1, -0x1.68894724e4e3ap-1, 0x1.23322c6b5aa1ap+1},
    {0x1.ef4f552e7611p-3, -0x1.59ea6f6a46866p-1, -0x1.bc3b25d782494p-1, 0x1.ea7ed33d87ac8p-3, 0x1.f1195669a851ep-1, 0x1.e5fa649807b58p-3, -0x1.3a1f3a1292f44p+0, -0x1.0ce9330dfe303p+0, 0x1.4f8474292080ep+1},
    {0x1.775c8f89d494dp-7, -0x1.e6580b728edbap-5, 0x1.ad02588915e98p-3, 0x1.775a758c059c7p-7, 0x1.fff76684f1b66p-1, 0x1.77585ba217559p-7, -0x1.6154012145fcep+0, 0x1.b035d79ab09aep-3, 0x1.5c18fa50ecbe2p+0},
    {-0x1.4a821e2780804p+12, -0x1.ce55b06bd50cbp+11, 0x1.425c14041ea94p-1, 0x1.7a7c523107304p-1, -0x1.58cedfe618d67p-1, -0x1.921350a6722c6p+0, -0x1.43fffb274a805p+1, 0x1.5cb28598f9d52p-1, 0x1.c78ce4ef8bcdep-1},
    {0x1.cca9792148caap+2, 0x1.ba4861da641c8p-2, 0x1.4d8fb126886dp-3, 0x1.95af76ab2f97fp-1, 0x1.3859f0aea1e8ep-1, 0x1.6ec8ab96e1146p+0, 0x1.eafbd659b5543p-5, 0x1.4f0dce0f0b7e1p-3, 0x1.683dfb826161cp+0},
    {0x1.29441e6b39833p-9, -0x1.94ac01204f71fp-9, 0x1.9480f17f91394p-2, 0x1.29440db7bedb7p-9, 0x1.ffffa9b43a3f5p-1, 0x1.2943fd044a652p-9, -0x1.dfdd198693294p-1, 0x1.9fd6d9d1076a2p-2, 0x1.2a29fed000f7p+0},
    {0x1.2f7614ac14636p+6, -0x1.9d97d52825667p+5, 0x1.992dea1e19dbap-1, 0x1.cd18b10957dc3p-2, 0x1.c927e8f8ad882p-1, 0x1.8ebfe951c1edep+0, -0x1.3243dc50e493fp-1, 0x1.da1320623ea92p-1, 0x1.4a2c4a2646f9ep-1},
    {-0x1.876b96d7b38acp+2, -0x1.81e23a9ff0b88p+1, -0x1.33e7b656c21fep-1, 0x1.54eb9d9499da7p-3, 0x1.f8db331279505p-1, -0x1.68a2184b51b13p+0, -0x1.5780d373e881ap+1, -0x1.4a5ac37cd301p-1, 0x1.1ba68b815629p+1},
    {-0x1.9db0588dff7d8p+12, 0x1.52b750f6e02c3p+12, -0x1.798776b2e66d6p-1, -0x1.3c60810460c1cp-2, -0x1.e6f339fdddcbp-1, -0x1.9215ce91c4172p+0, 0x1.3a4e2dd133992p+1, -0x1.a88728756e8eep-1, 0x1.3331a4bf7d0c8p+1},
    {0x1.fc7200c41fc68p-1, 0x1.4003df7a360dp-1, 0x1.33e3af7ed1a4p-6, 0x1.ace6f50e76375p-1, 0x1.179e86e8dec91p-1, 0x1.9057205ef4ba5p-1, 0x1.1f9e8fa61c5edp-1, 0x1.33e8534ab5e81p-6, 0x1.8d5013f717f9ep+0},
    {-0x1.f2a3e6bd4d71ep-1, 0x1.8ce4073d6843cp-2, 0x1.2a6ca81f54b7ep-1, -0x1.a7780ffb418f3p-1, 0x1.1fc7fbd4d45fcp-1, -0x1.8b5b2781e798fp-1, 0x1.61a492ce9c52p+1, 0x1.3e96cc1107d3cp-1, 0x1.e5a89e777dcf4p-1},
    {-0x1.6f1e337a5b70cp+6, -0x1.052cb48d7b195p+5, 0x1.46136874a60e8p-2, 0x1.3f451bd5f19c8p-1, -0x1.90436678f57eap-1, -0x1.8f55ad522dafcp+0, -0x1.66612d2920165p+1, 0x1.4bdaafd839cc3p-2, 0x1.3f29094e345e8p+0},
    {0x1.9cbdd922c400fp+9, 0x1.889a0ef76ddafp+8, 0x1.894065a4c8374p-1, 0x1.5f1ef1b1ff312p-1, -0x1.74a300958ba78p-1, 0x1.91d0512923392p+0, 0x1.c6982307b8261p-2, 0x1.c06b98b4e8a75p-1, 0x1.63d3d1d39cfbcp-1},
    {-0x1.c8b8a92b10136p+2, -0x1.fca85e914a53dp+1, -0x1.bd1f1b94560b2p-1, -0x1.81b2448b809fep-1, 0x1.50b910b9d744ep-1, -0x1.6e7b9c8378078p+0, -0x1.5116838fcfab4p+1, -0x1.0dcf265b54d9ep+0, 0x1.4ff76dcfcbd5bp+1},
    {-0x1.245e089d03dabp+9, -0x1.cb99f642858d5p+9, 0x1.405d2e17521dep-1, -0x1.8d424460e801cp-2, 0x1.d7e699cf296a1p-1, -0x1.91afa14724ea3p+0, -0x1.11950aae3bf7cp+1, 0x1.5a223ff54fcdfp-1, 0x1.ca1d2a9335d51p-1},
    {0x1.4951695fd2c1ap+12, 0x1.8385a5c64d722p+11, -0x1.ad4cc4888745p-3, -0x1.30ac50159cf3ep-1, -0x1.9b7ba9723376ap-1, 0x1.9213452ef0065p+0, 0x1.104b4f4d7b502p-1, -0x1.b081f4313bc7dp-3, 0x1.c82ff3ca6a4a8p+0},
    {-0x1.10e37d5a216cbp+3, 0x1.b08060bd7fac6p+1, -0x1.96b2cc10a28ap-2, -0x1.901c0247cf5fap-1, -0x1.3f7677f81630cp-1, -0x1.743da286cea7ap+0, 0x1.61d60b28dfa3p+1, -0x1.a23ac0a2a6582p-2, 0x1.faae656cec679p+0},
    {-0x1.2d2d63f80eecp-1, 0x1.0992b1bb001dp-1, -0x1.96d2c0268edecp-1, -0x1.1c1b37936f24cp-1, 0x1.a9f174dfba9eep-1, -0x1.103e4bc3bccdcp-1, 0x1.359f9fde10346p+1, -0x1.d62cba828aa0ap-1, 0x1.3e9b0942c410fp+1},
    {-0x1.86a728e5421b6p-1, 0x1.146470af7f10cp-2, -0x1.3cbafc4395528p-3, -0x1.61d65c674436dp-1, 0x1.720eeb8587d0bp-1, -0x1.4db437e9a37fcp-1, 0x1.669a01791ebe4p+1, -0x1.3e01bc064b09dp-3, 0x1.b9dfecc50c32cp+0},
    {-0x1.dcdb161420dcap+12, 0x1.ade3141737b2fp+9, 0x1.ccfe040bee6c4p-2, -0x1.e3841993f70eep-1, -0x1.50c94ed874a62p-2, -0x1.92171e545330bp+0, 0x1.83c2a9bfda0a6p+1, 0x1.de2ed8da68c27p-2, 0x1.1a93ff0da8a0ep+0},
    {-0x1.4715697625a5ep-1, 0x1.7377a28fa8958p-3, -0x1.06cee0adcbb4p-5, -0x1.314917eb3273ep-1, 0x1.9b0765810008bp-1, -0x1.2310a7c65ebdap-1, 0x1.6eb6a72d9d66p+1, -0x1.06da6c6b67819p-5, 0x1.9a5688a79e0d9p+0},
    {0x1.6e8843f2d095cp+1, 0x1.2e05bc724a544p+3, -0x1.3378cd270387p-3, 0x1.1913dfd604b59p-2, -0x1.ec5585e79202ap-1, 0x1.3c1d0093476bcp+0, 0x1.46b6aaf27bc95p+0, -0x1.34a389842b163p-3, 0x1.b8b42674c8345p+0},
    {-0x1.8977dd766410ap-4, 0x1.f9036a9f28dd7p-5, -0x1.c4e47b61841c6p-1, -0x1.88dd051ece21p-4, 0x1.fda3b5c5e9eap-1, -0x1.8843bc78b95dep-4, 0x1.4917e58ca97acp+1, -0x1.15e5fc6e7b8f1p+0, 0x1.5402d8d95f305p+1},
};

TEST(Elementary, EqualsTheWebAssemblyLibraryToTheBit) {
  for (const Sample& s : kSamples) {
    EXPECT_EQ(Sin(s.x), s.sin) << std::hexfloat << s.x;
    EXPECT_EQ(Cos(s.x), s.cos) << std::hexfloat << s.x;
    EXPECT_EQ(Atan(s.x), s.atan) << std::hexfloat << s.x;
    EXPECT_EQ(Atan2(s.y, s.x), s.atan2) << std::hexfloat << s.y << " " << s.x;
    EXPECT_EQ(Asin(s.u), s.asin) << std::hexfloat << s.u;
    EXPECT_EQ(Acos(s.u), s.acos) << std::hexfloat << s.u;
  }
}

// Within an ulp or two of the C library everywhere, including the reduction's edges
// (multiples of pi/2 and arguments up to 1e6) and the special values.
TEST(Elementary, CloseToTheCLibrary) {
  for (int k = -40; k <= 40; k++) {
    for (double offset : {-1e-9, 0.0, 1e-9, 0.3, -0.7}) {
      double x = k * 0.78539816339744828 + offset;
      EXPECT_NEAR(Sin(x), std::sin(x), 4e-16 * (1 + std::abs(x))) << x;
      EXPECT_NEAR(Cos(x), std::cos(x), 4e-16 * (1 + std::abs(x))) << x;
    }
  }
  for (double x : {1e3, 12345.678, 1e6, -987654.321}) {
    EXPECT_NEAR(Sin(x), std::sin(x), 1e-15) << x;
    EXPECT_NEAR(Cos(x), std::cos(x), 1e-15) << x;
  }
  for (double u = -1; u <= 1; u += 1.0 / 64) {
    EXPECT_NEAR(Asin(u), std::asin(u), 4e-16) << u;
    EXPECT_NEAR(Acos(u), std::acos(u), 8e-16) << u;
    EXPECT_NEAR(Atan(u * 100), std::atan(u * 100), 4e-16) << u;
  }
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(Atan2(0.0, -1.0), std::atan2(0.0, -1.0));
  EXPECT_EQ(Atan2(-0.0, -1.0), std::atan2(-0.0, -1.0));
  EXPECT_EQ(Atan2(1.0, 0.0), std::atan2(1.0, 0.0));
  EXPECT_EQ(Atan2(inf, -inf), std::atan2(inf, -inf));
  EXPECT_EQ(Atan2(1.0, inf), 0.0);
  EXPECT_EQ(Acos(-1.0), std::acos(-1.0));
  EXPECT_EQ(Asin(1.0), std::asin(1.0));
  EXPECT_TRUE(std::isnan(Asin(1.5)));
  EXPECT_TRUE(std::isnan(Sin(inf)));
  EXPECT_EQ(Sin(1e-30), 1e-30);
  EXPECT_EQ(Cos(1e-30), 1.0);
}

}  // namespace
}  // namespace simlab::math
