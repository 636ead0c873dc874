// Writing a whole output file with its errors seen: a stream keeps what it is given in a buffer
// and may only find the disk full when it is closed, after a check of the stream has passed.
#pragma once

#include <filesystem>
#include <functional>
#include <iosfwd>
#include <string_view>

namespace fuzzygait::io {

// Creates or truncates `path`, lets `write` fill it, and closes it. Throws std::runtime_error
// naming the file (and the system's reason, such as a full disk) when it cannot be opened,
// written or closed.
void write_file(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write);
void write_file(const std::filesystem::path& path, std::string_view text);

}  // namespace fuzzygait::io
