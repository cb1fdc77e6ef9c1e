#include "boomdyn/slack_coordinate.hpp"

#include "boomdyn/model_builder.hpp"

#include <sstream>

namespace boomdyn {

void addSlackCoordinate(const ComponentSpec &spec, ModelBuilder &b, const BodyBase &track, double s0)
{
  if (s0 < 0.0 || s0 > track.length()) {
    std::ostringstream os;
    os << ModelBuilder::where(spec.mark) << "sliding joint '" << spec.name << "': the slider point lies outside its track '"
       << track.name() << "' (at s = " << s0 << " m of " << track.length() << " m)";
    throw ModelError(os.str());
  }
  auto &mine = b.scratch(spec.type, spec.name);
  mine["s0"] = s0;
  mine["slack"] = static_cast<double>(b.addCoordinate(s0));
}

} // namespace boomdyn
