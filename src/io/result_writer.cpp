// Writing a run's results as it goes, with checkpoints, under a lock.
#include "latfrac/io/result_writer.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "latfrac/base/atomic_write.h"
#include "latfrac/base/error.h"
#include "latfrac/base/stop_signal.h"
#include "latfrac/io/result_file.h"
#include "latfrac/io/xdmf.h"

namespace latfrac {
namespace {

double seconds_between(std::chrono::steady_clock::time_point from,
                       std::chrono::steady_clock::time_point to) {
  return std::chrono::duration<double>(to - from).count();
}

std::string holder_of(int descriptor) {
  char text[32] = {};
  const ssize_t length = ::pread(descriptor, text, sizeof text - 1, 0);
  return length > 0 ? " (process " + std::string(text, static_cast<std::size_t>(length)) + ")" : "";
}

}  // namespace

ResultWriter::ResultWriter(std::string h5_path, std::string xmf_path, double checkpoint_minutes,
                           std::string problem_path, std::vector<std::string> overrides,
                           double wall_seconds_before)
    : h5_path_(std::move(h5_path)),
      xmf_path_(std::move(xmf_path)),
      lock_path_(h5_path_ + ".lock"),
      interval_seconds_(60 * checkpoint_minutes),
      problem_path_(std::move(problem_path)),
      overrides_(std::move(overrides)),
      wall_before_(wall_seconds_before),
      started_(std::chrono::steady_clock::now()),
      last_write_(started_) {}

// The output directory and the lock, at the first write: a run refused before it writes
// leaves nothing behind.
void ResultWriter::open() {
  make_directory(std::filesystem::path(h5_path_).parent_path());
  const int descriptor = ::open(lock_path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (descriptor < 0) {
    throw Error("cannot write results to '" + h5_path_ + "': cannot create '" + lock_path_ +
                "': " + std::strerror(errno));
  }
  if (::flock(descriptor, LOCK_EX | LOCK_NB) != 0) {
    const std::string holder = holder_of(descriptor);
    ::close(descriptor);
    throw Error("'" + h5_path_ + "' is being written by another latfrac run" + holder +
                "; wait for it to end, or write elsewhere (-o)");
  }
  lock_descriptor_ = descriptor;
  const std::string pid = std::to_string(::getpid());
  if (::ftruncate(lock_descriptor_, 0) == 0 &&
      ::pwrite(lock_descriptor_, pid.data(), pid.size(), 0) < 0) {
    // The process id is only for the message another run gives; the lock holds without it.
  }
}

ResultWriter::~ResultWriter() {
  if (lock_descriptor_ < 0) return;
  ::unlink(lock_path_.c_str());
  ::close(lock_descriptor_);
}

bool ResultWriter::stop_requested() const { return latfrac::stop_requested(); }

bool ResultWriter::checkpoint_due() {
  if (interval_seconds_ <= 0) return false;
  const double since = seconds_between(last_write_, std::chrono::steady_clock::now());
  return since >= std::max(interval_seconds_, 20 * last_write_seconds_);
}

void ResultWriter::write(const RunResult& result, const RunCheckpoint* checkpoint) {
  if (lock_descriptor_ < 0) open();
  const auto begin = std::chrono::steady_clock::now();
  try {
    write_result_file(h5_path_, result, checkpoint);
    write_xdmf(xmf_path_, std::filesystem::path(h5_path_).filename().string(), result);
  } catch (const Error& error) {
    throw Error(std::string(error.what()) +
                (writes_ > 0 ? "; the last checkpoint written is intact in '" + h5_path_ +
                                   "' (latfrac run --resume " + h5_path_ + ")"
                             : ""));
  }
  last_write_ = std::chrono::steady_clock::now();
  last_write_seconds_ = seconds_between(begin, last_write_);
  write_seconds_ += last_write_seconds_;
  ++writes_;
}

void ResultWriter::save(RunResult& result, RunCheckpoint& checkpoint) {
  checkpoint.problem_path = problem_path_;
  checkpoint.overrides = overrides_;
  result.summary.complete = false;
  result.summary.wall_seconds =
      wall_before_ + seconds_between(started_, std::chrono::steady_clock::now());
  write(result, &checkpoint);
}

void ResultWriter::finish(const RunResult& result) { write(result, nullptr); }

}  // namespace latfrac
