#pragma once
// Progress and cancellation for long-running stages. The library never prints; the CLI implements a sink.
#include <limits>
#include <mutex>
#include <string_view>

namespace quadcover {

/// Receives progress from a stage and can ask it to stop early (Ctrl-C, time limit).
/// Stages that honour cancelled() return their best result so far.
class ProgressSink {
 public:
  virtual ~ProgressSink() = default;
  /// `stage` names the pipeline stage, `fraction` is in [0,1] or negative when unknown, `message` is free text.
  /// \pre none
  virtual void report(std::string_view stage, double fraction, std::string_view message) = 0;
  virtual bool cancelled() const { return false; }  ///< \pre none
  /// True once the stages that only improve a valid result (relaxation, period-rounding search, keep-better,
  /// density re-solves, cone merging, fold refinement, quad smoothing) should be skipped or end early: after a
  /// Ctrl-C or past a time limit. Those stages test this, the stages a valid result needs test cancelled().
  virtual bool skip_improvements() const { return cancelled(); }  ///< \pre none
  /// Seconds until a time limit makes cancelled() true (infinity without one): lets a job leave its later, not
  /// interruptible stages their time. \pre none
  virtual double seconds_left() const;
};

/// Forwards reports to `inner` but never cancels: for the stages that make a result valid, which run to the end
/// even after a Ctrl-C or a time limit stopped the optimization (a second Ctrl-C still ends the process). The
/// improving stages still stop then (skip_improvements() is inner's cancelled()).
class FinishingProgress final : public ProgressSink {
 public:
  explicit FinishingProgress(ProgressSink& inner) : inner_(inner) {}  ///< \pre inner outlives this sink.
  void report(std::string_view stage, double fraction, std::string_view message) override {
    inner_.report(stage, fraction, message);
  }
  bool skip_improvements() const override { return inner_.cancelled(); }

 private:
  ProgressSink& inner_;
};

/// Forwards everything to `inner` one call at a time: for two stages that run at once and share a sink.
class SerializedProgress final : public ProgressSink {
 public:
  explicit SerializedProgress(ProgressSink& inner) : inner_(inner) {}  ///< \pre inner outlives this sink.
  void report(std::string_view stage, double fraction, std::string_view message) override {
    const std::lock_guard lock(mutex_);
    inner_.report(stage, fraction, message);
  }
  bool cancelled() const override {
    const std::lock_guard lock(mutex_);
    return inner_.cancelled();
  }
  bool skip_improvements() const override {
    const std::lock_guard lock(mutex_);
    return inner_.skip_improvements();
  }
  double seconds_left() const override {
    const std::lock_guard lock(mutex_);
    return inner_.seconds_left();
  }

 private:
  ProgressSink& inner_;
  mutable std::mutex mutex_;
};

/// A sink that ignores everything; the default for library calls.
class NullProgress final : public ProgressSink {
 public:
  void report(std::string_view, double, std::string_view) override {}
};

inline double ProgressSink::seconds_left() const { return std::numeric_limits<double>::infinity(); }

/// \pre none
inline NullProgress& null_progress() {
  static NullProgress sink;
  return sink;
}

}  // namespace quadcover
