// Sine, cosine and the inverse trigonometric functions, the same to the bit on every
// platform.
//
// MuJoCo's reference build is WebAssembly, whose C library (musl) computes these with the
// classic fdlibm algorithms: argument reduction by pi/2 in two or three pieces, then
// minimax polynomials on [-pi/4, pi/4]. glibc rounds differently in 1 to 18 cases out of
// 100 (measured with random arguments), and one ulp in a quaternion integrated every step,
// or in a replicated body's orientation, is enough to part two rollouts of a pile of
// objects. So the engine and the compiler call these instead of std::sin and company; the
// results equal the WebAssembly build's (tests/elementary_test.cc holds samples of them).
//
// Arguments of sine and cosine beyond 2^20 * pi/2 (about 1.6e6 radians) go to the C
// library: their reduction needs pi to a thousand bits, and no simulation angle is that
// large.
#pragma once

namespace simlab::math {

double Sin(double x);
double Cos(double x);
double Atan(double x);
double Atan2(double y, double x);
double Asin(double x);
double Acos(double x);

}  // namespace simlab::math
