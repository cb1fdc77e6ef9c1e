// The mode labels' energy split of beam elements (WorkItem::modeEnergy,
// docs/model.md §5 "Mode labels") against stiffness matrices formed
// independently: at the straight, unstrained state each kind's part of
// 1/2 s^T K s is 1/2 s^T K_kind s with K_kind the tangent of a section that
// has only that stiffness (Full axial integration, whose axial part does
// not depend on the bending stiffness), the parts sum to the element's whole
// 1/2 s^T K s and nothing is geometric; at a strained state the parts
// still sum to the whole, the rest being the stress stiffening.
#include "boomdyn/ancf_beam.hpp"
#include "boomdyn/beam_element_item.hpp"
#include "boomdyn/spatial_ancf_beam.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <random>

using namespace boomdyn;
namespace sb = boomdyn::spatial_beam;

namespace {

double half(const Eigen::MatrixXd &K, const Eigen::VectorXd &s) { return 0.5 * s.dot(K * s); }

// The spatial element's split of shape s at the element state q.
ModeEnergy spatialSplit(const SpatialBeamElementItem &item, const Eigen::VectorXd &q, const Eigen::VectorXd &s)
{
  const int n = sb::kCoordinates;
  std::vector<double> zeros(n, 0.0), block(n * n, 0.0), scratch(n);
  PencilPass pass;
  pass.ctx.kin = {1.0, 0.0, 0.0, 0.0};
  pass.ctx.pencil = true;
  pass.ctx.residualWanted = false;
  pass.in.q = q.data(), pass.in.v = zeros.data(), pass.in.a = zeros.data();
  pass.J = block.data();
  ModeEnergy e;
  item.modeEnergy(pass, n, s.data(), scratch.data(), e);
  return e;
}

double kind(const ModeEnergy &e, ModeEnergyKind k) { return e.kind[static_cast<int>(k)]; }

} // namespace

TEST(ModeEnergy, SpatialBeamSplitsByStrainAgainstSingleStiffnessTangents)
{
  sb::Section sec = sb::boxSection(2.1e11, 8.1e10, 7850, 0.3, 0.4, 0.01);
  sec.axialIntegration = sb::AxialIntegration::Full;
  const double length = 2.0;
  const SpatialAncfBeam beam("beam", length, 1, sec, Vec3::Zero(), Mat3::Identity(), 0);
  auto mass = std::make_shared<const sb::Mat14>(sb::massMatrix(sec, length));
  const SpatialBeamElementItem item(beam, 0, mass, Vec3::Zero());
  Eigen::VectorXd q(sb::kCoordinates);
  beam.initialCoordinates(q.data());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 5; ++trial) {
    Eigen::VectorXd s(sb::kCoordinates);
    for (int i = 0; i < s.size(); ++i) s[i] = u(rng);
    const ModeEnergy e = spatialSplit(item, q, s);
    // Sections with one stiffness each (the same element otherwise).
    const struct {
      ModeEnergyKind kind;
      double sb::Section::*keep;
    } parts[4] = {{ModeEnergyKind::Axial, &sb::Section::EA},
                  {ModeEnergyKind::BendingInPlane, &sb::Section::EIz},
                  {ModeEnergyKind::BendingOutOfPlane, &sb::Section::EIy},
                  {ModeEnergyKind::Torsion, &sb::Section::GJ}};
    double whole = 0;
    for (const auto &p : parts) {
      sb::Section only = sec;
      only.EA = only.EIy = only.EIz = only.GJ = 0;
      only.*(p.keep) = sec.*(p.keep);
      sb::Vec14 f;
      sb::Mat14 K;
      sb::internalForce(only, beam.geometry(0), q, f, &K);
      const double expected = half(K, s);
      EXPECT_NEAR(kind(e, p.kind), expected, 1e-12 * std::abs(expected)) << modeEnergyKindName((int)p.kind);
      whole += expected;
    }
    EXPECT_LT(std::abs(kind(e, ModeEnergyKind::Geometric)), 1e-12 * whole) << "unstrained: no stress stiffening";
  }
}

