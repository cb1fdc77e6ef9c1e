// Planar ANCF cable element (docs/model.md §1.1): pure kernels, no PETSc.
//
// Element vector e = [r_1, r'_1, r_2, r'_2] (8 entries), cubic Hermite shape
// functions in xi = x/l. Energy U = 1/2 ∫ EA eps^2 + EI K^2 dx with Green
// axial strain eps = (|r'|^2 - 1)/2 and material curvature K = (r' x r'')/|r'|^2.
// Sign convention: the kernels return the internal force f = dU/de and the
// tangent stiffness K = d^2U/de^2 (symmetric); the generalized elastic force
// of the paper is Q_k = -f.
#pragma once

#include "boomdyn/lanes.hpp"

#include <Eigen/Dense>

namespace boomdyn::ancf {

using Vec2 = Eigen::Vector2d;
using Vec8 = Eigen::Matrix<double, 8, 1>;
using Mat8 = Eigen::Matrix<double, 8, 8>;
using Mat28 = Eigen::Matrix<double, 2, 8>;

// Treatment of the axial strain (docs/model.md §1.1, "Axial strain").
// Full: axial and bending energy on the same 5 Gauss points. Reduced: the
// axial energy on 3 Gauss points (selective reduced integration), the
// bending energy on 5. Assumed: the Green strain projected in L2 onto linear
// polynomials per element (assumed strain of a Hellinger-Reissner mixed form
// with the stress eliminated), plus the pointwise strain with the small weight
// assumedPointwiseWeight() that stabilizes the one axial zero-energy mode of
// the projection. Reduced still locks at rate 2 in the inextensible limit (3
// constraints per element leave 1 bending freedom); Assumed (2 per element)
// converges at rate 4 at every EA L^2/EI (docs/verification.md).
enum class AxialIntegration { Full, Reduced, Assumed };

struct Section {
  double EA = 0, EI = 0, rhoA = 0;
  // Kelvin-Voigt retardation times (s): N = EA (eps + etaA eps'), M = EI (K + etaB K').
  double etaA = 0, etaB = 0;
  AxialIntegration axialIntegration = AxialIntegration::Full;
  // Length of the beam (m) that scales the pointwise part of the Assumed
  // axial energy (kAssumedStiffness); 0: the element length.
  double length = 0;
  bool damped() const { return etaA > 0 || etaB > 0; }
};

// Shape function values S1..S4 and their x-derivatives (order 0..3) at xi.
// S(x) = [S1 I, S2 I, S3 I, S4 I] (2x8).
Eigen::Vector4d shapeValues(double xi, double l, int derivative);
Mat28 shapeMatrix(double xi, double l, int derivative = 0);

// Centerline quantities at xi: r and its x-derivatives up to order 3.
Vec2 position(const Vec8 &e, double xi, double l, int derivative = 0);

// Consistent mass matrix  ∫ rhoA S^T S dx  (exact, closed form).
Mat8 massMatrix(double rhoA, double l);
// Gravity force ∫ rhoA S^T g dx (exact).
Vec8 gravityForce(double rhoA, double l, const Vec2 &g);

// Strain energy of the element (Gauss quadrature, see AxialIntegration).
double strainEnergy(const Section &sec, double l, const Vec8 &e);
// Internal force f = dU/de and, if K != nullptr, tangent K = d^2U/de^2.
void internalForce(const Section &sec, double l, const Vec8 &e, Vec8 &f, Mat8 *K);

// internalForce(sec, l, e_j, f_j, nullptr) for kForceBatch elements of one
// length and section at once, bit for bit (each element in one lane of a
// SIMD vector: the same IEEE operations in the same order). The residual of
// a long beam evaluates its elements in such batches (BeamElementItem).
// f_j may alias e_j.
constexpr int kForceBatch = 4;
using ForceLanes = lanes::Lanes4;
static_assert(kForceBatch == lanes::kWidth, "one element per lane");
void internalForceBatch(const Section &sec, double l, const double *const e[kForceBatch], double *const f[kForceBatch]);
// The same on lanes: e[i] holds entry i of every element (lane j: element j).
void internalForceLanes(const Section &sec, double l, const ForceLanes e[8], ForceLanes f[8]);

// Kelvin-Voigt damping force (docs/model.md §1.1, "Material damping")
//   fd = ∫ [EA etaA epsdot deps/de + EI etaB Kdot dK/de] dx,  epsdot = deps/de . edot,
// added to f like the internal force. Returns the dissipated power
// edot . fd = ∫ EA etaA epsdot^2 + EI etaB Kdot^2 dx >= 0. If Kq != nullptr it
// receives dfd/de (not symmetric), if Dv != nullptr dfd/dedot (symmetric,
// positive semi-definite). fd may alias e or edot.
// At edot = 0 (all entries zero) Kq is set to zero, not summed: bit for bit
// the sum's value, every term being a signed zero (ancf_element.cpp).
double dampingForce(const Section &sec, double l, const Vec8 &e, const Vec8 &edot, Vec8 &fd, Mat8 *Kq, Mat8 *Dv);
// dampingForce with Kq summed at every edot (tests compare the two).
double dampingForceSummed(const Section &sec, double l, const Vec8 &e, const Vec8 &edot, Vec8 &fd, Mat8 *Kq,
                          Mat8 *Dv);

// At edot = 0 (all entries zero; the eigen-analysis' pencil): Kt of
// internalForce and Kq (zero), Dv of dampingForce in one pass, bit-identical
// to those calls. False (outputs undefined) when edot is not zero or a factor
// is out of the range of dampingForce's rest shortcut: call the two.
bool stiffnessAndDampingAtRest(const Section &sec, double l, const Vec8 &e, const Vec8 &edot, Mat8 &Kt, Mat8 &Kq,
                               Mat8 &Dv);

// internalForce(sec, l, e, f, nullptr) and dampingForce(sec, l, e, edot, fd,
// nullptr, nullptr) in one pass (shared shape functions and strains), with
// bit-identical results: the residual of a damped element. Returns the
// dissipated power, dampingForce's return value bit for bit (a few
// operations per Gauss point: the element keeps it with fd for the energy
// diagnostics of the state Newton ends on).
double internalAndDampingForce(const Section &sec, double l, const Vec8 &e, const Vec8 &edot, Vec8 &f, Vec8 &fd);
// The same for kForceBatch elements of one length and section at once, bit
// for bit (one element per SIMD lane, as internalForceBatch): the residual
// of a damped beam's elements in batches (BeamElementItem). power[j] is
// element j's dissipated power; f_j and fd_j may alias e_j or edot_j.
void internalAndDampingForceBatch(const Section &sec, double l, const double *const e[kForceBatch],
                                  const double *const edot[kForceBatch], double *const f[kForceBatch],
                                  double *const fd[kForceBatch], double power[kForceBatch]);
// The same on lanes (e[i], edot[i]: entry i of every element); returns the powers.
ForceLanes internalAndDampingForceLanes(const Section &sec, double l, const ForceLanes e[8], const ForceLanes edot[8],
                                        ForceLanes f[8], ForceLanes fd[8]);

// Axial strain and material curvature at xi (for output and tests).
double axialStrain(const Vec8 &e, double xi, double l);
double curvature(const Vec8 &e, double xi, double l);

// Element vector of a straight, unstrained element from p0 along unit dir.
Vec8 straightElement(const Vec2 &p0, const Vec2 &dir, double l);

// Gauss points per element for the bending energy (and for the axial energy
// with AxialIntegration::Full; kReducedAxialPoints with Reduced). The axial energy is a
// polynomial of degree 8 in xi (exact with 5 points); the curvature term is
// rational and 5 points keep its quadrature error far below the
// discretization error of the cubic interpolation.
constexpr int kGaussPoints = 5;
constexpr int kReducedAxialPoints = 3;

// Assumed axial strain: basis functions per element (1, xi: linear), and c of
// the pointwise weight gamma = min(1, c EI / (EA L^2)) with L = Section::length:
// the pointwise part has the stiffness c EI / L^2 of the beam's bending scale,
// independent of the mesh, so it neither locks (gamma EA l^2/EI = c (l/L)^2 -> 0)
// nor spoils the rate; beams with EA L^2/EI <= c get the full element, bit for bit.
// c = 1e4, not smaller: with 1e3 the stabilized mode was too soft for the
// whip of the soft flexible_pendulum scene (no mesh convergence there).
constexpr int kAssumedTerms = 2;
constexpr double kAssumedStabilization = 1.0e4;
double assumedPointwiseWeight(const Section &sec, double l);

} // namespace boomdyn::ancf
