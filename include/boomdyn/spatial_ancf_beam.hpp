// Spatial flexible beam (type `ancf_beam` of spatial scenes, dimension 3):
// n equal ANCF14 elements (spatial_beam_element.hpp, docs/model.md §1.7).
// Coordinates per node: position r (3), slope r' (3), twist theta (1), node
// after node, so element e uses the 14 coordinates 7e .. 7e + 13 of the
// body's block. Each node has a reference triad (the initial section triad
// at the start); the smallest rotation from it to the current tangent is
// singular at half a turn, so the beam rebases its references (rebase())
// after converged steps and load steps once a node's tangent has turned far
// from its reference: a change of chart that keeps the state, which lets
// the tangents turn without limit. The references are part of the state a
// checkpoint saves (references(), setReferences()).
#pragma once

#include "boomdyn/spatial_beam_element.hpp"
#include "boomdyn/spatial_body.hpp"
#include "boomdyn/work_item.hpp"

#include <memory>
#include <vector>

namespace boomdyn {

class SpatialAncfBeam : public SpatialBody {
public:
  // origin: the point s = 0; triad: the initial section triad (columns: the
  // axis direction d1, then d2 and d3, the section's principal axes).
  SpatialAncfBeam(std::string name, double length, int elements, const spatial_beam::Section &section,
                  const Vec3 &origin, const Mat3 &triad, PetscInt first);
  PetscInt numCoordinates() const override { return 7 * (elements_ + 1); }
  void initialCoordinates(double *q) const override;
  SpatialLocation locate(double s) const override;
  void sample(const SpatialLocation &loc, double s, const double *values, SpatialSample &out) const override;
  void curvatureTerm(const SpatialLocation &loc, double s, const double *values, SpatialField field, const Vec3 &w,
                     SpatialHessian &H) const override;
  Vec3 initialPosition(double s) const override { return origin_ + s * triad_.col(0); }
  Mat3 initialTriad(double) const override { return triad_; }
  int outputSegments() const override { return kOutputSegmentsPerElement * elements_; }
  SpatialStrains sectionStrains(const SpatialLocation &loc, const double *values) const override;

  int numElements() const { return elements_; }
  double elementLength() const { return l_; }
  const spatial_beam::Section &section() const { return section_; }
  // An element's geometry: its length and its two nodes' reference triads.
  spatial_beam::Geometry geometry(int element) const { return {l_, {frames_[element], frames_[element + 1]}}; }
  PetscInt elementDof(int element, int k) const { return first_ + 7 * element + k; }
  // Global indices of every node's slope (3 per node, node after node).
  std::vector<PetscInt> slopeDofs() const;

  // Rebasing (docs/model.md §1.7): if some node's tangent (slopes: 3 per
  // node, node after node) has turned from its reference tangent by more
  // than kRebaseAngle, every node's reference becomes its current
  // zero-twist triad (rebasedNodeFrame): the same twists give the same
  // section triads, strains and energy. Returns whether it rebased.
  // always: rebase whatever the angles (tests).
  static constexpr double kRebaseAngle = 120.0; // degrees
  bool rebase(const double *slopes, bool always = false);
  // The node references as 6 numbers per node (tangent, normal), and back.
  std::vector<double> references() const;
  void setReferences(const double *values);

private:
  int elements_;
  spatial_beam::Section section_;
  Vec3 origin_;
  Mat3 triad_;
  double l_;
  std::vector<spatial_beam::NodeFrame> frames_; // one per node
};

// Inertia, gravity, elastic and Kelvin-Voigt forces of one element.
class SpatialBeamElementItem : public WorkItem {
public:
  SpatialBeamElementItem(const SpatialAncfBeam &beam, int element, std::shared_ptr<const spatial_beam::Mat14> mass,
                         const Vec3 &gravity);
  std::string name() const override;
  void coordinates(std::vector<PetscInt> &dofs) const override;
  void evaluate(const AssemblyContext &ctx, const ItemValues &in, double *residual, double *J) const override;
  void energy(const AssemblyContext &ctx, const ItemValues &in, EnergyParts &e) const override;
  bool physicalDamping() const override { return beam_->section().damped(); }
  bool dampingForce(const ItemValues &in, double *f) const override;
  void scales(const ItemValues &in, double &massDiag, double &stiffDiag, int &count) const override;
  // Mode labels: the element's strain energy by strain (axial, bending about d3 = in the plane of the
  // axis and `up`, bending about d2 = out of it, torsion),
  // its stress stiffening as geometric (docs/model.md §5).
  void modeEnergy(const PencilPass &stiffness, int n, const double *shape, double *scratch,
                  ModeEnergy &out) const override;

private:
  const SpatialAncfBeam *beam_;
  int element_;
  std::shared_ptr<const spatial_beam::Mat14> mass_;
  spatial_beam::Vec14 gravity_;
};

} // namespace boomdyn
