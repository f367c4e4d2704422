#include "ramap/util/staged_output.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <set>
#include <system_error>
#include <thread>

#include "ramap/util/error.h"

namespace ramap {
namespace fs = std::filesystem;

namespace {

// What a staged name adds to its final path, before the process id and a counter.
constexpr const char* kStagingSuffix = ".ramap-tmp-";

std::string MakeStagingName(const std::string& final_path) {
  static std::atomic<int> counter{0};
  fs::path path(final_path);
  // Strip a trailing separator so that "out/" stages as "out.ramap-tmp-..." beside it.
  if (!path.has_filename()) path = path.parent_path();
  return path.string() + kStagingSuffix + std::to_string(::getpid()) + "-" +
         std::to_string(counter++);
}

// Every path this process has staged or created and not yet committed, so that an interrupted run
// can remove them. The mutex also orders a Commit against the interrupt's clean-up.
struct LiveOutputs {
  std::mutex mutex;
  std::set<std::string> paths;
};

LiveOutputs& Live() {
  static LiveOutputs* live =
      new LiveOutputs;  // never destroyed: the signal thread may outlive main
  return *live;
}

void Track(const std::string& path) {
  std::lock_guard<std::mutex> lock(Live().mutex);
  Live().paths.insert(path);
}

void Untrack(const std::string& path) {
  std::lock_guard<std::mutex> lock(Live().mutex);
  Live().paths.erase(path);
}

void RemoveQuietly(const std::string& path) {
  std::error_code ec;
  fs::remove_all(path, ec);
}

}  // namespace

StagedPath::StagedPath(std::string final_path)
    : final_path_(std::move(final_path)), staging_path_(MakeStagingName(final_path_)) {
  RemoveQuietly(staging_path_);
  Track(staging_path_);
}

StagedPath::~StagedPath() {
  if (committed_) return;
  RemoveQuietly(staging_path_);
  Untrack(staging_path_);
}

void StagedPath::Commit() {
  std::lock_guard<std::mutex> lock(Live().mutex);
  std::error_code ec;
  fs::path target(final_path_);
  if (!target.has_filename()) target = target.parent_path();
  const fs::file_status existing = fs::symlink_status(target, ec);
  if (fs::is_directory(existing)) {
    // Never replace a folder: only an empty one (made by a concurrent run, say) may go.
    if (!fs::is_empty(target, ec) || !fs::remove(target, ec)) {
      throw InputError(final_path_,
                       "is a folder that is not empty; ramap does not replace a folder with its "
                       "output (choose another path)");
    }
  } else if (fs::exists(existing) && fs::is_directory(staging_path_, ec)) {
    throw InputError(final_path_, "exists and is not a folder");
  }
  // rename() replaces a file atomically; a reader sees the old file or the new one, never half.
  fs::rename(staging_path_, target, ec);
  if (ec)
    throw InputError(final_path_, "cannot move the finished output into place: " + ec.message());
  Live().paths.erase(staging_path_);
  committed_ = true;
}

CreatedOutput::CreatedOutput(std::string path) : path_(std::move(path)) {
  std::error_code ec;
  created_ = !fs::exists(fs::symlink_status(path_, ec));
  if (created_) Track(path_);
}

CreatedOutput::~CreatedOutput() {
  if (!created_ || kept_) return;
  RemoveQuietly(path_);
  Untrack(path_);
}

void CreatedOutput::Keep() {
  if (created_) Untrack(path_);
  kept_ = true;
}

void RemoveLiveOutputs() {
  std::lock_guard<std::mutex> lock(Live().mutex);
  for (const std::string& path : Live().paths) RemoveQuietly(path);
  Live().paths.clear();
}

namespace {

// The write end of the pipe through which the signal handler wakes the cleanup thread.
int interrupt_pipe_write = -1;

// Runs in whichever thread the signal reaches (libraries such as OpenBLAS start threads before
// main, with no signal blocked), so it only does what is async-signal-safe: pass the signal on.
void ForwardInterrupt(int signal) {
  const unsigned char number = static_cast<unsigned char>(signal);
  (void)!::write(interrupt_pipe_write, &number, 1);
}

}  // namespace

std::string FinalPathOf(const std::string& path) {
  return path.substr(0, path.find(kStagingSuffix));
}

void InstallInterruptCleanup() {
  // The cleanup runs as ordinary code in a thread of its own (removing folders is not safe in a
  // signal handler), woken through a pipe by the handler.
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) return;  // not inherited by the programs ramap runs
  interrupt_pipe_write = fds[1];
  const int read_end = fds[0];
  std::thread([read_end]() {
    unsigned char signal = 0;
    for (;;) {
      const ssize_t read = ::read(read_end, &signal, 1);
      if (read == 1) break;
      if (read == 0 || errno != EINTR) return;  // the pipe is gone: no cleanup to wait for
    }
    RemoveLiveOutputs();
    const char message[] = "ramap: interrupted; unfinished outputs removed\n";
    (void)!::write(STDERR_FILENO, message, sizeof(message) - 1);
    ::_exit(128 + signal);
  }).detach();
  struct sigaction action {};
  action.sa_handler = ForwardInterrupt;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  for (const int signal : {SIGINT, SIGTERM, SIGHUP}) sigaction(signal, &action, nullptr);
}

void WriteFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write,
                         bool binary) {
  StagedPath staged(path);
  {
    std::ofstream file(staged.path(), binary ? std::ios::binary | std::ios::out : std::ios::out);
    if (!file) throw InputError(path, "cannot open for writing");
    write(file);
    file.flush();
    if (!file) throw InputError(path, "write failed (disk full?)");
  }
  staged.Commit();
}

}  // namespace ramap
