// A scene as validated plain data: what the scene file says, in SI units
// (angles in radians), with nothing derived. The reader (io/scene_reader)
// fills it and rejects bad input; the Model is built from it. Nothing
// downstream reads the YAML text again, except to store it in the output.
#pragma once

#include "boomdyn/time_function.hpp"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace boomdyn {

using Vec2d = std::array<double, 2>;

// Where a value came from, for messages raised after parsing.
struct SourceMark {
  std::string file;
  int line = 0; // 1-based, 0 = unknown
  std::string key;
};

struct SectionSpec {
  double EA = 0;   // axial stiffness, N
  double EI = 0;   // bending stiffness, N m^2
  double rhoA = 0; // mass per length, kg/m
};

struct BodySpec {
  enum class Type { AncfBeam, Rigid };
  std::string name;
  Type type = Type::AncfBeam;
  double length = 0;  // m
  int elements = 1;   // ANCF beams only
  Vec2d origin{0, 0}; // position of s = 0 in the initial configuration, m
  double angle = 0;   // initial direction of the axis, rad (counter-clockwise from x)
  SectionSpec section;
  SourceMark mark;
};

// A material point: body name and material coordinate s in [0, length].
struct PointRef {
  std::string body;
  double s = 0;
};

// LuGre friction at a sliding joint (model.md §3): F_t = (sigma0 z + sigma1
// zdot) |lambda_n| + sigma2 v_r with zdot = v_r - sigma0 |v_r| z / g(v_r),
// g(v) = mu_c + (mu_s - mu_c) exp(-|v / v_s|^alpha).
struct FrictionSpec {
  double mu_s = 0.15, mu_c = 0.1; // static and kinetic coefficients
  double v_s = 1e-3;              // Stribeck velocity, m/s
  double alpha = 2.0;             // Stribeck exponent
  double sigma0 = 1e5;            // bristle stiffness per unit normal force, 1/m
  double sigma1 = 0.0;            // bristle damping per unit normal force, s/m
  double sigma2 = 0.0;            // viscous friction, N s/m
  double stick_velocity = -1;     // |v_r| below it counts as stick in the output, m/s (< 0: v_s / 10)
};

struct ConstraintSpec {
  // pin:         r_a(s_a) = ground point, or r_a(s_a) = r_b(s_b)
  // angle_drive: the tangent of body a at s_a points along theta(t)
  // clamp:       pin to ground + angle_drive (expanded by the Model)
  // sliding_joint: the point a (slider body, x_P) moves along the centerline
  //               of body `track`; its contact coordinate is an unknown
  // extraction_drive: the slack coordinate of sliding joint `joint` follows
  //               s(t) = s(0) + displacement(t)
  // rope:        L - |r_from - r_pulley| - |r_pulley - r_to| = 0 (points a, b, c)
  enum class Type { Pin, AngleDrive, Clamp, SlidingJoint, ExtractionDrive, Rope };
  Type type = Type::Pin;
  std::string name;
  PointRef a;
  std::optional<PointRef> b; // pin between bodies (absent: to ground); rope: the pulley
  std::optional<PointRef> c; // rope: the far end
  double length = 0;         // rope length, m; 0: the initial spanned length
  Vec2d ground{0, 0};        // ground point, m (pin/clamp to ground)
  TimeFunction angle;        // rad (angle_drive/clamp)
  std::string track;         // sliding_joint: the body the slider runs along
  std::string joint;         // extraction_drive: the sliding joint whose slack coordinate it drives
  TimeFunction displacement; // extraction_drive: d(t), m
  std::optional<FrictionSpec> friction; // sliding_joint: LuGre friction (absent: frictionless)
  SourceMark mark;
};

struct PointForceSpec {
  std::string name;
  PointRef at;
  Vec2d force{0, 0};  // N, global frame, multiplied by scale(t)
  TimeFunction scale = TimeFunction::constant(1.0);
  SourceMark mark;
};

struct PointMassSpec {
  std::string name;
  PointRef at;
  double mass = 0; // kg
  SourceMark mark;
};

// Linear spring-damper from a material point to another body's point or to
// a ground point.
struct SpringSpec {
  std::string name;
  PointRef a;
  std::optional<PointRef> b; // absent: to the ground point
  Vec2d ground{0, 0};
  double stiffness = 0;      // N/m
  double restLength = -1;    // m; < 0: the initial distance
  double damping = 0;        // N s/m
  SourceMark mark;
};

struct SensorSpec {
  std::string name;
  PointRef at;
};

// Deflection of a material point in a body's moving frame (paper Fig. 9):
// origin at the body's start (s = 0), x-axis through the contact point of
// sliding joint `axisJoint` on that body; the output is the point's
// coordinate normal to the axis (m).
struct FrameSensorSpec {
  std::string name;
  PointRef point;        // body and the material point whose deflection is measured
  std::string axisJoint; // sliding joint that has `point.body` as its track
};

struct DynamicSpec {
  double t_end = 1.0;     // s
  double dt = 1e-3;       // s
  double dt_min = 1e-9;   // s; a step cut below this stops the run
  double rho_inf = 0.8;   // spectral radius at infinity, in [0, 1]
  int max_newton = 25;
};

struct StaticSpec {
  int load_steps = 1; // equal increments of the load factor
  double time = 0;    // time at which time functions are evaluated
};

struct ModalSpec {
  int count = 0;           // 0: no eigen-analysis
  std::string at = "end";  // "start" (initial state) or "end" (after static/dynamic solve)
};

// Eigen-analysis along a dynamic run (model.md §5): every `interval` seconds
// the system is linearized at the current state and `count` modes are found;
// the first bending mode is followed by mode continuity (MAC).
struct TrackingSpec {
  double interval = 0;           // s; 0: no tracking
  int count = 4;                 // modes per analysis
  std::vector<double> shapesAt;  // times (s) at which the tracked shape is written
};

struct OutputSpec {
  double state_interval = 0; // s; 0: full state at the first and last step only
  std::vector<SensorSpec> sensors;
  std::vector<FrameSensorSpec> frames;
};

struct Scene {
  std::string file; // path as given
  std::string text; // full file text, stored in the output
  std::string name;
  std::string description;
  enum class Analysis { Static, Dynamic, Modal };
  Analysis analysis = Analysis::Dynamic;
  Vec2d gravity{0, 0}; // m/s^2
  std::vector<BodySpec> bodies;
  std::vector<ConstraintSpec> constraints;
  std::vector<PointForceSpec> forces;
  std::vector<PointMassSpec> masses;
  std::vector<SpringSpec> springs;
  DynamicSpec dynamic;
  StaticSpec statics;
  ModalSpec modal;
  TrackingSpec tracking;
  OutputSpec output;

  const BodySpec *findBody(const std::string &name) const;
};

} // namespace boomdyn
