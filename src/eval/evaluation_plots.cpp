#include "eval/evaluation_plots.h"

#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "eval/evaluation_plots_source.h"

extern char** environ;

namespace vt {
namespace {

// scripts/evaluation-plots.py exits with this status, one line on stderr, when matplotlib or
// numpy cannot be imported.
constexpr int kMissingMatplotlib = 3;

// Closes a descriptor once; -1 means none.
struct Descriptor {
  int fd = -1;
  Descriptor() = default;
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  ~Descriptor() { reset(); }
  void reset() {
    if (fd >= 0) ::close(fd);
    fd = -1;
  }
};

void makePipe(Descriptor& read, Descriptor& write) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0)
    throw std::runtime_error(std::string("plots: cannot make a pipe: ") + std::strerror(errno));
  read.fd = fds[0];
  write.fd = fds[1];
}

// Writes the whole text; false when the reader has gone (the interpreter exited early). SIGPIPE
// is blocked in this thread meanwhile, and a pending one taken back, so that an early exit shows as
// EPIPE here rather than killing vt.
bool writeAll(int fd, std::string_view text) {
  sigset_t pipeSignal, previous;
  sigemptyset(&pipeSignal);
  sigaddset(&pipeSignal, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &pipeSignal, &previous);
  bool complete = true;
  while (!text.empty()) {
    const ssize_t n = ::write(fd, text.data(), text.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      complete = false;
      break;
    }
    text.remove_prefix(static_cast<size_t>(n));
  }
  if (!complete) {
    const timespec now{};
    while (::sigtimedwait(&pipeSignal, nullptr, &now) == SIGPIPE) {
    }
  }
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
  return complete;
}

std::string readAll(int fd) {
  std::string text;
  char buffer[4096];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    text.append(buffer, static_cast<size_t>(n));
  }
  return text;
}

// The last non-empty line of a process's output (a Python traceback ends with the error).
std::string lastLine(const std::string& text) {
  const size_t end = text.find_last_not_of(" \n\r\t");
  if (end == std::string::npos) return "no message";
  const size_t newline = text.rfind('\n', end);
  const size_t begin = newline == std::string::npos ? 0 : newline + 1;
  return text.substr(begin, end + 1 - begin);
}

// The file `name` runs: itself when it holds a '/', else the first executable of that name on
// $PATH; empty when there is none. Resolved before fork, so that the child only calls execv.
std::string executablePath(const std::string& name) {
  if (name.find('/') != std::string::npos) return ::access(name.c_str(), X_OK) == 0 ? name : "";
  const char* path = std::getenv("PATH");
  std::string_view folders = path ? path : "/usr/bin:/bin";
  while (!folders.empty()) {
    const size_t colon = folders.find(':');
    const std::string_view folder = folders.substr(0, colon);
    const std::string candidate = (folder.empty() ? std::string(".") : std::string(folder)) + "/" +
                                  name;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
    if (colon == std::string_view::npos) break;
    folders.remove_prefix(colon + 1);
  }
  return "";
}

}  // namespace

std::string plotInterpreter() {
  if (const char* chosen = std::getenv("VT_PYTHON"); chosen && *chosen) return chosen;
  if (::access("/usr/bin/python3", X_OK) == 0) return "/usr/bin/python3";
  return "python3";
}

void drawEvaluationPlots(const std::filesystem::path& folder,
                         const std::filesystem::path& shownAs) {
  const std::string python = plotInterpreter();
  const std::string where = "plots of " + shownAs.string() + ": ";
  Descriptor inRead, inWrite, outRead, outWrite;
  makePipe(inRead, inWrite);
  makePipe(outRead, outWrite);
  std::vector<std::string> argv = {python, "-", folder.string()};
  std::vector<char*> pointers;
  for (std::string& arg : argv) pointers.push_back(arg.data());
  pointers.push_back(nullptr);
  const std::string program = executablePath(python);
  if (program.empty())
    throw std::runtime_error(where + "cannot run " + python +
                             " (not found); the plots need python3 with matplotlib "
                             "(python3-matplotlib)");
  // fork and exec rather than posix_spawn: the child asks to be killed when vt dies, so an
  // interrupted evaluation leaves no interpreter writing into its staging folder. Between fork and
  // exec only system calls run.
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0)
    throw std::runtime_error(where + "cannot start " + python + ": " + std::strerror(errno));
  if (pid == 0) {
    if (::prctl(PR_SET_PDEATHSIG, SIGKILL) != 0 || ::getppid() != parent) ::_exit(126);
    if (::dup2(inRead.fd, 0) < 0 || ::dup2(outWrite.fd, 1) < 0 || ::dup2(outWrite.fd, 2) < 0)
      ::_exit(126);
    ::execv(program.c_str(), pointers.data());
    ::_exit(127);
  }
  inRead.reset();
  outWrite.reset();
  writeAll(inWrite.fd, kEvaluationPlotsSource);
  inWrite.reset();
  const std::string output = readAll(outRead.fd);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return;
  if (WIFEXITED(status) && WEXITSTATUS(status) == kMissingMatplotlib)
    throw std::runtime_error(where + lastLine(output));
  if (WIFEXITED(status) && WEXITSTATUS(status) == 127)
    throw std::runtime_error(where + python + " not found; the plots need python3 with matplotlib");
  throw std::runtime_error(where + "scripts/evaluation-plots.py failed under " + python + " (" +
                           (WIFEXITED(status) ? "exit " + std::to_string(WEXITSTATUS(status))
                                              : "signal " + std::to_string(WTERMSIG(status))) +
                           "): " + lastLine(output));
}

}  // namespace vt
