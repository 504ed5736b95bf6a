#pragma once
// Running the `sluice` program itself from a test: a temporary case folder, the program
// started without a shell in that folder, its exit status and captured output.
#include <fcntl.h>
#include <spawn.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

extern char** environ;

namespace sluice::test {

namespace fs = std::filesystem;

// A folder of its own for one case: `work` is the program's working directory, the
// captured output lies beside it so that it is not part of what the program left.
class CaseDir {
 public:
  CaseDir() {
    std::string tmpl = (fs::temp_directory_path() / "sluice_cli_XXXXXX").string();
    if (!mkdtemp(tmpl.data())) throw std::runtime_error("mkdtemp failed");
    base_ = tmpl;
    fs::create_directory(work());
  }
  ~CaseDir() {
    std::error_code ec;
    fs::remove_all(base_, ec);
  }
  CaseDir(const CaseDir&) = delete;
  CaseDir& operator=(const CaseDir&) = delete;
  fs::path work() const { return base_ / "work"; }
  fs::path base() const { return base_; }

 private:
  fs::path base_;
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

struct Result {
  int status = -1;  // exit status, or 128 + signal
  std::string out, err;
};

// Runs SLUICE_EXE with `args` in `dir.work()`, without a shell. OMP_NUM_THREADS=1: the
// cases are tiny, and test processes must not compete for the shared cores. `path`
// replaces PATH when not empty.
inline Result run_sluice(const CaseDir& dir, const std::vector<std::string>& args, const std::string& path = "") {
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
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addchdir_np(&actions, dir.work().c_str());
  posix_spawn_file_actions_addopen(&actions, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  Result r;
  if (rc != 0) {
    r.err = std::string("cannot start ") + SLUICE_EXE + ": " + std::strerror(rc);
    return r;
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) break;
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.out = read_text(out);
  r.err = read_text(err);
  return r;
}

}  // namespace sluice::test
