// libFuzzer target for the scene reader (GitHub issue 8).
//
// Feeds arbitrary bytes to boomdyn::parseScene(text, "fuzz.yaml"). The reader
// must either return a Scene or throw boomdyn::SceneError with a located
// message. Everything else is a finding:
//   - a crash, hang, sanitizer report (ASan/UBSan) or out-of-memory;
//   - any exception other than SceneError escaping parseScene;
//   - a SceneError produced by parseScene's catch-all ("internal error while
//     reading the scene", "YAML error"), which turns an unexpected exception
//     (std::out_of_range from .at(), an unchecked yaml-cpp conversion, ...)
//     into a message: the input still is not crashing, but the reader's own
//     checks missed it;
//   - a message that does not start with "fuzz.yaml:<line>:<column>: " with a
//     line inside the file (the format promised in docs/scenes.md).
// After a successful parse every time function is evaluated at a few times,
// so that time_function.cpp runs under the sanitizers too.
//
// Built with clang++ -fsanitize=fuzzer,address,undefined from the reader's
// own sources, linked with PETSc and MPI: see tests/fuzz/run_fuzzer.sh.
#include "boomdyn/scene_reader.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <variant>

namespace {

const char *const kLabel = "fuzz.yaml";

[[noreturn]] void finding(const char *what, const std::string &detail)
{
  std::fprintf(stderr, "\n==scene_fuzzer== FINDING: %s\n==scene_fuzzer== %s\n", what, detail.c_str());
  std::fflush(stderr);
  std::abort(); // libFuzzer reports the abort as a crash and writes the input
}

// Length of the location prefix "fuzz.yaml:<line>:<column>: " with
// 1 <= line <= lines + 1 and column >= 1; 0 if the message does not start so.
std::size_t locationPrefix(const std::string &message, const std::string &text)
{
  const std::string head = std::string(kLabel) + ":";
  if (message.rfind(head, 0) != 0) return 0;
  std::size_t pos = head.size();
  auto number = [&](long &value) {
    const std::size_t start = pos;
    value = 0;
    while (pos < message.size() && message[pos] >= '0' && message[pos] <= '9' && pos - start < 12)
      value = value * 10 + (message[pos++] - '0');
    return pos > start;
  };
  long line = 0, column = 0;
  if (!number(line) || pos >= message.size() || message[pos++] != ':') return 0;
  if (!number(column) || message.compare(pos, 2, ": ") != 0) return 0;
  const long lines = static_cast<long>(std::count(text.begin(), text.end(), '\n')) + 1;
  if (line < 1 || line > lines + 1 || column < 1) return 0;
  return pos + 2;
}

// Checks a rejection message. The reader's own messages go on with
// "key '<path>': " or "YAML syntax error: "; parseScene's catch-all produces
// "<file>: internal error while reading the scene: ..." or
// "<file>:<l>:<c>: YAML error: ...".
void checkMessage(const std::string &message, const std::string &text)
{
  if (message.rfind(std::string(kLabel) + ": internal error while reading the scene:", 0) == 0)
    finding("parseScene's catch-all fired (an unexpected std::exception inside the reader)", message);
  const std::size_t at = locationPrefix(message, text);
  if (at == 0) finding("SceneError message not in the documented format <file>:<line>:<column>: ...", message);
  if (message.compare(at, 12, "YAML error: ") == 0)
    finding("parseScene's catch-all fired (an unexpected YAML::Exception inside the reader)", message);
  if (message.compare(at, 5, "key '") != 0 && message.compare(at, 19, "YAML syntax error: ") != 0)
    finding("SceneError message neither \"key '...'\" nor \"YAML syntax error\"", message);
}

void exercise(const boomdyn::TimeFunction &f)
{
  static const double times[] = {-1.0, 0.0, 1e-3, 0.5, 1.0, 2.5, 10.0, 1e6};
  volatile double sink = 0;
  for (double t : times) sink = sink + f.value(t) + f.rate(t) + f.accel(t);
  (void)f.describe();
  (void)f.scaled(0.5).value(1.0);
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  const std::string text(reinterpret_cast<const char *>(data), size);
  try {
    const boomdyn::Scene scene = boomdyn::parseScene(text, kLabel);
    // Every time function of every component (angles, displacements, scales).
    for (const std::string &section : boomdyn::Scene::componentSections())
      for (const auto &c : scene.components(section))
        for (const auto &[key, value] : c.values)
          if (const auto *f = std::get_if<boomdyn::TimeFunction>(&value)) exercise(*f);
  } catch (const boomdyn::SceneError &e) {
    checkMessage(e.what(), text);
  } catch (const std::exception &e) {
    finding("exception other than SceneError escaped parseScene", e.what());
  } catch (...) {
    finding("non-std exception escaped parseScene", "(unknown type)");
  }
  return 0;
}
