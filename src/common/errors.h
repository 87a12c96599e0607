#pragma once
// Typed errors with a location. The CLI maps InputError/TopologyError to exit status 2 (bad input)
// and NumericalError / anything else to 1 (internal failure).
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace quadcover {

/// The input file cannot be read or parsed: names the file and, where known, the line.
class InputError : public std::runtime_error {
 public:
  /// \pre none
  InputError(std::string file, long line, const std::string& what)
      : std::runtime_error(format(file, line, what)), file_(std::move(file)), line_(line) {}
  const std::string& file() const { return file_; }  ///< \pre none
  long line() const { return line_; }  ///< 1-based, 0 when not tied to a line \pre none

 private:
  static std::string format(const std::string& file, long line, const std::string& what) {
    std::string s;
    s.append(file.empty() ? std::string_view("<input>") : std::string_view(file));
    if (line > 0) s.append(":").append(std::to_string(line));
    s.append(": ").append(what);
    return s;
  }
  std::string file_;
  long line_;
};

/// The density leaves too few quads in the map to extract a quad mesh (an InputError: the user's density is refused;
/// at the default density the job is made again finer, pipeline/retry_until_valid.h).
class DensityTooCoarse : public InputError {
 public:
  /// \pre none
  explicit DensityTooCoarse(const std::string& what) : InputError("density", 0, what) {}
};

/// The mesh is readable but is not a surface quadcover can work on (non-manifold, non-orientable, ...).
/// problems() holds one located message per defect.
class TopologyError : public std::runtime_error {
 public:
  /// \pre none
  TopologyError(const std::string& what, std::vector<std::string> problems = {})
      : std::runtime_error(what), problems_(std::move(problems)) {}
  const std::vector<std::string>& problems() const { return problems_; }  ///< \pre none

 private:
  std::vector<std::string> problems_;
};

/// A numerical stage failed (e.g. a factorization was not positive definite): names the stage.
class NumericalError : public std::runtime_error {
 public:
  /// \pre none
  NumericalError(std::string stage, const std::string& what)
      : std::runtime_error(stage + ": " + what), stage_(std::move(stage)) {}
  const std::string& stage() const { return stage_; }  ///< \pre none

 private:
  std::string stage_;
};

}  // namespace quadcover
