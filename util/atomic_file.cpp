#include "util/atomic_file.hpp"

#include <atomic>
#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>

#include <cerrno>
#include <csignal>

#include <fcntl.h>
#include <unistd.h>

namespace hydrojump::util {
namespace {

// A temporary path beside `target`, unique within this process and across processes.
std::filesystem::path temporary_beside(const std::filesystem::path& target) {
  static std::atomic<unsigned long> counter{0};
  const auto n = counter.fetch_add(1);
  // Built by appending (GCC 12 reports a false -Wrestrict for "." + std::string temporaries).
  std::string name = ".";
  name += target.filename().string();
  name += ".tmp.";
  name += std::to_string(::getpid());
  name += '.';
  name += std::to_string(n);
  return target.parent_path() / name;
}

void ensure_parent(const std::filesystem::path& target) {
  const auto parent = target.parent_path();
  if (parent.empty()) return;
  std::error_code ec;
  std::filesystem::create_directories(parent, ec);
  if (ec) {
    throw std::runtime_error("cannot create directory '" + parent.string() + "': " + ec.message());
  }
}

// Flushes a finished file to disk, so that a crash after the rename cannot leave it empty.
void sync_file(const std::filesystem::path& p) {
  const int fd = ::open(p.c_str(), O_RDONLY);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

void rename_over(const std::filesystem::path& from, const std::filesystem::path& to) {
  sync_file(from);
  std::error_code ec;
  std::filesystem::rename(from, to, ec);
  if (ec) {
    std::error_code cleanup;
    std::filesystem::remove(from, cleanup);
    throw std::runtime_error("cannot move the finished file into place at '" + to.string() +
                             "': " + ec.message());
  }
  if (to.has_parent_path()) sync_file(to.parent_path());
}

}  // namespace

void write_file_atomically(const std::filesystem::path& target, std::string_view content) {
  write_file_atomically(target, [&](std::ostream& out) {
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
  });
}

void write_file_atomically(const std::filesystem::path& target,
                           const std::function<void(std::ostream&)>& produce) {
  write_via_temporary(target, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot open '" + tmp.string() + "' for writing");
    produce(out);
    out.close();
    if (out.fail()) throw std::runtime_error("write failed for '" + target.string() + "' (disk full?)");
  });
}

int remove_orphaned_temporaries(const std::filesystem::path& dir) {
  std::error_code ec;
  int removed = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    // ".<name>.tmp.<pid>.<n>" (temporary_beside)
    const auto tag = name.rfind(".tmp.");
    if (name.empty() || name[0] != '.' || tag == std::string::npos || tag == 0) continue;
    const std::string rest = name.substr(tag + 5);
    const auto dot = rest.find('.');
    if (dot == std::string::npos || dot == 0 || dot + 1 == rest.size() ||
        rest.find_first_not_of("0123456789.") != std::string::npos || rest.find('.', dot + 1) != std::string::npos)
      continue;
    const long pid = std::stol(rest.substr(0, dot));
    if (pid <= 0 || (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH)) {
      std::error_code remove_error;
      if (std::filesystem::remove(entry.path(), remove_error)) ++removed;
    }
  }
  return removed;
}

void write_via_temporary(const std::filesystem::path& target,
                         const std::function<void(const std::filesystem::path&)>& write_to) {
  ensure_parent(target);
  const auto tmp = temporary_beside(target);
  try {
    write_to(tmp);
  } catch (...) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw;
  }
  if (!std::filesystem::exists(tmp)) {
    throw std::runtime_error("nothing was written for '" + target.string() + "'");
  }
  rename_over(tmp, target);
}

}  // namespace hydrojump::util
