// What the planar and the spatial sliding joints share about their slack
// coordinate s (the arc length of the contact point on the track): when the
// contact point moves to another track element (the types' post-step hook,
// slack_coordinate.hpp, moves it there).
#pragma once

namespace boomdyn {

// A contact point stays with its element until it is more than this fraction
// of the element length past its end: the axis is C1 across nodes, so
// evaluating the element a little outside its span is accurate, and without
// this band a joint resting on a node would switch elements (and the solver
// its sparsity pattern) at every vibration.
constexpr double kSlackRelocationHysteresis = 1e-3;

// True when s, clamped to [0, length], lies outside the element
// [begin, end] by more than the hysteresis band; *clamped gets the clamped s.
bool slackLeavesElement(double s, double begin, double end, double length, double *clamped);

} // namespace boomdyn
