// Reading and validating scene files (YAML, format in docs/scenes.md).
//
// The reader is the only place that sees user input, so it rejects
// everything it cannot turn into a physically meaningful Scene, and says
// where: every message has the form
//   <file>:<line>:<column>: key '<path>': <reason>
// (YAML syntax errors: "<file>:<line>:<column>: YAML syntax error: <msg>",
// a file that cannot be read: "<file>: cannot open scene file").
#pragma once

#include "boomdyn/scene.hpp"

#include <stdexcept>
#include <string>

namespace boomdyn {

class SceneError : public std::runtime_error {
public:
  explicit SceneError(const std::string &message) : std::runtime_error(message) {}
};

// Reads the file at path; Scene::file is path, Scene::text the file content.
Scene readSceneFile(const std::string &path);

// Parses scene text; file_label is used in messages and as Scene::file.
Scene parseScene(const std::string &text, const std::string &file_label);

} // namespace boomdyn
