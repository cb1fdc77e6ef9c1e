// The test rig of the hydraulic cylinder's tests: a rigid block of m =
// 1000 kg (0.1 m long, rhoA = m / 0.1) with its centre 1 m above the base
// point (0, 0) of a vertical cylinder (D = 100 mm, d = 56 mm, stroke 0.6 m,
// initial stroke s0 = 0.3 m; 2e-4 + 3e-4 m^3 dead and hose volume on the
// piston side, 1.5e-4 + 2.5e-4 m^3 on the rod side; oil 1650 MPa), its
// rotation locked by an angle drive. A cylinder pinned at the ground that
// pushes a free block up is an inverted pendulum: a horizontal spring of 10 m
// (unstretched at the start, so it adds no vertical stiffness to first
// order) holds the block sideways.
#pragma once

#include <cmath>
#include <string>

namespace boomdyn::testing::cylinder_block {

constexpr double g = 9.81, m = 1000.0, D = 0.1, d = 0.056, L = 0.6, s0 = 0.3;
constexpr double Vd1 = 2e-4, Vh1 = 3e-4, Vd2 = 1.5e-4, Vh2 = 2.5e-4, Boil = 1.65e9;
const double A1 = 0.25 * M_PI * D * D, A2 = 0.25 * M_PI * (D * D - d * d);
const double C1 = (Vd1 + Vh1 + A1 * s0) / Boil, C2 = (Vd2 + Vh2 + A2 * (L - s0)) / Boil;

// The scene: `cylinder` are the cylinder's keys after the volumes (valve,
// pressures, friction), `dynamic` the dynamic section's flow mapping,
// `sideways` the spring's stiffness (N/m).
inline std::string scene(const std::string &cylinder, const std::string &dynamic, const std::string &sideways = "1.0e+6")
{
  return R"(
name: cylinder-block
analysis: dynamic
gravity: [0, -9.81]
bodies:
  - {name: block, type: rigid, length: 0.1, origin: [-0.05, 1.0], section: {rhoA: 10000}}
constraints:
  - {type: angle_drive, body: block, at: 0.05, angle: 0}
  - {type: hydraulic_cylinder, name: lift, body: block, at: 0.05, base_point: [0, 0], piston_diameter: 0.1,
     rod_diameter: 0.056, stroke: 0.6, closed_length: 0.7, dead_volume_piston: 2.0e-4, hose_volume_piston: 3.0e-4,
     dead_volume_rod: 1.5e-4, hose_volume_rod: 2.5e-4, bulk_modulus_oil: 1.65e9, )" +
         cylinder + R"(}
springs:
  - {body: block, at: 0.05, point: [10.0, 1.0], stiffness: )" + sideways + R"(}
dynamic: )" + dynamic + "\n";
}

} // namespace boomdyn::testing::cylinder_block
