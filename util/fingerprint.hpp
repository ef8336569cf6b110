// Text helpers shared by the run caches: reading a whole file, and a stable fingerprint of a text
// (FNV-1a, 64 bit, as 16 hex digits) that identifies a resolved case and program version. Not a
// security hash: it only tells whether a run's inputs changed.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace hydrojump::util {

// The whole content of `file`, or "" if it cannot be read.
std::string read_text_file(const std::filesystem::path& file);

// FNV-1a over the bytes of `text`, as 16 lower-case hex digits.
std::string fingerprint(std::string_view text);

}  // namespace hydrojump::util