TEST(ModeEnergy, SpatialBeamPartsSumToTheWholeTangentWhenStrained)
{
  sb::Section sec = sb::boxSection(2.1e11, 8.1e10, 7850, 0.3, 0.4, 0.01); // Assumed axial strain
  const double length = 2.0;
  const SpatialAncfBeam beam("beam", length, 1, sec, Vec3::Zero(), Mat3::Identity(), 0);
  auto mass = std::make_shared<const sb::Mat14>(sb::massMatrix(sec, length));
  const SpatialBeamElementItem item(beam, 0, mass, Vec3::Zero());
  Eigen::VectorXd q0(sb::kCoordinates);
  beam.initialCoordinates(q0.data());
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (double strain : {0.0, 1e-3}) {
    Eigen::VectorXd q = q0, s(sb::kCoordinates);
    for (int i = 0; i < q.size(); ++i) q[i] += strain * u(rng), s[i] = u(rng);
    const ModeEnergy e = spatialSplit(item, q, s);
    sb::Vec14 f;
    sb::Mat14 K;
    sb::internalForce(sec, beam.geometry(0), q, f, &K);
    double sum = 0;
    for (double x : e.kind) sum += x;
    const double whole = half(K, s);
    EXPECT_NEAR(sum, whole, 1e-12 * std::abs(whole));
    const double geometric = kind(e, ModeEnergyKind::Geometric);
    if (strain == 0) EXPECT_LT(std::abs(geometric), 1e-12 * whole);
    else EXPECT_GT(std::abs(geometric), 1e-9 * whole) << "a strained element has stress stiffening";
  }
}

TEST(ModeEnergy, PlanarBeamSplitsAxialAndBending)
{
  ancf::Section sec;
  sec.EA = 8.5176e8, sec.EI = 4.9531e6, sec.rhoA = 31.8396;
  sec.axialIntegration = ancf::AxialIntegration::Full;
  const AncfBeam beam("beam", 2.0, 4, sec, Vec2(0, 0), 0.3, 0);
  auto mass = std::make_shared<const ancf::Mat8>(ancf::massMatrix(sec.rhoA, beam.elementLength()));
  const BeamElementItem item(beam, 1, mass, Vec2(0, 0));
  ancf::Vec8 q;
  for (int node = 0; node < 2; ++node) {
    const double x = (1 + node) * beam.elementLength();
    q.segment<4>(4 * node) << x * std::cos(0.3), x * std::sin(0.3), std::cos(0.3), std::sin(0.3);
  }
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  ancf::Vec8 s;
  for (int i = 0; i < 8; ++i) s[i] = u(rng);
  std::vector<double> zeros(8, 0.0), block(64, 0.0), scratch(8);
  PencilPass pass;
  pass.ctx.kin = {1.0, 0.0, 0.0, 0.0};
  pass.ctx.pencil = true;
  pass.in.q = q.data(), pass.in.v = zeros.data(), pass.in.a = zeros.data();
  pass.J = block.data();
  ModeEnergy e;
  item.modeEnergy(pass, 8, s.data(), scratch.data(), e);
  for (const auto &[k, keepAxial] : {std::pair<ModeEnergyKind, bool>{ModeEnergyKind::Axial, true},
                                     {ModeEnergyKind::BendingInPlane, false}}) {
    ancf::Section only = sec;
    (keepAxial ? only.EI : only.EA) = 0;
    ancf::Vec8 f;
    ancf::Mat8 K;
    ancf::internalForce(only, beam.elementLength(), q, f, &K);
    const double expected = 0.5 * s.dot(K * s);
    EXPECT_NEAR(kind(e, k), expected, 1e-12 * std::abs(expected)) << modeEnergyKindName((int)k);
  }
  EXPECT_EQ(kind(e, ModeEnergyKind::BendingOutOfPlane), 0.0);
  EXPECT_EQ(kind(e, ModeEnergyKind::Torsion), 0.0);
}
