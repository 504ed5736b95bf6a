#pragma once
// Program invariants, the second error channel. A user's mistake (a bad scene value, an
// unwritable directory, a flag) raises a typed error that main() maps to its documented
// exit code (docs/cli.md); a broken invariant is a bug in sluice and goes through
// SLUICE_ASSERT, which prints the condition, file:line and a message and aborts.
// It is compiled in when SLUICE_ENABLE_ASSERTS is 1: by default in builds without
// NDEBUG (Debug), and in any build with the CMake option SLUICE_ASSERTIONS (the debug
// and sanitizer presets). Otherwise it costs nothing and does not evaluate its condition.
#include <cstdio>
#include <cstdlib>

#ifndef SLUICE_ENABLE_ASSERTS
#ifdef NDEBUG
#define SLUICE_ENABLE_ASSERTS 0
#else
#define SLUICE_ENABLE_ASSERTS 1
#endif
#endif

namespace sluice::detail {

[[noreturn]] inline void assertion_failed(const char* condition, const char* file, int line, const char* message) {
  std::fprintf(stderr, "sluice: internal error (a bug, please report it): %s:%d: %s failed: %s\n", file, line,
               condition, message);
  std::fflush(stderr);
  std::abort();
}

}  // namespace sluice::detail

#if SLUICE_ENABLE_ASSERTS
#define SLUICE_ASSERT(condition, message) \
  ((condition) ? static_cast<void>(0) : ::sluice::detail::assertion_failed(#condition, __FILE__, __LINE__, message))
#else
#define SLUICE_ASSERT(condition, message) static_cast<void>(sizeof(!(condition)))  // unevaluated
#endif
