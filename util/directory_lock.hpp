// One process at a time per run directory: `hydrojump sph DIR`, `hydrojump vof DIR` and `hydrojump
// study --out DIR` hold an advisory lock on DIR/.hydrojump.lock while they run, so a second process
// started on the same directory (a second terminal, a study and a hand-started run) stops at once with
// a message naming the holder, instead of both writing checkpoints and outputs into one directory.
//
// The lock is flock(2) on an open file: the kernel releases it when the holder exits, however it exits
// (SIGKILL, power loss of the process), so there is no stale lock to delete by hand. Child processes do
// not inherit it (close-on-exec), except one started with the lock's descriptor() among its
// ChildCommand::inherited_descriptors (the OpenFOAM solver), which then holds it until it ends too.
// The file keeps the holder's pid and command for the message, and a note on the child that holds
// the lock with it (set_note); when the holder has ended and that child runs on, the message says so
// and gives the note's hint (how to stop the child). On a file system without flock support the run
// goes on unprotected, with a warning.
//
// Usage
//   const DirectoryLock lock(run_dir, "hydrojump vof");   // throws DirectoryBusy if held
//   lock.set_note("its solver interFoam, pid 4242", "`kill -USR2 4242` stops it");  // while it runs
//   lock.set_note("");                                    // after
//   ... run; the lock is released when `lock` goes out of scope ...
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

namespace hydrojump::util {

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

  // Shows `note` after the holder in a second process's message: the child given descriptor(), as
  // "<what>, pid <pid>". When this process has ended and that child runs on, the message says so and
  // adds `hint_if_holder_ends` (how to stop the child). "" removes the note. Best effort, as the
  // holder text.
  void set_note(const std::string& note, const std::string& hint_if_holder_ends = "") const;

 private:
  int fd_ = -1;
  bool writable_ = false;
  std::string holder_text_;  // "<holder>, pid <pid>"
};

}  // namespace hydrojump::util
