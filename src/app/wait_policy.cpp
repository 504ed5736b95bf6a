#include "app/wait_policy.h"

#include <unistd.h>

#include <cstdlib>

namespace sluice::app {

void set_thread_wait_policy(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") != nullptr || std::getenv("GOMP_SPINCOUNT") != nullptr) return;
  if (setenv("GOMP_SPINCOUNT", kSpinCount, 1) != 0) return;
  execv("/proc/self/exe", argv);  // returns only on failure
  unsetenv("GOMP_SPINCOUNT");
}

std::string thread_wait_policy() {
  for (const char* var : {"OMP_WAIT_POLICY", "GOMP_SPINCOUNT"})
    if (const char* v = std::getenv(var)) return std::string(var) + "=" + v;
  return "libgomp default";
}

}  // namespace sluice::app
