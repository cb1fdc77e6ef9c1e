// Spatial ANCF beam element with twist ("ANCF14", docs/model.md §1.7): section
// law, mass and the Gauss-integrated elastic and Kelvin-Voigt forces with their
// Jacobians. Pure kernels, no PETSc; kinematics in spatial_beam_kinematics.hpp.
//
// Energy U = 1/2 ∫ EA eps^2 + GJ K1^2 + EIy K2^2 + EIz K3^2 dx (x: reference
// arc length). Sign convention as in the planar element: the kernels return
// the internal force f = dU/de and its tangent K = d^2U/de^2; the generalized
// elastic force is -f.
#pragma once

#include "boomdyn/ancf_element.hpp"
#include "boomdyn/spatial_beam_kinematics.hpp"

namespace boomdyn::spatial_beam {

using ancf::AxialIntegration;

// Section resultants about the principal axes of the section: d2 ("y") and
// d3 ("z"). EIy resists the curvature K2 about d2, EIz the curvature K3
// about d3; GJ the torsion K1 (for a closed thin-walled box, Bredt's J, not
// the polar moment); rhoIp the rotary inertia of the section about the axis
// (rho (Iy + Iz) for a homogeneous section).
struct Section {
  double EA = 0, EIy = 0, EIz = 0, GJ = 0, rhoA = 0, rhoIp = 0;
  // Kelvin-Voigt retardation times (s): N = EA (eps + etaA epsdot),
  // M_i = EI_i (K_i + etaB Kdot_i), T = GJ (K1 + etaT K1dot).
  double etaA = 0, etaB = 0, etaT = 0;
  AxialIntegration axialIntegration = AxialIntegration::Assumed;
  // Beam length for the Assumed axial strain's pointwise weight (as the
  // planar Section::length); 0: the element length.
  double length = 0;
  bool damped() const { return etaA > 0 || etaB > 0 || etaT > 0; }
};

// A closed thin-walled rectangular box: midline width b (along d2), midline
// height h (along d3), wall thickness t; material E, G, rho. Thin-wall
// formulas on the midline: A = 2 t (b + h), Iy = t h^2 (3b + h)/6,
// Iz = t b^2 (3h + b)/6, Bredt J = 4 A_m^2 / ∮ ds/t = 2 t b^2 h^2/(b + h).
Section boxSection(double E, double G, double rho, double b, double h, double t);

// Weight gamma of the pointwise axial energy in the Assumed treatment
// (ancf::assumedPointwiseWeight with the smaller bending stiffness): 1 for
// Full and Reduced.
double assumedPointwiseWeight(const Section &sec, double l);

// The stiffness and retardation time of each strain of Strains in its order
// (axial, torsion, curvature2, curvature3): the section law.
struct StrainLaw {
  double stiffness[4];
  double eta[4];
};
StrainLaw strainLaw(const Section &sec);

// Consistent mass matrix: ∫ rhoA S^T S dx for the centreline and, for the
// twist, ∫ rhoIp N^T N dx with the linear interpolation N of the nodal angles
// (the torsional inertia's dependence on the slopes is neglected, §1.7).
Mat14 massMatrix(const Section &sec, double l);
// Gravity ∫ rhoA S^T g dx.
Vec14 gravityForce(const Section &sec, double l, const Vec3 &g);

double strainEnergy(const Section &sec, const Geometry &geo, const Vec14 &e);
// f = dU/de and, if K != nullptr, K = d^2U/de^2 (symmetric).
void internalForce(const Section &sec, const Geometry &geo, const Vec14 &e, Vec14 &f, Mat14 *K);
// Kelvin-Voigt force fd = ∫ sum_i C_i eta_i Kdot_i dK_i/de dx (Kdot_i =
// dK_i/de . edot), dfd/de into Kq and dfd/dedot (symmetric) into Dv if not
// null. Returns the dissipated power edot . fd = ∫ sum_i C_i eta_i Kdot_i^2 dx.
double dampingForce(const Section &sec, const Geometry &geo, const Vec14 &e, const Vec14 &edot, Vec14 &fd, Mat14 *Kq,
                    Mat14 *Dv);

// internalForce and dampingForce in one pass (one evaluation of the strains
// and their derivatives, about half the cost of the two calls), with equal
// results: the residual and Jacobian blocks of a damped element.
double internalAndDampingForce(const Section &sec, const Geometry &geo, const Vec14 &e, const Vec14 &edot, Vec14 &f,
                               Mat14 *K, Vec14 &fd, Mat14 *Kq, Mat14 *Dv);

// The same three kernels with forward-mode jets carried through every
// operation of the strains (second_order_jet.hpp): slower, kept as the
// oracle the kernels above are tested against (equal to round-off).
namespace reference {
void internalForce(const Section &sec, const Geometry &geo, const Vec14 &e, Vec14 &f, Mat14 *K);
double dampingForce(const Section &sec, const Geometry &geo, const Vec14 &e, const Vec14 &edot, Vec14 &fd, Mat14 *Kq,
                    Mat14 *Dv);
double internalAndDampingForce(const Section &sec, const Geometry &geo, const Vec14 &e, const Vec14 &edot, Vec14 &f,
                               Mat14 *K, Vec14 &fd, Mat14 *Kq, Mat14 *Dv);
} // namespace reference

constexpr int kGaussPoints = 5;
constexpr int kReducedAxialPoints = 3;

} // namespace boomdyn::spatial_beam
