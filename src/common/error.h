#pragma once
// Errors that reach the user: every one names the file (or argument) and what was wrong, and the
// command line prints it as one line. Thrown for bad input; never used for programming errors.

#include <filesystem>
#include <stdexcept>
#include <string>

namespace vt {

class InputError : public std::runtime_error {
 public:
  // "<file>: <problem>", e.g. "scene.vt: header field page_size: 0 is not a power of two".
  InputError(const std::filesystem::path& file, const std::string& problem)
      : std::runtime_error(file.string() + ": " + problem), file_(file) {}

  const std::filesystem::path& file() const { return file_; }

 private:
  std::filesystem::path file_;
};

}  // namespace vt
