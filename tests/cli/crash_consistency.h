#pragma once
// Crash consistency of a command that writes one output, a file or a folder of files
// (docs/hardening.md): the command is killed with SIGKILL at random moments, and after each kill
// its output path must hold the previous complete output byte for byte (nothing, when there was
// none) or the complete new output, never a partial one; for a folder, every file of it together
// (never some files new and some old or missing). What the killed command leaves beside it must
// carry the temporary name (".<output name>.tmp-XXXXXX...", common/posix_file.h) and, for a
// deterministic command, must not pass for a complete output unless it is one. Used for
// `vt build` (a file), `vt eval` results and `vt golden generate` sets (folders).

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "cli/run_command.h"
#include "test_support.h"

namespace vt::test {

struct CrashTarget {
  std::string program;
  std::vector<std::string> args;  // a command line that writes `output`
  std::filesystem::path output;
  // Whether a file passes for a complete output (for a texture: `vt info` accepts it).
  std::function<bool(const std::filesystem::path&)> accepts;
  // Whether the uninterrupted command writes the same bytes every time; if not, a complete new
  // output is recognised by `accepts` alone.
  bool deterministic = true;
  bool folder = false;  // the output is a folder of files
  // Files of a folder output whose bytes differ from run to run (run times): compared by
  // presence only; `accepts` must check that they belong with the rest.
  std::set<std::string> variableFiles;
};

struct CrashRun {
  double killedAfter = 0.0;  // seconds after the start
  bool finished = false;     // the command had exited before the kill
  std::string outcome;       // what the output path held afterwards
  size_t leftovers = 0;      // temporary files left beside it
};

struct CrashReport {
  double fullRunSeconds = 0.0;      // an uninterrupted run
  double writingFromSeconds = 0.0;  // when it created its first file
  std::vector<CrashRun> runs;
  std::vector<std::string> problems;  // empty when consistent
};

namespace crash {

// The output's bytes: a file's, or a folder's files (name, size, bytes each, by name), the
// bytes of `variable` files left out.
inline std::optional<std::vector<std::byte>> contents(const std::filesystem::path& path,
                                                      const std::set<std::string>& variable = {}) {
  if (!std::filesystem::exists(path)) return std::nullopt;
  if (!std::filesystem::is_directory(path)) return readBytes(path);
  std::map<std::string, std::vector<std::byte>> files;
  for (const auto& entry : std::filesystem::directory_iterator(path)) {
    const std::string name = entry.path().filename().string();
    files[name] = variable.contains(name) ? std::vector<std::byte>{} : readBytes(entry.path());
  }
  std::vector<std::byte> bytes;
  for (const auto& [name, data] : files) {
    const std::string header = name + '\0' + std::to_string(data.size()) + '\0';
    for (const char c : header) bytes.push_back(static_cast<std::byte>(c));
    bytes.insert(bytes.end(), data.begin(), data.end());
  }
  return bytes;
}

inline std::set<std::filesystem::path> filesIn(const std::filesystem::path& folder) {
  std::set<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) files.insert(entry.path());
  return files;
}

// Starts the command (output to `log`), kills it after `delay` unless it has exited; returns
// whether it had exited (and then its exit code). `watch` is called every 0.2 ms meanwhile.
inline std::pair<bool, int> runAndKill(const CrashTarget& target, std::chrono::microseconds delay,
                                       const std::filesystem::path& log,
                                       const std::function<void()>& watch = {}) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  std::vector<std::string> argv = {target.program};
  argv.insert(argv.end(), target.args.begin(), target.args.end());
  std::vector<char*> pointers;
  for (std::string& arg : argv) pointers.push_back(arg.data());
  pointers.push_back(nullptr);
  pid_t pid = 0;
  const int spawned =
      posix_spawn(&pid, target.program.c_str(), &actions, nullptr, pointers.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) return {true, -1};
  // Polls each 0.2 ms, so that a command that exits early is not waited for.
  const auto deadline = std::chrono::steady_clock::now() + delay;
  int status = 0;
  while (std::chrono::steady_clock::now() < deadline) {
    if (waitpid(pid, &status, WNOHANG) == pid)
      return {true, WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status)};
    if (watch) watch();
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  kill(pid, SIGKILL);
  waitpid(pid, &status, 0);
  // It may have exited between the check and the kill.
  if (WIFEXITED(status)) return {true, WEXITSTATUS(status)};
  return {false, 0};
}

// Puts `bytes` (from contents()) back at `output`, or removes it.
inline void restore(const std::filesystem::path& output,
                    const std::optional<std::vector<std::byte>>& bytes, bool folder) {
  std::filesystem::remove_all(output);
  if (!bytes) return;
  if (!folder) return writeBytes(output, *bytes);
  std::filesystem::create_directories(output);
  const auto field = [&](size_t& at) {
    std::string text;
    while (static_cast<char>((*bytes)[at]) != '\0') text += static_cast<char>((*bytes)[at++]);
    ++at;
    return text;
  };
  for (size_t at = 0; at < bytes->size();) {
    const std::string name = field(at);
    const size_t size = std::stoull(field(at));
    writeBytes(output / name,
               std::vector<std::byte>(bytes->begin() + static_cast<std::ptrdiff_t>(at),
                                      bytes->begin() + static_cast<std::ptrdiff_t>(at + size)));
    at += size;
  }
}

}  // namespace crash

