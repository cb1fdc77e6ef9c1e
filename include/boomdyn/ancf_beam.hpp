// A boom as a chain of planar ANCF cable elements sharing nodes (C1 continuity).
// Coordinates are node-major: node k has (x, y, dx/ds, dy/ds) at first + 4k.
#pragma once

#include "boomdyn/ancf_element.hpp"
#include "boomdyn/body.hpp"

namespace boomdyn {

class AncfBeam : public Body {
public:
  AncfBeam(std::string name, double length, int elements, const ancf::Section &section, Vec2 origin, double angle,
           PetscInt first);
  PetscInt numCoordinates() const override { return 4 * (elements_ + 1); }
  void initialCoordinates(double *q) const override;
  CenterlineLocation locate(double s) const override;
  void sample(const CenterlineLocation &loc, double s, const double *values, CenterlineSample &out) const override;
  int outputSegments() const override { return kOutputSegmentsPerElement * elements_; }

  int numElements() const { return elements_; }
  double elementLength() const { return length_ / elements_; }
  const ancf::Section &section() const { return section_; }
  // Global index of entry k (0..7) of element el's vector.
  PetscInt elementDof(int el, int k) const { return first_ + 4 * el + k; }

private:
  int elements_;
  ancf::Section section_;
  Vec2 origin_, direction_;
};

} // namespace boomdyn
