// The program's operator new records the size of a request that fails
// before it throws std::bad_alloc, so that the error can say how much was
// asked for. Sanitizer builds keep their own operator new (their
// new/delete pairing checks need it).
#include "out_of_memory.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <new>

namespace {

std::atomic<std::size_t> failedRequest{0};

std::string bytesText(double bytes)
{
  char text[64];
  if (bytes >= 1e9) std::snprintf(text, sizeof text, "%.1f GB", bytes / 1e9);
  else std::snprintf(text, sizeof text, "%.1f MB", bytes / 1e6);
  return text;
}

} // namespace

#if !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)
void *operator new(std::size_t n)
{
  while (true) {
    if (void *p = std::malloc(n ? n : 1)) return p;
    if (const std::new_handler handler = std::get_new_handler()) handler();
    else {
      failedRequest = n;
      throw std::bad_alloc();
    }
  }
}
#endif

namespace boomdyn {

double lastFailedAllocation() { return static_cast<double>(failedRequest.load()); }

double petscRequestedBytes(const std::string &petscMessage)
{
  const std::string key = "Memory requested", mumps = "required memory"; // MUMPS: "... N megabytes"
  if (const auto at = petscMessage.find(key); at != std::string::npos)
    return std::atof(petscMessage.c_str() + at + key.size());
  if (const auto at = petscMessage.find(mumps); at != std::string::npos)
    return 1e6 * std::atof(petscMessage.c_str() + at + mumps.size());
  return 0;
}

std::string outOfMemoryMessage(double requestedBytes)
{
  std::string text = "out of memory: ";
  text += requestedBytes > 0 ? "an allocation of " + bytesText(requestedBytes) + " failed" : "an allocation failed";
  struct rlimit limit;
  if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
    text += "; this process may use at most " + bytesText(double(limit.rlim_cur)) + " of address space (ulimit -v)";
  const double physical = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
  if (physical > 0) text += "; the machine has " + bytesText(physical);
  return text + ". The scene needs more memory than the run may use: a coarser mesh (-boom_elements), fewer "
                "bodies or sheaves, or more ranks";
}

} // namespace boomdyn
