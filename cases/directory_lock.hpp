// One process at a time per run directory: `hydrojump sph DIR`, `hydrojump vof DIR` and `hydrojump
// study --out DIR` hold an advisory lock on DIR/.hydrojump.lock while they run, so a second process
// started on the same directory (a second terminal, a study and a hand-started run) stops at once with
// a message naming the holder, instead of both writing checkpoints and outputs into one directory.
//
// The lock is flock(2) on an open file: the kernel releases it when the holder exits, however it exits
// (SIGKILL, power loss of the process), so there is no stale lock to delete by hand. Child processes do
// not inherit it (close-on-exec), except one started with the lock's descriptor() among its
// ChildCommand::inherited_descriptors (the OpenFOAM solver), which then holds it until it ends too.
// The file keeps the holder's pid and command for the message. On a
// file system without flock support the run goes on unprotected, with a warning.
//
// Usage
//   const DirectoryLock lock(run_dir, "hydrojump sph");   // throws DirectoryBusy if held
//   ... run; the lock is released when `lock` goes out of scope ...
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

namespace hydrojump::cases {

// Thrown when another process holds the directory's lock.
class DirectoryBusy : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class DirectoryLock {
 public:
  // Locks `dir` (created if missing) for `holder` (what the message shows to a second process).
  // Throws DirectoryBusy naming the directory and the holder when it is held, std::runtime_error when
  // the lock file cannot be created.
  DirectoryLock(const std::filesystem::path& dir, const std::string& holder);
  ~DirectoryLock();
  DirectoryLock(const DirectoryLock&) = delete;
  DirectoryLock& operator=(const DirectoryLock&) = delete;

  static constexpr const char* file_name = ".hydrojump.lock";

  // The lock's descriptor (-1 on a file system without flock), for a child that must hold the lock as
  // long as it runs, also when this process dies first (ChildCommand::inherited_descriptors).
  int descriptor() const { return fd_; }

 private:
  int fd_ = -1;
};

}  // namespace hydrojump::cases
