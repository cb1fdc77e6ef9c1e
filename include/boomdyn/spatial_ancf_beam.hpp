// Spatial flexible beam (type `ancf_beam` of spatial scenes, dimension 3):
// n equal ANCF14 elements (spatial_beam_element.hpp, docs/model.md §1.7).
// Coordinates per node: position r (3), slope r' (3), twist theta (1), node
// after node, so element e uses the 14 coordinates 7e .. 7e + 13 of the
// body's block. Each node keeps the reference triad it starts with (the
// initial section triad); the smallest rotation from it to the current
// tangent is singular when the tangent has turned by half a turn, so a run
// in which a node's tangent turns by more than about 170 degrees is refused
// (SpatialBeamElementItem checks it) instead of rebasing the references.
#pragma once

#include "boomdyn/spatial_beam_element.hpp"
#include "boomdyn/spatial_body.hpp"
#include "boomdyn/work_item.hpp"

#include <memory>

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
  double elementLength() const { return geometry_.l; }
  const spatial_beam::Section &section() const { return section_; }
  // Every element's geometry: its length and the node reference triads
  // (all equal to the initial triad: the beam starts straight).
  const spatial_beam::Geometry &geometry() const { return geometry_; }
  PetscInt elementDof(int element, int k) const { return first_ + 7 * element + k; }

private:
  int elements_;
  spatial_beam::Section section_;
  Vec3 origin_;
  Mat3 triad_;
  spatial_beam::Geometry geometry_;
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

private:
  const SpatialAncfBeam *beam_;
  int element_;
  std::shared_ptr<const spatial_beam::Mat14> mass_;
  spatial_beam::Vec14 gravity_;
};

} // namespace boomdyn