// Runs the command once to completion (it must exit 0), then `kills` times killed after a
// random moment (std::mt19937 of `seed`): the even-numbered kills anywhere in that run's
// duration, the odd-numbered ones while it was writing (from the moment a new file appeared
// beside the output or a file of a folder output changed; process start-up can take much of a
// short run). The output path is
// restored to its state before each run. The output's folder must hold nothing else that changes
// meanwhile, and `scratch` (for the command's log) must be another folder.
inline CrashReport killAtRandomMoments(const CrashTarget& target, int kills, uint32_t seed,
                                       const std::filesystem::path& scratch) {
  using Clock = std::chrono::steady_clock;
  CrashReport report;
  const std::filesystem::path folder = target.output.parent_path(), log = scratch / "crash.log";
  const std::string temporaryPrefix = "." + target.output.filename().string() + ".tmp-";
  const std::optional<std::vector<std::byte>> saved = crash::contents(target.output),
                                              previous = crash::contents(target.output,
                                                                         target.variableFiles);
  const std::set<std::filesystem::path> before = crash::filesIn(folder);

  // What shows that the command writes: a new entry beside the output or, for a folder, a file
  // of the folder changed (a command that writes into the folder in place).
  const auto signature = [&] {
    std::vector<std::string> entries;
    for (const std::filesystem::path& file : crash::filesIn(folder)) entries.push_back(file);
    std::error_code error;
    if (target.folder)
      for (const auto& entry : std::filesystem::directory_iterator(target.output, error))
        entries.push_back(entry.path().string() + '@' +
                          std::to_string(entry.last_write_time(error).time_since_epoch().count()));
    return entries;
  };
  const std::vector<std::string> initial = signature();
  const auto start = Clock::now();
  std::optional<double> writingFrom;
  const auto [finished, exitCode] = crash::runAndKill(target, std::chrono::hours(1), log, [&] {
    if (!writingFrom && signature() != initial)
      writingFrom = std::chrono::duration<double>(Clock::now() - start).count();
  });
  report.fullRunSeconds = std::chrono::duration<double>(Clock::now() - start).count();
  report.writingFromSeconds = writingFrom.value_or(0.0);
  const std::optional<std::vector<std::byte>> complete =
      crash::contents(target.output, target.variableFiles);
  if (!finished || exitCode != 0 || !complete || !target.accepts(target.output)) {
    report.problems.push_back("the uninterrupted run failed (exit " + std::to_string(exitCode) +
                              "): " + slurp(log));
    return report;
  }
  crash::restore(target.output, saved, target.folder);

  std::mt19937 random(seed);
  std::uniform_real_distribution<double> anytime(0.0, report.fullRunSeconds),
      writing(report.writingFromSeconds, report.fullRunSeconds);
  for (int k = 0; k < kills; ++k) {
    CrashRun run;
    run.killedAfter = k % 2 == 0 ? anytime(random) : writing(random);
    const auto [exited, code] = crash::runAndKill(
        target, std::chrono::microseconds(static_cast<int64_t>(run.killedAfter * 1e6)), log);
    run.finished = exited;
    const std::string where =
        "kill " + std::to_string(k) + " after " + std::to_string(run.killedAfter) + " s: ";
    if (exited && code != 0)
      report.problems.push_back(where + "the command failed (exit " + std::to_string(code) + ")");

    // The output path: the previous file, or the complete new one.
    const std::optional<std::vector<std::byte>> now =
        crash::contents(target.output, target.variableFiles);
    if (now == previous) {
      run.outcome = previous ? "previous file" : "no file";
    } else if (now && (target.deterministic ? now == complete : target.accepts(target.output))) {
      run.outcome = "complete new file";
    } else {
      run.outcome = now ? "partial file" : "no file";
      report.problems.push_back(
          where + (now ? "the output holds " + std::to_string(now->size()) +
                             " bytes that are neither the previous nor the complete file" +
                             (target.accepts(target.output) ? ", and they pass for complete" : "")
                       : std::string("the previous file is gone")));
    }

    // Everything else the run left beside the output.
    for (const std::filesystem::path& file : crash::filesIn(folder)) {
      if (before.contains(file) || file == target.output) continue;
      ++run.leftovers;
      const std::string name = file.filename().string();
      if (!name.starts_with(temporaryPrefix))
        report.problems.push_back(where + "left " + name + ", not named as a temporary file");
      // A complete output may be left: the new one killed before its rename, or a folder's
      // previous one, exchanged out of place and killed while being removed. (A command whose
      // output differs from run to run may leave either; `accepts` alone must tell complete from
      // partial.)
      const std::optional<std::vector<std::byte>> left =
          crash::contents(file, target.variableFiles);
      if (target.deterministic && target.accepts(file) && left != complete && left != previous)
        report.problems.push_back(where + "left " + name + ", which passes for a complete output");
      std::filesystem::remove_all(file);
    }
    crash::restore(target.output, saved, target.folder);
    report.runs.push_back(run);
  }
  return report;
}

}  // namespace vt::test
