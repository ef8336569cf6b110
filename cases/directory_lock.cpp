#include "cases/directory_lock.hpp"

#include <cerrno>
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
    if (error == EWOULDBLOCK) {
      throw DirectoryBusy(dir.string() + " is in use by another process (" +
                          (other.empty() ? std::string("holder unknown") : other) +
                          "); wait for it to finish or stop it (Ctrl-C or SIGTERM: runs stop with a checkpoint) first");
    }
    // A file system without flock (some NFS, FUSE): run unprotected rather than not at all.
    std::cerr << "warning: cannot lock " << file.string() << " (" << std::strerror(error)
              << "); make sure no other hydrojump process uses " << dir.string() << "\n";
    return;
  }
  if (!writable) return;
  // Ours: record who holds it (best effort; the lock, not the text, is what counts).
  const std::string text = holder + ", pid " + std::to_string(::getpid()) + "\n";
  if (::ftruncate(fd_, 0) == 0) {
    ::lseek(fd_, 0, SEEK_SET);
    [[maybe_unused]] const auto written = ::write(fd_, text.data(), text.size());
  }
}

DirectoryLock::~DirectoryLock() {
  if (fd_ >= 0) ::close(fd_);  // closing the file releases the lock
}

}  // namespace hydrojump::cases
