#include "boomdyn/stick_slip.hpp"

#include <cmath>

namespace boomdyn {

std::vector<StickSlipEvent> StickSlipMonitor::update(double t, const std::vector<double> &values,
                                                     std::vector<FrictionReading> &out)
{
  const auto &frictions = model_.frictions();
  state_.resize(frictions.size(), -1);
  lastSign_.resize(frictions.size(), 0);
  filtered_.resize(frictions.size(), 0.0);
  out.assign(frictions.size(), FrictionReading{});
  std::vector<StickSlipEvent> fresh;
  if (values.size() < 5 * frictions.size()) return fresh; // not rank 0
  for (std::size_t k = 0; k < frictions.size(); ++k) {
    const double *v = values.data() + 5 * k; // s, sdot, z, zdot, lambda_n
    const LuGreFriction &f = *frictions[k];
    FrictionReading &r = out[k];
    r.slipVelocity = -v[1];
    r.z = v[2];
    r.normalForce = v[4];
    r.force = f.force(v[2], v[3], v[4], r.slipVelocity);
    // First-order low-pass filter of v_r (exact exponential weight for any step).
    const double w = state_[k] < 0 ? 1.0 : 1.0 - std::exp(-(t - lastTime_) / filterTime);
    filtered_[k] += w * (r.slipVelocity - filtered_[k]);
    r.filteredSlipVelocity = filtered_[k];
    const double speed = std::abs(filtered_[k]);
    const int now = state_[k] == 1 ? (speed < f.spec().stick_velocity ? 0 : 1) : (speed > f.spec().v_s ? 1 : 0);
    r.slipping = now == 1;
    if (r.slipping) lastSign_[k] = filtered_[k] > 0 ? 1 : -1;
    if (state_[k] >= 0 && now != state_[k]) {
      fresh.push_back({t, f.joint().name(), now == 1, lastSign_[k]});
      events_.push_back(fresh.back());
    }
    state_[k] = now;
  }
  lastTime_ = t;
  return fresh;
}

std::vector<double> StickSlipMonitor::state() const
{
  std::vector<double> out{lastTime_};
  for (std::size_t k = 0; k < state_.size(); ++k) out.insert(out.end(), {double(state_[k]), double(lastSign_[k]), filtered_[k]});
  return out;
}

void StickSlipMonitor::setState(const std::vector<double> &s)
{
  if (s.empty()) return;
  lastTime_ = s[0];
  const std::size_t n = (s.size() - 1) / 3;
  state_.resize(n), lastSign_.resize(n), filtered_.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    state_[k] = static_cast<int>(s[1 + 3 * k]);
    lastSign_[k] = static_cast<int>(s[2 + 3 * k]);
    filtered_[k] = s[3 + 3 * k];
  }
}

} // namespace boomdyn
