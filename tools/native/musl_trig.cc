// musl_trig.so: the trigonometric functions of the npm oracle's C library (musl), as
// simlab computes them (src/math/elementary.cc), for LD_PRELOAD under a native MuJoCo,
// so that a native reference rounds sine, cosine and the arc functions as the oracle
// and simlab do (glibc's differ in the last bit now and then, and a falling pile
// amplifies that). Built by tools/native/build_oracle_era.sh.
#include "math/elementary.h"

extern "C" {
double sin(double x) { return simlab::math::Sin(x); }
double cos(double x) { return simlab::math::Cos(x); }
double atan(double x) { return simlab::math::Atan(x); }
double atan2(double y, double x) { return simlab::math::Atan2(y, x); }
double asin(double x) { return simlab::math::Asin(x); }
double acos(double x) { return simlab::math::Acos(x); }
}
