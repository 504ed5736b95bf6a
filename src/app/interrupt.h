#pragma once
// SIGINT and SIGTERM during `simulate` and `render`: the handler only records the signal;
// the run loop stops at the next step, writes its record ("status": "interrupted") and
// leaves through Interrupted, which main turns into exit status 128 + signal.
#include <stdexcept>
#include <string>

namespace sluice::app {

class Interrupted : public std::runtime_error {
 public:
  Interrupted(int signal, const std::string& message) : std::runtime_error(message), signal_(signal) {}
  int signal() const { return signal_; }

 private:
  int signal_;
};

// Installs the handlers (once). A second signal of the same kind ends the program at once.
void catch_interrupts();
// The signal received (SIGINT or SIGTERM), 0 when none.
int interrupt_signal();
// "SIGINT" or "SIGTERM".
std::string signal_name(int signal);

}  // namespace sluice::app
