// docs/scenes.md's per-type tables, generated from the registered schemas
// (physics_type.hpp) so that the docs cannot drift from the reader. The
// document marks each generated block with HTML comments:
//   <!-- BEGIN generated: constraints -->  ...  <!-- END generated: constraints -->
// and everything outside the blocks is hand-written prose.
#pragma once

#include <stdexcept>
#include <string>

namespace boomdyn {

// The Markdown of one component section ("constraints", "loads", ...):
// one table per registered type, and one per nested map (friction).
std::string schemaMarkdown(const std::string &section);

// doc with every generated block's content replaced by schemaMarkdown() of
// its section. Throws std::runtime_error naming the section when a block of
// a component section is missing or not closed.
std::string regenerateSchemaBlocks(const std::string &doc);

} // namespace boomdyn
