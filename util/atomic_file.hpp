// Writing files so that nothing already written is ever lost or half-written: the content goes to a
// temporary file beside the target, is flushed, and is then renamed over the target in one step.
#pragma once

#include <filesystem>
#include <functional>
#include <iosfwd>
#include <string_view>

namespace hydrojump::util {

// Writes `content` to `target` atomically (temporary file in the same directory, then rename).
// Creates missing parent directories. Throws std::runtime_error naming the file on failure.
void write_file_atomically(const std::filesystem::path& target, std::string_view content);

// Same, for content produced by a callback that writes to a binary output stream.
void write_file_atomically(const std::filesystem::path& target,
                           const std::function<void(std::ostream&)>& produce);

// Runs `write_to(temporary_path)` (for libraries such as VTK that write files themselves), then
// renames the temporary file over `target`. The temporary is removed if `write_to` throws.
void write_via_temporary(const std::filesystem::path& target,
                         const std::function<void(const std::filesystem::path&)>& write_to);

// Removes the temporary files that writers killed outright (SIGKILL, a power cut) left in `dir` (not
// its subdirectories): ".<name>.tmp.<pid>.<n>" whose process <pid> no longer runs. Call it while holding
// the directory's lock, so that no live writer's file can match. Returns how many were removed.
int remove_orphaned_temporaries(const std::filesystem::path& dir);

}  // namespace hydrojump::util
