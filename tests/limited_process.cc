#include "tests/limited_process.h"

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <chrono>
#include <csignal>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace minenav::testing {

namespace {

// VmHWM of a running process in kB, -1 if it cannot be read.
int64_t ReadVmHwmKb(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("VmHWM:", 0) == 0) return std::strtoll(line.c_str() + 6, nullptr, 10);
  }
  return -1;
}

}  // namespace

LimitedProcess::LimitedProcess(const std::vector<std::string>& argv, const std::string& output_path,
                               uint64_t address_space_bytes)
    : output_path_(output_path) {
  if (argv.empty()) throw std::runtime_error("LimitedProcess: empty command");
  // Everything the child needs is prepared before fork: between fork and exec it only
  // makes async-signal-safe calls.
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const int out = ::open(output_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (out < 0) throw std::runtime_error("cannot create " + output_path + ": " + std::strerror(errno));
  struct rlimit limit {};
  limit.rlim_cur = address_space_bytes;
  limit.rlim_max = address_space_bytes;
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(out);
    throw std::runtime_error("fork failed: " + std::string(std::strerror(errno)));
  }
  if (pid == 0) {
    ::dup2(out, STDOUT_FILENO);
    ::dup2(out, STDERR_FILENO);
    if (address_space_bytes > 0 && ::setrlimit(RLIMIT_AS, &limit) != 0) ::_exit(126);
    ::execv(args[0], args.data());
    ::_exit(127);
  }
  ::close(out);
  pid_ = pid;
}

LimitedProcess::~LimitedProcess() {
  if (Running()) {
    ::kill(pid_, SIGKILL);
    Wait(5.0);
  }
}

void LimitedProcess::Signal(int signal) {
  if (!exit_code_) ::kill(pid_, signal);
}

std::optional<int> LimitedProcess::Wait(double timeout_s) {
  if (exit_code_) return exit_code_;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (true) {
    const int64_t hwm = ReadVmHwmKb(pid_);  // before reaping: the last value while alive
    if (hwm > peak_rss_kb_) peak_rss_kb_ = hwm;
    int status = 0;
    struct rusage usage {};
    const pid_t r = ::wait4(pid_, &status, WNOHANG, &usage);
    if (r == pid_) {
      exit_code_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      if (usage.ru_maxrss > peak_rss_kb_) peak_rss_kb_ = usage.ru_maxrss;
      return exit_code_;
    }
    if (r < 0 && errno != EINTR) {
      exit_code_ = -1;
      return exit_code_;
    }
    if (std::chrono::steady_clock::now() >= deadline) return std::nullopt;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

bool LimitedProcess::Running() { return pid_ > 0 && !Wait(0.0).has_value(); }

int64_t LimitedProcess::PeakRssKb() {
  Wait(0.0);  // samples VmHWM, or reaps a process that ended and takes its ru_maxrss
  return peak_rss_kb_;
}

double LimitedProcess::CpuSeconds() const {
  if (exit_code_) return -1.0;
  std::ifstream in("/proc/" + std::to_string(pid_) + "/stat");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t paren = text.rfind(')');
  if (paren == std::string::npos) return -1.0;
  std::istringstream fields(text.substr(paren + 1));
  std::string field;
  long long utime = -1, stime = -1;
  for (int i = 3; i <= 15 && fields >> field; ++i) {  // field 3 is the state
    if (i == 14) utime = std::atoll(field.c_str());
    if (i == 15) stime = std::atoll(field.c_str());
  }
  if (utime < 0 || stime < 0) return -1.0;
  return static_cast<double>(utime + stime) / static_cast<double>(::sysconf(_SC_CLK_TCK));
}

std::string LimitedProcess::OutputTail(size_t max_chars) const {
  std::ifstream in(output_path_);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  return text.size() <= max_chars ? text : "..." + text.substr(text.size() - max_chars);
}

ProcessResult RunLimited(const std::vector<std::string>& argv, const std::string& output_path, double timeout_s,
                         uint64_t address_space_bytes) {
  ProcessResult result;
  {
    LimitedProcess p(argv, output_path, address_space_bytes);
    result.exit_code = p.Wait(timeout_s);
    if (!result.exit_code) {
      p.Signal(SIGKILL);
      p.Wait(5.0);
    }
    result.peak_rss_kb = p.PeakRssKb();
  }
  std::ifstream in(output_path);
  std::stringstream ss;
  ss << in.rdbuf();
  result.output = ss.str();
  return result;
}

std::string DescribeExit(const std::optional<int>& exit_code) {
  if (!exit_code) return "still running at the timeout";
  const int c = *exit_code;
  if (c > 128) {
    const char* name = strsignal(c - 128);
    return "killed by signal " + std::to_string(c - 128) + " (" + (name ? name : "?") + ", exit " +
           std::to_string(c) + ")";
  }
  return "exit " + std::to_string(c);
}

}  // namespace minenav::testing
