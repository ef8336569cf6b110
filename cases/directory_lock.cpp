#include "cases/directory_lock.hpp"

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

namespace hydrojump::cases {

namespace {

std::string read_all(int fd) {
  std::string text;
  char buffer[512];
  ::lseek(fd, 0, SEEK_SET);
  for (ssize_t n; (n = ::read(fd, buffer, sizeof buffer)) > 0;) text.append(buffer, static_cast<std::size_t>(n));
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  return text;
}

// Replaces the file's text (best effort: the lock, not the text, is what counts).
void write_all(int fd, const std::string& text) {
  if (::ftruncate(fd, 0) != 0) return;
  ::lseek(fd, 0, SEEK_SET);
  [[maybe_unused]] const auto written = ::write(fd, text.data(), text.size());
}

// Whether the holder the text's first line names ("<holder>, pid <pid>") has ended while the lock is
// still held: then a child it gave the lock to runs on (a runner killed while its solver runs).
bool holder_has_ended(const std::string& text) {
  const std::string first_line = text.substr(0, text.find('\n'));
  const std::size_t at = first_line.rfind(", pid ");
  if (at == std::string::npos) return false;
  char* end = nullptr;
  const long pid = std::strtol(first_line.c_str() + at + 6, &end, 10);
  if (end == first_line.c_str() + at + 6 || *end != '\0' || pid <= 0) return false;
  return ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
}

// The message for a second process: the holder and its note; when the holder has ended, that what it
// left running holds the lock.
std::string busy_message(const std::filesystem::path& dir, const std::string& text) {
  if (text.empty()) {
    return dir.string() + " is in use by another process (holder unknown); wait for it to finish or stop it "
                          "(Ctrl-C or SIGTERM: runs stop with a checkpoint) first";
  }
  const std::size_t newline = text.find('\n');
  const std::string holder = text.substr(0, newline);
  const std::string note = newline == std::string::npos ? std::string() : text.substr(newline + 1);
  if (!note.empty() && holder_has_ended(text)) {
    return dir.string() + " is in use: " + holder + " has ended, but the child it left running holds the lock (" +
           note + "); wait for it to finish or stop it first";
  }
  return dir.string() + " is in use by another process (" + holder + (note.empty() ? "" : "; " + note) +
         "); wait for it to finish or stop it (Ctrl-C or SIGTERM: runs stop with a checkpoint) first";
}

}  // namespace

DirectoryLock::DirectoryLock(const std::filesystem::path& dir, const std::string& holder) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  const std::filesystem::path file = dir / file_name;
  fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  bool writable = fd_ >= 0;
  // A lock file left by another user (or a root run) can still be locked through a read-only
  // descriptor; only the holder text is not written then.
  if (fd_ < 0 && errno == EACCES) fd_ = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
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

void DirectoryLock::set_note(const std::string& note) const {
  if (fd_ < 0 || !writable_) return;
  write_all(fd_, holder_text_ + "\n" + (note.empty() ? std::string() : note + "\n"));
}

DirectoryLock::~DirectoryLock() {
  if (fd_ >= 0) ::close(fd_);  // closing the file releases the lock
}

}  // namespace hydrojump::cases
