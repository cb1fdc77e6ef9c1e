#include "boomdyn/scene.hpp"

#include <stdexcept>

namespace boomdyn {

const std::vector<std::string> &Scene::componentSections()
{
  static const std::vector<std::string> sections{"constraints", "loads", "masses", "springs", "output.sensors",
                                                 "output.frames"};
  return sections;
}

std::vector<ComponentSpec> &Scene::components(const std::string &section)
{
  if (section == "constraints") return constraints;
  if (section == "loads") return forces;
  if (section == "masses") return masses;
  if (section == "springs") return springs;
  if (section == "output.sensors") return output.sensors;
  if (section == "output.frames") return output.frames;
  throw std::logic_error("Scene: no component section '" + section + "'");
}

const std::vector<ComponentSpec> &Scene::components(const std::string &section) const
{
  return const_cast<Scene *>(this)->components(section);
}

} // namespace boomdyn
