// Stick/slip state of every frictional sliding joint along a run, and its
// transitions as events. The slip velocity is taken from the slack
// coordinate's rate, v_r = -ds/dt (exact on rigid tracks; on flexible tracks
// it differs from -|r'| ds/dt by the track's axial strain, ~1e-4 for steel
// booms). Elastic vibration moves the contact point back and forth without
// any net sliding, so the classification uses the slip velocity low-pass
// filtered over `filterTime` (0.05 s: longer than the booms' vibration
// periods) with hysteresis: stick -> slip when the filtered |v_r| exceeds v_s,
// slip -> stick when it falls below the stick velocity (v_s / 10 by default).
#pragma once

#include "boomdyn/lugre_friction.hpp"
#include "boomdyn/model.hpp"

#include <string>
#include <vector>

namespace boomdyn {

struct FrictionReading { // per frictional joint
  double slipVelocity = 0, filteredSlipVelocity = 0, force = 0, normalForce = 0, z = 0;
  bool slipping = false;
};

struct StickSlipEvent {
  double t;
  std::string joint;
  bool toSlip;       // stick -> slip (else slip -> stick)
  int direction;     // sign of the slip velocity at (or just before) the transition; + : s decreasing
};

class StickSlipMonitor {
public:
  explicit StickSlipMonitor(const Model &model) : model_(model) {}
  // values per joint: s, ds/dt, z, dz/dt, lambda_n (rank 0 data). Returns the new events.
  std::vector<StickSlipEvent> update(double t, const std::vector<double> &values, std::vector<FrictionReading> &out);
  const std::vector<StickSlipEvent> &events() const { return events_; }
  // State for checkpoints (filter, stick/slip state, last direction, time).
  std::vector<double> state() const;
  void setState(const std::vector<double> &s);

private:
  const Model &model_;
  std::vector<int> state_;   // -1 unknown, 0 stick, 1 slip
  std::vector<int> lastSign_;
  std::vector<double> filtered_;
  double lastTime_ = 0;
  static constexpr double filterTime = 0.05; // s
  std::vector<StickSlipEvent> events_;
};

} // namespace boomdyn
