// A scene as validated plain data: what the scene file says, in SI units
// (angles in radians). Analysis settings have fixed fields; bodies are the
// typed views (BodySpec) their registered body types fill; the other
// components (constraints, loads, masses, springs, sensors) are
// ComponentSpecs of registered physics types (physics_type.hpp). The reader
// (io/scene_reader) fills it and rejects bad input; the Model is built from
// it. Nothing downstream reads the YAML text again, except to store it in
// the output.
#pragma once

#include "boomdyn/component_spec.hpp"

#include <string>
#include <vector>

namespace boomdyn {

struct SectionSpec {
  double EA = 0;   // axial stiffness, N
  double EI = 0;   // bending stiffness, N m^2
  double rhoA = 0; // mass per length, kg/m
  // Kelvin-Voigt retardation times of axial strain and curvature, s (flexible bodies; 0: undamped)
  double etaAxial = 0, etaBending = 0;
  // Axial strain treatment of ANCF beams (ancf::AxialIntegration, option
  // -boom_axial_integration): full (5 Gauss points), reduced (3), assumed
  // (default: projected strain, no membrane locking; docs/model.md §1.1).
  enum class AxialIntegration { Full, Reduced, Assumed };
  AxialIntegration axialIntegration = AxialIntegration::Assumed;
  // Spatial beams (dimension 3): bending stiffnesses about the section axes
  // d2 (EIy) and d3 (EIz), torsional stiffness GJ (N m^2), rotary inertia of
  // the section about the axis rhoIp (kg m) and the retardation time of the
  // torsion (s).
  double EIy = 0, EIz = 0, GJ = 0, rhoIp = 0, etaTorsion = 0;
};

// A body as its type (src/bodies/*_type.cpp) describes it after reading,
// and as the command-line options (-boom_elements) and tests may change it
// before the Model is built from it by the same type. Type selects the
// registered body type (bodyType() in physics_type.hpp).
struct BodySpec {
  enum class Type { AncfBeam, Rigid, SpatialRigid, SpatialAncfBeam };
  std::string name;
  Type type = Type::AncfBeam;
  double length = 0;  // m
  int elements = 1;   // ANCF beams only
  Vec2d origin{0, 0}; // position of s = 0 in the initial configuration, m
  double angle = 0;   // initial direction of the axis, rad (counter-clockwise from x)
  SectionSpec section; // in the stiffness form, whichever form the scene used
  SourceMark mark;
  // Spatial scenes (dimension 3): origin3 is the position of s = 0; the
  // body axes are x along `axis` (the direction of s), y along the part of
  // `up` normal to it, z = x cross y. Mass properties of rigid bodies:
  // mass, the inertia tensor about the centre of mass in body axes
  // (inertia = [Jxx, Jyy, Jzz], products = [Jxy, Jyz, Jzx]) and the
  // centre of mass in body axes from the point s = 0.
  Vec3d origin3{0, 0, 0};
  Vec3d axis{1, 0, 0}, up{0, 1, 0};
  double mass = 0;
  Vec3d inertia{0, 0, 0}, products{0, 0, 0};
  Vec3d centerOfMass{0, 0, 0};
  // Initial velocity of the point s = 0 and angular velocity (global axes).
  Vec3d velocity{0, 0, 0}, angularVelocity{0, 0, 0};
};

struct DynamicSpec {
  double t_end = 1.0;     // s
  double dt = 1e-3;       // s
  double dt_min = 1e-9;   // s; a step cut below this stops the run
  double rho_inf = 0.8;   // spectral radius at infinity, in [0, 1]
  int max_newton = 25;
  // initial: static — start from the static equilibrium under the loads and
  // drives at t = 0 (at rest) instead of the undeformed state.
  bool startStatic = false;
};

struct StaticSpec {
  int load_steps = 1; // equal increments of the load factor
  double time = 0;    // time at which time functions are evaluated
};

struct ModalSpec {
  int count = 0;           // 0: no eigen-analysis
  std::string at = "end";  // "start" (initial state) or "end" (after static/dynamic solve)
};

// Eigen-analysis along a dynamic run (docs/model.md §5): every `interval` seconds
// the system is linearized at the current state and `count` modes are found;
// the followed modes are carried by mode continuity (MAC).
struct TrackingSpec {
  double interval = 0;           // s; 0: no tracking
  int count = 4;                 // modes per analysis
  std::vector<double> shapesAt;  // times (s) at which the tracked shape is written
  // The followed modes (key `follow`): at the first analysis the lowest
  // `follow` modes with omega^2 > 0, or, when followHz is given, for each of
  // its frequencies the mode nearest it (a different mode each). The first
  // followed mode is the one of /tracking/tracked_hz.
  int follow = 1;
  std::vector<double> followHz;  // Hz; empty: the lowest `follow` modes
};

struct OutputSpec {
  double state_interval = 0; // s; 0: full state at the first and last step only
  std::vector<ComponentSpec> sensors; // section output.sensors
  std::vector<ComponentSpec> frames;  // section output.frames
};

struct Scene {
  std::string file; // path as given
  std::string text; // full file text, stored in the output
  std::string name;
  std::string description;
  enum class Analysis { Static, Dynamic, Modal };
  Analysis analysis = Analysis::Dynamic;
  // 2: a planar scene (the default), 3: a spatial scene (key `dimension`).
  int dimension = 2;
  Vec2d gravity{0, 0}; // m/s^2 (planar scenes)
  Vec3d gravity3{0, 0, 0}; // m/s^2; planar scenes: [gx, gy, 0]
  std::vector<BodySpec> bodies;
  // Components of the registered physics types (physics_type.hpp), by
  // section, in file order.
  std::vector<ComponentSpec> constraints; // section constraints
  std::vector<ComponentSpec> forces;      // section loads
  std::vector<ComponentSpec> masses;      // section masses
  std::vector<ComponentSpec> springs;     // section springs
  DynamicSpec dynamic;
  StaticSpec statics;
  ModalSpec modal;
  TrackingSpec tracking;
  OutputSpec output;

  // The sections that hold components, in the order the Model builds them.
  static const std::vector<std::string> &componentSections();
  std::vector<ComponentSpec> &components(const std::string &section);
  const std::vector<ComponentSpec> &components(const std::string &section) const;
};

} // namespace boomdyn
