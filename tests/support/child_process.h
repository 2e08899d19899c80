// Child processes of the command-line tests: an executable started with its
// output in a log file, and its end as one exit code.
#pragma once
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <string>
#include <vector>

namespace wl::test {

// Starts `program ARGS...` with stdout and stderr to the file `log` (stderr to
// `stderr_fd` instead when ≥ 0); returns its pid.
inline pid_t spawn_logged(const std::string& program, std::vector<std::string> args, const std::string& log,
                          int stderr_fd = -1) {
  args.insert(args.begin(), program);
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {  // only async-signal-safe calls until exec
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, 1);
    ::dup2(stderr_fd >= 0 ? stderr_fd : fd, 2);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  return pid;
}

// The exit code of the child `pid` once it ends; 1000 + the signal when a signal ended it.
inline int wait_exit(pid_t pid) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : WIFSIGNALED(status) ? 1000 + WTERMSIG(status) : -1;
}

}  // namespace wl::test
