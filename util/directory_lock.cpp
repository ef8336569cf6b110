#include "util/directory_lock.hpp"

#include <cerrno>
#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <vector>
#include <iostream>
#include <string>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace hydrojump::util {

namespace {

std::string read_all(int fd) {
  std::string text;
  char buffer[512];
  ::lseek(fd, 0, SEEK_SET);
  for (ssize_t n; (n = ::read(fd, buffer, sizeof buffer)) > 0;) text.append(buffer, static_cast<std::size_t>(n));
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  return text;
}

// Replaces the file's text (best effort: the lock, not the text, is what counts). Written over the old
// text, then cut to its length, so that a reader never finds the file empty.
void write_all(int fd, const std::string& text) {
  if (::pwrite(fd, text.data(), text.size(), 0) != static_cast<ssize_t>(text.size())) return;
  [[maybe_unused]] const int cut = ::ftruncate(fd, static_cast<off_t>(text.size()));
}

// The process named by "..., pid <pid>" at the end of `line`, or 0.
pid_t pid_in(const std::string& line) {
  const std::size_t at = line.rfind("pid ");
  if (at == std::string::npos) return 0;
  char* end = nullptr;
  const long pid = std::strtol(line.c_str() + at + 4, &end, 10);
  if (end == line.c_str() + at + 4 || pid <= 0) return 0;
  return static_cast<pid_t>(pid);
}

bool process_exists(pid_t pid) { return pid > 0 && (::kill(pid, 0) == 0 || errno == EPERM); }

// The message for a second process. The file holds the holder ("<holder>, pid <pid>"), then the note
// on the child it runs and the hint for stopping that child (DirectoryLock::set_note). When the holder
// has ended and the child of the note still runs, the child holds the lock: the message says so, with
// the hint. (A note left by an earlier holder whose child has ended as well is not believed.)
std::string busy_message(const std::filesystem::path& dir, const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  lines.resize(std::max<std::size_t>(lines.size(), 3));
  const std::string& holder = lines[0];
  const std::string& note = lines[1];
  const std::string& hint = lines[2];
  const std::string wait = "; wait for it to finish or stop it (Ctrl-C or SIGTERM: runs stop with a checkpoint) first";
  if (holder.empty()) return dir.string() + " is in use by another process (holder unknown)" + wait;
  if (!note.empty() && !process_exists(pid_in(holder)) && process_exists(pid_in(note))) {
    return dir.string() + " is in use: " + holder + " has ended, but " + note + " runs on and holds the lock" +
           (hint.empty() ? std::string() : ": " + hint) + "; or wait for it to finish";
  }
  return dir.string() + " is in use by another process (" + holder + (note.empty() ? "" : "; " + note) + ")" + wait;
}

}  // namespace

DirectoryLock::DirectoryLock(const std::filesystem::path& dir, const std::string& holder) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  const std::filesystem::path file = dir / file_name;
  // Never through a symbolic link (its target would be truncated and written), nor on anything but
  // a regular file.
  fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
  bool writable = fd_ >= 0;
  // A lock file left by another user (or a root run) can still be locked through a read-only
  // descriptor; only the holder text is not written then.
  if (fd_ < 0 && errno == EACCES) fd_ = ::open(file.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK);
  // Not a FIFO or device either, nor a hard link to another file (it would be written too).
  struct stat info {};
  if (fd_ >= 0 && (::fstat(fd_, &info) != 0 || !S_ISREG(info.st_mode) || info.st_nlink > 1)) {
    ::close(fd_);
    fd_ = -1;
    errno = EINVAL;
  }
  if (fd_ < 0 && (errno == ELOOP || errno == EINVAL || errno == EISDIR)) {
    throw std::runtime_error("the lock file " + file.string() +
                             " is a symbolic link, a hard link or not a regular file: remove it (hydrojump creates its own)");
  }
  if (fd_ < 0) {
    throw std::runtime_error("cannot create the lock file " + file.string() + " (" + std::strerror(errno) +
                             "): is " + dir.string() + " writable?");
  }
  int rc = 0;
  do {
    rc = ::flock(fd_, LOCK_EX | LOCK_NB);
  } while (rc != 0 && errno == EINTR);
  if (rc != 0) {
    const int error = errno;
    const std::string other = read_all(fd_);
    ::close(fd_);
    fd_ = -1;
    if (error == EWOULDBLOCK) throw DirectoryBusy(busy_message(dir, other));
    // A file system without flock (some NFS, FUSE): run unprotected rather than not at all.
    std::cerr << "warning: cannot lock " << file.string() << " (" << std::strerror(error)
              << "); make sure no other hydrojump process uses " << dir.string() << "\n";
    return;
  }
  writable_ = writable;
  holder_text_ = holder + ", pid " + std::to_string(::getpid());
  // Ours: record who holds it.
  set_note("");
}

void DirectoryLock::set_note(const std::string& note, const std::string& hint_if_holder_ends) const {
  if (fd_ < 0 || !writable_) return;
  write_all(fd_, holder_text_ + "\n" + (note.empty() ? std::string() : note + "\n" + hint_if_holder_ends + "\n"));
}

DirectoryLock::~DirectoryLock() {
  if (fd_ >= 0) ::close(fd_);  // closing the file releases the lock
}

}  // namespace hydrojump::util
