// Design numbers of a dynamic run (issue 16; docs/output.md "Design
// numbers"): per rope the static tension (at t = 0), the peak and the
// smallest tension and their ratio to the static one (dynamic factors, as
// EN 13001-2's phi_2 for hoisting and phi_3 for a release; an elastic rope
// that carries nothing at t = 0, a lift-off, has them relative to the weight
// of the load it lifts); per clamp the
// peak reaction moment (the bending moment at a boom's root); per sliding
// joint the peak normal (contact or pad) force. Generic: built from the
// model's output channels (groups "rope", "elastic_rope", quantity
// "tension"; group "joint_resultants", quantity "normal_force") and its
// clamps (a pin "<name>.pin" with an angle drive "<name>.angle", clamp_type.cpp),
// so any scene with ropes, clamps or sliding joints gets them.
#pragma once

#include "boomdyn/model.hpp"

#include <string>
#include <utility>
#include <vector>

namespace boomdyn {

class DesignNumbers {
public:
  explicit DesignNumbers(const Model &model);
  // One accepted state (rank 0 data: outputs and the unscaled multipliers
  // as SensorProbe gives them; empty vectors on other ranks: no-op).
  void update(double t, const std::vector<double> &outputs, const std::vector<double> &multipliers);
  bool empty() const { return items_.empty(); }
  // /summary attributes: name, value (rank 0; empty before the first update).
  std::vector<std::pair<std::string, double>> attributes() const;
  // The terminal lines ("design numbers:" and one line per item).
  std::string report() const;
  // For checkpoints: the running extremes, and back.
  std::vector<double> state() const;
  void restore(const std::vector<double> &values);

private:
  enum class Kind { Tension, Moment, ContactForce };
  struct Item {
    Kind kind;
    std::string group, name; // e.g. "elastic_rope", "hoist"; "clamp", "base"; "joint_resultants", "j1"
    PetscInt index;          // output channel (Tension, ContactForce) or multiplier row (Moment)
    double start = 0, peak = 0, peakTime = 0, low = 0, lowTime = 0;
    bool seen = false;
    double loadWeight = 0; // elastic ropes: the weight of the load they lift (reference of a slack start)
  };
  static double reference(const Item &it);
  std::vector<Item> items_;
};

} // namespace boomdyn
