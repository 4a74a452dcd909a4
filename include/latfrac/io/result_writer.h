// Writing a run's results as it goes: the result file and its .xmf from the start, again
// at every checkpoint, and complete at the end (docs/restart.md).
//
// Every write replaces the whole file: it is written under a temporary name, synced and
// renamed into place, so a reader (or a resume) only ever sees a whole file, the last
// checkpoint's until the next one is in place. The writer holds a lock on
// "<result>.lock" for its lifetime, so that two runs cannot write one result file.
#pragma once

#include <chrono>
#include <string>
#include <vector>

#include "latfrac/fracture/run_control.h"

namespace latfrac {

class ResultWriter final : public RunControl {
 public:
  // At its first write, creates the output directory and locks the result file (Error
  // naming it when another run holds it). A checkpoint is
  // due every `checkpoint_minutes` (0: only when stopping), and never sooner than 20
  // times the last write took, which keeps writing under 5 % of the run's time.
  ResultWriter(std::string h5_path, std::string xmf_path, double checkpoint_minutes,
               std::string problem_path, std::vector<std::string> overrides,
               double wall_seconds_before = 0);
  ~ResultWriter() override;
  ResultWriter(const ResultWriter&) = delete;
  ResultWriter& operator=(const ResultWriter&) = delete;

  bool stop_requested() const override;
  bool checkpoint_due() override;
  void save(RunResult& result, RunCheckpoint& checkpoint) override;
  // The complete result (summary.complete true), with no checkpoint.
  void finish(const RunResult& result);

  int writes() const { return writes_; }
  double write_seconds() const { return write_seconds_; }

 private:
  void open();
  void write(const RunResult& result, const RunCheckpoint* checkpoint);

  std::string h5_path_, xmf_path_, lock_path_;
  int lock_descriptor_ = -1;
  double interval_seconds_;
  std::string problem_path_;
  std::vector<std::string> overrides_;
  double wall_before_;
  std::chrono::steady_clock::time_point started_, last_write_;
  double last_write_seconds_ = 0;
  double write_seconds_ = 0;
  int writes_ = 0;
};

}  // namespace latfrac
