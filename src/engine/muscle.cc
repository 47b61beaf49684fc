// MuJoCo's muscle model (documentation: Modeling > Muscles; engine_util_misc.c).
//
// prm = (range0, range1, force, scale, lmin, lmax, vmax, fpmax, fvmax). The actuator
// length l maps to the normalized length L = range0 + (l - lr0) / L0 with the optimal
// length L0 = (lr1 - lr0) / (range1 - range0) from the lengthrange (lr0, lr1), and the
// velocity to V = l' / (L0 vmax). Peak force F = force, or scale / acc0 when force < 0.
//
//   gain = -F FL(L) FV(V)    active force per unit activation
//   bias = -F FP(L)          passive force
//   act_dot = (clamp(u, 0, 1) - act) / tau, tau switching (smoothly with tausmooth)
//             between activation and deactivation time constants scaled by act.
#include <algorithm>

#include "engine/engine.h"

namespace simlab {

namespace {

// Peak force: `force`, or scale / acc0 when force is negative.
double PeakForce(const double* prm, double acc0) {
  return prm[2] < 0 ? prm[3] / std::max(kMinVal, acc0) : prm[2];
}

// Optimal length L0 and normalized length L.
double OptimalLength(const double* lengthrange, const double* prm) {
  return (lengthrange[1] - lengthrange[0]) / std::max(kMinVal, prm[1] - prm[0]);
}
double NormalizedLength(double len, const double* lengthrange, const double* prm, double l0) {
  return prm[0] + (len - lengthrange[0]) / std::max(kMinVal, l0);
}

// A muscle's peak force F, optimal length L0, normalized length L and velocity V.
struct Normalized {
  double force, l0, length, velocity;
};

Normalized Normalize(double len, double vel, const double* lengthrange, double acc0,
                     const double* prm) {
  Normalized n;
  n.force = PeakForce(prm, acc0);
  n.l0 = OptimalLength(lengthrange, prm);
  n.length = NormalizedLength(len, lengthrange, prm, n.l0);
  n.velocity = vel / std::max(kMinVal, n.l0 * prm[6]);
  return n;
}

// Quintic smooth step on [0, 1].
double Sigmoid(double x) {
  if (x <= 0) return 0;
  if (x >= 1) return 1;
  return x * x * x * (3 * x * (2 * x - 5) + 10);
}

}  // namespace

double MuscleGainLength(double length, double lmin, double lmax) {
  if (!(lmin <= length && length <= lmax)) return 0;
  // Two half-quadratics on each side of the peak at L = 1.
  double a = 0.5 * (lmin + 1), b = 0.5 * (1 + lmax);
  if (length <= a) {
    double x = (length - lmin) / std::max(kMinVal, a - lmin);
    return 0.5 * x * x;
  }
  if (length <= 1) {
    double x = (1 - length) / std::max(kMinVal, 1 - a);
    return 1 - 0.5 * x * x;
  }
  if (length <= b) {
    double x = (length - 1) / std::max(kMinVal, b - 1);
    return 1 - 0.5 * x * x;
  }
  double x = (lmax - length) / std::max(kMinVal, lmax - b);
  return 0.5 * x * x;
}

double MuscleGain(double len, double vel, const double* lengthrange, double acc0,
                  const double* prm) {
  Normalized n = Normalize(len, vel, lengthrange, acc0, prm);
  double force = n.force, v = n.velocity;
  double fl = MuscleGainLength(n.length, prm[4], prm[5]);

  // Force-velocity curve: zero below V = -1, quadratic up to fvmax at V = fvmax - 1.
  double fvmax = prm[8], y = fvmax - 1, fv;
  if (v <= -1) {
    fv = 0;
  } else if (v <= 0) {
    fv = (v + 1) * (v + 1);
  } else if (v <= y) {
    fv = fvmax - (y - v) * (y - v) / std::max(kMinVal, y);
  } else {
    fv = fvmax;
  }
  return -force * fl * fv;
}

double MuscleGainVelocity(double len, double vel, const double* lengthrange, double acc0,
                          const double* prm) {
  Normalized n = Normalize(len, vel, lengthrange, acc0, prm);
  double force = n.force, v = n.velocity, l0 = n.l0;
  double fl = MuscleGainLength(n.length, prm[4], prm[5]);

  // d FV / d V on each piece of the force-velocity curve.
  double y = prm[8] - 1, dfv = 0;
  if (v > -1 && v <= 0) {
    dfv = 2 * v + 2;
  } else if (v > 0 && v <= y) {
    dfv = (-2 * v + 2 * y) / std::max(kMinVal, y);
  }
  return -force * fl * dfv / std::max(kMinVal, l0 * prm[6]);
}

double MuscleBias(double len, const double* lengthrange, double acc0, const double* prm) {
  Normalized n = Normalize(len, 0, lengthrange, acc0, prm);
  double force = n.force, length = n.length;

  // Passive force: half-quadratic up to b = (1 + lmax) / 2, linear beyond.
  double b = 0.5 * (1 + prm[5]), fpmax = prm[7];
  if (length <= 1) return 0;
  if (length <= b) {
    double x = (length - 1) / std::max(kMinVal, b - 1);
    return -force * fpmax * 0.5 * x * x;
  }
  double x = (length - b) / std::max(kMinVal, b - 1);
  return -force * fpmax * (0.5 + x);
}

double MuscleDynamics(double ctrl, double act, const double* prm) {
  double ctrl_clamped = std::clamp(ctrl, 0.0, 1.0), act_clamped = std::clamp(act, 0.0, 1.0);

  // Time constants scale with activation (Millard et al. 2013).
  double tau_act = prm[0] * (0.5 + 1.5 * act_clamped);
  double tau_deact = prm[1] / (0.5 + 1.5 * act_clamped);
  double dctrl = ctrl_clamped - act, width = prm[2], tau;
  if (width < kMinVal) {
    tau = dctrl > 0 ? tau_act : tau_deact;
  } else {
    tau = tau_deact + (tau_act - tau_deact) * Sigmoid(dctrl / width + 0.5);
  }
  return dctrl / std::max(kMinVal, tau);
}

}  // namespace simlab
