#pragma once
// Running the `sluice` program itself from a test: a temporary case folder, the program
// started without a shell in that folder, its exit status and captured output.
#include <fcntl.h>
#include <spawn.h>
#include <stdlib.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "temp_dir.h"

extern char** environ;

namespace sluice::test {

namespace fs = std::filesystem;

// A folder of its own for one case (a TempDir): `work` is the program's working
// directory, the captured output lies beside it so that it is not part of what the
// program left.
class CaseDir {
 public:
  CaseDir() { fs::create_directory(work()); }
  fs::path work() const { return dir_.path() / "work"; }
  fs::path base() const { return dir_.path(); }

 private:
  TempDir dir_;
};

inline std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline void write_text(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
}

// A scene of 36 particles in a closed box, 0.1 s at 20 frames/s: a program run that
// takes milliseconds.
inline constexpr const char* kTinyScene =
    R"({"name": "tiny", "spacing": 0.05, "time": {"duration": 0.1, "fps": 20, "dt": 0.005},
  "fluid": [{"shape": "rectangle", "min": [0, 0], "max": [0.3, 0.3]}],
  "boundaries": [{"shape": "box", "min": [0, 0], "max": [0.5, 0.5]}]})";

struct Result {
  int status = -1;  // exit status, or 128 + signal
  std::string out, err;
};

// Resource limits of the child: RLIMIT_FSIZE makes a write past `file_size` bytes fail
// with EFBIG (SIGXFSZ ignored), which is how a full disk looks to the program without
// mounting anything; RLIMIT_AS caps its memory.
struct Limits {
  rlim_t file_size = RLIM_INFINITY;
  rlim_t address_space = RLIM_INFINITY;
};

// Starts SLUICE_EXE with `args` in `dir.work()`, without a shell; stdout and stderr go to
// files beside it. OMP_NUM_THREADS=1: the cases are tiny, and test processes must not
// compete for the shared cores. `path` replaces PATH when not empty. Returns the pid
// (-1 when it cannot be started).
inline pid_t start_sluice(const CaseDir& dir, const std::vector<std::string>& args, const std::string& path = "",
                          const Limits& limits = {}) {
  std::vector<std::string> argv_s = {SLUICE_EXE};
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);

  std::vector<std::string> env_s;
  for (char** e = environ; *e; ++e) {
    const std::string var = *e;
    if (var.starts_with("OMP_NUM_THREADS=") || (!path.empty() && var.starts_with("PATH="))) continue;
    env_s.push_back(var);
  }
  env_s.push_back("OMP_NUM_THREADS=1");
  if (!path.empty()) env_s.push_back("PATH=" + path);
  std::vector<char*> envp;
  for (std::string& e : env_s) envp.push_back(e.data());
  envp.push_back(nullptr);

  const std::string out = (dir.base() / "stdout").string(), err = (dir.base() / "stderr").string();
  const std::string work = dir.work().string();
  const pid_t pid = fork();
  if (pid != 0) return pid;
  // The child: only async-signal-safe calls until exec.
  const int fd1 = open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  const int fd2 = open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd1 < 0 || fd2 < 0 || dup2(fd1, 1) < 0 || dup2(fd2, 2) < 0 || chdir(work.c_str()) != 0) _exit(127);
  signal(SIGXFSZ, SIG_IGN);
  const rlimit fsize{limits.file_size, limits.file_size}, as{limits.address_space, limits.address_space};
  if (limits.file_size != RLIM_INFINITY) setrlimit(RLIMIT_FSIZE, &fsize);
  if (limits.address_space != RLIM_INFINITY) setrlimit(RLIMIT_AS, &as);
  execve(argv[0], argv.data(), envp.data());
  _exit(127);
}

// Waits for the program started by start_sluice and collects what it printed.
inline Result wait_sluice(const CaseDir& dir, pid_t pid) {
  Result r;
  if (pid < 0) {
    r.err = std::string("cannot start ") + SLUICE_EXE + ": " + std::strerror(errno);
    return r;
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) break;
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.out = read_text(dir.base() / "stdout");
  r.err = read_text(dir.base() / "stderr");
  return r;
}

// Runs SLUICE_EXE with `args` in `dir.work()` to its end (start_sluice, wait_sluice).
inline Result run_sluice(const CaseDir& dir, const std::vector<std::string>& args, const std::string& path = "",
                         const Limits& limits = {}) {
  return wait_sluice(dir, start_sluice(dir, args, path, limits));
}

}  // namespace sluice::test
