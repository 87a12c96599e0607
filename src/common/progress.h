#pragma once
// Progress and cancellation for long-running stages. The library never prints; the CLI implements a sink.
#include <string_view>

namespace quadcover {

/// Receives progress from a stage and can ask it to stop early (Ctrl-C, time limit).
/// Stages that honour cancelled() return their best result so far.
class ProgressSink {
 public:
  virtual ~ProgressSink() = default;
  /// `stage` names the pipeline stage, `fraction` is in [0,1] or negative when unknown, `message` is free text.
  virtual void report(std::string_view stage, double fraction, std::string_view message) = 0;
  virtual bool cancelled() const { return false; }
};

/// A sink that ignores everything; the default for library calls.
class NullProgress final : public ProgressSink {
 public:
  void report(std::string_view, double, std::string_view) override {}
};

inline NullProgress& null_progress() {
  static NullProgress sink;
  return sink;
}

}  // namespace quadcover
