#include "fleet/child_launcher.h"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include "common/file_io.h"

extern char** environ;

namespace minenav {

namespace {

bool IsExecutableFile(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(path.c_str(), X_OK) == 0;
}

// The environment of the child: the supervisor's, less systemd's notify variables (they are
// the supervisor's own), with the request's added.
std::vector<std::string> ChildEnvironment(const std::map<std::string, std::string>& extra) {
  std::vector<std::string> env;
  for (char** e = environ; *e != nullptr; ++e) {
    const std::string entry = *e;
    const std::string name = entry.substr(0, entry.find('='));
    if (name == "NOTIFY_SOCKET" || name == "WATCHDOG_USEC" || name == "WATCHDOG_PID" || extra.count(name) > 0) continue;
    env.push_back(entry);
  }
  for (const auto& [name, value] : extra) env.push_back(name + "=" + value);
  return env;
}

std::vector<char*> Pointers(std::vector<std::string>& strings) {
  std::vector<char*> out;
  for (std::string& s : strings) out.push_back(s.data());
  out.push_back(nullptr);
  return out;
}

// Between fork and exec only async-signal-safe calls: everything is prepared before.
[[noreturn]] void ExecChild(pid_t parent, int null_fd, int log_fd, bool stdout_to_log, int max_fd, const char* path,
                            char* const* argv, char* const* envp) {
  ::setpgid(0, 0);
  ::prctl(PR_SET_PDEATHSIG, SIGTERM);
  if (::getppid() != parent) ::_exit(128 + SIGTERM);  // the supervisor died before prctl
  sigset_t none;
  sigemptyset(&none);
  ::sigprocmask(SIG_SETMASK, &none, nullptr);
  ::dup2(null_fd, STDIN_FILENO);
  ::dup2(log_fd, STDERR_FILENO);
  if (stdout_to_log) ::dup2(log_fd, STDOUT_FILENO);
  // Nothing else of the supervisor's: liblcm opens its sockets without close-on-exec, and every
  // child would keep the supervisor's bus socket (and its multicast membership) open for life.
  if (::close_range(3, ~0U, 0) != 0)
    for (int fd = 3; fd < max_fd; ++fd) ::close(fd);  // a kernel before 5.9
  ::execve(path, argv, envp);
  static const char kFailed[] = "fleet: exec failed: ";
  const char* why = std::strerror(errno);
  ssize_t ignored = ::write(STDERR_FILENO, kFailed, sizeof(kFailed) - 1);
  ignored = ::write(STDERR_FILENO, why, std::strlen(why));
  ignored = ::write(STDERR_FILENO, "\n", 1);
  (void)ignored;
  ::_exit(127);
}

}  // namespace

std::string ResolveProgram(const std::string& program, const std::string& where) {
  if (program.find('/') != std::string::npos) {
    if (!IsExecutableFile(program))
      throw InputError(where + ": " + program + (::access(program.c_str(), F_OK) == 0 ? " is not executable" : " not found"));
    return program;
  }
  const char* path_env = std::getenv("PATH");
  std::istringstream dirs(path_env != nullptr ? path_env : "/usr/local/bin:/usr/bin:/bin");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const std::string candidate = (dir.empty() ? "." : dir) + "/" + program;
    if (IsExecutableFile(candidate)) return candidate;
  }
  throw InputError(where + ": " + program + " not found on $PATH");
}

pid_t LaunchProcess(const LaunchRequest& request) {
  if (request.argv.empty()) throw std::runtime_error("no program to start");
  const int log_fd = ::open(request.log_path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (log_fd < 0) throw std::runtime_error("cannot open " + request.log_path + ": " + std::strerror(errno));
  const int null_fd = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
  std::vector<std::string> argv_strings = request.argv;
  std::vector<std::string> env_strings = ChildEnvironment(request.env);
  const std::vector<char*> argv = Pointers(argv_strings);
  const std::vector<char*> envp = Pointers(env_strings);
  const pid_t parent = ::getpid();
  const long open_max = ::sysconf(_SC_OPEN_MAX);
  const int max_fd = open_max > 0 && open_max < 65536 ? static_cast<int>(open_max) : 65536;
  const pid_t pid = ::fork();
  if (pid == 0)
    ExecChild(parent, null_fd, log_fd, request.stdout_to_log, max_fd, argv[0], argv.data(), envp.data());
  const int fork_errno = errno;
  ::close(log_fd);
  if (null_fd >= 0) ::close(null_fd);
  if (pid < 0) throw std::runtime_error(std::string("fork failed: ") + std::strerror(fork_errno));
  // Also from here: a signal sent before the child ran its own setpgid reaches the group.
  ::setpgid(pid, pid);
  return pid;
}

void SignalProcessGroup(pid_t pid, int signal) {
  if (pid > 0) ::kill(-pid, signal);
}

std::optional<ExitStatus> PollExit(pid_t pid) {
  int status = 0;
  pid_t r;
  do {
    r = ::waitpid(pid, &status, WNOHANG);
  } while (r < 0 && errno == EINTR);
  if (r == 0) return std::nullopt;
  if (r < 0) return ExitStatus{127, 0};  // not our child any more: treat as gone
  if (WIFSIGNALED(status)) return ExitStatus{0, WTERMSIG(status)};
  return ExitStatus{WEXITSTATUS(status), 0};
}

}  // namespace minenav
