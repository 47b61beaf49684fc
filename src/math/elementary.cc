// Sine, cosine and inverse trigonometric functions computed as fdlibm computes them (the
// algorithms of musl, MuJoCo's WebAssembly C library), so that every platform rounds
// alike. The constants are the published fdlibm ones; the order of each floating-point
// operation matters and is kept.
#include "math/elementary.h"

#include <cmath>
#include <cstdint>
#include <cstring>

namespace simlab::math {

namespace {

// ---------------------------------------------------------------- bit access

uint64_t Bits(double x) {
  uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

// The upper 32 bits (sign, exponent, top of the mantissa).
uint32_t High(double x) { return static_cast<uint32_t>(Bits(x) >> 32); }

uint32_t Low(double x) { return static_cast<uint32_t>(Bits(x)); }

// x with its lower 32 bits cleared: a head whose square is exact.
double Head(double x) {
  uint64_t b = Bits(x) & 0xffffffff00000000ull;
  double h;
  std::memcpy(&h, &b, sizeof h);
  return h;
}

// ---------------------------------------------------------------- polynomial kernels

// sin(x + tail) for |x| <= pi/4, the tail a correction far below x's last bit (used when
// `with_tail`). An odd polynomial of degree 13.
double SinKernel(double x, double tail, bool with_tail) {
  constexpr double s1 = -1.66666666666666324348e-01, s2 = 8.33333333332248946124e-03,
                   s3 = -1.98412698298579493134e-04, s4 = 2.75573137070700676789e-06,
                   s5 = -2.50507602534068634195e-08, s6 = 1.58969099521155010221e-10;
  double z = x * x;
  double w = z * z;
  double r = s2 + z * (s3 + z * s4) + z * w * (s5 + z * s6);
  double v = z * x;
  if (!with_tail) return x + v * (s1 + z * r);
  return x - ((z * (0.5 * tail - v * r) - tail) - v * s1);
}

// cos(x + tail) for |x| <= pi/4: 1 - x^2/2 split so that its rounding error is recovered,
// plus an even polynomial.
double CosKernel(double x, double tail) {
  constexpr double c1 = 4.16666666666666019037e-02, c2 = -1.38888888888741095749e-03,
                   c3 = 2.48015872894767294178e-05, c4 = -2.75573143513906633035e-07,
                   c5 = 2.08757232129817482790e-09, c6 = -1.13596475577881948265e-11;
  double z = x * x;
  double w = z * z;
  double r = z * (c1 + z * (c2 + z * c3)) + w * w * (c4 + z * (c5 + z * c6));
  double half_z = 0.5 * z;
  w = 1.0 - half_z;
  return w + (((1.0 - w) - half_z) + (z * r - x * tail));
}

// ---------------------------------------------------------------- reduction by pi/2

// pi/2 in three pieces of 33 bits, each with the rest of pi/2 after it.
constexpr double kPio2_1 = 1.57079632673412561417e+00, kPio2_1t = 6.07710050650619224932e-11;
constexpr double kPio2_2 = 6.07710050630396597660e-11, kPio2_2t = 2.02226624879595063154e-21;
constexpr double kPio2_3 = 2.02226624871116645580e-21, kPio2_3t = 8.47842766036889956997e-32;
constexpr double kInvPio2 = 6.36619772367581382433e-01;
constexpr double kPio4 = 0x1.921fb54442d18p-1;

// x - k pi/2 for a small multiple k (1 to 4) already known, as head + tail.
int ReduceByMultiple(double x, int k, double* head, double* tail) {
  double z;
  if (x > 0) {
    z = x - k * kPio2_1;
    *head = z - k * kPio2_1t;
    *tail = (z - *head) - k * kPio2_1t;
    return k;
  }
  z = x + k * kPio2_1;
  *head = z + k * kPio2_1t;
  *tail = (z - *head) + k * kPio2_1t;
  return -k;
}

// x - n pi/2 for the nearest n, in up to three rounds (each round subtracts the next
// 33 bits of pi/2 when cancellation has eaten the previous ones).
int ReduceMedium(double x, uint32_t ix, double* head, double* tail) {
  constexpr double kToInt = 1.5 / 2.220446049250313080847e-16;
  double fn = x * kInvPio2 + kToInt - kToInt;
  int n = static_cast<int>(fn);
  double r = x - fn * kPio2_1;
  double w = fn * kPio2_1t;
  // (the nearest n by the first round; checked against the rounded remainder)
  if (r - w < -kPio4) {
    n--;
    fn--;
    r = x - fn * kPio2_1;
    w = fn * kPio2_1t;
  } else if (r - w > kPio4) {
    n++;
    fn++;
    r = x - fn * kPio2_1;
    w = fn * kPio2_1t;
  }
  *head = r - w;
  int ex = static_cast<int>(ix >> 20);
  if (ex - static_cast<int>((High(*head) >> 20) & 0x7ff) > 16) {
    double t = r;
    w = fn * kPio2_2;
    r = t - w;
    w = fn * kPio2_2t - ((t - r) - w);
    *head = r - w;
    if (ex - static_cast<int>((High(*head) >> 20) & 0x7ff) > 49) {
      t = r;
      w = fn * kPio2_3;
      r = t - w;
      w = fn * kPio2_3t - ((t - r) - w);
      *head = r - w;
    }
  }
  *tail = (r - *head) - w;
  return n;
}

// x = n pi/2 + head + tail with |head| <= pi/4; returns n (only n mod 4 is used). False
// for arguments too large for these reductions.
bool ReduceQuadrant(double x, int* n, double* head, double* tail) {
  uint32_t ix = High(x) & 0x7fffffff;
  bool near_multiple = (ix & 0xfffff) == 0x921fb;  // |x| close to pi/2 or pi
  if (ix <= 0x400f6a7a && !near_multiple) {        // |x| <= 5pi/4
    *n = ReduceByMultiple(x, ix <= 0x4002d97c ? 1 : 2, head, tail);
    return true;
  }
  if (ix <= 0x401c463b && !near_multiple) {  // |x| <= 9pi/4
    bool three = ix <= 0x4015fdbc;           // |x| <= 7pi/4
    uint32_t exact_multiple = three ? 0x4012d97c : 0x401921fb;  // 3pi/2, 2pi
    if (ix != exact_multiple) {
      *n = ReduceByMultiple(x, three ? 3 : 4, head, tail);
      return true;
    }
  }
  if (ix < 0x413921fb) {  // |x| < 2^20 pi/2
    *n = ReduceMedium(x, ix, head, tail);
    return true;
  }
  return false;
}

// ---------------------------------------------------------------- arc sine and cosine

constexpr double kPio2Hi = 1.57079632679489655800e+00, kPio2Lo = 6.12323399573676603587e-17;

// The rational approximation (asin(sqrt(z)) / sqrt(z) - 1) of both arc functions.
double ArcRatio(double z) {
  constexpr double p0 = 1.66666666666666657415e-01, p1 = -3.25565818622400915405e-01,
                   p2 = 2.01212532134862925881e-01, p3 = -4.00555345006794114027e-02,
                   p4 = 7.91534994289814532176e-04, p5 = 3.47933107596021167570e-05;
  constexpr double q1 = -2.40339491173441421878e+00, q2 = 2.02094576023350569471e+00,
                   q3 = -6.88283971605453293030e-01, q4 = 7.70381505559019352791e-02;
  double p = z * (p0 + z * (p1 + z * (p2 + z * (p3 + z * (p4 + z * p5)))));
  double q = 1.0 + z * (q1 + z * (q2 + z * (q3 + z * q4)));
  return p / q;
}

}  // namespace

// ---------------------------------------------------------------- sine and cosine

double Sin(double x) {
  uint32_t ix = High(x) & 0x7fffffff;
  if (ix <= 0x3fe921fb) {              // |x| <= pi/4
    if (ix < 0x3e500000) return x;     // |x| < 2^-26: sin x rounds to x
    return SinKernel(x, 0.0, false);
  }
  if (ix >= 0x7ff00000) return x - x;  // inf or nan
  int n;
  double head, tail;
  if (!ReduceQuadrant(x, &n, &head, &tail)) return std::sin(x);
  switch (n & 3) {
    case 0: return SinKernel(head, tail, true);
    case 1: return CosKernel(head, tail);
    case 2: return -SinKernel(head, tail, true);
    default: return -CosKernel(head, tail);
  }
}

double Cos(double x) {
  uint32_t ix = High(x) & 0x7fffffff;
  if (ix <= 0x3fe921fb) {              // |x| <= pi/4
    if (ix < 0x3e46a09e) return 1.0;   // |x| < 2^-27 sqrt(2): cos x rounds to 1
    return CosKernel(x, 0.0);
  }
  if (ix >= 0x7ff00000) return x - x;
  int n;
  double head, tail;
  if (!ReduceQuadrant(x, &n, &head, &tail)) return std::cos(x);
  switch (n & 3) {
    case 0: return CosKernel(head, tail);
    case 1: return -SinKernel(head, tail, true);
    case 2: return -CosKernel(head, tail);
    default: return SinKernel(head, tail, true);
  }
}

// ---------------------------------------------------------------- arc tangent

double Atan(double x) {
  // atan of the breakpoints 1/2, 1, 3/2 and infinity, each as head + tail.
  constexpr double kAtanHi[] = {4.63647609000806093515e-01, 7.85398163397448278999e-01,
                                9.82793723247329054082e-01, 1.57079632679489655800e+00};
  constexpr double kAtanLo[] = {2.26987774529616870924e-17, 3.06161699786838301793e-17,
                                1.39033110312309984516e-17, 6.12323399573676603587e-17};
  constexpr double a[] = {3.33333333333329318027e-01,  -1.99999999998764832476e-01,
                          1.42857142725034663711e-01,  -1.11111104054623557880e-01,
                          9.09088713343650656196e-02,  -7.69187620504482999495e-02,
                          6.66107313738753120669e-02,  -5.83357013379057348645e-02,
                          4.97687799461593236017e-02,  -3.65315727442169155270e-02,
                          1.62858201153657823623e-02};
  uint32_t hx = High(x);
  bool negative = hx >> 31;
  uint32_t ix = hx & 0x7fffffff;
  if (ix >= 0x44100000) {  // |x| >= 2^66 (or nan)
    if (std::isnan(x)) return x;
    return negative ? -kAtanHi[3] : kAtanHi[3];
  }

  // Move x near 0 by the breakpoint nearest it: atan x = atan c + atan((x - c)/(1 + c x)).
  int id = -1;
  if (ix < 0x3fdc0000) {                // |x| < 7/16
    if (ix < 0x3e400000) return x;      // |x| < 2^-27
  } else {
    x = std::fabs(x);
    if (ix < 0x3fe60000) {              // 7/16 <= |x| < 11/16
      id = 0;
      x = (2.0 * x - 1.0) / (2.0 + x);
    } else if (ix < 0x3ff30000) {       // 11/16 <= |x| < 19/16
      id = 1;
      x = (x - 1.0) / (x + 1.0);
    } else if (ix < 0x40038000) {       // 19/16 <= |x| < 39/16
      id = 2;
      x = (x - 1.5) / (1.0 + 1.5 * x);
    } else {
      id = 3;
      x = -1.0 / x;
    }
  }

  // The odd series in two interleaved halves.
  double z = x * x;
  double w = z * z;
  double odd = z * (a[0] + w * (a[2] + w * (a[4] + w * (a[6] + w * (a[8] + w * a[10])))));
  double even = w * (a[1] + w * (a[3] + w * (a[5] + w * (a[7] + w * a[9]))));
  if (id < 0) return x - x * (odd + even);
  double r = kAtanHi[id] - (x * (odd + even) - kAtanLo[id] - x);
  return negative ? -r : r;
}

double Atan2(double y, double x) {
  constexpr double kPi = 3.1415926535897931160e+00, kPiLo = 1.2246467991473531772e-16;
  if (std::isnan(x) || std::isnan(y)) return x + y;
  uint32_t ix = High(x), lx = Low(x), iy = High(y), ly = Low(y);
  if (((ix - 0x3ff00000) | lx) == 0) return Atan(y);  // x = 1
  int quadrant = ((iy >> 31) & 1) | ((ix >> 30) & 2);  // 2 sign(x) + sign(y)
  ix &= 0x7fffffff;
  iy &= 0x7fffffff;

  // Zeros and infinities.
  if ((iy | ly) == 0) {
    if (quadrant < 2) return y;
    return quadrant == 2 ? kPi : -kPi;
  }
  if ((ix | lx) == 0) return (quadrant & 1) ? -kPi / 2 : kPi / 2;
  if (ix == 0x7ff00000) {
    if (iy == 0x7ff00000) {
      constexpr double kCorner[] = {kPi / 4, -kPi / 4, 3 * kPi / 4, -3 * kPi / 4};
      return kCorner[quadrant];
    }
    constexpr double kAxis[] = {0.0, -0.0, kPi, -kPi};
    return kAxis[quadrant];
  }
  if (ix + (64u << 20) < iy || iy == 0x7ff00000) return (quadrant & 1) ? -kPi / 2 : kPi / 2;

  // atan |y/x|, then placed in its quadrant (0 when |y/x| < 2^-64 and x < 0).
  double z = ((quadrant & 2) && iy + (64u << 20) < ix) ? 0.0 : Atan(std::fabs(y / x));
  switch (quadrant) {
    case 0: return z;
    case 1: return -z;
    case 2: return kPi - (z - kPiLo);
    default: return (z - kPiLo) - kPi;
  }
}

// ---------------------------------------------------------------- arc sine and cosine

double Asin(double x) {
  uint32_t hx = High(x);
  uint32_t ix = hx & 0x7fffffff;
  if (ix >= 0x3ff00000) {  // |x| >= 1 or nan
    if (((ix - 0x3ff00000) | Low(x)) == 0) return x * kPio2Hi;
    return std::nan("");
  }
  if (ix < 0x3fe00000) {  // |x| < 1/2
    if (ix < 0x3e500000 && ix >= 0x00100000) return x;
    return x + x * ArcRatio(x * x);
  }

  // 1/2 <= |x| < 1: asin x = pi/2 - 2 asin sqrt((1 - |x|)/2).
  double z = (1 - std::fabs(x)) * 0.5;
  double s = std::sqrt(z);
  double r = ArcRatio(z);
  double result;
  if (ix >= 0x3fef3333) {  // |x| > 0.975
    result = kPio2Hi - (2 * (s + s * r) - kPio2Lo);
  } else {
    // sqrt(z) as head + c, the head's square exact.
    double head = Head(s);
    double c = (z - head * head) / (s + head);
    result = 0.5 * kPio2Hi - (2 * s * r - (kPio2Lo - 2 * c) - (0.5 * kPio2Hi - 2 * head));
  }
  return (hx >> 31) ? -result : result;
}

double Acos(double x) {
  uint32_t hx = High(x);
  uint32_t ix = hx & 0x7fffffff;
  if (ix >= 0x3ff00000) {  // |x| >= 1 or nan
    if (((ix - 0x3ff00000) | Low(x)) == 0) return (hx >> 31) ? 2 * kPio2Hi : 0.0;
    return std::nan("");
  }
  if (ix < 0x3fe00000) {  // |x| < 1/2
    if (ix <= 0x3c600000) return kPio2Hi;
    return kPio2Hi - (x - (kPio2Lo - x * ArcRatio(x * x)));
  }
  if (hx >> 31) {  // x <= -1/2: acos x = pi - 2 asin sqrt((1 + x)/2)
    double z = (1.0 + x) * 0.5;
    double s = std::sqrt(z);
    double w = ArcRatio(z) * s - kPio2Lo;
    return 2 * (kPio2Hi - (s + w));
  }
  // x >= 1/2: acos x = 2 asin sqrt((1 - x)/2), the square root as head + c.
  double z = (1.0 - x) * 0.5;
  double s = std::sqrt(z);
  double head = Head(s);
  double c = (z - head * head) / (s + head);
  double w = ArcRatio(z) * s + c;
  return 2 * (head + w);
}

}  // namespace simlab::math
