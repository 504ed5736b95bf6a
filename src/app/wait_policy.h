#pragma once
// How OpenMP's idle threads wait, set by the program (docs/performance.md, "Threads").

#include <string>

namespace sluice::app {

// libgomp spins about 300 000 times at every barrier before it sleeps. On a machine
// whose cores are busy with other work, a spinning thread holds the core that the thread
// it waits for needs, and each of the step's barriers can cost a time slice
// (docs/performance.md, "Threads on a busy machine"). 1000 spins (libgomp's own choice when threads outnumber cores)
// keep 2 threads at least as fast as 1 there. libgomp reads GOMP_SPINCOUNT once, when it loads, before main(): so when
// the user has set neither it nor OMP_WAIT_POLICY, the program starts itself again with it set. If that fails, it runs
// on with the default.
inline constexpr const char* kSpinCount = "1000";
void set_thread_wait_policy(char** argv);

// The policy in force, for summary.json: "OMP_WAIT_POLICY=...", "GOMP_SPINCOUNT=..." or
// "libgomp default".
std::string thread_wait_policy();

}  // namespace sluice::app
