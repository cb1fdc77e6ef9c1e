// boomdyn_schema_docs: keeps docs/scenes.md's generated tables equal to the
// registered schemas (include/boomdyn/schema_markdown.hpp).
//
//   boomdyn_schema_docs --check FILE   exit 1 (with the command to fix it) if FILE's blocks differ
//   boomdyn_schema_docs --write FILE   rewrite FILE's blocks
//   boomdyn_schema_docs SECTION        print one section's tables
#include "boomdyn/schema_markdown.hpp"

#include <fstream>
#include <iostream>
#include <sstream>

int main(int argc, char **argv)
{
  const std::string mode = argc > 1 ? argv[1] : "";
  if (argc == 2 && mode.rfind("--", 0) != 0) {
    std::cout << boomdyn::schemaMarkdown(mode);
    return 0;
  }
  if (argc != 3 || (mode != "--check" && mode != "--write")) {
    std::cerr << "usage: " << argv[0] << " --check FILE | --write FILE | SECTION\n";
    return 2;
  }
  const std::string path = argv[2];
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    std::cerr << path << ": cannot open\n";
    return 2;
  }
  std::ostringstream text;
  text << in.rdbuf();
  std::string fresh;
  try {
    fresh = boomdyn::regenerateSchemaBlocks(text.str());
  } catch (const std::exception &e) {
    std::cerr << path << ": " << e.what() << "\n";
    return 1;
  }
  if (mode == "--write") {
    if (fresh != text.str()) std::ofstream(path, std::ios::binary) << fresh;
    return 0;
  }
  if (fresh == text.str()) return 0;
  std::cerr << path << ": the generated tables differ from the registered schemas (src/model/physics_types.cpp); regenerate with\n"
            << "  " << argv[0] << " --write " << path << "\n";
  return 1;
}
