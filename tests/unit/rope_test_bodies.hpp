// The three bodies the rope kernels are tested on (inextensible rope in
// test_constraints.cpp, elastic rope and the shared path in
// test_elastic_rope.cpp): two 4-element ANCF beams and a rigid body, so
// that a rope path crosses element interiors, nodes and a body with a
// curved (nonlinear) centerline map. Coordinates 0-19, 20-39, 40-42.
#pragma once

#include "boomdyn/ancf_beam.hpp"
#include "boomdyn/rigid_body.hpp"

#include <vector>

namespace boomdyn::rope_test {

inline const ancf::Section kSection{1e8, 1e5, 30};

struct Bodies {
  AncfBeam b1{"b1", 2.0, 4, kSection, Vec2(0, 0), 0.1, 0};
  AncfBeam b2{"b2", 2.0, 4, kSection, Vec2(0.5, 0.05), 0.1, 20};
  RigidBody b3{"b3", 2.0, 10.0, Vec2(1.0, 0.1), 0.1, 40};
  std::vector<double> q0 = std::vector<double>(43);
  Bodies()
  {
    b1.initialCoordinates(q0.data());
    b2.initialCoordinates(q0.data() + 20);
    b3.initialCoordinates(q0.data() + 40);
  }
};

} // namespace boomdyn::rope_test
