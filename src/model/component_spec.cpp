#include "boomdyn/component_spec.hpp"

#include <stdexcept>

namespace boomdyn {

namespace {

// The schema guarantees presence and kind, so a miss is a bug in a type file.
template <typename T> const T &valueOf(const ComponentSpec &spec, const std::string &key, const char *kind)
{
  const auto it = spec.values.find(key);
  if (it == spec.values.end())
    throw std::logic_error("component '" + spec.name + "' (" + spec.type + "): no value for key '" + key + "'");
  const T *value = std::get_if<T>(&it->second);
  if (!value)
    throw std::logic_error("component '" + spec.name + "' (" + spec.type + "): key '" + key + "' is not " + kind);
  return *value;
}

} // namespace

double ComponentSpec::number(const std::string &key) const { return valueOf<double>(*this, key, "a number"); }

int ComponentSpec::integer(const std::string &key) const { return static_cast<int>(number(key)); }

const std::string &ComponentSpec::text(const std::string &key) const
{
  return valueOf<std::string>(*this, key, "a text");
}

Vec2d ComponentSpec::vec2(const std::string &key) const { return valueOf<Vec2d>(*this, key, "a vector"); }
Vec3d ComponentSpec::vec3(const std::string &key) const { return valueOf<Vec3d>(*this, key, "a 3-vector"); }

const TimeFunction &ComponentSpec::function(const std::string &key) const
{
  return valueOf<TimeFunction>(*this, key, "a time function");
}

const ComponentSpec &ComponentSpec::map(const std::string &key) const
{
  return *valueOf<std::shared_ptr<const ComponentSpec>>(*this, key, "a map");
}

PointRef ComponentSpec::point(const std::string &bodyKey, const std::string &atKey) const
{
  return PointRef{text(bodyKey), number(atKey)};
}

} // namespace boomdyn
